// A scenario error pointed at the key as the file wrote it: its source, its line and the lines of
// the other keys a combined check names.
#include <cctype>
#include <map>
#include <string>
#include <vector>

#include "fogradar/core/error.hpp"
#include "scenario_parts.hpp"

namespace fogradar::experiment::detail {

namespace {

bool is_key_char(char c) {
  return std::isalnum(static_cast<unsigned char>(c)) != 0 || c == '_' || c == '.';
}

// Positions where `key` occurs in `text` as a whole key, not as part of a longer one.
std::vector<std::size_t> key_positions(std::string_view text, std::string_view key) {
  std::vector<std::size_t> found;
  for (std::size_t at = text.find(key); at != std::string_view::npos; at = text.find(key, at + 1)) {
    const std::size_t end = at + key.size();
    const bool starts = at == 0 || !is_key_char(text[at - 1]);
    const bool ends = end == text.size() || !is_key_char(text[end]) ||
                      (text[end] == '.' && (end + 1 == text.size() || !is_key_char(text[end + 1])));
    if (starts && (key.back() == '.' || ends)) found.push_back(at);
  }
  return found;
}

// The lines of the other keys a combined check names, so every key involved can be found.
std::string other_key_lines(const std::string& message, const std::string& key,
                            const KeyLines& lines) {
  std::string listed;
  for (const auto& [other, line] : lines) {
    if (other == key || key_positions(message, other).empty()) continue;
    listed += (listed.empty() ? " (" : ", ") + other + " at line " + std::to_string(line);
  }
  return listed.empty() ? listed : listed + ")";
}

// A check's message "<key> = <value>: must be ..." with the number as the file typed it, where it
// gave one (a check writes the double it holds: "3e-07" for 3e-7, "100000" for 1e5).
std::string as_typed(const std::string& message, const std::string& key,
                     const std::map<std::string, std::string>& typed_numbers) {
  const auto typed = typed_numbers.find(key);
  const std::string head = key + " = ";
  if (typed == typed_numbers.end() || !message.starts_with(head)) return message;
  const std::size_t end = message.find(": ", head.size());
  if (end == std::string::npos || message[head.size()] == '\'') return message;
  return head + typed->second + message.substr(end);
}

}  // namespace

[[noreturn]] void throw_at(std::string_view source, std::size_t line, const std::string& key,
                           const std::string& message) {
  throw InvalidParameter(key, message, {std::string(source), line});
}

void relocate(const InvalidParameter& e, std::string_view source_name, const KeyLines& lines,
              const std::map<std::string, std::string>& typed_numbers) {
  // A reader's error already names its key and line; it may name keys read before it.
  if (e.location().source == source_name) {
    throw InvalidParameter(e.field(), e.message() + other_key_lines(e.message(), e.field(), lines),
                           e.location());
  }
  // A range check: point at the key as the user wrote it, and its line.
  const std::string& key = e.field();
  const std::string message =
      as_typed(e.message(), key, typed_numbers) + other_key_lines(e.message(), key, lines);
  // A key the file does not give keeps its paper value; a check combining it with keys the file
  // gives points at the first of those.
  std::size_t line = 0;
  std::size_t within = 0;  // the longest table given that holds the key: a layer of an array
  for (const auto& [table, table_line] : lines) {
    if (key.size() > table.size() && key.starts_with(table) && key[table.size()] == '.' &&
        table.size() > within) {
      within = table.size();
      line = table_line;
    }
  }
  if (const auto given = lines.find(key); given != lines.end()) {
    line = given->second;
  } else if (line == 0) {
    for (const auto& [other, other_line] : lines) {
      if (!key_positions(e.message(), other).empty() && (line == 0 || other_line < line))
        line = other_line;
    }
  }
  throw_at(source_name, line, key, message);
}

}  // namespace fogradar::experiment::detail
