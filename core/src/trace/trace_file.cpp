#include "raystep/trace/trace_file.h"

#include "raystep/render/pixel_filter.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <map>
#include <new>
#include <sstream>
#include <stdexcept>
#include <string_view>
#include <unordered_map>
#include <unordered_set>

#include <nlohmann/json.hpp>

#include "raystep/render/pixel_filter.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/json_locate.h"
#include "raystep/scene/json_tape.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"
#include "trace_file_detail.h"

namespace raystep {

using nlohmann::json;
using ordered = nlohmann::ordered_json;

// ---- names ----

namespace {
const char* const kEventNames[kEventTypeCount] = {
    "ray_begin", "cell",        "node",         "push",         "pop",     "leaf",
    "prim_test", "mailbox_hit", "hit_deferred", "hit_accepted", "ray_end", "sah_candidate",
    "split",     "leaf_made",   "box_test",     "skip"};
const char* const kReasonNames[kAcceptReasonCount] = {"inside_cell", "any_hit", "structure_done",
                                                      "next_node_beyond"};
const char* const kRayKinds[4] = {"primary", "shadow", "reflected", "refracted"};
const char* const kAxes[3] = {"x", "y", "z"};
const char* const kOutcomes[3] = {"agree", "depth_limit", "subdivided"};  // AdaptiveSquare::Outcome

// Names to enums without building strings: the index of name in names, or -1.
template <size_t N>
int name_index(std::string_view name, const char* const (&names)[N]) {
  for (size_t i = 0; i < N; ++i)
    if (name == names[i]) return int(i);
  return -1;
}

}  // namespace

const char* event_type_name(EventType type) {
  return kEventNames[int(type)];
}

bool parse_event_type(const std::string& name, EventType* type) {
  const int i = name_index(name, kEventNames);
  if (i >= 0) *type = EventType(i);
  return i >= 0;
}

const char* accept_reason_name(AcceptReason reason) {
  return kReasonNames[int(reason)];
}

bool parse_accept_reason(const std::string& name, AcceptReason* reason) {
  const int i = name_index(name, kReasonNames);
  if (i >= 0) *reason = AcceptReason(i);
  return i >= 0;
}

const char* ray_kind_name(RayKind kind) {
  return kRayKinds[int(kind)];
}

bool parse_leaf_reason(const std::string& name, LeafReason* reason) {
  for (LeafReason r : {LeafReason::few_primitives, LeafReason::max_depth, LeafReason::no_cheaper_split,
                       LeafReason::no_candidate, LeafReason::budget})
    if (name == leaf_reason_name(r)) {
      *reason = r;
      return true;
    }
  return false;
}

std::string file_content_hash(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot read the file");
  uint64_t h = 1469598103934665603ull;
  char buf[1 << 16];
  while (in) {
    in.read(buf, sizeof buf);
    for (std::streamsize i = 0; i < in.gcount(); ++i) {
      h ^= uint8_t(buf[i]);
      h *= 1099511628211ull;
    }
  }
  char hex[17];
  std::snprintf(hex, sizeof hex, "%016llx", static_cast<unsigned long long>(h));
  return std::string("fnv1a64:") + hex;
}

// ---- writing ----

namespace {

// JSON has no infinity: +inf and -inf are written as the strings "inf" and "-inf".
ordered number(float v) {
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return double(v);
}
ordered vec(const glm::vec3& v) {
  return ordered::array({number(v.x), number(v.y), number(v.z)});
}

// The rows of one of the file's arrays, one a line ("\n   row,\n   row"): the caller opens and closes it.
template <class T, class ToJson>
void write_rows(std::ostream& out, const std::vector<T>& items, ToJson to_json) {
  for (size_t i = 0; i < items.size(); ++i)
    out << (i ? ",\n   " : "\n   ") << ordered(to_json(items[i])).dump();
}

ordered event_to_json(const Event& e) {
  ordered j;
  j["seq"] = e.seq;
  j["type"] = event_type_name(e.type);
  switch (e.type) {
    case EventType::cell:
      j["cell"] = {e.cell[0], e.cell[1], e.cell[2]};
      j["t_enter"] = number(e.t_enter);
      j["t_exit"] = number(e.t_exit);
      j["t_max"] = vec(e.t_max);
      j["t_delta"] = vec(e.t_delta);
      j["next_axis"] = e.next_axis < 0 ? ordered(nullptr) : ordered(kAxes[e.next_axis]);
      break;
    case EventType::node:
    case EventType::push:
    case EventType::pop:
    case EventType::leaf:
    case EventType::skip:
      j["node"] = e.node;
      j["depth"] = e.depth;
      j["t_min"] = number(e.t_min_node);
      j["t_max"] = number(e.t_max_node);
      break;
    case EventType::box_test:
      j["parent"] = e.parent;
      j["node"] = e.node;
      j["depth"] = e.depth;
      j["hit"] = e.hit;
      if (e.hit) {
        j["t_near"] = number(e.t_min_node);
        j["t_far"] = number(e.t_max_node);
      }
      break;
    case EventType::prim_test:
      j["prim"] = e.prim;
      j["hit"] = e.hit;
      if (e.hit) j["t"] = number(e.t);
      break;
    case EventType::mailbox_hit:
      j["prim"] = e.prim;
      break;
    case EventType::hit_deferred:
      j["prim"] = e.prim;
      j["t"] = number(e.t);
      j["t_exit"] = number(e.t_exit);
      break;
    case EventType::hit_accepted:
      j["prim"] = e.prim;
      j["t"] = number(e.t);
      j["reason"] = accept_reason_name(e.reason);
      break;
    case EventType::ray_end:
      j["prim"] = e.prim;
      j["t"] = number(e.t);
      break;
    default:
      break;
  }
  return j;
}

RayCounters count_events(const std::vector<Event>& events) {
  RayCounters c;
  for (const Event& e : events) {
    switch (e.type) {
      case EventType::cell:
        ++c.cells;
        break;
      case EventType::node:
        ++c.nodes;
        break;
      case EventType::push:
        ++c.pushes;
        break;
      case EventType::pop:
        ++c.pops;
        break;
      case EventType::prim_test:
        ++c.prim_tests;
        c.prim_hits += e.hit;
        break;
      case EventType::mailbox_hit:
        ++c.mailbox_hits;
        break;
      case EventType::box_test:
        ++c.box_tests;
        break;
      default:
        break;
    }
  }
  return c;
}

// The pixel section: its head on one line, then one sample and one square per line.
std::string pixel_json(const TracePixel& p) {
  const PixelSampling& s = p.sampling;
  ordered head;
  head["x"] = s.x;
  head["y"] = s.y;
  head["width"] = p.width;
  head["height"] = p.height;
  head["seed"] = p.seed;
  head["aa"] = to_string(s.aa);
  head["value"] = vec(s.value);
  if (p.exact) head["exact"] = vec(*p.exact);
  const bool tent = s.aa.filter == AntiAliasing::Filter::tent;
  std::string h = head.dump();
  h.pop_back();  // reopen the object to append the samples and squares, one per line
  std::ostringstream out;
  out << h << ",\n  \"samples\": [";
  write_rows(out, s.samples, [&](const PixelSample& ps) {
    ordered j;
    j["px"] = number(ps.px);
    j["py"] = number(ps.py);
    j["colour"] = vec(ps.colour);
    if (ps.stratum[0] >= 0) j["stratum"] = {ps.stratum[0], ps.stratum[1]};
    if (ps.lattice[0] >= 0) j["lattice"] = {ps.lattice[0], ps.lattice[1]};
    if (tent) j["weight"] = number(ps.weight);
    return j;
  });
  out << (s.samples.empty() ? "],\n" : "\n  ],\n");
  if (tent) {  // the neighbours' samples the tent reaches, and the pixel's own box-filtered value
    out << "  \"box_value\": " << vec(s.box_value).dump() << ",\n  \"neighbours\": [";
    write_rows(out, s.neighbours, [&](const PixelSample& ps) {
      ordered j;
      j["px"] = number(ps.px);
      j["py"] = number(ps.py);
      j["colour"] = vec(ps.colour);
      j["weight"] = number(ps.weight);
      return j;
    });
    out << (s.neighbours.empty() ? "],\n" : "\n  ],\n");
  }
  out << "  \"squares\": [";
  write_rows(out, s.squares, [&](const AdaptiveSquare& q) {
    ordered j;
    j["parent"] = q.parent;
    j["depth"] = q.depth;
    j["i0"] = q.i0;
    j["j0"] = q.j0;
    j["size"] = q.size;
    j["samples"] = {q.samples[0], q.samples[1], q.samples[2], q.samples[3], q.samples[4]};
    j["new_samples"] = q.new_samples;
    j["contrast"] = vec(q.contrast);
    j["outcome"] = kOutcomes[int(q.outcome)];
    j["children"] = {q.children[0], q.children[1], q.children[2], q.children[3]};
    j["value"] = vec(q.value);
    return j;
  });
  out << (s.squares.empty() ? "]}" : "\n  ]}");
  return out.str();
}

}  // namespace

std::string build_event_json(const TraceBuildEvent& b, size_t seq) {
  ordered j;
  j["seq"] = seq;
  j["type"] = event_type_name(b.type);
  j["node"] = b.node;
  if (b.type == EventType::sah_candidate) {
    const SahCandidate& c = b.candidate;
    j["axis"] = kAxes[c.axis];
    j["position"] = number(c.position);
    j["n_below"] = c.n_below;
    j["n_above"] = c.n_above;
    j["n_planar"] = c.n_planar;
    j["area_below"] = number(c.area_below);
    j["area_above"] = number(c.area_above);
    j["area_node"] = number(c.area_node);
    j["cost"] = number(c.cost);
    j["planar_side"] = c.planar_below ? "below" : "above";
    return j.dump();
  }
  j["depth"] = b.depth;
  j["min"] = vec(b.box.lo);
  j["max"] = vec(b.box.hi);
  j["prims"] = b.prims;
  j["leaf_cost"] = number(b.leaf_cost);
  if (b.type == EventType::split) {
    j["axis"] = kAxes[b.axis];
    j["position"] = number(b.position);
    j["cost"] = number(b.cost);
  } else {
    j["reason"] = leaf_reason_name(b.reason);
  }
  return j.dump();
}

std::string trace_to_json(const Trace& t) {
  return trace_json_opening(t) + trace_json_rest(t);
}

std::string trace_json_opening(const Trace& t) {
  std::ostringstream out;
  out << "{\n";
  out << " \"format\": " << ordered(kTraceFormat).dump() << ",\n";
  out << " \"version\": " << kTraceVersion << ",\n";
  out << " \"scene\": "
      << ordered({{"path", t.scene_path}, {"hash", t.scene_hash}, {"primitives", t.scene_primitives}}).dump()
      << ",\n";
  return out.str();
}

// Laid out for people: one event, cell or primitive per line, small objects on one line.
std::string trace_json_rest(const Trace& t) {
  std::ostringstream out;
  if (!t.build.empty()) {
    out << " \"build\": [";
    for (size_t i = 0; i < t.build.size(); ++i)
      out << (i ? ",\n  " : "\n  ") << build_event_json(t.build[i], i);
    out << "\n ],\n";
  }
  ordered s;
  s["kind"] = t.structure.kind;
  s["bounds_min"] = vec(t.structure.bounds.lo);
  s["bounds_max"] = vec(t.structure.bounds.hi);
  if (t.structure.kind == "grid")
    s["resolution"] = {t.structure.resolution[0], t.structure.resolution[1], t.structure.resolution[2]};
  for (const TraceParam& p : t.structure.params) {
    bool integral = !p.is_text && p.number == std::floor(p.number) && std::fabs(p.number) < 1e15;
    s[p.key] = p.is_text ? ordered(p.text) : integral ? ordered(int64_t(p.number)) : ordered(p.number);
  }
  out << " \"structure\": " << s.dump() << ",\n";
  if (t.pixel) out << " \"pixel\": " << pixel_json(*t.pixel) << ",\n";

  out << " \"rays\": [";
  for (size_t r = 0; r < t.rays.size(); ++r) {
    const TracedRay& tr = t.rays[r];
    ordered head;
    head["origin"] = vec(tr.ray.origin);
    head["direction"] = vec(tr.ray.direction);
    head["tmin"] = number(tr.ray.tmin);
    head["tmax"] = number(tr.ray.tmax);
    head["kind"] = ray_kind_name(tr.kind);
    head["depth"] = tr.depth;
    if (tr.has_pixel) head["pixel"] = {tr.pixel[0], tr.pixel[1]};
    if (tr.sample >= 0) head["sample"] = tr.sample;
    RayCounters c = count_events(tr.events);
    head["counters"] = {{"cells", c.cells},
                        {"nodes", c.nodes},
                        {"prim_tests", c.prim_tests},
                        {"prim_hits", c.prim_hits},
                        {"mailbox_hits", c.mailbox_hits},
                        {"pushes", c.pushes},
                        {"pops", c.pops},
                        {"box_tests", c.box_tests}};
    std::string h = head.dump();
    h.pop_back();  // reopen the object to append the events, one per line
    out << (r ? ",\n  " : "\n  ") << h << ",\n   \"events\": [";
    for (size_t i = 0; i < tr.events.size(); ++i)
      out << (i ? ",\n    " : "\n    ") << event_to_json(tr.events[i]).dump();
    out << "\n   ]}";
  }
  out << (t.rays.empty() ? "],\n" : "\n ],\n");

  out << " \"geometry\": {\n  \"cells\": [";
  write_rows(out, t.cells, [&](const TraceCell& c) {
    ordered jc = {
        {"cell", {c.cell[0], c.cell[1], c.cell[2]}}, {"min", vec(c.box.lo)}, {"max", vec(c.box.hi)}};
    return jc;
  });
  out << (t.cells.empty() ? "],\n" : "\n  ],\n");
  // A tree's trace always lists its nodes, [] for a ray that misses the root's box, so readers find the key.
  if (!t.nodes.empty() || t.structure.kind != "grid") {
    out << "  \"nodes\": [";
    write_rows(out, t.nodes, [&](const TraceNode& n) {
      ordered jn;
      jn["id"] = n.id;
      jn["parent"] = n.parent;
      jn["depth"] = n.depth;
      jn["min"] = vec(n.box.lo);
      jn["max"] = vec(n.box.hi);
      jn["leaf"] = n.leaf;
      if (n.leaf) {
        jn["prims"] = n.prims;
      } else if (n.has_plane) {  // a BSP node (version 4): its general plane
        jn["normal"] = vec(n.normal);
        jn["offset"] = number(n.offset);
      } else if (!n.children.empty()) {  // a BVH node: its children; its axis, if the builder split on one
        jn["axis"] = n.axis >= 0 && n.axis < 3 ? ordered(kAxes[n.axis]) : ordered(nullptr);
        jn["children"] = n.children;
      } else {
        jn["axis"] = kAxes[n.axis];
        jn["split"] = number(n.split);
      }
      return jn;
    });
    out << (t.nodes.empty() ? "],\n" : "\n  ],\n");
  }
  out << "  \"primitives\": [";
  write_rows(out, t.primitives, [&](const TracePrimitive& p) {
    ordered jp;
    jp["id"] = p.id;
    if (p.type == PrimType::triangle) {
      jp["type"] = "triangle";
      jp["vertices"] = {vec(p.v[0]), vec(p.v[1]), vec(p.v[2])};
    } else {
      jp["type"] = "sphere";
      jp["center"] = vec(p.v[0]);
      jp["radius"] = number(p.radius);
    }
    return jp;
  });
  out << (t.primitives.empty() ? "]\n" : "\n  ]\n");
  out << " }\n}\n";
  return out.str();
}

void write_trace_json(const std::string& path, const Trace& trace) {
  std::string text = trace_to_json(trace);
  write_file_atomically(path, [&](std::ostream& out) { out << text; });
}

namespace detail {

const char* const kTraceCsvHeader =
    "ray,seq,type,i,j,k,t_enter,t_exit,t_max_x,t_max_y,t_max_z,t_delta_x,t_delta_y,t_delta_z,next_axis,"
    "node,depth,t_min,t_max,prim,hit,t,reason,sample,parent\n";

void write_trace_csv_rows(std::ostream& out, const Trace& t, const std::string& prefix) {
  enum Col {
    ray,
    seq,
    type,
    i,
    j,
    k,
    t_enter,
    t_exit,
    t_max_x,
    t_max_y,
    t_max_z,
    t_delta_x,
    t_delta_y,
    t_delta_z,
    next_axis,
    node,
    depth,
    t_min,
    t_max,
    prim,
    hit,
    t_hit,
    reason,
    sample,
    parent,
    kColumns
  };
  // Columns are only ever appended, so that scripts reading by position still work: sample in version 2,
  // parent (box_test's) in version 3.
  auto num = [](float v) {
    if (std::isinf(v)) return std::string(v > 0 ? "inf" : "-inf");
    char buf[32];
    std::snprintf(buf, sizeof buf, "%.9g", double(v));
    return std::string(buf);
  };
  {
    for (size_t r = 0; r < t.rays.size(); ++r) {
      for (const Event& e : t.rays[r].events) {
        std::string row[kColumns];
        row[ray] = std::to_string(r);
        row[seq] = std::to_string(e.seq);
        row[type] = event_type_name(e.type);
        if (t.rays[r].sample >= 0) row[sample] = std::to_string(t.rays[r].sample);
        switch (e.type) {
          case EventType::cell:
            for (int a = 0; a < 3; ++a) {
              row[i + a] = std::to_string(e.cell[a]);
              row[t_max_x + a] = num(e.t_max[a]);
              row[t_delta_x + a] = num(e.t_delta[a]);
            }
            row[t_enter] = num(e.t_enter);
            row[t_exit] = num(e.t_exit);
            if (e.next_axis >= 0) row[next_axis] = kAxes[e.next_axis];
            break;
          case EventType::node:
          case EventType::push:
          case EventType::pop:
          case EventType::leaf:
          case EventType::skip:
            row[node] = std::to_string(e.node);
            row[depth] = std::to_string(e.depth);
            row[t_min] = num(e.t_min_node);
            row[t_max] = num(e.t_max_node);
            break;
          case EventType::box_test:  // the child's box: [t_near, t_far] in t_min, t_max on a hit
            row[parent] = std::to_string(e.parent);
            row[node] = std::to_string(e.node);
            row[depth] = std::to_string(e.depth);
            row[hit] = e.hit ? "1" : "0";
            if (e.hit) {
              row[t_min] = num(e.t_min_node);
              row[t_max] = num(e.t_max_node);
            }
            break;
          case EventType::prim_test:
            row[prim] = std::to_string(e.prim);
            row[hit] = e.hit ? "1" : "0";
            if (e.hit) row[t_hit] = num(e.t);
            break;
          case EventType::mailbox_hit:
            row[prim] = std::to_string(e.prim);
            break;
          case EventType::hit_deferred:
            row[prim] = std::to_string(e.prim);
            row[t_hit] = num(e.t);
            row[t_exit] = num(e.t_exit);
            break;
          case EventType::hit_accepted:
            row[prim] = std::to_string(e.prim);
            row[t_hit] = num(e.t);
            row[reason] = accept_reason_name(e.reason);
            break;
          case EventType::ray_end:
            row[prim] = std::to_string(e.prim);
            row[t_hit] = num(e.t);
            break;
          default:
            break;
        }
        out << prefix;
        for (int c = 0; c < kColumns; ++c) out << (c ? "," : "") << row[c];
        out << '\n';
      }
    }
  }
}

}  // namespace detail

void write_trace_csv(const std::string& path, const Trace& t) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << detail::kTraceCsvHeader;
    detail::write_trace_csv_rows(out, t, "");
  });
}

