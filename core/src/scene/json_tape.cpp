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
    size_t mark;      // where its children start in `pending`
    size_t next = 0;  // arrays: the index of the next element
    std::string key;  // the member it is the value of ("" in an array, or the root)
  };
  std::vector<Open> open;         // the containers not closed yet, outermost first
  std::vector<uint32_t> pending;  // the children of the open containers, innermost last

  uint32_t add(Kind kind, uint64_t bits, uint32_t count = 0) {
    if (tape.nodes_.size() >= UINT32_MAX) throw std::length_error("JSON document: too many values");
    uint32_t id = uint32_t(tape.nodes_.size());
    tape.nodes_.push_back(JsonTape::Node{bits, count, kind, false});
    if (!open.empty()) {
      pending.push_back(id);
      ++open.back().next;
    }
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
    open.push_back(Open{id, pending.size(), 0, std::string()});
  }
  void begin(Kind kind, const std::string& key) {
    begin(kind);
    open.back().key = key;
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
  JsonTape::Node& node(uint32_t id) { return tape.nodes_[id]; }
  const JsonTape::Node& node(uint32_t id) const { return tape.nodes_[id]; }
  void clear() {  // for the next element, keeping the capacity
    tape.nodes_.clear();
    tape.children_.clear();
    tape.strings_.clear();
    open.clear();
    pending.clear();
  }
};

namespace {

// nlohmann's SAX events into the builder; errors are thrown as json::parse would throw them. Inside a
// streamed array every value goes to a second builder, one element at a time, and each finished element to
// the handler.
struct SaxToTape {
  using json = nlohmann::json;
  JsonTapeBuilder* b;
  JsonStreamHandler* handler;
  JsonTapeBuilder element;  // the streamed element being built
  bool streaming = false;   // the innermost open container of b is a streamed array
  size_t streams = 0;       // streamed arrays so far
  std::string key_;         // the last key of b's innermost object
  std::vector<size_t> where;

  SaxToTape(JsonTapeBuilder* builder, JsonStreamHandler* stream_handler)
      : b(builder), handler(stream_handler) {}

  JsonTapeBuilder& to() { return streaming ? element : *b; }
  // After a value of the streamed array's element: the element is done once its builder has nothing open.
  void value_done() {
    if (!streaming || !element.open.empty()) return;
    where.clear();
    for (const JsonTapeBuilder::Open& o : b->open)
      if (b->node(o.node).kind == Kind::array) where.push_back(o.next - 1);
    where.back() = b->open.back().next;  // the streamed array counts its elements itself
    handler->element(size_t(b->node(b->open.back().node).bits), where, element.tape.root());
    ++b->open.back().next;
    element.clear();
  }
  bool scalar_done() { return value_done(), true; }

  bool null() { return to().add(Kind::null, 0), scalar_done(); }
  bool boolean(bool v) { return to().add(Kind::boolean, v), scalar_done(); }
  bool number_integer(json::number_integer_t v) {
    return to().add(Kind::number_integer, uint64_t(v)), scalar_done();
  }
  bool number_unsigned(json::number_unsigned_t v) {
    return to().add(Kind::number_unsigned, v), scalar_done();
  }
  bool number_float(json::number_float_t v, const json::string_t&) {
    return to().add_double(v), scalar_done();
  }
  bool string(json::string_t& s) { return to().add_string(s), scalar_done(); }
  bool binary(json::binary_t&) { return false; }  // not produced by the JSON text parser
  bool start_object(std::size_t) {
    if (!streaming && handler && in_object()) return b->begin(Kind::object, key_), true;
    return to().begin(Kind::object), true;
  }
  bool in_object() const { return !b->open.empty() && b->node(b->open.back().node).kind == Kind::object; }
  // The path of an array opening as member key_ of the innermost object: "rays[].events".
  std::string path_here() const {
    std::string path;
    for (size_t i = 1; i < b->open.size(); ++i) {
      const JsonTapeBuilder::Open& o = b->open[i];
      if (!o.key.empty()) path += (path.empty() ? "" : ".") + o.key;
      if (b->node(o.node).kind == Kind::array) path += "[]";
    }
    return path + (path.empty() ? "" : ".") + key_;
  }
  bool key(json::string_t& s) {
    if (!streaming) key_ = s;
    return to().add_string(s), true;
  }
  bool end_object() { return to().end(), value_done(), true; }
  bool start_array(std::size_t) {
    if (!streaming && handler && in_object() && handler->stream(path_here())) {
      const uint32_t id = b->add(Kind::array, streams++);
      b->node(id).streamed = true;
      b->open.push_back(JsonTapeBuilder::Open{id, b->pending.size(), 0, key_});
      streaming = true;
      return true;
    }
    if (!streaming && handler && in_object()) return b->begin(Kind::array, key_), true;
    return to().begin(Kind::array), true;
  }
  bool end_array() {
    if (streaming && element.open.empty()) {  // the streamed array itself closes
      const JsonTapeBuilder::Open o = b->open.back();
      b->open.pop_back();
      auto& n = b->node(o.node);
      n.count = uint32_t(o.next);
      streaming = false;
      handler->end(size_t(n.bits), o.next);
      return true;
    }
    return to().end(), value_done(), true;
  }
  template <class Exception>
  bool parse_error(std::size_t, const std::string&, const Exception& e) {
    throw e;
  }
};

}  // namespace

JsonTape JsonTape::parse(std::string_view text, JsonStreamHandler* handler) {
  JsonTapeBuilder b;
  // A trace spends about 10 bytes of text per value (without streaming: with it, the rest is small).
  if (!handler) {
    b.tape.nodes_.reserve(text.size() / 10);
    b.tape.children_.reserve(text.size() / 10);
  }
  SaxToTape sax(&b, handler);
  nlohmann::json::sax_parse(text.begin(), text.end(), &sax);
  return std::move(b.tape);
}

JsonTape JsonTape::parse_file(std::FILE* file, JsonStreamHandler* handler) {
  JsonTapeBuilder b;
  SaxToTape sax(&b, handler);
  nlohmann::json::sax_parse(file, &sax);
  return std::move(b.tape);
}

// ---- reading ----

Kind JsonValue::kind() const {
  return tape_ ? tape_->nodes_[id_].kind : Kind::null;
}  // absent: null

bool JsonValue::get_bool() const {
  return tape_->nodes_[id_].bits != 0;
}

double JsonValue::get_double() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  switch (n.kind) {
    case Kind::number_integer:
      return double(int64_t(n.bits));
    case Kind::number_unsigned:
      return double(n.bits);
    case Kind::number_float: {
      double d;
      std::memcpy(&d, &n.bits, sizeof d);
      return d;
    }
    default:
      return 0.0;
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

bool JsonValue::is_streamed() const {
  return tape_ && tape_->nodes_[id_].streamed;
}

size_t JsonValue::stream_number() const {
  return size_t(tape_->nodes_[id_].bits);
}

size_t JsonValue::size() const {
  const JsonTape::Node& n = tape_->nodes_[id_];
  if (n.kind == Kind::array) return n.count;
  if (n.kind == Kind::object) return members().size();
  return n.kind == Kind::null ? 0 : 1;
}

JsonValue JsonValue::operator[](size_t i) const {
  if (tape_->nodes_[id_].streamed) return JsonValue();  // its elements went to the handler
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
