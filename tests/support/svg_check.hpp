// Test helpers for SVG output: a minimal XML well-formedness checker (written here, independent of
// the writer: balanced and nested tags, double-quoted unique attributes, only the predefined
// entities) and a reader of the text elements of one class with their x positions.
#pragma once

#include <cctype>
#include <cstdlib>
#include <string>
#include <string_view>
#include <vector>

namespace fogradar::test_support {

// Character data or an attribute value: no '<', every '&' starts a predefined entity.
inline bool valid_text(std::string_view text) {
  if (text.find('<') != std::string_view::npos) return false;
  for (auto pos = text.find('&'); pos != std::string_view::npos; pos = text.find('&', pos + 1)) {
    const std::string_view rest = text.substr(pos);
    bool known = false;
    for (const std::string_view entity : {"&amp;", "&lt;", "&gt;", "&quot;", "&apos;"}) {
      known = known || rest.starts_with(entity);
    }
    if (!known) return false;
  }
  return true;
}

inline bool is_name_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) || c == '-' || c == ':' || c == '_';
}

// Minimal XML well-formedness check: one root element, balanced and properly nested tags,
// double-quoted unique attributes, valid character data. Returns "" or a description.
inline std::string xml_error(std::string_view doc) {
  std::size_t pos = 0;
  if (doc.starts_with("<?xml")) pos = doc.find("?>") + 2;
  std::vector<std::string> open;
  int roots = 0;
  while (true) {
    const std::size_t lt = doc.find('<', pos);
    const std::string_view text =
        doc.substr(pos, lt == std::string_view::npos ? doc.npos : lt - pos);
    if (!valid_text(text)) return "bad character data near " + std::to_string(pos);
    if (open.empty() && text.find_first_not_of(" \n\t\r") != std::string_view::npos) {
      return "text outside the root element";
    }
    if (lt == std::string_view::npos) break;
    pos = lt + 1;
    if (doc.substr(pos).starts_with("/")) {  // end tag
      const std::size_t gt = doc.find('>', pos);
      const std::string name(doc.substr(pos + 1, gt - pos - 1));
      if (open.empty() || open.back() != name) return "mismatched </" + name + ">";
      open.pop_back();
      pos = gt + 1;
      continue;
    }
    std::size_t end = pos;
    while (end < doc.size() && is_name_char(doc[end])) ++end;
    if (end == pos) return "missing element name at " + std::to_string(pos);
    const std::string name(doc.substr(pos, end - pos));
    if (open.empty() && ++roots > 1) return "second root element <" + name + ">";
    std::vector<std::string> attributes;
    pos = end;
    while (true) {
      while (pos < doc.size() && std::isspace(static_cast<unsigned char>(doc[pos]))) ++pos;
      if (doc.substr(pos).starts_with("/>")) {
        pos += 2;
        break;
      }
      if (doc.substr(pos).starts_with(">")) {
        open.push_back(name);
        pos += 1;
        break;
      }
      end = pos;
      while (end < doc.size() && is_name_char(doc[end])) ++end;
      const std::string attribute(doc.substr(pos, end - pos));
      if (attribute.empty() || doc.substr(end, 2) != "=\"")
        return "bad attribute in <" + name + ">";
      for (const std::string& seen : attributes) {
        if (seen == attribute) return "duplicate attribute " + attribute;
      }
      attributes.push_back(attribute);
      const std::size_t close = doc.find('"', end + 2);
      if (close == std::string_view::npos) return "unterminated attribute " + attribute;
      if (!valid_text(doc.substr(end + 2, close - end - 2))) return "bad value of " + attribute;
      pos = close + 1;
    }
  }
  if (!open.empty()) return "unclosed <" + open.back() + ">";
  return roots == 1 ? "" : "no root element";
}

// Occurrences of `needle` in `haystack`.
inline std::size_t count(std::string_view haystack, std::string_view needle) {
  std::size_t n = 0;
  for (auto pos = haystack.find(needle); pos != std::string_view::npos;
       pos = haystack.find(needle, pos + needle.size())) {
    ++n;
  }
  return n;
}

// Value of attribute `name` in the start tag that begins at `tag` ("" if absent).
inline std::string attribute(std::string_view doc, std::size_t tag, std::string_view name) {
  const std::size_t end = doc.find('>', tag);
  std::string key = " ";  // appended, not "+": GCC 12 -O3 warns falsely (-Wrestrict) on the latter
  key += name;
  key += "=\"";
  const std::size_t at = doc.substr(0, end).find(key, tag);
  if (at == std::string_view::npos) return "";
  const std::size_t value = at + key.size();
  return std::string(doc.substr(value, doc.find('"', value) - value));
}

struct SvgText {
  double x;
  double y;
  std::string content;  // as written (XML-escaped)
};

// Every <text> element whose class attribute is `class_name`, in document order.
inline std::vector<SvgText> texts_of_class(std::string_view doc, std::string_view class_name) {
  std::vector<SvgText> texts;
  for (auto tag = doc.find("<text "); tag != std::string_view::npos;
       tag = doc.find("<text ", tag + 1)) {
    if (attribute(doc, tag, "class") != class_name) continue;
    const std::size_t open_end = doc.find('>', tag) + 1;
    texts.push_back({std::strtod(attribute(doc, tag, "x").c_str(), nullptr),
                     std::strtod(attribute(doc, tag, "y").c_str(), nullptr),
                     std::string(doc.substr(open_end, doc.find("</text>", open_end) - open_end))});
  }
  return texts;
}

// Start positions of the elements `<element ` whose class attribute is `class_name`.
inline std::vector<std::size_t> elements_of_class(std::string_view doc, std::string_view element,
                                                  std::string_view class_name) {
  std::vector<std::size_t> found;
  std::string open = "<";
  open += element;
  open += ' ';
  for (auto tag = doc.find(open); tag != std::string_view::npos; tag = doc.find(open, tag + 1)) {
    if (attribute(doc, tag, "class") == class_name) found.push_back(tag);
  }
  return found;
}

// "" when no two consecutive texts of `class_name` (centred at x, 12 px font) overlap with at least
// 2 px between them, else a description. A text's width is taken as 0.64 em per character: DejaVu
// Sans, Debian's default sans-serif face, advances its digits by 1303/2048 = 0.636 em, more than
// the other common faces (Liberation Sans and Arial 0.556 em).
inline std::string text_overlap(std::string_view doc, std::string_view class_name) {
  const auto width = [](const std::string& text) {
    std::size_t chars = 0;
    for (const char c : text) chars += (static_cast<unsigned char>(c) & 0xC0) != 0x80 ? 1 : 0;
    return 0.64 * 12.0 * static_cast<double>(chars);
  };
  const std::vector<SvgText> texts = texts_of_class(doc, class_name);
  for (std::size_t i = 1; i < texts.size(); ++i) {
    const double space =
        texts[i].x - texts[i - 1].x - 0.5 * (width(texts[i].content) + width(texts[i - 1].content));
    if (space < 2.0) {
      return "'" + texts[i - 1].content + "' at x = " + std::to_string(texts[i - 1].x) + " and '" +
             texts[i].content + "' at x = " + std::to_string(texts[i].x) + " are " +
             std::to_string(space) + " px apart";
    }
  }
  return "";
}

}  // namespace fogradar::test_support