// ---- reading ----

namespace {

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
  Reader(const std::string& name, const std::string& text) : name_(name), text_(text) {}

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
  const std::string& text_;
};

// The line of a value named in display form ("rays[0].events[3].prim"): converted to a JSON pointer.
int Reader::line_of(const std::string& path) const {
  std::string pointer;
  std::string rest = path.rfind("trace", 0) == 0 ? path.substr(5) : path;
  for (char c : rest) {
    if (c == '.' || c == '[')
      pointer += '/';
    else if (c != ']')
      pointer += c;
  }
  if (!pointer.empty() && pointer[0] != '/') pointer.insert(pointer.begin(), '/');
  return json_line_of(text_, pointer);
}

// The pixel section (version 2): every index in range, every sample where its pattern puts it, the adaptive
// tree well formed (parents before children, each child naming its parent).
template <class Capped>
TracePixel read_pixel(const Reader& rd, const Value& jp, const Path& pp, Capped capped) {
  TracePixel p;
  PixelSampling& s = p.sampling;
  constexpr int64_t kMaxSide = 1 << 15;  // render_image's limit
  p.width = int(rd.integer_at(jp, pp, "width", 1, kMaxSide));
  p.height = int(rd.integer_at(jp, pp, "height", 1, kMaxSide));
  s.x = int(rd.integer_at(jp, pp, "x", 0, p.width - 1));
  s.y = int(rd.integer_at(jp, pp, "y", 0, p.height - 1));
  const Value seed = rd.member(jp, pp, "seed");
  if (!seed.is_number_integer() || (seed.kind() != Value::Kind::number_unsigned && seed.get_int64() < 0))
    rd.fail(pp.key("seed"), "expected an integer in 0..2^64-1");
  p.seed = uint64_t(seed.get_int64());
  const std::string spec = rd.text_at(jp, pp, "aa");
  try {
    s.aa = parse_antialiasing(spec);
  } catch (const InputError& e) {
    rd.fail(pp.key("aa"), e.detail());
  }
  s.value = rd.vec_at(jp, pp, "value");
  if (jp.contains("exact")) p.exact = rd.vec_at(jp, pp, "exact");

  // Samples: as many as the pattern casts, each inside the pixel, labelled with its stratum or lattice point.
  using Mode = AntiAliasing::Mode;
  const Value samples = rd.array_at(jp, pp, "samples");
  const Path sp = pp.key("samples");
  const size_t count = samples.size();
  const bool stratified = s.aa.mode == Mode::regular || s.aa.mode == Mode::jitter;
  const bool adaptive = s.aa.mode == Mode::adaptive;
  const size_t expected = stratified                  ? size_t(s.aa.k) * size_t(s.aa.k)
                          : s.aa.mode == Mode::random ? size_t(s.aa.k)
                          : s.aa.mode == Mode::none   ? 1
                                                      : 0;
  if (adaptive ? count < 5 || count > max_samples_per_pixel(s.aa) : count != expected)
    rd.fail(sp,
            std::to_string(count) + " samples, but " + spec + " casts " +
                (adaptive ? "5.." + std::to_string(max_samples_per_pixel(s.aa)) : std::to_string(expected)));
  const int n = 2 << s.aa.max_depth;  // adaptive: lattice steps per pixel side
  auto pair = [&](const Value& v, const Path& path, int64_t hi) {
    if (!v.is_array() || v.size() != 2) rd.fail(path, "expected [i, j]");
    return std::array<int, 2>{int(rd.integer(v[0], path.at(0), 0, hi)),
                              int(rd.integer(v[1], path.at(1), 0, hi))};
  };
  s.samples.reserve(capped(count));
  for (size_t i = 0; i < count; ++i) {
    const Path ip = sp.at(i);
    const Value js = samples[i];
    PixelSample ps;
    ps.px = rd.real_at(js, ip, "px");
    ps.py = rd.real_at(js, ip, "py");
    if (!(ps.px >= float(s.x) && ps.px <= float(s.x + 1)))
      rd.fail(ip.key("px"), "outside pixel " + std::to_string(s.x) + "'s span [x, x+1]");
    if (!(ps.py >= float(s.y) && ps.py <= float(s.y + 1)))
      rd.fail(ip.key("py"), "outside pixel row " + std::to_string(s.y) + "'s span [y, y+1]");
    ps.colour = rd.vec_at(js, ip, "colour");
    if (stratified) {
      const std::array<int, 2> c = pair(rd.member(js, ip, "stratum"), ip.key("stratum"), s.aa.k - 1);
      ps.stratum[0] = c[0];
      ps.stratum[1] = c[1];
    } else if (js.contains("stratum")) {
      rd.fail(ip.key("stratum"), "only regular and jittered samples have a stratum");
    }
    if (adaptive) {
      const std::array<int, 2> c = pair(rd.member(js, ip, "lattice"), ip.key("lattice"), n);
      ps.lattice[0] = c[0];
      ps.lattice[1] = c[1];
    } else if (js.contains("lattice")) {
      rd.fail(ip.key("lattice"), "only adaptive samples lie on the lattice");
    }
    s.samples.push_back(ps);
  }

  // The tent filter: each sample's weight from its place, and the neighbours' samples it reaches.
  const bool tent = s.aa.filter == AntiAliasing::Filter::tent;
  const float cx = float(s.x) + 0.5f, cy = float(s.y) + 0.5f;
  auto check_weight = [&](PixelSample& ps, const Value& js, const Path& ip) {
    ps.weight = tent_weight(ps.px - cx, ps.py - cy);
    if (js.contains("weight") && !(std::fabs(rd.real_at(js, ip, "weight") - ps.weight) <= 1e-6f))
      rd.fail(ip.key("weight"), "not the tent's weight (1 - |dx|)(1 - |dy|) at the sample, " +
                                    std::to_string(ps.weight));
  };
  if (tent)
    for (size_t i = 0; i < count; ++i) check_weight(s.samples[i], samples[i], sp.at(i));
  s.box_value = tent && jp.contains("box_value") ? rd.vec_at(jp, pp, "box_value") : s.value;
  if (jp.contains("neighbours") && !tent) rd.fail(pp.key("neighbours"), "only the tent filter has neighbours");
  if (tent) {
    const Value nb = rd.array_at(jp, pp, "neighbours");
    const Path np = pp.key("neighbours");
    if (nb.size() > 8 * expected) rd.fail(np, std::to_string(nb.size()) + " neighbours' samples, but eight "
                                                  "neighbours of " + spec + " cast at most " +
                                                  std::to_string(8 * expected));
    s.neighbours.reserve(capped(nb.size()));
    for (size_t i = 0; i < nb.size(); ++i) {
      const Path ip = np.at(i);
      const Value js = nb[i];
      PixelSample ps;
      ps.px = rd.real_at(js, ip, "px");
      ps.py = rd.real_at(js, ip, "py");
      ps.colour = rd.vec_at(js, ip, "colour");
      const bool inside = ps.px >= float(s.x) && ps.px < float(s.x + 1) && ps.py >= float(s.y) &&
                          ps.py < float(s.y + 1);
      if (inside || !(tent_weight(ps.px - cx, ps.py - cy) > 0.f))
        rd.fail(ip, "not a neighbour's sample within the tent's reach (outside the pixel, less than one "
                    "pixel from its centre on each axis)");
      check_weight(ps, js, ip);
      s.neighbours.push_back(ps);
    }
  }

  // Adaptive squares, depth first.
  const Value squares = jp.contains("squares") ? rd.array_at(jp, pp, "squares") : Value();
  const Path qp = pp.key("squares");
  const size_t nsq = squares.exists() ? squares.size() : 0;
  if (adaptive && nsq == 0) rd.fail(qp, "adaptive sampling has at least the whole pixel's square");
  if (!adaptive && nsq > 0) rd.fail(qp, "only adaptive sampling has squares");
  s.squares.reserve(capped(nsq));
  for (size_t i = 0; i < nsq; ++i) {
    const Path ip = qp.at(i);
    const Value jq = squares[i];
    AdaptiveSquare q;
    q.parent = int(rd.integer_at(jq, ip, "parent", i == 0 ? -1 : 0, int64_t(i) - 1));
    q.depth = int(rd.integer_at(jq, ip, "depth", 0, s.aa.max_depth));
    q.i0 = int(rd.integer_at(jq, ip, "i0", 0, n));
    q.j0 = int(rd.integer_at(jq, ip, "j0", 0, n));
    q.size = int(rd.integer_at(jq, ip, "size", 1, n));
    const Value idx = rd.array_at(jq, ip, "samples");
    const Path xp = ip.key("samples");
    if (idx.size() != 5) rd.fail(xp, "expected the 5 sample indices (4 corners, then the centre)");
    for (int k = 0; k < 5; ++k) q.samples[k] = int(rd.integer(idx[k], xp.at(k), 0, int64_t(count) - 1));
    q.new_samples = int(rd.integer_at(jq, ip, "new_samples", 0, 5));
    q.contrast = rd.vec_at(jq, ip, "contrast");
    const std::string_view outcome = rd.view_at(jq, ip, "outcome");
    const int o = name_index(outcome, kOutcomes);
    if (o < 0)
      rd.fail(ip.key("outcome"),
              "unknown outcome \"" + std::string(outcome) + "\" (agree, depth_limit, subdivided)");
    q.outcome = AdaptiveSquare::Outcome(o);
    const Value ch = rd.array_at(jq, ip, "children");
    const Path cp = ip.key("children");
    if (ch.size() != 4) rd.fail(cp, "expected 4 children (-1 for none)");
    const bool split = q.outcome == AdaptiveSquare::Outcome::subdivided;
    for (int k = 0; k < 4; ++k)
      q.children[k] = int(split ? rd.integer(ch[k], cp.at(k), int64_t(i) + 1, int64_t(nsq) - 1)
                                : rd.integer(ch[k], cp.at(k), -1, -1));
    q.value = rd.vec_at(jq, ip, "value");
    if (q.parent >= 0) {
      const AdaptiveSquare& parent = s.squares[size_t(q.parent)];
      if (parent.outcome != AdaptiveSquare::Outcome::subdivided ||
          std::find(parent.children, parent.children + 4, int(i)) == parent.children + 4)
        rd.fail(ip.key("parent"), "square " + std::to_string(q.parent) + " does not list it as a child");
    }
    s.squares.push_back(q);
  }
  for (size_t i = 0; i < s.squares.size(); ++i)
    for (int c : s.squares[i].children)
      if (c >= 0 && s.squares[size_t(c)].parent != int(i))
        rd.fail(qp.at(size_t(c)).key("parent"), "expected " + std::to_string(i) + ", the square listing it");
  return p;
}

}  // namespace

