// The same ray, side by side (lecture: "BSP vs. k-d: a tradeoff between speed from simplicity and better
// adaptability", seen rather than asserted): a window with two to four 3D views under ONE camera, each
// showing one structure's walk of the same ray; one timeline over the ray's parameter t (at t every view
// shows its walk as core's replay::walk_at_t (replay/side_by_side.h) defines it); the counters side by side; and each structure's
// cumulative cost (t_t per step, t_i per test) against t. Reads a version 5 trace (core's MultiTrace) or
// records one.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QJsonObject>
#include <QStringList>
#include <QWidget>

#include "raystep/replay/side_by_side.h"


class QComboBox;
class QGridLayout;
class QLabel;
class QSlider;
class QTableWidget;

namespace raystep {
struct MultiTrace;
}

namespace raystep::viz {

class CostChart;
class SceneView;
class Session;
struct SceneData;
struct StructureData;

class CompareWindow : public QWidget {
  Q_OBJECT
 public:
  explicit CompareWindow(QWidget* parent = nullptr);  // a window of its own (Qt::Window)
  ~CompareWindow() override;

  // The walks to show (2 to 4; a version 5 trace, or recordComparePixel's). structures: the live structures
  // walked, in the walks' order, over scene (both empty for a trace opened on its own: the views then draw
  // the trace's own geometry). source: where the walks come from, for the title.
  void setWalks(std::shared_ptr<const MultiTrace> walks, std::shared_ptr<const SceneData> scene,
                std::vector<std::shared_ptr<const StructureData>> structures, const QString& source);
  int viewCount() const { return int(panes_.size()); }
  SceneView* view(int i) const;
  int rayIndex() const { return ray_; }
  int rayCount() const;
  void setRay(
      int index);  // another ray of the walks (a pixel traced with its secondary rays); t to its start
  // The timeline: t clamped to [tStart, tEnd]; the slider has 1000 steps between them.
  void setT(double t);
  double t() const { return t_; }
  double tStart() const { return tStart_; }
  double tEnd() const { return tEnd_; }
  void setSliderPosition(int position);  // 0 .. 1000, as the user drags it
  void renderNow();
  // What every view, the counters and the chart show at t (JSON, for the scripted mode and the tests).
  QJsonObject dumpState() const;

  // Frames the walks in the (shared) camera at the views' present size.
  void fitCamera();

  // The rule that says which event is "at t", as the window's status line shows it.
  static QString atTRule();

 Q_SIGNALS:
  void tChanged(double t);

 protected:
  void showEvent(QShowEvent* event) override;

 private:
  struct Pane;
  void clearPanes();
  void showT();
  void fillTable();

  std::shared_ptr<const MultiTrace> walks_;
  std::shared_ptr<const SceneData> scene_;
  std::vector<std::shared_ptr<const StructureData>> structures_;
  std::vector<std::unique_ptr<Pane>> panes_;
  QLabel* header_;
  QWidget* viewsBox_;
  QGridLayout* viewsGrid_;
  QLabel* legend_;
  QSlider* slider_;
  QLabel* startLabel_;
  QLabel* endLabel_;
  QLabel* tLabel_;
  QLabel* rule_;
  QComboBox* rayCombo_;
  QTableWidget* table_;
  CostChart* chart_;
  int ray_ = 0;
  bool needsFit_ = false;  // new walks, framed once the window is laid out
  double t_ = 0.0, tStart_ = 0.0, tEnd_ = 1.0;
};

// The same pixel's rays (with secondary, its ray tree) through each structure, built over one scene: what
// `raystep trace SCENE --accel A,B,... --pixel X,Y` writes (the rays spawned once, by the first structure).
std::shared_ptr<const MultiTrace> recordComparePixel(
    const std::vector<std::shared_ptr<const StructureData>>& structures, int width, int height, int px,
    int py, bool secondary);

// Whether the file is a version 5 trace (several structures' walks), by its first kilobytes.
bool isMultiTraceFile(const QString& path);

// A small dialog: pick 2 to 4 structures (those that record events), `checked` ticked at first. Empty when
// cancelled.
QStringList pickCompareStructures(QWidget* parent, const QStringList& checked);

}  // namespace raystep::viz
