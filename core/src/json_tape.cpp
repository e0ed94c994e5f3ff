#include "raystep/scene/json_tape.h"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace raystep {

using Kind = JsonValue::Kind;

// ---- building: the same steps for the fast scanner and for nlohmann's SAX events ----

struct JsonTapeBuilder {
  JsonTape tape;
  struct Open {
    uint32_t node;
    size_t mark;  // where its children start in `pending`
  };
  std::vector<Open> open;         // the containers not closed yet, outermost first
  std::vector<uint32_t> pending;  // the children of the open containers, innermost last

  uint32_t add(Kind kind, uint64_t bits, uint32_t count = 0) {
    if (tape.nodes_.size() >= UINT32_MAX) throw std::length_error("JSON document: too many values");
    uint32_t id = uint32_t(tape.nodes_.size());
    tape.nodes_.push_back(JsonTape::Node{bits, count, kind});
    if (!open.empty()) pending.push_back(id);
    return id;
  }
  void add_string(std::string_view s) {
    if (s.size() >= UINT32_MAX) throw std::length_error("JSON document: string too long");
    size_t at = tape.strings_.size();
    tape.strings_.append(s);
    add(Kind::string, at, uint32_t(s.size()));
  }
  void add_double(double d) {
    uint64_t bits;
    std::memcpy(&bits, &d, sizeof bits);
    add(Kind::number_float, bits);
  }
  void begin(Kind kind) {
    uint32_t id = add(kind, 0);
    open.push_back(Open{id, pending.size()});
  }
  void end() {
    Open o = open.back();
    open.pop_back();
    JsonTape::Node& n = tape.nodes_[o.node];
    size_t entries = pending.size() - o.mark;
    n.bits = tape.children_.size();
    n.count = uint32_t(n.kind == Kind::object ? entries / 2 : entries);
    tape.children_.insert(tape.children_.end(), pending.begin() + std::ptrdiff_t(o.mark), pending.end());
    pending.resize(o.mark);
  }
  bool in_object() const { return tape.nodes_[open.back().node].kind == Kind::object; }
};

namespace {

// nlohmann's SAX events into the builder; errors are thrown as json::parse would throw them.
struct SaxToTape {
  using json = nlohmann::json;
  JsonTapeBuilder* b;
  bool null() { return b->add(Kind::null, 0), true; }
  bool boolean(bool v) { return b->add(Kind::boolean, v), true; }
  bool number_integer(json::number_integer_t v) { return b->add(Kind::number_integer, uint64_t(v)), true; }
  bool number_unsigned(json::number_unsigned_t v) { return b->add(Kind::number_unsigned, v), true; }
  bool number_float(json::number_float_t v, const json::string_t&) { return b->add_double(v), true; }
  bool string(json::string_t& s) { return b->add_string(s), true; }
  bool binary(json::binary_t&) { return false; }  // not produced by the JSON text parser
  bool start_object(std::size_t) { return b->begin(Kind::object), true; }
  bool key(json::string_t& s) { return b->add_string(s), true; }
  bool end_object() { return b->end(), true; }
  bool start_array(std::size_t) { return b->begin(Kind::array), true; }
  bool end_array() { return b->end(), true; }
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& e) {
    throw e;
  }
};

// The fast path: a scanner for the plain JSON that raystep writes. It accepts a strict subset of JSON whose
// values are unambiguous (strings without \u escapes; numbers that convert without overflow, underflow or
// subnormals) and gives up on anything else, so that nlohmann's parser decides: the result is then the same on
// every text, and so is every error.
class FastScanner {
 public:
  FastScanner(std::string_view text, JsonTapeBuilder* b) : t_(text), b_(b) {}

  bool run() {
    enum class State { value, key, after };
    State state = State::value;
    skip_ws();
    for (;;) {
      switch (state) {
        case State::value: {
          if (p_ >= t_.size()) return false;
          char c = t_[p_];
          if (c == '{' || c == '[') {
            bool object = c == '{';
            b_->begin(object ? Kind::object : Kind::array);
            ++p_;
            skip_ws();
            if (p_ < t_.size() && t_[p_] == (object ? '}' : ']')) {
              ++p_;
              b_->end();
              state = State::after;
            } else {
              state = object ? State::key : State::value;
            }
            continue;
          }
          bool ok = c == '"' ? string() : c == '-' || (c >= '0' && c <= '9') ? number() : literal();
          if (!ok) return false;
          state = State::after;
          continue;
        }
        case State::key:
          if (p_ >= t_.size() || t_[p_] != '"' || !string()) return false;
          skip_ws();
          if (p_ >= t_.size() || t_[p_] != ':') return false;
          ++p_;
          skip_ws();
          state = State::value;
          continue;
        case State::after: {
          skip_ws();
          if (b_->open.empty()) return p_ == t_.size();
          if (p_ >= t_.size()) return false;
          bool object = b_->in_object();
          char c = t_[p_];
          if (c == ',') {
            ++p_;
            skip_ws();
            state = object ? State::key : State::value;
          } else if (c == (object ? '}' : ']')) {
            ++p_;
            b_->end();
          } else {
            return false;
          }
          continue;
        }
      }
    }
  }