namespace {

// A path below a walk of a multi-walk document (walks[i].rays...), or at the top of a single trace (rays...).
Path sub(const Path* base, const char* key) {
  return base ? base->key(key) : Path(key);
}

// The document's JSON, or an InputError saying where it is malformed or that it is truncated.
JsonTape parse_tape(const std::string& text, const std::string& name) {
  try {
    return JsonTape::parse(text);
  } catch (const std::length_error& e) {
    throw InputError(name, 0, std::string("too large to read: ") + e.what());
  } catch (const std::bad_alloc&) {
    throw InputError(name, 0, "not enough memory to read it");
  } catch (const json::parse_error& e) {
    int line = json_line_at_byte(text, e.byte);
    bool truncated = e.byte >= text.size();
    throw InputError(name, line,
                     truncated ? "the trace is truncated (unexpected end of the file)"
                               : std::string("malformed JSON: ") + e.what());
  } catch (const json::out_of_range& e) {
    // "number overflow parsing '1e400'" comes without a position: the line of that literal.
    std::string what = e.what();
    size_t q = what.find('\'');
    std::string literal = q == std::string::npos ? "" : what.substr(q + 1, what.rfind('\'') - q - 1);
    throw InputError(name, json_line_of_number(text, literal), "malformed JSON: " + what);
  } catch (const json::exception& e) {
    throw InputError(name, 0, std::string("malformed JSON: ") + e.what());
  }
}

// Everything of a trace below its scene: the build events, structure, pixel, rays and geometry, read from doc
// (the document itself, or one walk of a multi-walk document at base) with the rules of this version.
template <class Capped>
void read_walk(const Reader& rd, const Value& doc, const Path& root, const Path* base, int64_t version,
               Trace& t, Capped capped) {
  const Value st = rd.member(doc, root, "structure");
  const Path sp = sub(base, "structure");
  t.structure.kind = rd.text_at(st, sp, "kind");
  t.structure.bounds.lo = rd.vec_at(st, sp, "bounds_min");
  t.structure.bounds.hi = rd.vec_at(st, sp, "bounds_max");
  bool grid = t.structure.kind == "grid";
  if (grid) {
    const Value res = rd.array_at(st, sp, "resolution");
    const Path rp = sp.key("resolution");
    if (res.size() != 3) rd.fail(rp, "expected [nx, ny, nz]");
    for (int a = 0; a < 3; ++a) t.structure.resolution[a] = int(rd.integer(res[a], rp.at(a), 1, 4096));
  }
  for (const auto& [key, value] : st.members()) {
    if (key == "kind" || key == "bounds_min" || key == "bounds_max" || key == "resolution") continue;
    TraceParam p;
    p.key = std::string(key);
    if (value.is_string()) {
      p.is_text = true;
      p.text = std::string(value.get_string());
    } else {
      p.number = rd.real(value, sp.key(key));
    }
    t.structure.params.push_back(p);
  }

  // Version 3's bounding volume hierarchies: "bvh", "bvh-sweep", "bvh-median", "bvh4", "bvh8"; and the
  // octree (version 3 too), whose inner nodes list their eight children the same way.
  const bool octree = version >= 3 && t.structure.kind == "octree";
  const bool lists_children = (version >= 3 && t.structure.kind.rfind("bvh", 0) == 0) || octree;
  // Version 4's general BSP tree: every inner node has a plane.
  const bool bsp = version >= 4 && t.structure.kind == "bsp";
  const int64_t max_prim = int64_t(t.scene_primitives) - 1;
  int64_t max_node = INT32_MAX;  // trees: ids below the structure's node count, when it gives one
  for (const TraceParam& p : t.structure.params)
    if (p.key == "nodes" && !p.is_text) max_node = std::min<int64_t>(int64_t(p.number) - 1, INT32_MAX);
  auto axis_index = [&](const Value& v, const Path& path) {
    if (v.is_null()) return -1;
    int a = v.is_string() ? name_index(v.get_string(), kAxes) : -1;
    if (a < 0) rd.fail(path, "expected \"x\", \"y\", \"z\" or null");
    return a;
  };

  // Version 2: an anti-aliased pixel's samples (version 1 had no such key: a reader ignores keys it does not
  // know).
  if (version >= 2 && doc.contains("pixel"))
    t.pixel = read_pixel(rd, doc.find("pixel"), sub(base, "pixel"), capped);

  const Value rays = rd.array_at(doc, root, "rays");
  t.rays.reserve(capped(rays.size()));
  const Path rays_path = sub(base, "rays");
  for (size_t r = 0; r < rays.size(); ++r) {
    const Path rp = rays_path.at(r);
    const Value jr = rays[r];
    TracedRay tr;
    tr.ray.origin = rd.vec_at(jr, rp, "origin");
    tr.ray.direction = rd.vec_at(jr, rp, "direction");
    tr.ray.tmin = rd.real_at(jr, rp, "tmin");
    tr.ray.tmax = rd.real_at(jr, rp, "tmax");
    std::string_view kind = rd.view_at(jr, rp, "kind");
    int k = name_index(kind, kRayKinds);
    if (k < 0) rd.fail(rp.key("kind"), "unknown ray kind \"" + std::string(kind) + "\"");
    tr.kind = RayKind(k);
    tr.depth = int(rd.integer_at(jr, rp, "depth", 0, 1000));
    if (jr.contains("pixel")) {
      const Value px = jr.find("pixel");
      const Path pp = rp.key("pixel");
      if (!px.is_array() || px.size() != 2) rd.fail(pp, "expected [x, y]");
      tr.has_pixel = true;
      tr.pixel[0] = int(rd.integer(px[0], pp.at(0), 0, 1 << 20));
      tr.pixel[1] = int(rd.integer(px[1], pp.at(1), 0, 1 << 20));
    }
    if (version >= 2 && jr.contains("sample")) {
      if (!t.pixel) rd.fail(rp.key("sample"), "a ray's sample needs the trace's \"pixel\" section");
      tr.sample = int(rd.integer_at(jr, rp, "sample", 0, int64_t(t.pixel->sampling.samples.size()) - 1));
    }
    const Value events = rd.array_at(jr, rp, "events");
    const Path events_path = rp.key("events");
    tr.events.reserve(capped(events.size()));
    for (size_t i = 0; i < events.size(); ++i) {
      const Path ep = events_path.at(i);
      const Value je = events[i];
      Event e;
      e.seq = uint32_t(rd.integer_at(je, ep, "seq", 0, 1ll << 32));
      if (e.seq != i)
        rd.fail(ep.key("seq"), "expected " + std::to_string(i) + " (events are numbered in order)");
      std::string_view type = rd.view_at(je, ep, "type");
      int type_index = name_index(type, kEventNames);
      if (type_index < 0) rd.fail(ep.key("type"), "unknown event type \"" + std::string(type) + "\"");
      e.type = EventType(type_index);
      if (version < 3 && (e.type == EventType::box_test || e.type == EventType::skip))
        rd.fail(ep.key("type"), "event type \"" + std::string(type) + "\" needs version 3");
      switch (e.type) {
        case EventType::cell: {
          const Value c = rd.array_at(je, ep, "cell");
          const Path cp = ep.key("cell");
          if (c.size() != 3) rd.fail(cp, "expected [i, j, k]");
          for (int a = 0; a < 3; ++a)
            e.cell[a] = int(rd.integer(c[a], cp.at(a), 0, grid ? t.structure.resolution[a] - 1 : (1 << 20)));
          e.t_enter = rd.real_at(je, ep, "t_enter");
          e.t_exit = rd.real_at(je, ep, "t_exit");
          e.t_max = rd.vec_at(je, ep, "t_max");
          e.t_delta = rd.vec_at(je, ep, "t_delta");
          e.next_axis = axis_index(rd.member(je, ep, "next_axis"), ep.key("next_axis"));
          break;
        }
        case EventType::node:
        case EventType::push:
        case EventType::pop:
        case EventType::leaf:
        case EventType::skip:
          e.node = int32_t(rd.integer_at(je, ep, "node", 0, max_node));
          e.depth = int32_t(rd.integer_at(je, ep, "depth", 0, 1 << 16));
          e.t_min_node = rd.real_at(je, ep, "t_min");
          e.t_max_node = rd.real_at(je, ep, "t_max");
          break;
        case EventType::box_test: {
          // A child's box tested from its parent (-1: the root's box, tested first): [t_near, t_far] on a
          // hit, finite (boxes are) and in order.
          e.parent = int32_t(rd.integer_at(je, ep, "parent", -1, max_node));
          e.node = int32_t(rd.integer_at(je, ep, "node", 0, max_node));
          if (e.node == e.parent) rd.fail(ep.key("node"), "a node is not its own child");
          e.depth = int32_t(rd.integer_at(je, ep, "depth", 0, 1 << 16));
          const Value h = rd.member(je, ep, "hit");
          if (!h.is_boolean()) rd.fail(ep.key("hit"), "expected true or false");
          e.hit = h.get_bool();
          if (e.hit) {
            e.t_min_node = rd.real_at(je, ep, "t_near");
            if (!std::isfinite(e.t_min_node)) rd.fail(ep.key("t_near"), "expected a finite number");
            e.t_max_node = rd.real_at(je, ep, "t_far");
            if (!std::isfinite(e.t_max_node)) rd.fail(ep.key("t_far"), "expected a finite number");
            if (e.t_max_node < e.t_min_node) rd.fail(ep.key("t_far"), "below t_near");
          }
          break;
        }
        case EventType::prim_test: {
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          const Value h = rd.member(je, ep, "hit");
          if (!h.is_boolean()) rd.fail(ep.key("hit"), "expected true or false");
          e.hit = h.get_bool();
          if (e.hit) e.t = rd.real_at(je, ep, "t");
          break;
        }
        case EventType::mailbox_hit:
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          break;
        case EventType::hit_deferred:
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          e.t = rd.real_at(je, ep, "t");
          e.t_exit = rd.real_at(je, ep, "t_exit");
          break;
        case EventType::hit_accepted: {
          e.prim = int32_t(rd.integer_at(je, ep, "prim", 0, max_prim));
          e.t = rd.real_at(je, ep, "t");
          std::string_view reason = rd.view_at(je, ep, "reason");
          int reason_index = name_index(reason, kReasonNames);
          if (reason_index < 0) rd.fail(ep.key("reason"), "unknown reason \"" + std::string(reason) + "\"");
          e.reason = AcceptReason(reason_index);
          break;
        }
        case EventType::ray_end:
          e.prim = int32_t(rd.integer_at(je, ep, "prim", -1, max_prim));
          e.hit = e.prim >= 0;
          e.t = rd.real_at(je, ep, "t");
          break;
        default:
          break;
      }
      tr.events.push_back(e);
    }
    if (tr.events.empty() || tr.events.front().type != EventType::ray_begin ||
        tr.events.back().type != EventType::ray_end)
      rd.fail(events_path, "a ray's events start with ray_begin and end with ray_end");
    t.rays.push_back(std::move(tr));
  }

  const Value geo = rd.member(doc, root, "geometry");
  const Path gp = sub(base, "geometry");
  const Value cells = rd.array_at(geo, gp, "cells");
  const Path cells_path = gp.key("cells");
  t.cells.reserve(capped(cells.size()));
  for (size_t i = 0; i < cells.size(); ++i) {
    const Path cp = cells_path.at(i);
    TraceCell c;
    const Value idx = rd.array_at(cells[i], cp, "cell");
    const Path ip = cp.key("cell");
    if (idx.size() != 3) rd.fail(ip, "expected [i, j, k]");
    for (int a = 0; a < 3; ++a)
      c.cell[a] = int(rd.integer(idx[a], ip.at(a), 0, grid ? t.structure.resolution[a] - 1 : (1 << 20)));
    c.box.lo = rd.vec_at(cells[i], cp, "min");
    c.box.hi = rd.vec_at(cells[i], cp, "max");
    t.cells.push_back(c);
  }
  // Tree nodes: ids below the structure's node count, each listed once, every node an event names listed.
  std::unordered_set<int32_t> listed;
  if (geo.contains("nodes")) {
    const Value nodes = rd.array_at(geo, gp, "nodes");
    const Path nodes_path = gp.key("nodes");
    t.nodes.reserve(capped(nodes.size()));
    listed.reserve(capped(nodes.size()));
    for (size_t i = 0; i < nodes.size(); ++i) {
      const Path np = nodes_path.at(i);
      const Value jn = nodes[i];
      TraceNode n;
      n.id = int32_t(rd.integer_at(jn, np, "id", 0, max_node));
      if (!listed.insert(n.id).second)
        rd.fail(np.key("id"), "node " + std::to_string(n.id) + " is listed twice");
      n.parent = int32_t(rd.integer_at(jn, np, "parent", -1, max_node));
      n.depth = int32_t(rd.integer_at(jn, np, "depth", 0, 1 << 16));
      n.box.lo = rd.vec_at(jn, np, "min");
      n.box.hi = rd.vec_at(jn, np, "max");
      const Value leaf = rd.member(jn, np, "leaf");
      if (!leaf.is_boolean()) rd.fail(np.key("leaf"), "expected true or false");
      n.leaf = leaf.get_bool();
      // Version 3: a BVH's inner node lists its children (1 to 8 distinct ids, not its own), and its axis may
      // be null (the wide BVH); a kd node has a split plane instead. Older versions had no children: ignored
      const bool has_children = version >= 3 && jn.contains("children");
      if (n.leaf) {
        const Value ids = rd.array_at(jn, np, "prims");
        const Path pp = np.key("prims");
        n.prims.reserve(capped(ids.size()));
        for (size_t k = 0; k < ids.size(); ++k)
          n.prims.push_back(int32_t(rd.integer(ids[k], pp.at(k), 0, max_prim)));
        if (has_children) rd.fail(np.key("children"), "a leaf has no children");
      } else if (has_children) {
        const Value ids = rd.array_at(jn, np, "children");
        const Path cp = np.key("children");
        if (ids.size() < 1 || ids.size() > 8) rd.fail(cp, "expected 1 to 8 child ids");
        for (size_t k = 0; k < ids.size(); ++k) {
          const int32_t c = int32_t(rd.integer(ids[k], cp.at(k), 0, max_node));
          if (c == n.id) rd.fail(cp.at(k), "a node is not its own child");
          if (std::find(n.children.begin(), n.children.end(), c) != n.children.end())
            rd.fail(cp.at(k), "child " + std::to_string(c) + " is listed twice");
          n.children.push_back(c);
        }
        n.axis = axis_index(rd.member(jn, np, "axis"), np.key("axis"));
        if (octree && (ids.size() != 8 || n.axis != -1))
          rd.fail(cp, "an inner octree node has 8 children and axis null");
      } else if (bsp || (version >= 4 && jn.contains("normal"))) {
        // Version 4: a BSP node's plane, a finite unit normal (to float rounding) and a finite offset.
        n.has_plane = true;
        n.normal = rd.vec_at(jn, np, "normal");
        const float len =
            std::sqrt(n.normal.x * n.normal.x + n.normal.y * n.normal.y + n.normal.z * n.normal.z);
        if (!is_finite(n.normal) || !(std::fabs(len - 1.f) <= 1e-3f))
          rd.fail(np.key("normal"), "expected a finite unit normal");
        n.offset = rd.real_at(jn, np, "offset");
        if (!std::isfinite(n.offset)) rd.fail(np.key("offset"), "expected a finite number");
      } else {
        if (lists_children)
          rd.fail(np, octree ? "missing \"children\" (an inner octree node lists its 8 children)"
                             : "missing \"children\" (an inner BVH node lists its children)");
        n.axis = axis_index(rd.member(jn, np, "axis"), np.key("axis"));
        if (n.axis < 0) rd.fail(np.key("axis"), "an inner node has a split axis");
        n.split = rd.real_at(jn, np, "split");
      }
      t.nodes.push_back(std::move(n));
    }
  }
  // A BVH's nodes (version 3) hang together: each listed node's parent is listed (the chain up to the root),
  // names it among its children, and lies one level above it.
  std::unordered_map<int32_t, size_t> node_at;
  for (size_t i = 0; i < t.nodes.size(); ++i) node_at.emplace(t.nodes[i].id, i);
  if (lists_children) {
    const Path nodes_path = gp.key("nodes");
    for (size_t i = 0; i < t.nodes.size(); ++i) {
      const TraceNode& n = t.nodes[i];
      const Path np = nodes_path.at(i);
      if (n.parent < 0) {
        if (n.depth != 0) rd.fail(np.key("depth"), "the root (parent -1) has depth 0");
        continue;
      }
      auto p = node_at.find(n.parent);
      if (p == node_at.end())
        rd.fail(np.key("parent"), "node " + std::to_string(n.parent) + " is not in geometry.nodes");
      const TraceNode& parent = t.nodes[p->second];
      if (std::find(parent.children.begin(), parent.children.end(), n.id) == parent.children.end())
        rd.fail(np.key("parent"), "node " + std::to_string(n.parent) + " does not list it as a child");
      if (n.depth != parent.depth + 1)
        rd.fail(np.key("depth"), "expected " + std::to_string(parent.depth + 1) + ", one below its parent");
    }
  }
  if (t.structure.kind != "grid") {
    for (size_t r = 0; r < t.rays.size(); ++r)
      for (size_t i = 0; i < t.rays[r].events.size(); ++i) {
        const Event& e = t.rays[r].events[i];
        bool tree_event = e.type == EventType::node || e.type == EventType::push ||
                          e.type == EventType::pop || e.type == EventType::leaf ||
                          e.type == EventType::skip || e.type == EventType::box_test;
        const Path rp = rays_path.at(r);
        const Path esp = rp.key("events");
        const Path ep = esp.at(i);
        if (tree_event && !listed.count(e.node))
          rd.fail(ep.key("node"), "node " + std::to_string(e.node) + " is not in geometry.nodes");
        if (e.type == EventType::box_test) {
          const TraceNode& child = t.nodes[node_at.at(e.node)];
          if (e.parent < 0) {
            if (child.parent >= 0)
              rd.fail(ep.key("parent"), "only the root's box (node 0) is tested without a parent");
          } else {
            auto p = node_at.find(e.parent);
            if (p == node_at.end())
              rd.fail(ep.key("parent"), "node " + std::to_string(e.parent) + " is not in geometry.nodes");
            const std::vector<int32_t>& children = t.nodes[p->second].children;
            if (std::find(children.begin(), children.end(), e.node) == children.end())
              rd.fail(ep.key("node"), "node " + std::to_string(e.node) + " is not a child of node " +
                                          std::to_string(e.parent));
          }
          if (e.depth != child.depth)
            rd.fail(ep.key("depth"), "expected " + std::to_string(child.depth) + ", the depth of node " +
                                         std::to_string(e.node) + " in geometry.nodes");
        }
      }
  }

  if (doc.contains("build")) {
    const Value build = rd.array_at(doc, root, "build");
    t.build.reserve(capped(build.size()));
    const Path build_path = sub(base, "build");
    for (size_t i = 0; i < build.size(); ++i) {
      const Path bp = build_path.at(i);
      const Value jb = build[i];
      TraceBuildEvent b;
      if (rd.integer_at(jb, bp, "seq", 0, 1ll << 40) != int64_t(i))
        rd.fail(bp.key("seq"), "expected " + std::to_string(i) + " (build events are numbered in order)");
      std::string_view type = rd.view_at(jb, bp, "type");
      int type_index = name_index(type, kEventNames);
      if (type_index >= 0) b.type = EventType(type_index);
      if (type_index < 0 || (b.type != EventType::sah_candidate && b.type != EventType::split &&
                             b.type != EventType::leaf_made))
        rd.fail(bp.key("type"),
                "unknown build event type \"" + std::string(type) + "\" (sah_candidate, split, leaf_made)");
      b.node = uint32_t(rd.integer_at(jb, bp, "node", 0, std::max<int64_t>(max_node, 0)));
      if (b.type == EventType::sah_candidate) {
        SahCandidate& c = b.candidate;
        c.axis = axis_index(rd.member(jb, bp, "axis"), bp.key("axis"));
        if (c.axis < 0) rd.fail(bp.key("axis"), "expected \"x\", \"y\" or \"z\"");
        c.position = rd.real_at(jb, bp, "position");
        c.n_below = uint32_t(rd.integer_at(jb, bp, "n_below", 0, UINT32_MAX));
        c.n_above = uint32_t(rd.integer_at(jb, bp, "n_above", 0, UINT32_MAX));
        c.n_planar = uint32_t(rd.integer_at(jb, bp, "n_planar", 0, UINT32_MAX));
        c.area_below = rd.real_at(jb, bp, "area_below");
        c.area_above = rd.real_at(jb, bp, "area_above");
        c.area_node = rd.real_at(jb, bp, "area_node");
        c.cost = rd.real_at(jb, bp, "cost");
        std::string_view side = rd.view_at(jb, bp, "planar_side");
        if (side != "below" && side != "above")
          rd.fail(bp.key("planar_side"), "expected \"below\" or \"above\"");
        c.planar_below = side == "below";
      } else {
        b.depth = int32_t(rd.integer_at(jb, bp, "depth", 0, 1 << 16));
        b.box.lo = rd.vec_at(jb, bp, "min");
        b.box.hi = rd.vec_at(jb, bp, "max");
        b.prims = uint32_t(rd.integer_at(jb, bp, "prims", 0, UINT32_MAX));
        b.leaf_cost = rd.real_at(jb, bp, "leaf_cost");
        if (b.type == EventType::split) {
          b.axis = axis_index(rd.member(jb, bp, "axis"), bp.key("axis"));
          if (b.axis < 0) rd.fail(bp.key("axis"), "expected \"x\", \"y\" or \"z\"");
          b.position = rd.real_at(jb, bp, "position");
          b.cost = rd.real_at(jb, bp, "cost");
        } else {
          std::string reason = rd.text_at(jb, bp, "reason");
          if (!parse_leaf_reason(reason, &b.reason))
            rd.fail(bp.key("reason"), "unknown leaf reason \"" + reason + "\"");
        }
      }
      t.build.push_back(b);
    }
  }

  const Value prims = rd.array_at(geo, gp, "primitives");
  const Path prims_path = gp.key("primitives");
  t.primitives.reserve(capped(prims.size()));
  for (size_t i = 0; i < prims.size(); ++i) {
    const Path pp = prims_path.at(i);
    TracePrimitive p;
    p.id = int32_t(rd.integer_at(prims[i], pp, "id", 0, max_prim));
    std::string_view type = rd.view_at(prims[i], pp, "type");
    if (type == "triangle") {
      const Value v = rd.array_at(prims[i], pp, "vertices");
      const Path vsp = pp.key("vertices");
      if (v.size() != 3) rd.fail(vsp, "expected 3 vertices");
      for (int k = 0; k < 3; ++k) {
        const Path vp = vsp.at(k);
        if (!v[k].is_array() || v[k].size() != 3) rd.fail(vp, "expected an array of 3 numbers");
        p.v[k] =
            glm::vec3(rd.real(v[k][0], vp.at(0)), rd.real(v[k][1], vp.at(1)), rd.real(v[k][2], vp.at(2)));
      }
    } else if (type == "sphere") {
      p.type = PrimType::sphere;
      p.v[0] = rd.vec_at(prims[i], pp, "center");
      p.radius = rd.real_at(prims[i], pp, "radius");
    } else {
      rd.fail(pp.key("type"), "unknown primitive type \"" + std::string(type) + "\"");
    }
    t.primitives.push_back(p);
  }
}

}  // namespace

