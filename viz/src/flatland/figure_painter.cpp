#include "flatland/figure_painter.h"

#include <algorithm>

#include <QPainter>
#include <QPainterPath>
#include <QPolygonF>

namespace raystep::viz {

namespace {

QColor colour(const glm::vec3& c, float opacity = 1.f) {
  return QColor::fromRgbF(std::clamp(c.r, 0.f, 1.f), std::clamp(c.g, 0.f, 1.f), std::clamp(c.b, 0.f, 1.f),
                          std::clamp(opacity, 0.f, 1.f));
}

}  // namespace

FigureFrame FigureFrame::fit(const Figure& figure, const QRectF& area, double pointScale) {
  FigureFrame f;
  f.lo = figure.lo;
  f.hi = figure.hi;
  const double w = std::max(1e-30, double(f.hi.x - f.lo.x)), h = std::max(1e-30, double(f.hi.y - f.lo.y));
  f.pixelsPerUnit = std::max(1e-30, std::min(area.width() / w, area.height() / h));
  const QSizeF size(w * f.pixelsPerUnit, h * f.pixelsPerUnit);
  f.target = QRectF(area.center() - QPointF(size.width() / 2, size.height() / 2), size);
  f.pixelsPerPoint = pointScale;
  return f;
}

QPointF FigureFrame::map(glm::vec2 p) const {
  return {target.left() + double(p.x - lo.x) * pixelsPerUnit, target.bottom() - double(p.y - lo.y) * pixelsPerUnit};
}

glm::vec2 FigureFrame::unmap(QPointF q) const {
  return {lo.x + float((q.x() - target.left()) / pixelsPerUnit), lo.y + float((target.bottom() - q.y()) / pixelsPerUnit)};
}

void paintFigureLayer(QPainter& painter, const FigureFrame& frame, const FigureLayer& layer) {
  painter.save();
  painter.setRenderHint(QPainter::Antialiasing, true);
  painter.setRenderHint(QPainter::TextAntialiasing, true);
  for (const FigureItem& it : layer.items) {
    const FigureStyle& s = it.style;
    if (it.kind == FigureItem::Kind::text) {
      QFont font = painter.font();
      font.setPixelSize(std::max(6, int(it.radius * frame.pixelsPerPoint + 0.5)));
      painter.setFont(font);
      painter.setPen(colour(s.fill));
      const QPointF p = frame.map(it.points[0]);
      const QFontMetricsF fm(font);
      const double width = fm.horizontalAdvance(QString::fromStdString(it.text));
      // Centred on its point, as the SVG's text-anchor middle.
      painter.drawText(QPointF(p.x() - width / 2, p.y() + 0.35 * fm.ascent()), QString::fromStdString(it.text));
      continue;
    }
    QPen pen(Qt::NoPen);
    if (s.has_stroke && s.stroke_width > 0.f) {
      pen = QPen(colour(s.stroke), std::max(0.5, double(s.stroke_width) * frame.pixelsPerPoint));
      pen.setCapStyle(Qt::RoundCap);
      pen.setJoinStyle(Qt::RoundJoin);
      if (s.dashed) pen.setDashPattern({3.0, 2.0});  // in pen widths, as the SVG's 3w,2w
    }
    painter.setPen(pen);
    painter.setBrush(s.fill_opacity > 0.f ? QBrush(colour(s.fill, s.fill_opacity)) : QBrush(Qt::NoBrush));
    switch (it.kind) {
      case FigureItem::Kind::line:
        painter.drawLine(frame.map(it.points[0]), frame.map(it.points[1]));
        break;
      case FigureItem::Kind::polyline:
      case FigureItem::Kind::polygon: {
        QPolygonF poly;
        for (const glm::vec2& p : it.points) poly << frame.map(p);
        if (it.kind == FigureItem::Kind::polygon)
          painter.drawPolygon(poly);
        else
          painter.drawPolyline(poly);
        break;
      }
      case FigureItem::Kind::circle: {
        const double r = std::max(1.0, double(it.radius) * frame.pixelsPerUnit);
        painter.drawEllipse(frame.map(it.points[0]), r, r);
        break;
      }
      case FigureItem::Kind::text:
        break;
    }
  }
  painter.restore();
}

}  // namespace raystep::viz
