// A figure for slides: layers of plain 2D items (lines, polygons, circles, text) in the scene's own
// coordinates, with their styles, that any back end draws alike (figure_file.h: SVG with text as text and one
// group per layer, PDF, PNG). Built by flat_figure.h from a 2D scene, a structure and a walk.
#pragma once

#include <string>
#include <vector>

#include <glm/vec2.hpp>
#include <glm/vec3.hpp>

namespace raystep {

struct FigureStyle {
  glm::vec3 stroke{0.f};
  float stroke_width = 1.f;  // in points (1/72 inch at the figure's width)
  bool has_stroke = true;
  glm::vec3 fill{1.f};
  float fill_opacity = 0.f;  // 0: no fill
  bool dashed = false;
};

struct FigureItem {
  enum class Kind { line, polyline, polygon, circle, text };
  Kind kind = Kind::line;
  std::vector<glm::vec2> points;  // line: 2; polyline: 2+ (open); polygon: 3+ (closed); circle, text: 1
  float radius = 0.f;             // circle, in scene units; text: the size in points
  std::string text;
  std::string css;  // a class for restyling the SVG ("leaf", "current", ...)
  FigureStyle style;
};

// A text item centred on p, `points` tall.
inline FigureItem figure_text(glm::vec2 p, const std::string& words, float points, glm::vec3 colour,
                              const std::string& css) {
  FigureItem it;
  it.kind = FigureItem::Kind::text;
  it.points = {p};
  it.text = words;
  it.radius = points;
  it.style.fill = colour;
  it.css = css;
  return it;
}

struct FigureLayer {
  std::string name;  // the SVG group's id: "cells", "shapes", "ray", ...
  std::vector<FigureItem> items;
};

struct Figure {
  glm::vec2 lo{0.f}, hi{1.f};  // the part of the plane shown
  float caption_points = 0.f;  // room under the picture for the caption lines, in points
  std::vector<std::string> caption;
  std::vector<FigureLayer> layers;
};

}  // namespace raystep