namespace detail {

int parse_trace_document(const std::string& text, const std::string& name, bool walks_allowed,
                         std::vector<Trace>* walks) {
  // A count read from the file reserves at most what its text could hold (an element takes a few bytes of
  // text and up to ~100 bytes of memory): a hostile "[0,0,0,...]" cannot make the reader ask for many times
  // the size of the file before its first element is checked.
  auto capped = [&](size_t n) { return std::min(n, text.size() / 64); };
  JsonTape tape = parse_tape(text, name);
  const Value doc = tape.root();
  Reader rd(name, text);
  const Path root = "trace";
  if (!doc.is_object()) rd.fail(root, "expected a JSON object");
  Value format_value = doc.find("format");
  std::string_view format =
      format_value.exists() && format_value.is_string() ? format_value.get_string() : "";
  if (format != kTraceFormat) rd.fail("format", "not a raystep trace (format must be \"raystep-trace\")");
  int64_t version = rd.integer_at(doc, root, "version", 0, 1 << 30);
  if (version == kMultiTraceVersion && !walks_allowed)
    rd.fail("version",
            "version " + std::to_string(version) +
                " holds the walks of several structures (raystep trace --accel A,B,...); this reader "
                "reads a single structure's trace, versions " +
                std::to_string(kTraceOldestVersion) + " to " + std::to_string(kTraceVersion));
  if (version < kTraceOldestVersion || version > (walks_allowed ? kMultiTraceVersion : kTraceVersion))
    rd.fail("version", "unsupported trace version " + std::to_string(version) +
                           " (this raystep reads versions " + std::to_string(kTraceOldestVersion) + " to " +
                           std::to_string(walks_allowed ? kMultiTraceVersion : kTraceVersion) + ")");

  Trace t;
  t.version = int(version);
  const Value scene = rd.member(doc, root, "scene");
  t.scene_path = rd.text_at(scene, "scene", "path");
  t.scene_hash = rd.text_at(scene, "scene", "hash");
  t.scene_primitives = uint64_t(rd.integer_at(scene, "scene", "primitives", 0, int64_t(1) << 40));
  walks->clear();
  if (version < kMultiTraceVersion) {
    read_walk(rd, doc, root, nullptr, version, t, capped);
    walks->push_back(std::move(t));
    return int(version);
  }

  // Version 5: the scene once, then 2 to 6 walks, each a version 4 trace's structure, pixel, rays, geometry
  // and build, read with that version's rules; every walk traces the same rays in the same order.
  const Value jw = rd.array_at(doc, root, "walks");
  const Path walks_path = "walks";
  if (jw.size() < size_t(kMinWalks) || jw.size() > size_t(kMaxWalks))
    rd.fail(walks_path, "expected " + std::to_string(kMinWalks) + " to " + std::to_string(kMaxWalks) +
                            " walks, found " + std::to_string(jw.size()));
  walks->reserve(jw.size());
  for (size_t w = 0; w < jw.size(); ++w) {
    const Path wp = walks_path.at(w);
    Trace walk;
    walk.version = int(version);
    walk.scene_path = t.scene_path;
    walk.scene_hash = t.scene_hash;
    walk.scene_primitives = t.scene_primitives;
    read_walk(rd, jw[w], wp, &wp, kTraceVersion, walk, capped);
    if (w > 0) {
      const Trace& first = walks->front();
      const Path rays_path = wp.key("rays");
      if (walk.rays.size() != first.rays.size())
        rd.fail(rays_path, std::to_string(walk.rays.size()) + " rays, but walks[0] has " +
                               std::to_string(first.rays.size()) + " (every walk traces the same rays)");
      for (size_t r = 0; r < walk.rays.size(); ++r) {
        const TracedRay& a = first.rays[r];
        const TracedRay& b = walk.rays[r];
        if (a.ray.origin != b.ray.origin || a.ray.direction != b.ray.direction || a.ray.tmin != b.ray.tmin ||
            a.ray.tmax != b.ray.tmax || a.kind != b.kind || a.depth != b.depth ||
            a.has_pixel != b.has_pixel || a.pixel[0] != b.pixel[0] || a.pixel[1] != b.pixel[1] ||
            a.sample != b.sample)
          rd.fail(rays_path.at(r), "not the same ray as walks[0].rays[" + std::to_string(r) +
                                       "] (every walk traces the same rays)");
      }
    }
    walks->push_back(std::move(walk));
  }
  return int(version);
}

std::string read_trace_text(const std::string& path) {
  // A regular file only: a directory, a device such as /dev/zero or a FIFO would fail oddly, never end, or
  // block; the scene and ray readers refuse them the same way.
  std::error_code ec;
  std::filesystem::file_status status = std::filesystem::status(path, ec);
  if (!std::filesystem::exists(status)) throw InputError(path, 0, "cannot read the file: no such file");
  if (!std::filesystem::is_regular_file(status))
    throw InputError(path, 0, "cannot read the file: not a regular file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot read the file");
  std::string text;
  in.seekg(0, std::ios::end);
  std::streamoff size = in.tellg();
  in.seekg(0, std::ios::beg);
  // Refused before a byte is read when it would not fit (util/memory_limit.h).
  if (size > 0) check_read_memory(path, InputKind::trace_json, uint64_t(size));
  if (size > 0 && in) {  // read it in one go
    text.resize(size_t(size));
    in.read(text.data(), size);
    text.resize(size_t(in.gcount()));
  }
  return text;
}

}  // namespace detail

