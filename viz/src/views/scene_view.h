// The 3D view: the scene's geometry flat shaded (optionally translucent), the grid's outline, and on top of
// it the replayed walk: the ray with its current [tmin, tmax] interval, the hit point, the current cell,
// the cells already visited, and the current cell's primitives coloured by state; the kd-tree node selected
// in the tree view. BVH: the current node's children's boxes, translucent in two colours with their overlap
// outlined ("bounding volumes can overlap"), the stack, the visited and the skipped nodes. A click on the
// scene picks a point (the main window selects the leaf holding it). VTK stays inside scene_view.cpp; actors
// are made once per scene or trace and only their data changes per step.
#pragma once

#include <memory>

#include <QJsonObject>
#include <QWidget>

namespace raystep::viz {

class Session;

class SceneView : public QWidget {
  Q_OBJECT
 public:
  explicit SceneView(Session* session, QWidget* parent = nullptr);
  ~SceneView() override;
  // The OpenGL format VTK needs; call before the QApplication is made.
  static void prepareSurfaceFormat();

  void setTranslucent(bool on);
  // kd-tree: the build so far, the split planes of every node made before the selected one (pale green) and
  // the selected node's own plane (a lecture's kd build, split by split, as the selected node steps on).
  void setBuildPlanes(bool on);
  bool buildPlanes() const;
  void setFollowCell(bool on);
  // A lesson's question about the walk's next move: the drawing that gives the answer away waits for Reveal
  // (an octree cell's children are outlined in one colour, not in the order the ray crosses them).
  void setConceal(bool on);
  void fitCamera();
  // The camera framing the scene (or trace) as when it was opened, at the view's present size: a lesson step
  // starts from it, so that entering a step gives the view a fresh run of the same state gives, whatever the
  // class did with the mouse before.
  void restoreHomeCamera();
  // Presenter scale: line widths and the hit marker (readable from the back of a room).
  void setScale(double scale);
  bool translucent() const;
  bool followCell() const;
  void renderNow();
  // Dormant: hidden behind the 2D view of a 2D scene, the view neither updates nor renders at a step (a
  // dragged ray's walk would wait for software OpenGL); woken, it catches up with the session's state.
  void setDormant(bool dormant);
  // The 3D view's own pixels (for "export 3D view").
  QImage grabView();
  // The camera and what was drawn, with window-pixel projections of the current cell and the ray.
  QJsonObject dumpState() const;
  // Milliseconds the last step's update and render took.
  double lastUpdateMs() const;
  // A click on the scene at window position `at` (as a user makes it, without dragging): the point picked on
  // the geometry is reported by pointPicked; false when nothing was hit.
  bool pickAt(const QPoint& at);
  // The side-by-side view (compare_window.h): no tool bar nor legend (the compare window has one of each),
  // the camera of `leader` (one camera for every view: cameraMoved tells the others to draw again), and the
  // ray drawn bright up to t (NaN: up to the walk's current interval, as always).
  void setCompact(bool on);
  void shareCamera(SceneView* leader);
  void setRayMark(float t);
  // The primitive under the last click that hit the scene (-1: none yet, or unknown).
  int pickedPrimitive() const;

 Q_SIGNALS:
  // The user turned, moved or zoomed the camera (a drag or the wheel in this view).
  void cameraMoved();
  // A click (without dragging) hit the scene at this world point.
  void pointPicked(float x, float y, float z);

 private:
  void rebuildGeometry();
  void fitCameraTo(const double* bounds);  // xmin, xmax, ymin, ymax, zmin, zmax
  void updateStep();
  void updateSelected();  // the selected kd-tree node's box
  void updateBvhChildren();  // BVH: the current node's children's boxes, their overlap, the skipped nodes
  bool pickDisplay(int x, int y);
  bool eventFilter(QObject* watched, QEvent* event) override;  // a click without a drag picks  // VTK display coordinates (origin bottom left, device pixels)
  struct Impl;
  std::unique_ptr<Impl> d_;
  Session* session_;
};

}  // namespace raystep::viz
