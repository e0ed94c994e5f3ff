// A lesson step's state, one `key: value` setting at a time (docs/lesson-format.md), and the raystep-gui
// command line that shows the same state. Ranges and messages follow the scripted mode
// (viz/src/app/script.cpp), so a value a lesson accepts is one the GUI accepts too.
#include "raystep/lesson/lesson_state.h"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <functional>
#include <map>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bsp_build.h"
#include "raystep/accel/bvh_names.h"
#include "raystep/render/antialiasing.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

// "key 'value': expected ...": every message names the setting and what it was given.
[[noreturn]] void bad(const std::string& key, const std::string& value, const std::string& expected) {
  fail(key + " '" + value + "': expected " + expected);
}

// A whole number in [lo, hi], digits only (no sign, no spaces): small enough never to overflow.
bool parse_int(const std::string& s, long lo, long hi, int* out) {
  if (s.empty() || s.size() > 9) return false;
  for (char c : s)
    if (c < '0' || c > '9') return false;
  long v = std::strtol(s.c_str(), nullptr, 10);
  if (v < lo || v > hi) return false;
  *out = int(v);
  return true;
}

// A finite decimal number, the whole text.
bool parse_number(const std::string& s, double* out) {
  if (s.empty() || s.size() > 64 || std::isspace(static_cast<unsigned char>(s[0]))) return false;
  errno = 0;
  char* end = nullptr;
  double v = std::strtod(s.c_str(), &end);
  if (end != s.c_str() + s.size() || !std::isfinite(v)) return false;
  *out = v;
  return true;
}

// Comma-separated whole numbers, exactly n of them, each in [lo, hi].
bool parse_ints(const std::string& s, int n, long lo, long hi, int* out) {
  size_t start = 0;
  for (int i = 0; i < n; ++i) {
    size_t comma = s.find(',', start);
    bool last = i == n - 1;
    if (last != (comma == std::string::npos)) return false;
    std::string part = s.substr(start, last ? std::string::npos : comma - start);
    if (!parse_int(part, lo, hi, &out[i])) return false;
    start = comma + 1;
  }
  return true;
}

bool parse_on_off(const std::string& key, const std::string& value) {
  if (value == "on") return true;
  if (value == "off") return false;
  bad(key, value, "on or off");
}

// At least the integer part's digits, so that 20 reads "20", not "2e+01".
int integer_digits(double v) {
  const double a = std::fabs(v);
  return a >= 1.0 && a < 1e17 ? int(std::floor(std::log10(a))) + 1 : 1;
}

// The shortest decimal text that reads back to the same float (the command line must rebuild the same tree).
std::string float_text(float v) {
  char buf[32];
  for (int precision = std::min(9, integer_digits(v)); precision <= 9; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, double(v));
    if (std::strtof(buf, nullptr) == v) break;
  }
  return buf;
}

std::string double_text(double v) {
  char buf[40];
  for (int precision = std::min(17, integer_digits(v)); precision <= 17; ++precision) {
    std::snprintf(buf, sizeof buf, "%.*g", precision, v);
    if (std::strtod(buf, nullptr) == v) break;
  }
  return buf;
}

// The kinds of event `step-to` may name: those of a ray's walk ("hit" is hit_accepted, as in the GUI).
bool parse_step_kind(const std::string& name, EventType* type) {
  static const std::map<std::string, EventType> kinds = {{"cell", EventType::cell},
                                                         {"prim_test", EventType::prim_test},
                                                         {"mailbox_hit", EventType::mailbox_hit},
                                                         {"hit_deferred", EventType::hit_deferred},
                                                         {"hit", EventType::hit_accepted},
                                                         {"hit_accepted", EventType::hit_accepted},
                                                         {"ray_end", EventType::ray_end},
                                                         {"node", EventType::node},
                                                         {"push", EventType::push},
                                                         {"pop", EventType::pop},
                                                         {"leaf", EventType::leaf},
                                                         {"box_test", EventType::box_test},
                                                         {"skip", EventType::skip}};
  auto it = kinds.find(name);
  if (it == kinds.end()) return false;
  *type = it->second;
  return true;
}

using Setter = std::function<void(LessonState&, const std::string& key, const std::string& value,
                                  const std::string& base_dir)>;

