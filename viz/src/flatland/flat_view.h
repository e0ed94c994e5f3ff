// The 2D view: a 2D scene as the lecture's slides draw it (QPainter, anti-aliased, on white, large type for a
// projector): the structure's cells or nodes (accel/plane_outline.h), the shapes, and the session's walk at its
// step (core's flat figure, figure/flat_figure.h: the cells or nodes visited, the current one, the stack's
// nodes, the mailbox's shapes, a grid's tMax ticks, the ray with its [t_min, t_max] and the nearest hit), the
// caption with the stack as the slides write it ("Stack: LLR,R   Current: LLL"), and for a tree the tree
// beside the picture with the walk's marks. Dragging the ray's origin (the red dot) or anywhere else (its
// direction: the ray aims at the mouse) asks for the walk to be traced again (rayMoved); the main window
// traces it and the session's new walk redraws the view at once. A right click selects the leaf under the
// pointer (again: its parent, and so on up), for the SAH inspector; *Build so far* draws only the splits of the
// nodes made up to the selected one (the builders make them in id order), *Crofton lines* throws random lines
// at the selected node and counts the share meeting each child against its perimeter ratio.
#pragma once

#include <memory>

#include <QJsonObject>
#include <QPixmap>
#include <QTimer>
#include <QWidget>

#include "flatland/figure_painter.h"
#include "raystep/accel/plane_outline.h"
#include "raystep/accel/random_lines.h"
#include "raystep/figure/flat_aa_figure.h"
#include "raystep/figure/flat_figure.h"

class QCheckBox;
class QPainter;

namespace raystep::viz {

class Session;
struct StructureData;
class TreeShape;

class FlatView : public QWidget {
  Q_OBJECT
 public:
  explicit FlatView(Session* session, QWidget* parent = nullptr);
  ~FlatView() override;

  void setScale(double scale);  // the presenter scale: type and lines
  // The build so far (a lesson's build-planes) and Crofton's random lines at the selected node.
  void setBuildSoFar(bool on);
  bool buildSoFar() const;
  void setCroftonLines(bool on);
  bool croftonLines() const;
  // *Anti-aliasing*: the picture's pixels over the scene instead of the walk (figure/flat_aa_figure.h):
  // sampled with the picture's anti-aliasing (spec as the image view's: "scene" the scene file's), the exact
  // coverage, the error per pixel.
  void setAntiAliasingView(bool on);
  bool antiAliasingView() const;
  void setAntiAliasing(const QString& spec);
  // A right click at p (scene units): the leaf holding it, or the parent of the selected node when that
  // holds it (-1: no tree, or outside).
  int nodeAt(glm::vec2 p) const;
  // The ray the view shows (its origin and direction in the plane) and where the origin is on screen.
  glm::vec2 rayOrigin() const { return origin_; }
  glm::vec2 rayDirection() const { return direction_; }
  QPointF toWidget(glm::vec2 p) const { return frame_.map(p); }
  // The figure as `raystep figure` writes it, at the session's step (export: figure_file.h).
  Figure figure() const;
  const PlaneOutline* outline() const { return hasOutline_ ? &outline_ : nullptr; }
  QJsonObject dumpState() const;

 Q_SIGNALS:
  void rayMoved(QPointF origin, QPointF direction);
  void nodePicked(int node);

 protected:
  void paintEvent(QPaintEvent*) override;
  void resizeEvent(QResizeEvent*) override;
  void mousePressEvent(QMouseEvent*) override;
  void mouseMoveEvent(QMouseEvent*) override;
  void mouseReleaseEvent(QMouseEvent*) override;

 private:
  void structureChanged();
  void makeStill();    // the still layers (the whole structure, or the build so far)
  void throwLines();   // Crofton's lines at the selected node
  void sampleAa();     // the anti-aliasing figure, when shown
  void walkChanged();
  void drawTree();         // the tree with the walk's marks at the step
  void paintCaption(QPainter& p);
  void layout();           // the picture's frame, the tree's column, the caption's height
  void cacheStill();       // the still layers as pixmaps at the frame's size
  void drag(QPointF pos);  // moves the origin or aims the ray, and asks for the walk again
  bool rayInPlane() const;

  Session* session_;
  std::shared_ptr<const StructureData> structure_;  // the outline's and the tree's structure
  PlaneOutline outline_;
  bool hasOutline_ = false;
  Figure still_;
  FlatWalkLayers walk_;
  std::unique_ptr<TreeShape> tree_;
  QImage treeImage_;
  QTimer treeTimer_;  // the tree drawn again after a drag's move
  glm::vec2 origin_{0.f}, direction_{1.f, 0.f};
  double scale_ = 1.0;
  FigureFrame frame_, aaFrame_;
  QRectF treeRoom_, treeRect_, captionRect_, hintRect_;
  QPixmap under_, over_;  // the structure and the leaves' names; the shapes (the walk goes between)
  enum class Drag { none, origin, direction } drag_ = Drag::none;
  QString problem_;  // why no picture ("" : drawn)
  QCheckBox* buildBox_;
  QCheckBox* linesBox_;
  QCheckBox* aaBox_;
  QString aaSpec_ = "scene";
  std::unique_ptr<FlatAa> aa_;  // shown when aaBox_ is checked
  QString aaProblem_;
  bool aaColumn_ = false;  // the panels one above the other (a tall view)
  LinesMeetingChildren crofton_;
  int croftonNode_ = -1;
  std::vector<std::string> croftonCaption_;
};

}  // namespace raystep::viz
