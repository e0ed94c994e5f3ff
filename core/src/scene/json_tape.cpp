#include "raystep/scene/json_tape.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include <nlohmann/json.hpp>

namespace raystep {

using Kind = JsonValue::Kind;

// ---- building, from nlohmann's SAX events ----

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

}  // namespace

JsonTape JsonTape::parse(std::string_view text) {
  JsonTapeBuilder b;
  // A trace spends about 10 bytes of text per value.
  b.tape.nodes_.reserve(text.size() / 10);
  b.tape.children_.reserve(text.size() / 10);
  SaxToTape sax{&b};
  nlohmann::json::sax_parse(text.begin(), text.end(), &sax);
  return std::move(b.tape);
}

// ---- reading ----

Kind JsonValue::kind() const { return tape_ ? tape_->nodes_[id_].kind : Kind::null; }  // absent: null

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
  if (!is_string()) return {};
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
  if (!is_object()) return JsonValue();
  const JsonTape::Node& n = tape_->nodes_[id_];
  const uint32_t* entries = tape_->children_.data() + n.bits;
  for (uint32_t m = n.count; m-- > 0;)  // from the end: the last of duplicate keys wins
    if (JsonValue(tape_, entries[2 * m]).get_string() == key) return JsonValue(tape_, entries[2 * m + 1]);
  return JsonValue();
}

std::vector<std::pair<std::string_view, JsonValue>> JsonValue::members() const {
  if (!is_object()) return {};
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
