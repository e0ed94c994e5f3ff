#include "raystep/figure/flat_figure.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>

#include "raystep/replay/explain.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/replayer.h"
#include "raystep/replay/slide_stack.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

// The debugger's meanings (viz/src/common/palette.h): current yellow, stacked pink, visited pale blue.
const glm::vec3 kInk(0.15f, 0.15f, 0.18f), kStructure(0.35f, 0.45f, 0.6f), kVisited(0.55f, 0.75f, 0.95f),
    kCurrent(1.f, 0.82f, 0.2f), kStacked(0.95f, 0.4f, 0.6f), kRay(0.85f, 0.1f, 0.1f),
    kTesting(0.9f, 0.35f, 0.0f), kMailbox(0.45f, 0.2f, 0.65f), kTick(0.1f, 0.45f, 0.25f);

FigureItem line(glm::vec2 a, glm::vec2 b, glm::vec3 colour, float width, const std::string& css) {
  FigureItem it;
  it.kind = FigureItem::Kind::line;
  it.points = {a, b};
  it.style.stroke = colour;
  it.style.stroke_width = width;
  it.css = css;
  return it;
}

FigureItem polygon(const std::vector<glm::vec2>& points, glm::vec3 stroke, float width, glm::vec3 fill,
                   float opacity, const std::string& css) {
  FigureItem it;
  it.kind = FigureItem::Kind::polygon;
  it.points = points;
  it.style.stroke = stroke;
  it.style.stroke_width = width;
  it.style.has_stroke = width > 0.f;
  it.style.fill = fill;
  it.style.fill_opacity = opacity;
  it.css = css;
  return it;
}

FigureItem dot(glm::vec2 p, float radius, glm::vec3 colour, const std::string& css) {
  FigureItem it;
  it.kind = FigureItem::Kind::circle;
  it.points = {p};
  it.radius = radius;
  it.style.has_stroke = false;
  it.style.fill = colour;
  it.style.fill_opacity = 1.f;
  it.css = css;
  return it;
}

// A shape drawn again over itself, in a mark's colour (no fill): the one tested, those in the mailbox.
FigureItem shape_outline(const FlatShape& s, glm::vec3 colour, float width, const std::string& css) {
  FigureItem it;
  if (s.kind == FlatShape::Kind::circle) {
    it.kind = FigureItem::Kind::circle;
    it.points = {s.center};
    it.radius = s.radius;
  } else {
    it.kind = s.kind == FlatShape::Kind::polygon ? FigureItem::Kind::polygon : FigureItem::Kind::polyline;
    it.points = s.points;
  }
  it.style.stroke = colour;
  it.style.stroke_width = width;
  it.style.fill_opacity = 0.f;
  it.css = css;
  return it;
}

const OutlineRegion* region_of(const PlaneOutline& o, int32_t node) {
  if (node >= 0 && size_t(node) < o.regions.size() && o.regions[size_t(node)].node == node)
    return &o.regions[size_t(node)];
  return nullptr;
}

// The shapes as the slides draw them: walls as lines, filled polygons and circles with their material.
FigureLayer shapes_layer(const Scene& scene) {
  FigureLayer layer{"shapes", {}};
  for (const FlatShape& s : scene.flat->shapes) {
    const glm::vec3 colour = s.material < scene.materials.size() ? scene.materials[s.material].diffuse : kInk;
    switch (s.kind) {
      case FlatShape::Kind::segment:
      case FlatShape::Kind::polyline: {
        FigureItem it;
        it.kind = FigureItem::Kind::polyline;
        it.points = s.points;
        it.style.stroke = kInk;
        it.style.stroke_width = 1.6f;
        it.css = "shape " + std::string(flat_kind_name(s.kind));
        layer.items.push_back(it);
        break;
      }
      case FlatShape::Kind::polygon:
        layer.items.push_back(polygon(s.points, kInk, 1.6f, colour, s.filled ? 1.f : 0.35f, "shape polygon"));
        break;
      case FlatShape::Kind::circle: {
        FigureItem it = dot(s.center, s.radius, colour, "shape circle");
        it.style.fill_opacity = 0.35f;
        it.style.has_stroke = true;
        it.style.stroke = kInk;
        it.style.stroke_width = 1.6f;
        layer.items.push_back(it);
        break;
      }
    }
  }
  return layer;
}