void set_scene(LessonState& s, const std::string& key, const std::string& value,
               const std::string& base_dir) {
  namespace fs = std::filesystem;
  if (value.empty()) bad(key, value, "a scene file (.json or .obj)");
  fs::path p(value);
  if (p.is_relative() && !base_dir.empty()) p = fs::path(base_dir) / p;
  p = p.lexically_normal();
  std::error_code ec;
  if (!fs::is_regular_file(p, ec)) fail(key + " '" + value + "': no such file (" + p.string() + ")");
  s.scene = p.string();
}

// The settings in the documented order (lesson_setting_keys lists them so).
const std::vector<std::pair<std::string, Setter>>& setters() {
  static const std::
      vector<std::pair<std::string, Setter>>
          table =
              {
                  {"scene", set_scene},
                  {"accel",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v != "grid" && v != "kd" && v != "kd-median" && !is_bvh_name(v) && v != "octree" &&
                         v != "bsp")
                       bad(k, v, recorded_structure_list());
                     s.accel = v;
                   }},
                  {"grid-res",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "none") return void(s.structure.grid.resolution.reset());
                     int r[3];
                     if (!parse_ints(v, 3, 1, 4096, r))
                       bad(k, v, "NX,NY,NZ, each a whole number 1..4096, or none");
                     s.structure.grid.resolution = std::array<int, 3>{r[0], r[1], r[2]};
                   }},
                  {"grid-density",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     double d;
                     if (!parse_number(v, &d) || !(d > 0.0 && d <= 64.0)) bad(k, v, "a number in (0, 64]");
                     s.structure.grid.density = float(d);
                   }},
                  {"grid-insert",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v != "exact" && v != "bbox") bad(k, v, "exact or bbox");
                     s.structure.grid.exact_insert = v == "exact";
                   }},
                  {"ti",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     double d;
                     if (!parse_number(v, &d) || !(d > 0.0 && d <= 1e4)) bad(k, v, "a number in (0, 10000]");
                     s.structure.kd.t_i = float(d);  // the BVH's SAH takes the kd-tree's constants
                     s.structure.bvh.t_i = float(d);
                     s.structure.bsp.t_i = float(d);  // and the BSP tree's, as raystep --ti
                   }},
                  {"tt",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     double d;
                     if (!parse_number(v, &d) || !(d >= 0.0 && d <= 1e4)) bad(k, v, "a number in [0, 10000]");
                     s.structure.kd.t_t = float(d);
                     s.structure.bvh.t_t = float(d);
                     s.structure.bsp.t_t = float(d);
                   }},
                  {"empty-bonus",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     double d;
                     if (!parse_number(v, &d) || !(d >= 0.0 && d < 1.0)) bad(k, v, "a number in [0, 1)");
                     s.structure.kd.empty_bonus = float(d);
                   }},
                  {"max-depth",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 0, std::min(kKdMaxDepth, kBvhMaxDepth), &s.structure.kd.max_depth))
                       bad(k, v,
                           "a whole number 0.." + std::to_string(std::min(kKdMaxDepth, kBvhMaxDepth)) +
                               " (0: by the rule)");
                     // The BVH's limit, as raystep --max-depth sets it (0: kBvhMaxDepth).
                     const int depth = s.structure.kd.max_depth;
                     s.structure.bvh.max_depth = depth == 0 ? kBvhMaxDepth : depth;
                     // The BSP tree's and the octree's, as raystep's (the octree's build refuses > 20).
                     s.structure.bsp.max_depth = depth;
                     s.structure.octree.max_depth = depth;
                   }},
                  {"leaf-size",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 1, 1000000, &s.structure.kd.leaf_size))
                       bad(k, v, "a whole number >= 1");
                     s.structure.bsp.leaf_size = s.structure.kd.leaf_size;
                   }},
                  {"mailbox", [](LessonState& s, const std::string& k, const std::string& v,
                                 const std::string&) { s.structure.kd_mailboxes = parse_on_off(k, v); }},
                  // The BVH's own options, named as raystep's --bins, --bvh-leaf, --bvh-max-leaf, --bvh-order.
                  {"bins",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 2, 256, &s.structure.bvh.bins)) bad(k, v, "a whole number 2..256");
                   }},
                  {"bvh-leaf",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 1, 1000000, &s.structure.bvh.leaf_size)) bad(k, v, "a whole number >= 1");
                   }},
                  {"bvh-max-leaf",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     // At least bvh-leaf: checked when the structure is built (the order of the keys is free).
                     if (!parse_int(v, 1, 1000000, &s.structure.bvh.max_leaf_size))
                       bad(k, v, "a whole number >= 1");
                   }},
                  {"bvh-order",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v != "entry" && v != "axis") bad(k, v, "entry or axis");
                     s.structure.bvh_order = v == "axis" ? BvhOrder::split_axis : BvhOrder::entry_distance;
                   }},
                  // The octree's and the BSP tree's own options, named as raystep's.
                  {"octree-leaf",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 1, 1 << 24, &s.structure.octree.leaf_size))
                       bad(k, v, "a whole number 1..16777216");
                   }},
                  {"bsp-directions",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_bsp_directions(v, &s.structure.bsp.directions))
                       bad(k, v, "both, kdop or autopartition");
                   }},
                  {"bsp-candidates",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 1, 4096, &s.structure.bsp.candidates)) bad(k, v, "a whole number 1..4096");
                   }},
                  {"aa",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "scene") return void(s.aa.clear());
                     try {
                       parse_antialiasing(v);
                     } catch (const InputError&) {
                       bad(k, v, "none, regular:K, jitter:K, random:N, adaptive:T[:D] or scene");
                     }
                     s.aa = v;
                   }},
                  {"size",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "scene") return void(s.size.reset());
                     size_t x = v.find('x');
                     int w, h;
                     if (x == std::string::npos || !parse_int(v.substr(0, x), 1, 16384, &w) ||
                         !parse_int(v.substr(x + 1), 1, 16384, &h))
                       bad(k, v, "WxH with 1 <= W, H <= 16384, or scene");
                     s.size = std::array<int, 2>{w, h};
                   }},
                  {"heat",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "none") return void(s.heat.clear());
                     if (v != "cells" && v != "tests" && v != "mailbox" && v != "boxes" && v != "samples" &&
                         v != "error")
                       bad(k, v, "cells, tests, mailbox, boxes, samples, error or none");
                     s.heat = v;
                   }},
                  {"pixel",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     // A new pixel is a new trace: the GUI shows its primary ray from its first event.
                     s.ray = 0;
                     s.event = EventSpec{};
                     s.sample.reset();
                     s.square.reset();
                     if (v == "none") return void(s.pixel.reset());
                     int p[2];
                     if (!parse_ints(v, 2, 0, 16383, p)) bad(k, v, "X,Y whole numbers >= 0, or none");
                     s.pixel = std::array<int, 2>{p[0], p[1]};
                   }},
                  {"secondary", [](LessonState& s, const std::string& k, const std::string& v,
                                   const std::string&) { s.secondary = parse_on_off(k, v); }},
                  {"ray",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (!parse_int(v, 0, 1000000, &s.ray)) bad(k, v, "a whole number >= 0");
                     s.event = EventSpec{};  // another ray: from its first event
                     s.sample.reset();       // the ray named by its index, not by its sample
                   }},
                  {"sample",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     // A sample's ray tree replaces the ray named before: its primary ray, from its first
                     // event.
                     s.ray = 0;
                     s.event = EventSpec{};
                     if (v == "none") return void(s.sample.reset());
                     int n;
                     if (!parse_int(v, 0, int(kMaxSamplesPerPixel) - 1, &n))
                       bad(k, v, "a sample index, a whole number >= 0, or none");
                     s.sample = n;
                   }},
                  {"step",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     EventSpec e;
                     e.by = EventSpec::By::index;
                     if (!parse_int(v, 0, 100000000, &e.index))
                       bad(k, v, "an event index, a whole number >= 0");
                     e.text = v;
                     s.event = e;
                   }},
                  {"step-to",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     EventSpec e;
                     e.by = EventSpec::By::nth;
                     size_t colon = v.find(':');
                     if (colon == std::string::npos || !parse_step_kind(v.substr(0, colon), &e.type) ||
                         !parse_int(v.substr(colon + 1), 1, 100000000, &e.k))
                       bad(k, v,
                           "KIND:K with K >= 1 and KIND one of cell, prim_test, mailbox_hit, hit_deferred, "
                           "hit, ray_end, "
                           "node, push, pop, leaf, box_test, skip");
                     e.text = v;
                     s.event = e;
                   }},
                  {"panel",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "none") return void(s.panel.clear());
                     if (v != "sah" && v != "kd") bad(k, v, "sah, kd or none");
                     s.panel = v;
                   }},
                  {"node",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "none") return void(s.node = NodeSpec{});
                     NodeSpec n;
                     n.by = NodeSpec::By::id;
                     if (!parse_int(v, 0, 1000000000, &n.id))
                       bad(k, v, "a node id, a whole number >= 0, or none");
                     s.node = n;
                   }},
                  {"node-path",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     // L and R: a kd-tree's, BSP tree's or binary BVH's children; 0..7: an octree's octants.
                     bool ok = !v.empty() && v.size() <= size_t(kKdMaxDepth);
                     bool lr = true, octants = true;
                     for (char c : v) lr = lr && (c == 'L' || c == 'R'), octants = octants && c >= '0' && c <= '7';
                     if (!ok || !(lr || octants))
                       bad(k, v,
                           "a path of L (below) and R (above), or of octants 0..7 (an octree), 1.." +
                               std::to_string(kKdMaxDepth) + " letters (the root is node: 0)");
                     NodeSpec n;
                     n.by = NodeSpec::By::path;
                     n.path = v;
                     s.node = n;
                   }},
                  {"inspect", [](LessonState& s, const std::string& k, const std::string& v,
                                 const std::string&) { s.inspect = parse_on_off(k, v); }},
                  {"square",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "none") return void(s.square.reset());
                     int n;
                     if (!parse_int(v, 0, 1000000, &n))
                       bad(k, v,
                           "an adaptive square's index, a whole number >= 0 (0: the whole pixel), or none");
                     s.square = n;
                   }},
                  {"follow", [](LessonState& s, const std::string& k, const std::string& v,
                                const std::string&) { s.follow = parse_on_off(k, v); }},
                  {"translucent", [](LessonState& s, const std::string& k, const std::string& v,
                                     const std::string&) { s.translucent = parse_on_off(k, v); }},
                  {"build-planes", [](LessonState& s, const std::string& k, const std::string& v,
                                      const std::string&) { s.build_planes = parse_on_off(k, v); }},
                  {"crofton-lines", [](LessonState& s, const std::string& k, const std::string& v,
                                       const std::string&) { s.crofton_lines = parse_on_off(k, v); }},
                  {"flat-aa", [](LessonState& s, const std::string& k, const std::string& v,
                                 const std::string&) { s.flat_aa = parse_on_off(k, v); }},
                  {"zoom",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     double z;
                     if (!parse_number(v, &z) || !(z >= 0.0 && z <= 64.0))
                       bad(k, v, "a number in [0, 64] (0: fit)");
                     s.zoom = z;
                   }},
                  {"sample-overlay", [](LessonState& s, const std::string& k, const std::string& v,
                                        const std::string&) { s.sample_overlay = parse_on_off(k, v); }},
                  {"show",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v != "window" && v != "3d" && v != "tree" && v != "chart" && v != "picture" && v != "report")
                       bad(k, v, "window, 3d, tree, chart, picture or report");
                     s.show = v;
                   }},
                  {"report",
                   [](LessonState& s, const std::string& k, const std::string& v, const std::string&) {
                     if (v == "none") return void(s.report.clear());
                     // A list of report windows, each named once.
                     std::vector<std::string> seen;
                     size_t start = 0;
                     for (;;) {
                       const size_t comma = v.find(',', start);
                       const std::string r = v.substr(start, comma == std::string::npos ? comma : comma - start);
                       if ((r != "aa" && r != "grid-sweep" && r != "bvol") ||
                           std::find(seen.begin(), seen.end(), r) != seen.end())
                         bad(k, v, "aa, grid-sweep or bvol (several: comma-separated, each once), or none");
                       seen.push_back(r);
                       if (comma == std::string::npos) break;
                       start = comma + 1;
                     }
                     s.report = v;
                   }},
              };
  return table;
}

}  // namespace

