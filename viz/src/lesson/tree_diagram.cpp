#include "lesson/tree_diagram.h"

#include <algorithm>
#include <functional>

#include <QFont>
#include <QFontMetrics>
#include <QPainter>

#include "common/palette.h"
#include "views/kd_tree_model.h"

namespace raystep::viz {
namespace {

constexpr int kBoxW = 58, kBoxH = 30, kSlot = 66, kLevel = 74, kMargin = 24, kLegend = 40;

struct Placed {
  int node;
  int depth;
  double x;
  int parent;  // index into the placed list, -1: the root
};

}  // namespace

QImage drawTreeDiagram(const TreeShape& tree, const TreeMarks& marks, int whole) {
  const int n = int(tree.size());
  if (n == 0) return {};
  auto valid = [n](int id) { return id >= 0 && id < n; };

  // The nodes drawn: all of a small tree; else every marked node, its ancestors and their children.
  std::vector<char> shown(size_t(n), n <= whole ? 1 : 0);
  auto showChildren = [&](int v) {
    for (int r = 0; r < tree.children(uint32_t(v)); ++r) shown[tree.child(uint32_t(v), r)] = 1;
  };
  if (n > whole) {
    shown[0] = 1;
    showChildren(0);
    std::vector<int> marked = marks.stack;
    marked.insert(marked.end(), marks.visited.begin(), marks.visited.end());
    marked.push_back(marks.current);
    marked.push_back(marks.selected);
    for (int id : marked) {
      if (!valid(id)) continue;
      for (int v = id; v >= 0; v = tree.parent(uint32_t(v))) {
        shown[size_t(v)] = 1;
        showChildren(v);
      }
    }
  }

  // Each drawn node's place: the drawing's leaves side by side from the left, an inner node centred over its
  // drawn children (the slides' picture of a tree).
  std::vector<Placed> placed;
  int slots = 0, depthMax = 0;
  std::function<double(int, int, int)> place = [&](int v, int depth, int parent) -> double {
    const int self = int(placed.size());
    placed.push_back({v, depth, 0.0, parent});
    depthMax = std::max(depthMax, depth);
    double first = -1, last = -1;
    for (int r = 0; r < tree.children(uint32_t(v)); ++r) {
      const int c = int(tree.child(uint32_t(v), r));
      if (!shown[size_t(c)]) continue;
      const double x = place(c, depth + 1, self);
      if (first < 0) first = x;
      last = x;
    }
    placed[size_t(self)].x = first < 0 ? slots++ : (first + last) / 2;
    return placed[size_t(self)].x;
  };
  place(0, 0, -1);

  // As wide as the tree, or as its legend line.
  QFont legendFont;
  legendFont.setPixelSize(14);
  const QFontMetrics lm(legendFont);
  const QString title =
      n <= whole
          ? QObject::tr("%1: %2 nodes").arg(tree.name()).arg(n)
          : QObject::tr("%1: %2 nodes; the branches off the marked nodes folded").arg(tree.name()).arg(n);
  const QString legendText[] = {QObject::tr("current node"), QObject::tr("on the stack"),
                                QObject::tr("visited"), QObject::tr("selected")};
  int legendWidth = kMargin + lm.horizontalAdvance(title) + kMargin;
  for (const QString& t : legendText) legendWidth += 22 + lm.horizontalAdvance(t) + 18;
  const int width = std::max(2 * kMargin + slots * kSlot, legendWidth);
  const int height = kLegend + 2 * kMargin + depthMax * kLevel + kBoxH + 16;
  QImage image(width, height, QImage::Format_RGB32);
  image.fill(Qt::white);
  QPainter p(&image);
  p.setRenderHint(QPainter::Antialiasing);
  QFont font = legendFont;
  p.setFont(font);
  auto centre = [&](const Placed& e) {
    return QPointF(kMargin + e.x * kSlot + kSlot / 2.0, kLegend + kMargin + e.depth * kLevel + kBoxH / 2.0);
  };

  // The legend: the colours' meanings, and whether the tree is drawn whole.
  const std::pair<QColor, QString> legend[] = {{palette::currentCell, legendText[0]},
                                               {palette::stackNode, legendText[1]},
                                               {palette::visitedCell, legendText[2]},
                                               {palette::selectedNode, legendText[3]}};
  int lx = kMargin;
  for (const auto& [colour, text] : legend) {
    p.fillRect(QRect(lx, 10, 16, 16), colour);
    p.setPen(Qt::black);
    p.drawRect(QRect(lx, 10, 16, 16));
    p.drawText(lx + 22, 23, text);
    lx += 22 + QFontMetrics(font).horizontalAdvance(text) + 18;
  }
  p.drawText(lx, 23, title);

  // Edges first, each labelled by its side (L / R, an octant).
  QFont small = font;
  small.setPixelSize(12);
  for (const Placed& e : placed) {
    if (e.parent < 0) continue;
    const QPointF a = centre(placed[size_t(e.parent)]) + QPointF(0, kBoxH / 2.0);
    const QPointF b = centre(e) - QPointF(0, kBoxH / 2.0);
    p.setPen(QPen(QColor(90, 90, 90), 1.5));
    p.drawLine(a, b);
    p.setFont(small);
    p.setPen(QColor(60, 60, 60));
    const QFontMetrics sm(small);
    const QString side = tree.side(uint32_t(e.node));
    if (tree.children(uint32_t(placed[size_t(e.parent)].node)) <= 2 &&
        sm.horizontalAdvance(side) <= kSlot / 2 - 8) {  // L / R beside the edge's middle
      const QPointF mid = (a + b) / 2;
      const bool left = b.x() < a.x();
      const int w = sm.horizontalAdvance(side);
      p.drawText(QPointF(left ? mid.x() - w - 4 : mid.x() + 4, mid.y()), side);
    } else {  // many edges meet at the parent, or a long label: over its own child, within the child's slot
      const QString text = sm.elidedText(side, Qt::ElideRight, kSlot - 6);
      const QRectF r(b.x() - kSlot / 2.0 + 3, b.y() - sm.height() - 3, kSlot - 6, sm.height());
      const int w = sm.horizontalAdvance(text);
      p.fillRect(QRectF(b.x() - w / 2.0 - 2, r.top(), w + 4, r.height()), Qt::white);
      p.drawText(r, Qt::AlignHCenter | Qt::AlignVCenter, text);
    }
  }

  // The nodes: a box with the id; leaves square-cornered, inner nodes rounded; a stub below an inner node
  // whose children are not drawn.
  auto in = [](const std::vector<int>& v, int id) { return std::find(v.begin(), v.end(), id) != v.end(); };
  for (const Placed& e : placed) {
    const QColor fill = e.node == marks.current     ? palette::currentCell
                        : in(marks.stack, e.node)   ? palette::stackNode
                        : e.node == marks.selected  ? palette::selectedNode
                        : in(marks.visited, e.node) ? palette::visitedCell
                                                    : QColor(245, 245, 245);
    const QPointF c = centre(e);
    const QRectF box(c.x() - kBoxW / 2.0, c.y() - kBoxH / 2.0, kBoxW, kBoxH);
    p.setPen(QPen(Qt::black, 1.2));
    p.setBrush(fill);
    if (tree.leaf(uint32_t(e.node)))
      p.drawRect(box);
    else
      p.drawRoundedRect(box, 10, 10);
    QFont bold = font;
    bold.setBold(true);
    p.setFont(bold);
    p.setPen(fill == palette::selectedNode ? Qt::white : Qt::black);
    p.drawText(box, Qt::AlignCenter, QString::number(e.node));
    bool childrenDrawn = false;
    for (int r = 0; r < tree.children(uint32_t(e.node)); ++r)
      childrenDrawn = childrenDrawn || shown[tree.child(uint32_t(e.node), r)];
    if (!tree.leaf(uint32_t(e.node)) && !childrenDrawn) {
      p.setPen(QPen(QColor(120, 120, 120), 1.2));
      p.setBrush(Qt::NoBrush);
      const QPointF top = c + QPointF(0, kBoxH / 2.0);
      p.drawPolygon(QPolygonF({top, top + QPointF(-12, 16), top + QPointF(12, 16)}));
    }
  }
  return image;
}

}  // namespace raystep::viz