// built_up_to >= 0: only the splits (a BVH: the boxes) of the nodes made so far, 0 .. built_up_to.
FigureLayer structure_layer(const PlaneOutline& o, int32_t built_up_to) {
  auto built = [built_up_to](int32_t node) { return built_up_to < 0 || node <= built_up_to; };
  FigureLayer layer{"structure", {}};
  layer.items.push_back(polygon({{o.lo.x, o.lo.y}, {o.hi.x, o.lo.y}, {o.hi.x, o.hi.y}, {o.lo.x, o.hi.y}},
                                kStructure, 1.4f, glm::vec3(1.f), 0.f, "root"));
  if (o.boxes) {
    for (const OutlineRegion& r : o.regions)
      if (r.node > 0 && built(r.node))
        layer.items.push_back(polygon(r.polygon, kStructure, std::max(0.5f, 1.3f - 0.12f * float(r.depth)),
                                      glm::vec3(1.f), 0.f, r.leaf ? "box leaf" : "box"));
    return layer;
  }
  for (const OutlineLine& l : o.lines)
    if (l.node < 0 || built(l.node))
      layer.items.push_back(line(l.a, l.b, kStructure,
                                 l.node < 0 ? 0.6f : std::max(0.5f, 1.4f - 0.15f * float(l.depth)),
                                 l.node < 0 ? "grid-line" : "split"));
  return layer;
}

}  // namespace

Figure flat_figure_still(const Scene& scene, const PlaneOutline* outline, const glm::vec2* origin,
                         int32_t built_up_to) {
  if (!scene.flat) throw InputError("", 0, "a figure draws a 2D scene (\"dimensions\": 2); this scene is 3D");
  const Flatland& flat = *scene.flat;
  Figure fig;
  glm::vec2 lo = flat.lo, hi = flat.hi;
  if (outline) {
    lo = glm::min(lo, outline->lo);
    hi = glm::max(hi, outline->hi);
  }
  if (origin) {  // the ray's origin in the picture
    lo = glm::min(lo, *origin);
    hi = glm::max(hi, *origin);
  }
  const glm::vec2 margin = 0.04f * glm::vec2(std::max(hi.x - lo.x, hi.y - lo.y));
  fig.lo = lo - margin;
  fig.hi = hi + margin;
  if (outline) fig.layers.push_back(structure_layer(*outline, built_up_to));
  if (outline && built_up_to < 0) {  // the leaves' names, where they are few enough to read
    FigureLayer labels{"labels", {}};
    size_t leaves = 0;
    for (const OutlineRegion& r : outline->regions) leaves += r.leaf;
    if (leaves <= 24 && !outline->boxes)
      for (const OutlineRegion& r : outline->regions) {
        if (!r.leaf || r.path.empty() || r.polygon.empty()) continue;
        // Only where the name fits: a deep leaf's cell is too small for its long path (they would overlap).
        glm::vec2 rlo = r.polygon[0], rhi = r.polygon[0];
        for (const glm::vec2& p : r.polygon) rlo = glm::min(rlo, p), rhi = glm::max(rhi, p);
        const float span = std::max(fig.hi.x - fig.lo.x, fig.hi.y - fig.lo.y);
        if (std::min(rhi.x - rlo.x, rhi.y - rlo.y) < 0.05f * span ||
            rhi.x - rlo.x < 0.018f * span * float(r.path.size()))
          continue;
        glm::vec2 c(0.f);
        for (const glm::vec2& p : r.polygon) c += p;
        FigureItem it;
        it.kind = FigureItem::Kind::text;
        it.points = {c / float(r.polygon.size())};
        it.text = r.path;
        it.radius = 11.f;
        it.style.fill = kStructure;
        it.css = "leaf-name";
        labels.items.push_back(it);
      }
    if (!labels.items.empty()) fig.layers.push_back(std::move(labels));
  }
  fig.layers.push_back(shapes_layer(scene));
  return fig;
}

