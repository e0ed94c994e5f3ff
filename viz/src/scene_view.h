// The 3D view: the scene's geometry flat shaded (optionally translucent), the grid's outline, and on top of
// it the replayed walk: the ray with its current [tmin, tmax] interval, the hit point, the current cell,
// the cells already visited, and the current cell's primitives coloured by state. VTK stays inside
// scene_view.cpp; actors are made once per scene or trace and only their data changes per step.
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
  void setFollowCell(bool on);
  void fitCamera();
  void renderNow();
  // The 3D view's own pixels (for "export 3D view").
  QImage grabView();
  // The camera and what was drawn, with window-pixel projections of the current cell and the ray.
  QJsonObject dumpState() const;
  // Milliseconds the last step's update and render took.
  double lastUpdateMs() const;

 private:
  void rebuildGeometry();
  void updateStep();
  struct Impl;
  std::unique_ptr<Impl> d_;
  Session* session_;
};

}  // namespace raystep::viz