Trace parse_trace_json(const std::string& text, const std::string& name) {
  std::vector<Trace> walks;
  detail::parse_trace_document(text, name, false, &walks);
  return std::move(walks.front());
}

Trace read_trace_json(const std::string& path) {
  return parse_trace_json(detail::read_trace_text(path), path);
}

namespace {

std::string rgb(const glm::vec3& v) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "(%.6g, %.6g, %.6g)", double(v.x), double(v.y), double(v.z));
  return buf;
}

// The pixel section in two or three lines: the pattern, the samples, the adaptive tree, the value.
std::string pixel_summary(const TracePixel& p) {
  const PixelSampling& s = p.sampling;
  std::ostringstream out;
  out << "pixel " << s.x << "," << s.y << " of " << p.width << "x" << p.height << ": aa " << to_string(s.aa)
      << ", seed " << p.seed << ", " << s.samples.size() << " sample(s)\n";
  if (!s.squares.empty()) {
    size_t n[3] = {0, 0, 0};
    int depth = 0;
    for (const AdaptiveSquare& q : s.squares) {
      ++n[int(q.outcome)];
      depth = std::max(depth, q.depth);
    }
    out << "adaptive: " << s.squares.size() << " squares, depth " << depth << " reached (limit "
        << s.aa.max_depth << "), " << n[2] << " subdivided, " << n[0] << " agree, " << n[1]
        << " at the depth limit; threshold " << s.aa.threshold << "\n";
  }
  out << "value " << rgb(s.value);
  if (p.exact) {
    const glm::vec3 d = s.value - *p.exact;
    out << ", exact " << rgb(*p.exact) << ", error " << rgb(d);
  }
  out << "\n";
  return out.str();
}

}  // namespace

