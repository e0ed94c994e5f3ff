// A trace's human summary (raystep trace-info): rays, events by type, counters, the pixel section.
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

