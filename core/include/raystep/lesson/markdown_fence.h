// Code fences as CommonMark reads them, for the lesson parser, the numbers' scanner and the handout's HTML (a
// fence closes only with the same character, at least as long, and no info string).
#pragma once

#include <string>

namespace raystep {

inline std::string fence_trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// A fence line: up to 3 spaces, then 3 or more ` or ~; `info` is the rest, trimmed.
struct Fence {
  char ch = 0;
  size_t length = 0;
  std::string info;
};
inline bool fence_of(const std::string& line, Fence* f) {
  size_t i = 0;
  while (i < line.size() && i < 3 && line[i] == ' ') ++i;
  if (i >= line.size() || (line[i] != '`' && line[i] != '~')) return false;
  char ch = line[i];
  size_t n = 0;
  while (i + n < line.size() && line[i + n] == ch) ++n;
  if (n < 3) return false;
  std::string info = fence_trim(line.substr(i + n));
  if (ch == '`' && info.find('`') != std::string::npos) return false;  // CommonMark: not a fence
  *f = Fence{ch, n, info};
  return true;
}
inline bool fence_closes(const Fence& open, const std::string& line) {
  Fence f;
  return fence_of(line, &f) && f.ch == open.ch && f.length >= open.length && f.info.empty();
}

}  // namespace raystep