const std::vector<std::string>& lesson_setting_keys() {
  static const std::vector<std::string> keys = [] {
    std::vector<std::string> k;
    for (const auto& [key, setter] : setters()) k.push_back(key);
    return k;
  }();
  return keys;
}

void apply_setting(LessonState& state, const std::string& key, const std::string& value,
                   const std::string& base_dir) {
  if (key == "ask") fail("ask is not a state setting (it names the step's question)");
  for (const auto& [k, setter] : setters())
    if (k == key) return setter(state, key, value, base_dir);
  std::string known;
  for (const std::string& k : lesson_setting_keys()) known += (known.empty() ? "" : ", ") + k;
  fail("unknown setting '" + key + "' (known: " + known + ", ask)");
}

std::vector<std::string> LessonState::scripted_args() const {
  std::vector<std::string> a;
  auto opt = [&](const char* name, const std::string& value) {
    a.push_back(std::string("--") + name);
    a.push_back(value);
  };
  if (!scene.empty()) a.push_back(scene);
  // The structure, then the picture, then the trace and the event, then the kd-tree's panel, then the views:
  // the order in which the GUI's scripted mode applies them. Defaults are left out.
  const StructureOptions defaults;
  if (accel != "grid") opt("accel", accel);
  const GridOptions& g = structure.grid;
  if (g.resolution)
    opt("grid-res", std::to_string((*g.resolution)[0]) + "," + std::to_string((*g.resolution)[1]) + "," +
                        std::to_string((*g.resolution)[2]));
  if (g.density != defaults.grid.density) opt("grid-density", float_text(g.density));
  if (g.exact_insert != defaults.grid.exact_insert) opt("grid-insert", g.exact_insert ? "exact" : "bbox");
  const KdOptions& kd = structure.kd;
  if (kd.t_i != defaults.kd.t_i) opt("ti", float_text(kd.t_i));
  if (kd.t_t != defaults.kd.t_t) opt("tt", float_text(kd.t_t));
  if (kd.empty_bonus != defaults.kd.empty_bonus) opt("empty-bonus", float_text(kd.empty_bonus));
  if (kd.max_depth != defaults.kd.max_depth) opt("max-depth", std::to_string(kd.max_depth));
  if (kd.leaf_size != defaults.kd.leaf_size) opt("leaf-size", std::to_string(kd.leaf_size));
  if (structure.kd_mailboxes != defaults.kd_mailboxes) opt("mailbox", structure.kd_mailboxes ? "on" : "off");
  const BvhOptions& bvh = structure.bvh;
  if (bvh.bins != defaults.bvh.bins) opt("bins", std::to_string(bvh.bins));
  if (bvh.leaf_size != defaults.bvh.leaf_size) opt("bvh-leaf", std::to_string(bvh.leaf_size));
  if (bvh.max_leaf_size != defaults.bvh.max_leaf_size) opt("bvh-max-leaf", std::to_string(bvh.max_leaf_size));
  if (structure.bvh_order != defaults.bvh_order)
    opt("bvh-order", structure.bvh_order == BvhOrder::split_axis ? "axis" : "entry");
  if (structure.octree.leaf_size != defaults.octree.leaf_size)
    opt("octree-leaf", std::to_string(structure.octree.leaf_size));
  if (structure.bsp.directions != defaults.bsp.directions)
    opt("bsp-directions", bsp_directions_name(structure.bsp.directions));
  if (structure.bsp.candidates != defaults.bsp.candidates)
    opt("bsp-candidates", std::to_string(structure.bsp.candidates));
  if (!aa.empty()) opt("aa", aa);
  if (size) opt("size", std::to_string((*size)[0]) + "x" + std::to_string((*size)[1]));
  if (!heat.empty()) opt("heat", heat);
  if (pixel) opt("pixel", std::to_string((*pixel)[0]) + "," + std::to_string((*pixel)[1]));
  if (secondary) a.push_back("--secondary");
  if (ray != 0) opt("ray", std::to_string(ray));
  if (sample) opt("sample", std::to_string(*sample));
  if (event.by == EventSpec::By::index) opt("step", std::to_string(event.index));
  if (event.by == EventSpec::By::nth)
    opt("step-to", std::string(event.type == EventType::hit_accepted ? "hit" : event_type_name(event.type)) +
                       ":" + std::to_string(event.k));
  if (!panel.empty()) opt("panel", panel);
  if (node.by == NodeSpec::By::id) opt("node", std::to_string(node.id));
  if (node.by == NodeSpec::By::path) opt("node-path", node.path);
  if (inspect) a.push_back("--inspect");
  if (square) opt("square", std::to_string(*square));
  if (follow) a.push_back("--follow");
  if (translucent) a.push_back("--translucent");
  if (build_planes) a.push_back("--build-planes");
  if (crofton_lines) a.push_back("--crofton-lines");
  if (flat_aa) a.push_back("--flat-aa");
  if (zoom) opt("zoom", double_text(*zoom));
  if (sample_overlay) a.push_back("--sample-overlay");
  if (!report.empty()) opt("report", report);
  return a;
}

}  // namespace raystep
