#include "raystep/scene/json_locate.h"

#include <algorithm>
#include <cstdint>
#include <unordered_set>

namespace raystep {

JsonPath JsonPath::child(const std::string& key) const {
  JsonPath p = *this;
  p.tokens_.push_back(key);
  p.is_index_.push_back(false);
  return p;
}

JsonPath JsonPath::child(size_t index) const {
  JsonPath p = *this;
  p.tokens_.push_back(std::to_string(index));
  p.is_index_.push_back(true);
  return p;
}

std::string JsonPath::pointer() const {
  std::string s;
  for (const std::string& t : tokens_) {
    s += '/';
    for (char c : t) {
      if (c == '~') s += "~0";
      else if (c == '/') s += "~1";
      else s += c;
    }
  }
  return s;
}

std::string JsonPath::display() const {
  std::string s;
  for (size_t i = 0; i < tokens_.size(); ++i) {
    if (is_index_[i]) s += "[" + tokens_[i] + "]";
    else s += (s.empty() ? "" : ".") + tokens_[i];
  }
  return s;
}

namespace {

int line_at(std::string_view text, size_t pos) {
  pos = std::min(pos, text.size());
  return 1 + int(std::count(text.begin(), text.begin() + pos, '\n'));
}

void append_utf8(uint32_t c, std::string* out) {
  if (c < 0x80) {
    *out += char(c);
  } else if (c < 0x800) {
    *out += char(0xC0 | (c >> 6));
    *out += char(0x80 | (c & 0x3F));
  } else if (c < 0x10000) {
    *out += char(0xE0 | (c >> 12));
    *out += char(0x80 | ((c >> 6) & 0x3F));
    *out += char(0x80 | (c & 0x3F));
  } else {
    *out += char(0xF0 | (c >> 18));
    *out += char(0x80 | ((c >> 12) & 0x3F));
    *out += char(0x80 | ((c >> 6) & 0x3F));
    *out += char(0x80 | (c & 0x3F));
  }
}

// An iterative walk over a JSON text that notes where the value at `target` starts (and its deepest
// existing ancestor), and optionally the first duplicate key. Every step advances, so it ends on any input.
class JsonWalker {
 public:
  JsonWalker(std::string_view text, std::vector<std::string> target, bool find_duplicates)
      : t_(text), target_(std::move(target)), find_duplicates_(find_duplicates) {}

  bool run() {
    bool child_matches = true;  // the root's (empty) path matches the target's first 0 tokens
    bool expect_value = true;
    for (;;) {
      skip_ws();
      if (expect_value) {
        note_value(child_matches);
        if (pos_ >= t_.size()) return false;
        char c = t_[pos_];
        if (c == '{' || c == '[') {
          stack_.push_back(Frame{c == '{', 0, "", child_matches, {}});
          ++pos_;
          skip_ws();
          if (pos_ < t_.size() && t_[pos_] == (c == '{' ? '}' : ']')) {
            ++pos_;
            stack_.pop_back();
            expect_value = false;
          } else if (c == '{') {
            if (!member_key(&child_matches)) return false;
          } else {
            child_matches = matches_child("0");
          }
          continue;
        }
        if (c == '"' ? !read_string(nullptr) : !skip_scalar()) return false;
        expect_value = false;
        continue;
      }
      // After a value: end of text, next element or member, or the container's end.
      if (stack_.empty()) return pos_ == t_.size();
      if (pos_ >= t_.size()) return false;
      Frame& f = stack_.back();
      char c = t_[pos_];
      if (c == ',') {
        ++pos_;
        skip_ws();
        if (f.object) {
          if (!member_key(&child_matches)) return false;
        } else {
          child_matches = matches_child(std::to_string(++f.index));
        }
        expect_value = true;
      } else if (c == (f.object ? '}' : ']')) {
        ++pos_;
        stack_.pop_back();
      } else {
        return false;
      }
    }
  }

  size_t target_pos = SIZE_MAX;    // where the target value starts (the last one, if keys repeat)
  size_t ancestor_pos = SIZE_MAX;  // where its deepest existing ancestor starts
  size_t duplicate_pos = SIZE_MAX;
  std::string duplicate_pointer, duplicate_display;

 private:
  struct Frame {
    bool object;
    size_t index;       // arrays: the current element
    std::string key;    // objects: the current member
    bool matches;       // this container's path equals the target's first stack-depth tokens
    std::unordered_set<std::string> keys;  // seen so far (duplicate search only)
  };

  void note_value(bool matches) {
    if (!matches) return;
    size_t depth = stack_.size();
    if (depth == target_.size()) target_pos = pos_;
    else if (int(depth) >= ancestor_depth_) ancestor_depth_ = int(depth), ancestor_pos = pos_;
  }

  bool matches_child(const std::string& token) const {
    const Frame& f = stack_.back();
    size_t d = stack_.size() - 1;
    return f.matches && d < target_.size() && target_[d] == token;
  }

  // At a member's key: read it, the colon, and decide whether the member's value is on the target path.
  bool member_key(bool* child_matches) {
    size_t key_pos = pos_;
    Frame& f = stack_.back();
    if (pos_ >= t_.size() || t_[pos_] != '"' || !read_string(&f.key)) return false;
    skip_ws();
    if (pos_ >= t_.size() || t_[pos_] != ':') return false;
    ++pos_;
    if (find_duplicates_ && !f.keys.insert(f.key).second && duplicate_pos == SIZE_MAX) {
      duplicate_pos = key_pos;
      JsonPath p;
      for (const Frame& g : stack_) p = g.object ? p.child(g.key) : p.child(g.index);
      duplicate_pointer = p.pointer();
      duplicate_display = p.display();
    }
    *child_matches = matches_child(f.key);
    return true;
  }