std::string trace_summary(const Trace& t) {
  std::ostringstream out;
  out << "trace: " << t.rays.size() << " ray(s), structure " << t.structure.kind;
  if (t.structure.kind == "grid") {
    out << " " << t.structure.resolution[0] << "x" << t.structure.resolution[1] << "x"
        << t.structure.resolution[2];
    std::string from, why;
    for (const TraceParam& p : t.structure.params)
      if (p.is_text && p.key == "coarsened_from")
        from = p.text;
      else if (p.is_text && p.key == "coarsening")
        why = p.text;
    if (!from.empty()) out << " (coarsened from " << from << (why.empty() ? "" : ": " + why) << ")";
  }
  out << ", scene " << t.scene_path << " (" << t.scene_primitives << " primitives)\n";
  if (t.pixel) out << pixel_summary(*t.pixel);
  std::map<std::string, size_t> totals;
  for (size_t r = 0; r < t.rays.size(); ++r) {
    const TracedRay& tr = t.rays[r];
    RayCounters c = count_events(tr.events);
    const Event& end = tr.events.back();
    out << "ray " << r << ": " << ray_kind_name(tr.kind) << ", depth " << tr.depth;
    if (tr.has_pixel) out << ", pixel " << tr.pixel[0] << "," << tr.pixel[1];
    if (tr.sample >= 0) out << ", sample " << tr.sample;
    out << ", " << tr.events.size() << " events, ";
    if (t.structure.kind == "grid")
      out << c.cells << " cells, ";
    else
      out << c.nodes << " nodes, " << c.pushes << " pushes, " << c.pops << " pops, ";
    const bool bvh = t.structure.kind.rfind("bvh", 0) == 0;
    if (bvh) {  // version 3: the boxes tested and the entries skipped
      size_t skips = 0;
      for (const Event& e : tr.events) skips += e.type == EventType::skip;
      out << c.box_tests << " box tests, " << skips << " skips, ";
    }
    out << c.prim_tests << " tests (" << c.prim_hits << " hits)";
    if (!bvh) out << ", " << c.mailbox_hits << " mailbox hits";  // a BVH has none: a primitive is in one leaf
    out << "; ";
    if (end.prim >= 0)
      out << "hit primitive " << end.prim << " at t=" << end.t << "\n";
    else
      out << "miss\n";
    for (const Event& e : tr.events) ++totals[event_type_name(e.type)];
  }
  if (!t.build.empty()) {
    size_t n[3] = {0, 0, 0};
    for (const TraceBuildEvent& b : t.build)
      ++n[b.type == EventType::sah_candidate ? 0 : b.type == EventType::split ? 1 : 2];
    out << "build: " << n[0] << " sah_candidate, " << n[1] << " split, " << n[2] << " leaf_made\n";
  }
  out << "events by type:";
  for (const auto& [name, n] : totals) out << " " << name << "=" << n;
  out << "\n";
  return out.str();
}

}  // namespace raystep
