// Writing traces: the JSON document (also in two parts, for a build streamed while the tree is built) and the
// CSV with one event per row, both atomically.
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

using namespace detail;


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

}  // namespace raystep
