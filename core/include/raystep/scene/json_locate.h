// Line numbers for messages about JSON files. nlohmann-json reports a byte position for syntax errors only;
// these helpers find the line of a value named by a path (a JSON pointer, RFC 6901), walking the text
// without recursion. They run only when an error is reported, so they favour simplicity over speed.
#pragma once

#include <cstddef>
#include <string>
#include <string_view>
#include <vector>

namespace raystep {

// A path into a JSON document, kept in two spellings: the JSON pointer "/objects/2/radius" and the
// display form "objects[2].radius" used in messages.
class JsonPath {
 public:
  JsonPath child(const std::string& key) const;
  JsonPath child(size_t index) const;
  std::string pointer() const;
  std::string display() const;  // "" for the root
  const std::vector<std::string>& tokens() const { return tokens_; }

 private:
  std::vector<std::string> tokens_;  // unescaped keys and decimal indices
  std::vector<bool> is_index_;
};

// Line (1-based) at which the value named by `pointer` starts. When that value does not exist (a missing
// member), the line of its deepest existing ancestor. The last of duplicate keys counts (as in
// nlohmann-json). 0 when the text is not valid JSON.
int json_line_of(std::string_view text, const JsonPath& path);
int json_line_of(std::string_view text, std::string_view pointer);

// Line of nlohmann-json's parse_error::byte (the 1-based index of the last character read), never past
// the last line that has text.
int json_line_at_byte(std::string_view text, size_t byte);

// Line of the first number token spelled exactly `literal` (nlohmann's number-overflow error names the
// literal but not its position); 0 if none.
int json_line_of_number(std::string_view text, std::string_view literal);

// The first key that occurs twice in one object, in text order: its path (pointer form) and line.
struct JsonDuplicateKey {
  std::string pointer;
  std::string display;
  int line = 0;
};
bool json_find_duplicate_key(std::string_view text, JsonDuplicateKey* dup);

}  // namespace raystep
