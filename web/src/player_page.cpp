#include "raystep/web/player_page.h"

#include <zlib.h>

#include <algorithm>
#include <array>
#include <cmath>
#include <map>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "player_data.h"
#include "raystep/figure/figure_file.h"
#include "raystep/figure/flat_figure.h"
#include "raystep/replay/explain.h"
#include "raystep/replay/replayer.h"
#include "raystep/replay/storyboard.h"
#include "raystep/util/error.h"
#include "raystep/util/xml_escape.h"
#include "web_assets.h"

namespace raystep::web {

namespace {

// The figure's layers named, in the frame of `frame` (so that every SVG of a step lies on the others).
Figure layers_of(const Figure& frame, std::vector<FigureLayer> layers) {
  Figure f;
  f.lo = frame.lo;
  f.hi = frame.hi;
  f.layers = std::move(layers);
  return f;
}

// One ray's picture at every step, as the 2D view paints it: the structure under the walk, the shapes over
// it, the marks and the ray on top; the still parts once, the walk's per step.
ordered flat_picture(const Scene& scene, const Trace& walk, size_t ray_index, const PlaneOutline* outline,
                     int width) {
  Trace one = walk;
  one.rays = {walk.rays[ray_index]};
  const TracedRay& ray = one.rays[0];
  const glm::vec2 origin(ray.ray.origin);
  const Figure still = flat_figure_still(scene, outline, &origin);
  std::vector<FigureLayer> under, over;
  for (const FigureLayer& l : still.layers) (l.name == "shapes" ? over : under).push_back(l);
  ordered p;
  p["width"] = width;
  p["under"] = figure_svg(layers_of(still, under), width, false);
  p["over"] = figure_svg(layers_of(still, over), width, false);
  ordered walks = ordered::array(), tops = ordered::array(), captions = ordered::array();
  FlatFigureInput fin;
  fin.scene = &scene;
  fin.outline = outline;
  fin.trace = &one;
  for (int k = 0; k < int(ray.events.size()); ++k) {
    fin.step = k;
    FlatWalkLayers w = flat_figure_walk(fin, still);
    walks.push_back(figure_svg(layers_of(still, {std::move(w.walk)}), width, false));
    tops.push_back(figure_svg(layers_of(still, {std::move(w.marks), std::move(w.ray)}), width, false));
    captions.push_back(w.caption);
  }
  p["walk"] = std::move(walks);
  p["top"] = std::move(tops);
  p["caption"] = std::move(captions);
  return p;
}

// A walk's 3D picture (the page's three.js view): the boxes the trace carries (its cells, or its nodes), and
// at each step the current one, the stack's and the interval on the ray. The page marks as visited the
// boxes that were current before.
ordered walk3d(const Trace& t, const TracedRay& ray) {
  ordered boxes = ordered::array();
  std::map<std::array<int, 3>, int> cell_box;
  std::map<int32_t, int> node_box;
  auto box = [](const Bounds3& b, bool leaf) {
    return ordered::array({b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z, leaf ? 1 : 0});
  };
  for (const TraceCell& c : t.cells) {
    cell_box[{c.cell[0], c.cell[1], c.cell[2]}] = int(boxes.size());
    boxes.push_back(box(c.box, true));
  }
  for (const TraceNode& n : t.nodes) {
    node_box[n.id] = int(boxes.size());
    boxes.push_back(box(n.box, n.leaf));
  }
  ordered current = ordered::array(), stacks = ordered::array(), intervals = ordered::array();
  const replay::Replayer replayer(ray);
  for (int k = 0; k < replayer.size(); ++k) {
    const replay::ReplayState s = replayer.at(k);
    int cur = -1;
    if (s.cell_event >= 0) {
      const Event& e = ray.events[size_t(s.cell_event)];
      if (auto it = cell_box.find({e.cell[0], e.cell[1], e.cell[2]}); it != cell_box.end()) cur = it->second;
    } else if (s.node_event >= 0) {
      if (auto it = node_box.find(ray.events[size_t(s.node_event)].node); it != node_box.end())
        cur = it->second;
    }
    current.push_back(s.ended ? -1 : cur);
    ordered stack = ordered::array();
    if (!s.ended)
      for (const replay::StackEntry& e : s.stack)
        if (auto it = node_box.find(e.node); it != node_box.end()) stack.push_back(it->second);
    stacks.push_back(std::move(stack));
    if (s.has_interval && !s.ended && std::isfinite(s.t_min) && std::isfinite(s.t_max))
      intervals.push_back(ordered::array({s.t_min, s.t_max}));
    else
      intervals.push_back(nullptr);
  }
  const replay::ReplayState end = replayer.at(replayer.size() - 1);
  ordered w;
  w["origin"] = ordered::array({ray.ray.origin.x, ray.ray.origin.y, ray.ray.origin.z});
  w["direction"] = ordered::array({ray.ray.direction.x, ray.ray.direction.y, ray.ray.direction.z});
  w["hit_t"] =
      end.nearest_prim >= 0 && std::isfinite(end.nearest_t) ? ordered(end.nearest_t) : ordered(nullptr);
  w["boxes"] = std::move(boxes);
  w["current"] = std::move(current);
  w["stack"] = std::move(stacks);
  w["interval"] = std::move(intervals);
  return w;
}

std::string gzip(const std::string& text) {
  z_stream z{};
  if (deflateInit2(&z, 9, Z_DEFLATED, 15 + 16, 9, Z_DEFAULT_STRATEGY) != Z_OK)
    throw std::runtime_error("export-html: zlib did not start");
  std::string out(deflateBound(&z, uLong(text.size())), '\0');
  z.next_in = reinterpret_cast<Bytef*>(const_cast<char*>(text.data()));
  z.avail_in = uInt(text.size());
  z.next_out = reinterpret_cast<Bytef*>(out.data());
  z.avail_out = uInt(out.size());
  const int r = deflate(&z, Z_FINISH);
  out.resize(z.total_out);
  deflateEnd(&z);
  if (r != Z_STREAM_END) throw std::runtime_error("export-html: zlib did not finish");
  return out;
}

}  // namespace

std::string base64(const std::string& bytes, bool wrap) {
  static const char* k = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4 + bytes.size() / 57 + 1);
  size_t i = 0;
  for (; i + 2 < bytes.size(); i += 3) {
    const uint32_t v =
        uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], k[v & 63]};
    if (wrap && (i / 3 + 1) % 19 == 0) out += '\n';  // 76 characters a line
  }
  if (i + 1 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16;
    out += {k[v >> 18], k[(v >> 12) & 63], '=', '='};
  } else if (i + 2 == bytes.size()) {
    const uint32_t v = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8;
    out += {k[v >> 18], k[(v >> 12) & 63], k[(v >> 6) & 63], '='};
  }
  return out;
}

