#include "toml_bytes.hpp"

#include <cstddef>
#include <string>

#include "fogradar/core/error.hpp"

namespace fogradar::experiment::detail {
namespace {

[[noreturn]] void refuse(std::string_view source_name, std::size_t line,
                         const std::string& message) {
  throw InvalidParameter("toml", message, {std::string(source_name), line});
}

// Length of the well-formed UTF-8 sequence at text[i] (RFC 3629, section 4: no overlong forms, no
// surrogates, nothing above U+10FFFF), or 0.
std::size_t utf8_length(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  if (lead < 0x80) return 1;
  std::size_t length = 0;
  unsigned char low = 0x80, high = 0xBF;  // allowed range of the second byte
  if (lead >= 0xC2 && lead <= 0xDF) {
    length = 2;
  } else if (lead >= 0xE0 && lead <= 0xEF) {
    length = 3;
    if (lead == 0xE0) low = 0xA0;
    if (lead == 0xED) high = 0x9F;
  } else if (lead >= 0xF0 && lead <= 0xF4) {
    length = 4;
    if (lead == 0xF0) low = 0x90;
    if (lead == 0xF4) high = 0x8F;
  } else {
    return 0;
  }
  if (i + length > text.size()) return 0;
  if (byte(i + 1) < low || byte(i + 1) > high) return 0;
  for (std::size_t k = 2; k < length; ++k) {
    if (byte(i + k) < 0x80 || byte(i + k) > 0xBF) return 0;
  }
  return length;
}

// A backslash escaping the next character, which is ASCII and not a line break (a line-ending
// backslash is counted as a line like any other; a non-ASCII escaped byte is checked as UTF-8).
bool escapes_ascii(std::string_view text, std::size_t i) {
  return text[i] == '\\' && i + 1 < text.size() && text[i + 1] != '\n' &&
         static_cast<unsigned char>(text[i + 1]) < 0x80;
}

// Consecutive `quote`s at the start of `text`: a multi-line string's closing delimiter takes up to
// two quotes of content before it ("""a""""" is a""), so the whole run closes it.
std::size_t quote_run(std::string_view text, char quote) {
  std::size_t n = 0;
  while (n < text.size() && text[n] == quote) ++n;
  return n;
}

enum class Context { bare, comment, basic, literal, multiline_basic, multiline_literal };

}  // namespace

void require_toml_safe_bytes(std::string_view text, std::string_view source_name) {
  Context context = Context::bare;
  std::size_t line = 1;
  for (std::size_t i = 0; i < text.size();) {
    const char c = text[i];
    if (static_cast<unsigned char>(c) >= 0x80) {
      if (context == Context::bare) {
        refuse(source_name, line,
               "non-ASCII byte outside a string or comment (keys and values must be ASCII there; "
               "toml++ 3.3.0 cannot parse it, marzer/tomlplusplus issue #295)");
      }
      const std::size_t length = utf8_length(text, i);
      if (length == 0) refuse(source_name, line, "invalid UTF-8 (a TOML file is UTF-8 text)");
      i += length;
      continue;
    }
    const std::string_view rest = text.substr(i);
    std::size_t step = 1;
    switch (context) {
      case Context::bare:
        if (c == '#') context = Context::comment;
        if (rest.starts_with("\"\"\"")) {
          context = Context::multiline_basic;
          step = 3;
        } else if (rest.starts_with("'''")) {
          context = Context::multiline_literal;
          step = 3;
        } else if (c == '"') {
          context = Context::basic;
        } else if (c == '\'') {
          context = Context::literal;
        }
        break;
      case Context::comment:
        if (c == '\n') context = Context::bare;
        break;
      case Context::basic:
        // A string ends at its quote or, malformed, at the line's end (toml++ reports that).
        if (escapes_ascii(text, i))
          step = 2;
        else if (c == '"' || c == '\n')
          context = Context::bare;
        break;
      case Context::literal:
        if (c == '\'' || c == '\n') context = Context::bare;
        break;
      case Context::multiline_basic:
        if (escapes_ascii(text, i))
          step = 2;
        else if (rest.starts_with("\"\"\"")) {
          context = Context::bare;
          step = quote_run(rest, '"');
        }
        break;
      case Context::multiline_literal:
        if (rest.starts_with("'''")) {
          context = Context::bare;
          step = quote_run(rest, '\'');
        }
        break;
    }
    if (c == '\n') ++line;
    i += step;
  }
}

}  // namespace fogradar::experiment::detail
