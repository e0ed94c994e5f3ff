// The grid sweep in the debugger (lecture: "how fine should the grid be? max(nx, ny, nz) = d * cbrt(n)"):
// core's run_grid_sweep on the current scene, on a worker thread, drawn as its rows come against the
// density d: cells and primitive tests per ray (the trade-off), references per primitive, trace and build
// time (memory in the table). A slider over the measured densities (and the values between them) rebuilds the
// main window's grid at the chosen d, so that the 3D view and the heat map show that grid; the charts mark
// it. VTK stays inside the .cpp.
#pragma once

#include <memory>

#include <QJsonObject>
#include <QString>

#include "raystep/report/grid_sweep.h"
#include "reports/report_window.h"

class QLabel;
class QLineEdit;
class QSlider;
class QTableWidget;
class QTimer;

namespace raystep::viz {

class Session;

class GridSweepView : public ReportWindow {
  Q_OBJECT
 public:
  explicit GridSweepView(Session* session, QWidget* parent = nullptr);
  ~GridSweepView() override;  // cancels a running sweep and waits for its current density

  // Comma-separated densities of the next run ("" : core's defaults, 0.5 .. 8).
  void setDensities(const QString& densities);
  // Runs the sweep on the session's scene; the error (empty: started) is also shown in the view. Cancel, the
  // state: ReportWindow.
  QString start() override;

  // Moves the slider to d (clamped to the measured range) and asks for the grid at d, as a user's drag does.
  void chooseDensity(float d);
  float chosenDensity() const { return chosen_; }

  const GridSweep& sweep() const { return sweep_; }
  QJsonObject dumpState() const;
  void renderNow() override;  // saveChart: ReportWindow

 Q_SIGNALS:
  // The user chose density d on the slider: the main window rebuilds its grid with it.
  void densityChosen(float d);

 protected:
  QOpenGLWidget* chartWidget() const override;

 private:
  void addRow(const GridSweepRow& row);
  void done(const GridSweep& sweep, const QString& state, const QString& error);
  void redraw();
  void updateSlider();
  void sliderMoved(int value);
  void updateChosenText();
  float densityAt(int sliderValue) const;
  int sliderAt(float density) const;

  struct Impl;
  std::unique_ptr<Impl> d_;
  Session* session_;
  GridSweep sweep_;
  QString sceneName_;
  float chosen_ = 0.f;  // 0: none chosen yet (the charts mark the built grid's density)
  bool settingSlider_ = false;

  QLineEdit* densities_;
  QSlider* slider_;
  QLabel* chosenText_;
  QTableWidget* table_;
  QTimer* rebuildTimer_;
};

}  // namespace raystep::viz