 private:
  void skip_ws() {
    while (p_ < t_.size() && (t_[p_] == ' ' || t_[p_] == '\n' || t_[p_] == '\r' || t_[p_] == '\t')) ++p_;
  }

  // At '"': the string up to the closing quote, as nlohmann decodes it: UTF-8 checked by RFC 3629's table and
  // kept as it is, the two-character escapes decoded. \u escapes and control characters give up.
  bool string() {
    size_t start = ++p_;
    while (p_ < t_.size()) {  // the common case: nothing to decode, the bytes are the string
      unsigned char c = static_cast<unsigned char>(t_[p_]);
      if (c == '"') {
        b_->add_string(t_.substr(start, p_ - start));
        ++p_;
        return true;
      }
      if (c == '\\') break;
      if (c < 0x20) return false;
      size_t n = c < 0x80 ? 1 : utf8_length();
      if (n == 0) return false;
      p_ += n;
    }
    decoded_.assign(t_.data() + start, p_ - start);
    while (p_ < t_.size()) {
      unsigned char c = static_cast<unsigned char>(t_[p_]);
      if (c == '"') {
        b_->add_string(decoded_);
        ++p_;
        return true;
      }
      if (c == '\\') {
        if (p_ + 1 >= t_.size()) return false;
        char e;
        switch (t_[p_ + 1]) {
          case '"': e = '"'; break;
          case '\\': e = '\\'; break;
          case '/': e = '/'; break;
          case 'b': e = '\b'; break;
          case 'f': e = '\f'; break;
          case 'n': e = '\n'; break;
          case 'r': e = '\r'; break;
          case 't': e = '\t'; break;
          default: return false;  // \u (surrogates and all) and invalid escapes: nlohmann decides
        }
        decoded_ += e;
        p_ += 2;
        continue;
      }
      if (c < 0x20) return false;
      size_t n = c < 0x80 ? 1 : utf8_length();
      if (n == 0) return false;
      decoded_.append(t_.data() + p_, n);
      p_ += n;
    }
    return false;
  }

  // The length of the well-formed UTF-8 sequence at p_ (its first byte >= 0x80), 0 if it is not one.
  size_t utf8_length() const {
    auto in = [&](size_t i, unsigned lo, unsigned hi) {
      if (p_ + i >= t_.size()) return false;
      unsigned char c = static_cast<unsigned char>(t_[p_ + i]);
      return c >= lo && c <= hi;
    };
    unsigned char c = static_cast<unsigned char>(t_[p_]);
    if (c >= 0xC2 && c <= 0xDF) return in(1, 0x80, 0xBF) ? 2 : 0;
    if (c == 0xE0) return in(1, 0xA0, 0xBF) && in(2, 0x80, 0xBF) ? 3 : 0;
    if ((c >= 0xE1 && c <= 0xEC) || c == 0xEE || c == 0xEF) return in(1, 0x80, 0xBF) && in(2, 0x80, 0xBF) ? 3 : 0;
    if (c == 0xED) return in(1, 0x80, 0x9F) && in(2, 0x80, 0xBF) ? 3 : 0;  // no surrogates
    if (c == 0xF0) return in(1, 0x90, 0xBF) && in(2, 0x80, 0xBF) && in(3, 0x80, 0xBF) ? 4 : 0;
    if (c >= 0xF1 && c <= 0xF3) return in(1, 0x80, 0xBF) && in(2, 0x80, 0xBF) && in(3, 0x80, 0xBF) ? 4 : 0;
    if (c == 0xF4) return in(1, 0x80, 0x8F) && in(2, 0x80, 0xBF) && in(3, 0x80, 0xBF) ? 4 : 0;  // <= U+10FFFF
    return 0;
  }

  bool literal() {
    auto is = [&](std::string_view word) { return t_.substr(p_, word.size()) == word; };
    if (is("true")) b_->add(Kind::boolean, 1), p_ += 4;
    else if (is("false")) b_->add(Kind::boolean, 0), p_ += 5;
    else if (is("null")) b_->add(Kind::null, 0), p_ += 4;
    else return false;
    return true;
  }