// The template with each @NAME@ marker replaced, in one pass: what is put in is never scanned again.
std::string fill(const std::string& tmpl, const std::vector<std::pair<std::string, std::string>>& values) {
  std::string out;
  size_t at = 0;
  while (at < tmpl.size()) {
    const size_t open = tmpl.find('@', at);
    if (open == std::string::npos) break;
    bool replaced = false;
    for (const auto& [name, value] : values)
      if (tmpl.compare(open, name.size(), name) == 0) {
        out.append(tmpl, at, open - at);
        out += value;
        at = open + name.size();
        replaced = true;
        break;
      }
    if (!replaced) {
      out.append(tmpl, at, open + 1 - at);
      at = open + 1;
    }
  }
  out.append(tmpl, std::min(at, tmpl.size()), std::string::npos);
  return out;
}

ordered ray_json(const Trace& t, size_t w, size_t i, const Scene* flat_scene, const PlaneOutline* outline,
                 int picture_width) {
  const TracedRay& ray = t.rays[i];
  ordered r;
  r["ray"] = i;
  r["kind"] = ray_kind_name(ray.kind);
  // The header `raystep replay` writes before the ray's states.
  r["header"] = "walk " + std::to_string(w) + " (" + t.structure.kind + "), ray " + std::to_string(i) + " (" +
                ray_kind_name(ray.kind) + "), " + std::to_string(ray.events.size()) + " events";
  ordered lines = ordered::array(), states = ordered::array();
  const replay::Replayer replayer(ray);
  for (int k = 0; k < replayer.size(); ++k) {
    const replay::ReplayState s = replayer.at(k);
    lines.push_back(replay::describe_event(ray.events[size_t(k)]));
    states.push_back(replay::state_text(t, ray, s));
  }
  r["lines"] = std::move(lines);
  r["states"] = std::move(states);
  if (flat_scene && flat_scene->flat)
    r["picture"] = flat_picture(*flat_scene, t, i, outline, picture_width);
  else
    r["walk3d"] = walk3d(t, ray);
  return r;
}

