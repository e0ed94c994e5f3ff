// A read-only JSON document in flat arrays (a "tape", as in simdjson), for validating readers of large files
// (traces of 100,000 events). It has the value semantics of nlohmann-json's DOM, which the readers were written
// against: the same numbers and number kinds (unsigned, integer, float), the last of duplicate keys wins, an
// object's members in key order; and parse() throws what nlohmann::json::parse throws on a bad text. nlohmann's
// SAX parser reads the text and fills the tape: no DOM of maps and vectors (a 100,000-event trace reads in a
// third of the time), and the parsing stays the library's. Arrays of many small elements (a trace's events) can
// be streamed instead of kept: each element is handed to a JsonStreamHandler as it is parsed, and a file is read
// through a small buffer, so a document of millions of events never lives in memory as text or as a tape.
#pragma once

#include <cstddef>
#include <cstdio>
#include <cstdint>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace raystep {

class JsonTape;

// A value of a JsonTape (the tape must outlive it). A default-constructed value is "absent" (find's miss).
class JsonValue {
 public:
  enum class Kind : uint8_t { null, boolean, number_integer, number_unsigned, number_float, string, array, object };

  JsonValue() = default;
  bool exists() const { return tape_ != nullptr; }
  Kind kind() const;

  bool is_null() const { return kind() == Kind::null; }
  bool is_boolean() const { return kind() == Kind::boolean; }
  bool is_number() const { return kind() >= Kind::number_integer && kind() <= Kind::number_float; }
  bool is_number_integer() const { return kind() == Kind::number_integer || kind() == Kind::number_unsigned; }
  bool is_string() const { return kind() == Kind::string; }
  bool is_array() const { return kind() == Kind::array; }
  bool is_object() const { return kind() == Kind::object; }

  // As nlohmann's get<T>() on the same value: a number converted by static_cast.
  bool get_bool() const;
  double get_double() const;
  int64_t get_int64() const;
  std::string_view get_string() const;
  bool operator==(std::string_view s) const { return is_string() && get_string() == s; }

  // Arrays: element count and element i (i < size(); not for a streamed array, whose elements went to the
  // handler).
  size_t size() const;
  bool is_streamed() const;
  size_t stream_number() const;  // a streamed array's number: 0, 1, ... in document order
  JsonValue operator[](size_t i) const;
  // Objects: the member named key (the last, if the key repeats), or an absent value (also for a non-object).
  JsonValue find(std::string_view key) const;
  bool contains(std::string_view key) const { return find(key).exists(); }
  // Objects: the members in key order, each key once (its last value), as nlohmann's object iteration; none
  // for a non-object.
  std::vector<std::pair<std::string_view, JsonValue>> members() const;

 private:
  friend class JsonTape;
  JsonValue(const JsonTape* tape, uint32_t id) : tape_(tape), id_(id) {}
  const JsonTape* tape_ = nullptr;
  uint32_t id_ = 0;
};

// What to stream: an array for which stream() says yes is not kept in the tape; each element is handed to
// element() as soon as it is parsed, as a value valid during the call only.
class JsonStreamHandler {
 public:
  virtual ~JsonStreamHandler() = default;
  // The array about to open, named by the member keys on the way to it with "[]" for each array it is in:
  // "rays[].events" for {"rays": [{"events": [...]}]}.
  virtual bool stream(std::string_view path) = 0;
  // Element `where.back()` of streamed array `array`; `where` holds the index of every array around it,
  // outermost first (rays[3].events[7]: {3, 7}).
  virtual void element(size_t array, const std::vector<size_t>& where, const JsonValue& value) = 0;
  // The streamed array has closed with `count` elements.
  virtual void end(size_t array, size_t count) = 0;
};

class JsonTape {
 public:
  // Parses the whole text as one JSON value (RFC 8259, whitespace around it). On a bad text throws exactly the
  // nlohmann::json::parse_error or out_of_range (number overflow) that nlohmann::json::parse(text) throws. With
  // a handler, the arrays it asks for are streamed to it; what it throws, parse throws.
  static JsonTape parse(std::string_view text, JsonStreamHandler* handler = nullptr);
  // The same from an open file, read through a buffer (the text is never held whole).
  static JsonTape parse_file(std::FILE* file, JsonStreamHandler* handler = nullptr);

  JsonValue root() const { return JsonValue(this, 0); }

 private:
  friend class JsonValue;
  friend struct JsonTapeBuilder;
  struct Node {
    uint64_t bits = 0;   // the number (int64, uint64 or double bits), the boolean, a string's arena offset,
                         // a container's first entry in children_
    uint32_t count = 0;  // a string's length; an array's elements; an object's members
    JsonValue::Kind kind = JsonValue::Kind::null;
    bool streamed = false;  // an array whose elements went to the handler; bits is its stream number
  };
  std::vector<Node> nodes_;           // in text order; keys are string nodes too
  std::vector<uint32_t> children_;    // arrays: element ids; objects: key id, value id per member
  std::string strings_;               // decoded strings, back to back
};

}  // namespace raystep