  // -? (0 | [1-9][0-9]*) (. [0-9]+)? ([eE] [+-]? [0-9]+)?, as nlohmann reads it: an integer token is unsigned
  // (no sign) or integer (a sign), anything with a fraction or an exponent a double, correctly rounded.
  bool number() {
    size_t start = p_;
    auto digits = [&] {
      size_t from = p_;
      while (p_ < t_.size() && t_[p_] >= '0' && t_[p_] <= '9') ++p_;
      return p_ > from;
    };
    bool negative = t_[p_] == '-';
    if (negative) ++p_;
    if (p_ < t_.size() && t_[p_] == '0') ++p_;
    else if (!digits()) return false;
    bool integral = true;
    if (p_ < t_.size() && t_[p_] == '.') {
      ++p_;
      integral = false;
      if (!digits()) return false;
    }
    if (p_ < t_.size() && (t_[p_] == 'e' || t_[p_] == 'E')) {
      ++p_;
      integral = false;
      if (p_ < t_.size() && (t_[p_] == '+' || t_[p_] == '-')) ++p_;
      if (!digits()) return false;
    }
    const char* first = t_.data() + start;
    const char* last = t_.data() + p_;
    if (integral) {
      if (negative) {
        int64_t v;
        auto r = std::from_chars(first, last, v);
        if (r.ec != std::errc() || r.ptr != last) return false;  // out of int64: nlohmann makes it a double
        b_->add(Kind::number_integer, uint64_t(v));
      } else {
        uint64_t v;
        auto r = std::from_chars(first, last, v);
        if (r.ec != std::errc() || r.ptr != last) return false;
        b_->add(Kind::number_unsigned, v);
      }
      return true;
    }
    double d;
    auto r = std::from_chars(first, last, d);
    if (r.ec != std::errc() || r.ptr != last) return false;
    if (!std::isfinite(d) || (d != 0.0 && !std::isnormal(d))) return false;
    if (d == 0.0)  // a zero spelled with a nonzero digit underflowed
      for (const char* c = first; c < last && *c != 'e' && *c != 'E'; ++c)
        if (*c >= '1' && *c <= '9') return false;
    b_->add_double(d);
    return true;
  }

  std::string_view t_;
  JsonTapeBuilder* b_;
  size_t p_ = 0;
  std::string decoded_;  // a string with escapes, decoded
};

}  // namespace

JsonTape JsonTape::parse(std::string_view text) {
  JsonTape tape;
  if (parse_plain(text, &tape)) return tape;
  return parse_with_nlohmann(text);
}

bool JsonTape::parse_plain(std::string_view text, JsonTape* tape) {
  JsonTapeBuilder b;
  // A trace spends about 10 bytes of text per value.
  b.tape.nodes_.reserve(text.size() / 10);
  b.tape.children_.reserve(text.size() / 10);
  if (!FastScanner(text, &b).run()) return false;
  *tape = std::move(b.tape);
  return true;
}

JsonTape JsonTape::parse_with_nlohmann(std::string_view text) {
  JsonTapeBuilder b;
  SaxToTape sax{&b};
  nlohmann::json::sax_parse(text.begin(), text.end(), &sax);
  return std::move(b.tape);
}

// ---- reading ----

Kind JsonValue::kind() const { return tape_->nodes_[id_].kind; }

bool JsonValue::get_bool() const { return tape_->nodes_[id_].bits != 0; }

double JsonValue::get_double() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  switch (n.kind) {
    case Kind::number_integer: return double(int64_t(n.bits));
    case Kind::number_unsigned: return double(n.bits);
    case Kind::number_float: {
      double d;
      std::memcpy(&d, &n.bits, sizeof d);
      return d;
    }
    default: return 0.0;
  }
}

int64_t JsonValue::get_int64() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  if (n.kind == Kind::number_float) return int64_t(get_double());
  return int64_t(n.bits);
}

std::string_view JsonValue::get_string() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  return std::string_view(tape_->strings_).substr(n.bits, n.count);
}

size_t JsonValue::size() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  if (n.kind == Kind::array) return n.count;
  if (n.kind == Kind::object) return members().size();
  return n.kind == Kind::null ? 0 : 1;
}

JsonValue JsonValue::operator[](size_t i) const {
  return JsonValue(tape_, tape_->children_[tape_->nodes_[id_].bits + i]);
}

JsonValue JsonValue::find(std::string_view key) const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  const uint32_t* entries = tape_->children_.data() + n.bits;
  for (uint32_t m = n.count; m-- > 0;)  // from the end: the last of duplicate keys wins
    if (JsonValue(tape_, entries[2 * m]).get_string() == key) return JsonValue(tape_, entries[2 * m + 1]);
  return JsonValue();
}

std::vector<std::pair<std::string_view, JsonValue>> JsonValue::members() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  const uint32_t* entries = tape_->children_.data() + n.bits;
  std::vector<std::pair<std::string_view, JsonValue>> out;
  for (uint32_t m = 0; m < n.count; ++m)
    out.emplace_back(JsonValue(tape_, entries[2 * m]).get_string(), JsonValue(tape_, entries[2 * m + 1]));
  // Key order (std::map's: bytes compared as unsigned char), the last value of a repeated key.
  std::stable_sort(out.begin(), out.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
  std::vector<std::pair<std::string_view, JsonValue>> unique;
  for (size_t i = 0; i < out.size(); ++i)
    if (i + 1 == out.size() || out[i + 1].first != out[i].first) unique.push_back(out[i]);
  return unique;
}

}  // namespace raystep