FlatWalkLayers flat_figure_walk(const FlatFigureInput& in, const Figure& still) {
  if (!in.scene || !in.scene->flat)
    throw InputError("", 0, "a figure draws a 2D scene (\"dimensions\": 2); this scene is 3D");
  const Flatland& flat = *in.scene->flat;
  const Figure& fig = still;
  const float unit = std::max(fig.hi.x - fig.lo.x, fig.hi.y - fig.lo.y);
  const TracedRay* ray = in.trace && !in.trace->rays.empty() ? &in.trace->rays[0] : nullptr;
  // The walk after the step.
  std::optional<replay::ReplayState> state;
  if (ray) {
    const int n = int(ray->events.size());
    if (in.step >= n)
      throw InputError("", 0,
                       "--step " + std::to_string(in.step) + ": the walk has " + std::to_string(n) +
                           " events (steps 0.." + std::to_string(n - 1) + ")");
    const replay::Replayer replayer(*ray);
    state = replayer.at(in.step < 0 ? n - 1 : in.step);
  }

  FigureLayer walk{"walk", {}};
  if (state && in.outline) {
    const PlaneOutline& o = *in.outline;
    const Trace& t = *in.trace;
    auto cell_box = [&](int event) -> const Bounds3* {
      const Event& e = ray->events[size_t(event)];
      for (const TraceCell& c : t.cells)
        if (c.cell[0] == e.cell[0] && c.cell[1] == e.cell[1] && c.cell[2] == e.cell[2]) return &c.box;
      return nullptr;
    };
    auto box_polygon = [](const Bounds3& b) {
      return std::vector<glm::vec2>{{b.lo.x, b.lo.y}, {b.hi.x, b.lo.y}, {b.hi.x, b.hi.y}, {b.lo.x, b.hi.y}};
    };
    for (int e : state->visited_cell_events)
      if (const Bounds3* b = cell_box(e))
        walk.items.push_back(polygon(box_polygon(*b), kVisited, 0.f, kVisited, 0.45f, "visited"));
    if (state->cell_event >= 0 && !state->ended)
      if (const Bounds3* b = cell_box(state->cell_event))
        walk.items.push_back(polygon(box_polygon(*b), kInk, 1.2f, kCurrent, 0.6f, "current"));
    // Trees: the leaves visited (inner nodes hold them all), the stack's nodes, the current node.
    for (int32_t id : state->visited_nodes) {
      const OutlineRegion* r = region_of(o, id);
      if (r && r->leaf) walk.items.push_back(polygon(r->polygon, kVisited, 0.f, kVisited, 0.45f, "visited"));
    }
    for (const replay::StackEntry& st : state->stack)  // what waits when the walk ends is never walked
      if (const OutlineRegion* r = state->ended ? nullptr : region_of(o, st.node)) {
        FigureItem it = polygon(r->polygon, kStacked, 1.8f, kStacked, 0.12f, "stacked");
        it.style.dashed = true;
        walk.items.push_back(it);
      }
    if (state->node_event >= 0 && !state->ended)
      if (const OutlineRegion* r = region_of(o, ray->events[size_t(state->node_event)].node))
        walk.items.push_back(polygon(r->polygon, kInk, 1.6f, kCurrent, 0.5f, "current"));
  }

  FigureLayer ray_layer{"ray", {}};
  if (ray || flat.has_ray) {
    const glm::vec2 o = ray ? glm::vec2(ray->ray.origin) : flat.ray_origin;
    glm::vec2 d = ray ? glm::vec2(ray->ray.direction) : flat.ray_direction;
    const float len = glm::length(d);
    if (len > 0.f) {
      // To the frame's edge: the largest t with o + t d inside it.
      float t_end = kInfinity;
      for (int a = 0; a < 2; ++a)
        if (d[a] != 0.f) t_end = std::min(t_end, ((d[a] > 0.f ? fig.hi[a] : fig.lo[a]) - o[a]) / d[a]);
      if (!std::isfinite(t_end) || t_end < 0.f) t_end = 0.f;
      ray_layer.items.push_back(line(o, o + t_end * d, kRay, 1.f, "ray"));
      if (state && state->has_interval && !state->ended)
        ray_layer.items.push_back(
            line(o + state->t_min * d, o + std::min(state->t_max, t_end) * d, kRay, 3.5f, "interval"));
      ray_layer.items.push_back(dot(o, 0.008f * unit, kRay, "origin"));
      if (state && state->nearest_prim >= 0) {
        FigureItem hit =
            dot(o + state->nearest_t * d, 0.009f * unit, kRay, state->accepted ? "hit final" : "hit");
        hit.style.has_stroke = true;
        hit.style.stroke = kInk;
        ray_layer.items.push_back(hit);
      }
    }
  }

  // Over the shapes: the mailbox's shapes (tested already, dashed), the shape tested at this step, and for a
  // grid the 3D-DDA's next boundaries along the ray: tMax x and tMax y, then tDelta further on each axis.
  FigureLayer marks{"marks", {}};
  if (state && ray && !state->ended) {
    auto shape_of = [&](int32_t prim) -> const FlatShape* {
      const int s = prim < 0 ? -1 : flat.shape_of(uint32_t(prim));
      return s < 0 ? nullptr : &flat.shapes[size_t(s)];
    };
    std::vector<const FlatShape*> drawn;
    for (const replay::MailboxEntry& m : state->mailbox)
      if (const FlatShape* s = shape_of(m.prim); s && std::find(drawn.begin(), drawn.end(), s) == drawn.end()) {
        FigureItem it = shape_outline(*s, kMailbox, 2.6f, "mailboxed");
        it.style.dashed = true;
        marks.items.push_back(it);
        drawn.push_back(s);
      }
    const Event& e = *state->event;
    if (e.type == EventType::prim_test || e.type == EventType::mailbox_hit)
      if (const FlatShape* s = shape_of(e.prim))
        marks.items.push_back(shape_outline(*s, e.type == EventType::mailbox_hit ? kMailbox : kTesting, 4.f,
                                            e.type == EventType::mailbox_hit ? "mailbox-hit" : "testing"));
    const glm::vec2 o(ray->ray.origin), d(ray->ray.direction);
    const float len = glm::length(d);
    // A kd-tree's or BSP tree's inner node: t*, where the ray meets its split, ticked on the ray.
    if (len > 0.f && state->node_event >= 0 && replay::is_tree_ray(*ray)) {
      const replay::NodeCrossing x = replay::node_crossing(*in.trace, *ray, *state);
      if (x.valid && std::isfinite(x.t_star) && x.t_star >= 0.f) {
        const glm::vec2 p = o + x.t_star * d, across = glm::vec2(-d.y, d.x) / len;
        const float tick = 0.022f * unit;
        if (p.x >= fig.lo.x && p.y >= fig.lo.y && p.x <= fig.hi.x && p.y <= fig.hi.y) {
          marks.items.push_back(line(p - tick * across, p + tick * across, kInk, 2.2f, "t-star"));
          marks.items.push_back(figure_text(p + 2.2f * tick * across, "t*", 11.f, kInk, "t-star-label"));
        }
      }
    }
    if (state->cell_event >= 0 && len > 0.f) {
      const Event& c = ray->events[size_t(state->cell_event)];
      const glm::vec2 across = glm::vec2(-d.y, d.x) / len;
      const float tick = 0.018f * unit;
      for (int a = 0; a < 2; ++a) {
        if (!std::isfinite(c.t_delta[a]) || !std::isfinite(c.t_max[a]) || c.t_delta[a] <= 0.f) continue;
        const std::string axis = a == 0 ? "x" : "y";
        for (int k = 0; k < 3; ++k) {
          const float t = c.t_max[a] + float(k) * c.t_delta[a];
          const glm::vec2 p = o + t * d;
          if (p.x < fig.lo.x || p.y < fig.lo.y || p.x > fig.hi.x || p.y > fig.hi.y) break;
          // x ticks on one side of the ray, y ticks on the other, so that the two never share a label.
          const glm::vec2 side = (a == 0 ? 1.f : -1.f) * across;
          marks.items.push_back(line(p - 0.5f * tick * side, p + tick * side, kTick, k == 0 ? 2.2f : 1.f,
                                     k == 0 ? "tmax-" + axis : "tdelta-" + axis));
          if (k == 0) marks.items.push_back(figure_text(p + 2.4f * tick * side, "tMax " + axis, 10.f, kTick, "tmax-label"));
        }
      }
    }
  }

  FlatWalkLayers out;
  out.walk = std::move(walk);
  out.marks = std::move(marks);
  out.ray = std::move(ray_layer);
  if (state) {
    // The event's line without its index (the step says it): "node  3 depth 3  t 0.2..1.6".
    std::string event = replay::describe_event(*state->event);
    const size_t words = event.find_first_not_of("0123456789 ");
    if (words != std::string::npos && words > 0 && std::isdigit(static_cast<unsigned char>(event[0])))
      event = event.substr(words);
    out.caption.push_back("Step " + std::to_string(state->step) + " of " + std::to_string(ray->events.size() - 1) +
                          ": " + event);
    const std::string slides = state->ended ? "" : replay::slide_stack_text(*in.trace, *ray, *state);
    if (!slides.empty()) out.caption.push_back(slides);
    if (state->cell_event >= 0 && !state->ended) {  // the 3D-DDA's numbers, as the ticks draw them
      const Event& c = ray->events[size_t(state->cell_event)];
      auto num = [](float v) {
        if (!std::isfinite(v)) return std::string("inf");
        char b[32];
        std::snprintf(b, sizeof b, "%.3g", double(v));
        return std::string(b);
      };
      out.caption.push_back("tMax x " + num(c.t_max.x) + ", y " + num(c.t_max.y) + "   tDelta x " +
                            num(c.t_delta.x) + ", y " + num(c.t_delta.y) + "   next step: " +
                            (c.next_axis < 0 ? std::string("none (the walk ends here)")
                                             : std::string(replay::axis_name(c.next_axis))));
    }
  }
  return out;
}

Figure flat_figure(const FlatFigureInput& in) {
  if (!in.scene || !in.scene->flat)
    throw InputError("", 0, "a figure draws a 2D scene (\"dimensions\": 2); this scene is 3D");
  const TracedRay* ray = in.trace && !in.trace->rays.empty() ? &in.trace->rays[0] : nullptr;
  const glm::vec2 origin = ray ? glm::vec2(ray->ray.origin) : in.scene->flat->ray_origin;
  Figure fig = flat_figure_still(*in.scene, in.outline, ray || in.scene->flat->has_ray ? &origin : nullptr);
  FlatWalkLayers walk = flat_figure_walk(in, fig);
  // Under the shapes, over the structure and the names; the ray on top.
  fig.layers.insert(fig.layers.end() - 1, std::move(walk.walk));
  if (!walk.marks.items.empty()) fig.layers.push_back(std::move(walk.marks));
  fig.layers.push_back(std::move(walk.ray));
  fig.caption = std::move(walk.caption);
  fig.caption_points = 16.f * float(fig.caption.size()) + (fig.caption.empty() ? 0.f : 8.f);
  return fig;
}

}  // namespace raystep
