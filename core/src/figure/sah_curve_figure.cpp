#include "raystep/figure/sah_curve_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

namespace raystep {

namespace {

// One candidate on the chart: its axis, its position across the node (0..1) and its cost.
struct Dot {
  int axis = 0;
  float t = 0.f, cost = 0.f;
  bool spatial = false;  // an SBVH's spatial candidate: its own dashed series
};

struct Decision {
  bool leaf = false;
  int chosen = -1;     // index into the dots
  std::string words;   // "split z at 0.31: C = 25.1" or "leaf: every split costs at least N t_i"
};

std::string fixed(double v, int digits) {
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  return b;
}

float across(const Bounds3& box, int axis, float position) {
  const float lo = box.lo[axis], hi = box.hi[axis];
  return hi > lo ? std::clamp((position - lo) / (hi - lo), 0.f, 1.f) : 0.5f;
}

// The chart in a frame 1.6 wide and 1.06 tall (y up): the plot from (x0, y0) to (x1, y1), labels around it.
Figure chart(const std::vector<Dot>& dots, float leaf_cost, const Decision& decision,
             std::vector<std::string> caption) {
  constexpr float x0 = 0.2f, x1 = 1.5f, y0 = 0.14f, y1 = 0.86f;
  const glm::vec3 axis_colour[3] = {{0.85f, 0.2f, 0.15f}, {0.15f, 0.6f, 0.2f}, {0.15f, 0.35f, 0.85f}};
  const glm::vec3 ink{0.1f}, grey{0.55f};
  float top = leaf_cost;
  for (const Dot& d : dots)
    if (std::isfinite(d.cost)) top = std::max(top, d.cost);
  // Round ticks: 1, 2 or 5 times a power of ten, four or five of them.
  const double raw = std::max(1e-30, double(top) / 4.0), ten = std::pow(10.0, std::floor(std::log10(raw)));
  const double tick = raw / ten <= 1.0 ? ten : raw / ten <= 2.0 ? 2 * ten : raw / ten <= 5.0 ? 5 * ten : 10 * ten;
  top = float(tick * std::ceil(double(top) / tick * 1.0001));
  if (!(top > 0.f)) top = 1.f;
  auto at = [&](float t, float cost) {
    return glm::vec2(x0 + (x1 - x0) * t, y0 + (y1 - y0) * std::clamp(cost / top, 0.f, 1.f));
  };
  Figure f;
  f.lo = {0.f, 0.f};
  f.hi = {1.6f, 1.06f};
  FigureLayer frame{"axes", {}}, curves{"curves", {}}, answer{"decision", {}};
  auto line = [](glm::vec2 a, glm::vec2 b, glm::vec3 colour, float width, bool dashed, const std::string& css) {
    FigureItem it;
    it.kind = FigureItem::Kind::line;
    it.points = {a, b};
    it.style.stroke = colour;
    it.style.stroke_width = width;
    it.style.dashed = dashed;
    it.css = css;
    return it;
  };
  frame.items.push_back(line({x0, y0}, {x1, y0}, ink, 1.f, false, "axis"));
  frame.items.push_back(line({x0, y0}, {x0, y1}, ink, 1.f, false, "axis"));
  for (int k = 0; k <= 4; ++k) {
    const float t = float(k) / 4.f;
    frame.items.push_back(figure_text({x0 + (x1 - x0) * t, y0 - 0.05f}, fixed(t, 2), 12.f, ink, "tick"));
  }
  for (double c = 0.0; c <= double(top) * 1.0001; c += tick)
    frame.items.push_back(figure_text({x0 - 0.075f, at(0.f, float(c)).y}, fixed(c, tick < 1.0 ? 2 : 0), 12.f, ink,
                                      "tick"));
  frame.items.push_back(
      figure_text({0.5f * (x0 + x1), 0.035f}, "plane position across the node (0 = min, 1 = max)", 13.f, ink, "label"));
  frame.items.push_back(figure_text({x0 + 0.02f, y1 + 0.05f}, "cost C", 13.f, ink, "label"));
  // The leaf cost: a split pays only below it.
  frame.items.push_back(line(at(0.f, leaf_cost), at(1.f, leaf_cost), grey, 1.5f, true, "leaf-cost"));
  frame.items.push_back(figure_text(at(0.86f, leaf_cost) + glm::vec2(0.f, 0.035f),
                                    "leaf: N t_i = " + fixed(leaf_cost, 0), 12.f, grey, "leaf-cost"));
  bool any_spatial = false;
  for (const Dot& d : dots) any_spatial |= d.spatial;
  if (any_spatial)
    frame.items.push_back(figure_text({x1 - 0.24f, y1 + 0.015f}, "dashed: spatial splits", 11.f, grey, "label"));
  for (int axis = 0; axis < 3; ++axis) {
    const char* name[3] = {"x", "y", "z"};
    frame.items.push_back(figure_text({x1 - 0.24f + 0.09f * float(axis), y1 + 0.05f}, name[axis], 15.f,
                                      axis_colour[axis], std::string("axis-") + name[axis]));
    for (bool spatial : {false, true}) {
      std::vector<Dot> mine;
      for (const Dot& d : dots)
        if (d.axis == axis && d.spatial == spatial && std::isfinite(d.cost)) mine.push_back(d);
      std::stable_sort(mine.begin(), mine.end(), [](const Dot& a, const Dot& b) { return a.t < b.t; });
      if (mine.empty()) continue;
      const std::string kind = spatial ? " spatial" : "";
      FigureItem poly;
      poly.kind = FigureItem::Kind::polyline;
      for (const Dot& d : mine) poly.points.push_back(at(d.t, d.cost));
      poly.style.stroke = axis_colour[axis];
      poly.style.stroke_width = 1.f;
      poly.style.dashed = spatial;
      poly.css = std::string("curve-") + name[axis] + kind;
      if (poly.points.size() >= 2) curves.items.push_back(poly);
      for (const Dot& d : mine) {
        FigureItem dot;
        dot.kind = FigureItem::Kind::circle;
        dot.points = {at(d.t, d.cost)};
        dot.radius = spatial ? 0.004f : 0.006f;
        dot.style.has_stroke = false;
        dot.style.fill = axis_colour[axis];
        dot.style.fill_opacity = 1.f;
        dot.css = std::string("candidate-") + name[axis] + kind;
        curves.items.push_back(dot);
      }
    }
  }
  if (decision.chosen >= 0) {
    const Dot& d = dots[size_t(decision.chosen)];
    answer.items.push_back(line(at(d.t, 0.f), at(d.t, top), axis_colour[d.axis], 1.5f, false, "answer chosen"));
    FigureItem ring;
    ring.kind = FigureItem::Kind::circle;
    ring.points = {at(d.t, d.cost)};
    ring.radius = 0.014f;
    ring.style.stroke = ink;
    ring.style.stroke_width = 1.5f;
    ring.css = "answer chosen";
    answer.items.push_back(ring);
  }
  answer.items.push_back(figure_text({0.5f * (x0 + x1), 1.015f}, decision.words, 13.f, ink, "answer"));
  f.layers = {std::move(frame), std::move(curves), std::move(answer)};
  f.caption = std::move(caption);
  f.caption_points = 16.f * float(f.caption.size());
  return f;
}

std::string node_words(uint32_t node, const std::string& path, int depth, uint32_t n) {
  const std::string where = node == 0 ? " (the root)" : path.empty() ? "" : " (path " + path + ")";
  return "node " + std::to_string(node) + where + ", depth " +
         std::to_string(depth) + ", N = " + std::to_string(n) + " primitives";
}

std::string candidates_words(size_t n) { return std::to_string(n) + (n == 1 ? " candidate" : " candidates"); }

const char* axis_name(int axis) { return axis == 0 ? "x" : axis == 1 ? "y" : "z"; }

// "chosen: split x at 0.110, C = 225024.8 (N below 2573, above 2171)"
std::string split_words(int axis, float position, float cost, const char* one, uint32_t n_one, const char* other,
                        uint32_t n_other) {
  return std::string("chosen: split ") + axis_name(axis) + " at " + fixed(position, 3) + ", C = " + fixed(cost, 1) +
         " (N " + one + " " + std::to_string(n_one) + ", " + other + " " + std::to_string(n_other) + ")";
}

}  // namespace

Figure sah_curve_figure(const SahCurve& curve, const std::string& path) {
  std::vector<Dot> dots;
  for (const SahCandidate& c : curve.candidates)
    dots.push_back({c.axis, across(curve.info.box, c.axis, c.position), c.cost});
  const SahCandidate* c = curve.chosen >= 0 ? &curve.candidates[size_t(curve.chosen)] : nullptr;
  const Decision d{curve.leaf, curve.chosen,
                   c ? split_words(c->axis, c->position, c->cost, "below", c->n_below, "above", c->n_above)
                     : std::string("a leaf: ") + leaf_reason_name(curve.leaf_reason)};
  return chart(dots, curve.leaf_cost, d,
               {"The SAH cost of every candidate plane, kd-tree " +
                    node_words(curve.node, path, curve.info.depth, curve.n_prims),
                candidates_words(curve.candidates.size()) + ": C = t_t + p_a N_a t_i + p_b N_b t_i"});
}

Figure sah_curve_figure(const BvhSahCurve& curve, const std::string& path) {
  std::vector<Dot> dots;
  for (const BvhCandidate& c : curve.candidates)
    dots.push_back({c.axis, across(curve.bvh_node.box, c.axis, c.position), c.cost, c.spatial});
  const BvhCandidate* c = curve.chosen >= 0 ? &curve.candidates[size_t(curve.chosen)] : nullptr;
  std::string words = c ? split_words(c->axis, c->position, c->cost, "left", c->n_left, "right", c->n_right)
                        : std::string("a leaf: ") + bvh_leaf_reason_name(curve.leaf_reason);
  if (c && c->spatial) words.replace(0, std::string("chosen: split").size(), "chosen: spatial split");
  const Decision d{curve.leaf, curve.chosen, words};
  return chart(dots, curve.leaf_cost, d,
               {"The SAH cost of every candidate split, BVH " +
                    node_words(curve.node, path, curve.info.depth, curve.info.prims),
                candidates_words(curve.candidates.size()) + ": C = t_t + p_l N_l t_i + p_r N_r t_i"});
}

}  // namespace raystep