  void skip_ws() {
    while (pos_ < t_.size() && (t_[pos_] == ' ' || t_[pos_] == '\t' || t_[pos_] == '\n' || t_[pos_] == '\r'))
      ++pos_;
  }

  // Numbers, true, false, null: up to the next delimiter.
  bool skip_scalar() {
    size_t start = pos_;
    while (pos_ < t_.size() && std::string_view(",]} \t\r\n").find(t_[pos_]) == std::string_view::npos) ++pos_;
    return pos_ > start;
  }

  // At '"': decode the string (escapes, \u with surrogate pairs, to UTF-8) into *out if not null.
  bool read_string(std::string* out) {
    if (out) out->clear();
    ++pos_;
    while (pos_ < t_.size()) {
      char c = t_[pos_++];
      if (c == '"') return true;
      if (c != '\\') {
        if (out) *out += c;
        continue;
      }
      if (pos_ >= t_.size()) return false;
      char e = t_[pos_++];
      uint32_t code = 0;
      switch (e) {
        case 'b': code = '\b'; break;
        case 'f': code = '\f'; break;
        case 'n': code = '\n'; break;
        case 'r': code = '\r'; break;
        case 't': code = '\t'; break;
        case 'u':
          if (!hex4(&code)) return false;
          if (code >= 0xD800 && code < 0xDC00 && pos_ + 1 < t_.size() && t_[pos_] == '\\' && t_[pos_ + 1] == 'u') {
            pos_ += 2;
            uint32_t low;
            if (!hex4(&low)) return false;
            code = 0x10000 + ((code - 0xD800) << 10) + (low - 0xDC00);
          }
          break;
        default: code = uint32_t(static_cast<unsigned char>(e)); break;  // \" \\ \/
      }
      if (out) append_utf8(code, out);
    }
    return false;
  }

  bool hex4(uint32_t* code) {
    if (pos_ + 4 > t_.size()) return false;
    *code = 0;
    for (int i = 0; i < 4; ++i) {
      char h = t_[pos_++];
      int v = (h >= '0' && h <= '9') ? h - '0' : (h >= 'a' && h <= 'f') ? h - 'a' + 10
                                               : (h >= 'A' && h <= 'F') ? h - 'A' + 10 : -1;
      if (v < 0) return false;
      *code = *code * 16 + uint32_t(v);
    }
    return true;
  }

  std::string_view t_;
  std::vector<std::string> target_;
  bool find_duplicates_;
  size_t pos_ = 0;
  int ancestor_depth_ = -1;
  std::vector<Frame> stack_;
};

std::vector<std::string> pointer_tokens(std::string_view pointer) {
  std::vector<std::string> tokens;
  size_t i = 0;
  while (i < pointer.size()) {
    if (pointer[i] != '/') return tokens;  // not a pointer: stop at the valid prefix
    ++i;
    std::string tok;
    while (i < pointer.size() && pointer[i] != '/') {
      if (pointer[i] == '~' && i + 1 < pointer.size() && (pointer[i + 1] == '0' || pointer[i + 1] == '1')) {
        tok += pointer[i + 1] == '0' ? '~' : '/';
        i += 2;
      } else {
        tok += pointer[i++];
      }
    }
    tokens.push_back(tok);
  }
  return tokens;
}

int line_of_tokens(std::string_view text, std::vector<std::string> tokens) {
  JsonWalker w(text, std::move(tokens), false);
  if (!w.run()) return 0;
  if (w.target_pos != SIZE_MAX) return line_at(text, w.target_pos);
  if (w.ancestor_pos != SIZE_MAX) return line_at(text, w.ancestor_pos);
  return 0;
}

}  // namespace

int json_line_of(std::string_view text, const JsonPath& path) { return line_of_tokens(text, path.tokens()); }

int json_line_of(std::string_view text, std::string_view pointer) {
  return line_of_tokens(text, pointer_tokens(pointer));
}

int json_line_at_byte(std::string_view text, size_t byte) {
  // Lines that hold text: a final newline does not start another line.
  int last = int(std::count(text.begin(), text.end(), '\n')) + (!text.empty() && text.back() != '\n' ? 1 : 0);
  int line = line_at(text, byte > 0 ? byte - 1 : 0);
  return std::max(1, std::min(line, last));
}

int json_line_of_number(std::string_view text, std::string_view literal) {
  size_t i = 0;
  while (i < text.size()) {
    char c = text[i];
    if (c == '"') {  // skip strings, escapes included
      for (++i; i < text.size() && text[i] != '"'; ++i)
        if (text[i] == '\\') ++i;
      ++i;
    } else if (c == '-' || (c >= '0' && c <= '9')) {
      size_t j = i;
      while (j < text.size() && std::string_view(",]} \t\r\n:").find(text[j]) == std::string_view::npos) ++j;
      if (text.substr(i, j - i) == literal) return line_at(text, i);
      i = j;
    } else {
      ++i;
    }
  }
  return 0;
}

bool json_find_duplicate_key(std::string_view text, JsonDuplicateKey* dup) {
  JsonWalker w(text, {}, true);
  w.run();
  if (w.duplicate_pos == SIZE_MAX) return false;
  dup->pointer = w.duplicate_pointer;
  dup->display = w.duplicate_display;
  dup->line = line_at(text, w.duplicate_pos);
  return true;
}

}  // namespace raystep
