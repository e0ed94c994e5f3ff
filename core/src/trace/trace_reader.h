// Private to core/src/trace: the validating trace reader's tools, shared by its files (trace_read.cpp, the
// document and every walk; trace_read_events.cpp, the events, streamed as they are parsed;
// trace_read_pixel.cpp, the pixel section): JSON paths for messages, a reader that names the file, the line and
// the path of what is wrong, and the text an error's line is found in.
#pragma once

#include <algorithm>
#include <array>
#include <climits>
#include <vector>
#include <cmath>
#include <cstdint>
#include <string>
#include <string_view>

#include "raystep/geometry/numerics.h"
#include "raystep/scene/json_tape.h"
#include "raystep/trace/trace_file.h"
#include "raystep/util/error.h"
#include "trace_file_detail.h"

namespace raystep::detail {

// The document's text, for the line of an error: the text itself, or the file it was streamed from, read again
// only when an error is reported.
class TraceText {
 public:
  explicit TraceText(const std::string& text) : text_(&text), size_(text.size()) {}
  TraceText(std::string path, uint64_t size) : path_(std::move(path)), size_(size) {}
  const std::string& text() const;
  uint64_t size() const { return size_; }

 private:
  const std::string* text_ = nullptr;
  std::string path_;
  uint64_t size_ = 0;
  mutable std::string read_;
  mutable bool have_ = false;
};

// A count read from the file reserves at most what its text could hold (an element takes a few bytes of text
// and up to ~100 bytes of memory): a hostile "[0,0,0,...]" cannot make the reader ask for many times the size
// of the file before its first element is checked.
struct Capped {
  size_t limit = 0;
  size_t operator()(size_t n) const { return std::min(n, limit); }
};

// A JSON path in display form ("rays[0].events[3].prim"), spelled out only when an error names it: a chain
// of a root, member keys and array indices on the stack of the reader.
class Path {
 public:
  Path(const char* root) : root_(root) {}  // NOLINT: "scene", "trace", ... are paths
  // The parent must outlive the child: keep each level in a named local.
  Path key(std::string_view k) const { return Path(this, k, 0, false); }
  Path at(size_t index) const { return Path(this, {}, index, true); }
  std::string str() const {
    if (!parent_) return std::string(root_);
    std::string s = parent_->str();
    if (is_index_)
      s += "[" + std::to_string(index_) + "]";
    else
      (s += ".") += key_;
    return s;
  }

 private:
  Path(const Path* parent, std::string_view k, size_t index, bool is_index)
      : parent_(parent), key_(k), index_(index), is_index_(is_index) {}
  const Path* parent_ = nullptr;
  const char* root_ = nullptr;
  std::string_view key_;
  size_t index_ = 0;
  bool is_index_ = false;
};

using Value = JsonValue;

// Walks a parsed document with the JSON path of every value, so that errors say where.
class Reader {
 public:
  Reader(const std::string& name, const TraceText& text) : name_(name), text_(text) {}

  [[noreturn]] void fail(const Path& path, const std::string& what) const {
    std::string p = path.str();
    throw InputError(name_, line_of(p), p + ": " + what);
  }

  Value member(const Value& obj, const Path& path, const char* key) const {
    if (!obj.is_object()) fail(path, "expected an object");
    Value v = obj.find(key);
    if (!v.exists()) fail(path, std::string("missing \"") + key + "\"");
    return v;
  }
  float real(const Value& v, const Path& path) const {
    if (v.is_string()) {
      if (v == "inf") return kInfinity;
      if (v == "-inf") return -kInfinity;
    }
    if (!v.is_number())
      fail(path, v.is_null() ? "expected a number, found null (NaN?)" : "expected a number");
    double d = v.get_double();
    if (!std::isfinite(d) || std::fabs(d) > 3.4028234663852886e38) fail(path, "number out of float range");
    return float(d);
  }
  float real_at(const Value& obj, const Path& path, const char* key) const {
    return real(member(obj, path, key), path.key(key));
  }
  int64_t integer(const Value& v, const Path& path, int64_t lo, int64_t hi) const {
    if (!v.is_number_integer()) fail(path, "expected an integer");
    int64_t i = v.get_int64();
    if (i < lo || i > hi)
      fail(path,
           "value " + std::to_string(i) + " out of range " + std::to_string(lo) + ".." + std::to_string(hi));
    return i;
  }
  int64_t integer_at(const Value& obj, const Path& path, const char* key, int64_t lo, int64_t hi) const {
    return integer(member(obj, path, key), path.key(key), lo, hi);
  }
  std::string text_at(const Value& obj, const Path& path, const char* key) const {
    return std::string(view_at(obj, path, key));
  }
  std::string_view view_at(const Value& obj, const Path& path, const char* key) const {
    Value v = member(obj, path, key);
    if (!v.is_string()) fail(path.key(key), "expected a string");
    return v.get_string();
  }
  glm::vec3 vec_at(const Value& obj, const Path& path, const char* key) const {
    Value v = member(obj, path, key);
    Path p = path.key(key);
    if (!v.is_array() || v.size() != 3) fail(p, "expected an array of 3 numbers");
    return glm::vec3(real(v[0], p.at(0)), real(v[1], p.at(1)), real(v[2], p.at(2)));
  }
  Value array_at(const Value& obj, const Path& path, const char* key) const {
    Value v = member(obj, path, key);
    if (!v.is_array()) fail(path.key(key), "expected an array");
    return v;
  }

 private:
  // The line where the value at a path like rays[0].events[3].prim starts (only when reporting an error).
  int line_of(const std::string& path) const;

  std::string name_;
  const TraceText& text_;
};

// A path below a walk of a multi-walk document (walks[i].rays...), or at the top of a single trace (rays...).
inline Path sub(const Path* base, const char* key) {
  return base ? base->key(key) : Path(key);
}

int axis_index(const Reader& rd, const Value& v, const Path& path);  // "x", "y", "z" or null (-1)

// What an event's numbers may be: the walk's rules (its version, the grid's resolution, the node and primitive
// counts), or, while the events are streamed before the rest of the document is known, wide ones.
struct EventLimits {
  int64_t version = kTraceVersion;
  bool grid = false;
  std::array<int, 3> resolution{1, 1, 1};
  int64_t max_node = INT32_MAX, max_prim = INT32_MAX;
};
// Event i of a ray, from its JSON object at path ep.
Event read_event(const Reader& rd, const Value& je, const Path& ep, size_t i, const EventLimits& lim);
// The numbers read_event checked against wide limits, against the walk's own.
void check_events(const Reader& rd, const std::vector<Event>& events, const Path& events_path,
                  const EventLimits& lim);

// The events of every ray, taken from the JSON parser as it goes (rays[].events, walks[].rays[].events): the
// tape keeps each such array as a streamed array, whose number take() gives its events by.
class EventStreams final : public JsonStreamHandler {
 public:
  explicit EventStreams(const Reader& rd) : rd_(rd) {}
  bool stream(std::string_view path) override;
  void element(size_t array, const std::vector<size_t>& where, const JsonValue& value) override;
  void end(size_t array, size_t count) override;
  std::vector<Event> take(size_t array);

 private:
  static constexpr size_t kChunk = 1 << 16;
  struct Stream {
    std::vector<std::vector<Event>> chunks;  // while the array is parsed
    std::vector<Event> events;               // once it has closed
  };
  const Reader& rd_;
  std::vector<Stream> streams_;
};

// The pixel section (version 2).
TracePixel read_pixel(const Reader& rd, const JsonValue& jp, const Path& pp, Capped capped);

}  // namespace raystep::detail