ordered scene3d_json(const Scene& scene, size_t max_triangles) {
  const Geometry& g = scene.geometry;
  ordered j;
  const Bounds3& b = g.bounds();
  j["bounds"] = ordered::array({b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z});
  std::vector<float> tri;
  ordered spheres = ordered::array();
  size_t triangles = 0;
  for (uint32_t id = 0; id < g.size(); ++id) {
    if (g.type(id) == PrimType::sphere) {
      const Sphere& sp = g.sphere(id);
      spheres.push_back(ordered::array({sp.center.x, sp.center.y, sp.center.z, sp.radius}));
    } else if (++triangles <= max_triangles) {
      for (int k = 0; k < 3; ++k)
        for (int a = 0; a < 3; ++a) tri.push_back(g.vertex(id, k)[a]);
    }
  }
  j["triangles"] = std::move(tri);
  j["spheres"] = std::move(spheres);
  j["omitted"] = triangles > max_triangles ? triangles - max_triangles : 0;
  return j;
}

ordered player_data(const PlayerInput& in) {
  if (!in.trace || in.trace->walks.empty()) throw InputError("", 0, "export-html: no trace to play");
  ordered d;
  d["format"] = "raystep-player";
  d["version"] = 1;
  d["title"] = in.title;
  d["source"] = in.source;
  ordered walks = ordered::array();
  size_t rays = 0;
  for (size_t w = 0; w < in.trace->walks.size(); ++w) {
    const Trace& t = in.trace->walks[w];
    ordered jw{{"walk", w}, {"structure", t.structure.kind}};
    ordered jr = ordered::array();
    for (size_t i = 0; i < t.rays.size(); ++i) {
      const TracedRay& ray = t.rays[i];
      if (ray.events.empty()) continue;
      ordered r = ray_json(t, w, i, in.flat_scene, w < in.outlines.size() ? in.outlines[w] : nullptr,
                           in.picture_width);
      jr.push_back(std::move(r));
      ++rays;
    }
    jw["rays"] = std::move(jr);
    walks.push_back(std::move(jw));
  }
  if (rays == 0) throw InputError("", 0, "export-html: the trace has no ray with events to play");
  d["walks"] = std::move(walks);
  if (in.scene3d && !in.flat_scene) {  // every walk is of the one scene
    d["scenes"] = ordered::array({scene3d_json(*in.scene3d, kMaxPageTriangles)});
    for (ordered& jw : d["walks"]) jw["scene"] = 0;
  }
  return d;
}

std::string player_data_json(const PlayerInput& in) {
  return player_data(in).dump();
}

std::string page_html(const std::string& title, const ordered& data) {
  // The 3D view's script (three.js, about 0.5 MB) only in a page with a 3D walk.
  bool walk3d = false;
  for (const ordered& w : data["walks"])
    for (const ordered& r : w["rays"]) walk3d |= r.contains("walk3d");
  // The styles and the script inlined; the data gzip-compressed, as base64 (the script inflates it with the
  // browser's DecompressionStream).
  return fill(assets::player_html, {{"@TITLE@", xml_escape(title)},
                                    {"@CSS@", assets::player_css},
                                    {"@DATA@", base64(gzip(data.dump()))},
                                    {"@VIEW3D@", walk3d ? assets::view3d_js : ""},
                                    {"@JS@", assets::player_js}});
}

std::string player_page(const PlayerInput& in) {
  return page_html(in.title, player_data(in));
}

}  // namespace raystep::web
