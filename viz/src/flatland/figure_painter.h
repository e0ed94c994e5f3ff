// A core figure (figure/figure.h) painted with QPainter, anti-aliased, as the SVG draws it: the 2D view's
// picture. The frame maps the figure's part of the plane into a widget's rectangle (y up, the aspect kept)
// and back, for the mouse; sizes in points (line widths, text) become pixels times the view's scale.
#pragma once

#include <QPointF>
#include <QRectF>

#include <glm/vec2.hpp>

#include "raystep/figure/figure.h"

class QPainter;

namespace raystep::viz {

struct FigureFrame {
  glm::vec2 lo{0.f}, hi{1.f};  // the figure's part of the plane
  QRectF target;               // where it is drawn, in widget pixels
  double pixelsPerUnit = 1.0;
  double pixelsPerPoint = 1.0;  // line widths and type

  // The largest rectangle of the figure's aspect centred in `area`; points at `pointScale` pixels each.
  static FigureFrame fit(const Figure& figure, const QRectF& area, double pointScale);
  QPointF map(glm::vec2 p) const;
  glm::vec2 unmap(QPointF q) const;
};

void paintFigureLayer(QPainter& painter, const FigureFrame& frame, const FigureLayer& layer);

}  // namespace raystep::viz
