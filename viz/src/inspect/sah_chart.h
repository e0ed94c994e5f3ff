// The SAH inspector (lecture: "kd-tree build by the Surface Area Heuristic"): for one kd-tree node, the cost
// C = t_t + p_a N_a t_i + p_b N_b t_i of every candidate plane the builder evaluated, against the plane's
// position across the node (0 = the box's min, 1 = its max) for x, y and z, one point per candidate; the leaf
// cost N t_i as a dashed line (a split must come below it); the chosen split as a vertical line, or the
// reason the node became a leaf. Beside it the node's id, path, depth, N, box and decision. The curve itself
// is recorded by the main window off the GUI thread (core's record_sah_curve); VTK stays inside
// sah_chart.cpp. A BVH node's binned curve is drawn the same way (setBvhCurve), a general BSP node's
// candidates by orientation (setBspCurve).
#pragma once

#include <memory>

#include <QImage>
#include <QJsonObject>
#include <QString>
#include <QWidget>

class QComboBox;
class QScrollArea;
class QLabel;

namespace raystep {
struct SahCurve;
struct BvhSahCurve;
struct BspSahCurve;
}  // namespace raystep

namespace raystep::viz {

class SahChart : public QWidget {
  Q_OBJECT
 public:
  explicit SahChart(QWidget* parent = nullptr);
  ~SahChart() override;

  // The curve of a node (path: its "LRL" from the root), with the costs' t_i for the text.
  void setCurve(std::shared_ptr<const SahCurve> curve, const QString& path, float t_i, float t_t,
                float empty_bonus = 0.f);
  // A BVH node's binned curve (core's record_bvh_sah_curve): the same chart, one point per bin boundary and
  // axis at the plane's position across the node's box, the chosen bin's line, and the text in the BVH's
  // terms (N left and right, bin k).
  void setBvhCurve(std::shared_ptr<const BvhSahCurve> curve, const QString& path, float t_i, float t_t);
  std::shared_ptr<const BvhSahCurve> bvhCurve() const { return bvhCurve_; }
  // A general BSP node's candidates by orientation (core's record_bsp_sah_curve): one series per k-DOP
  // direction (cost against the plane's position across the cell along that direction: 0 = the cell's
  // lowest point, 1 = its highest) and the own planes as points, coloured by group (axes as x, y, z; face
  // diagonals orange, body diagonals violet, own planes teal), the chosen plane marked; a picker above the
  // text shows all orientations, one group, or one direction.
  void setBspCurve(std::shared_ptr<const BspSahCurve> curve, const QString& path, float t_i, float t_t);
  std::shared_ptr<const BspSahCurve> bspCurve() const { return bspCurve_; }
  // The picker's choice by name: all, axes, face, body, own, or a direction ("x", "x+y", "-x+y+z"); false
  // for an unknown name.
  bool setBspOrientation(const QString& name);
  // No curve: a message instead ("Select a node ...", "Recording node 5 ...").
  void showMessage(const QString& text);
  std::shared_ptr<const SahCurve> curve() const { return curve_; }

  // The quiz's sah-plane question: the chosen plane (its line, the title, the decision in the text) hidden
  // until the answer is revealed, so that neither the room nor the handout's figure gives it away.
  // builder: who chooses the plane, as the hidden title asks it ("SAH", or "median builder").
  void setConceal(bool on, const QString& builder = "SAH");
  bool concealed() const { return conceal_; }
  // Presenter scale: the chart's fonts, lines and markers, and the text's width.
  void setScale(double scale);
  void renderNow();
  QImage grabChart();
  // The chart as PNG, atomically (a temporary file, then renamed); false when it cannot be written.
  bool saveChart(const QString& path);
  // What the chart shows: the node, points per axis, the chosen split, the colours and where it is on screen.
  QJsonObject dumpState() const;
  // The candidate nearest to widget position `at` of the chart (a click): its axis and position; false
  // without a curve or when nothing is within 20 pixels.
  bool candidateAt(const QPoint& at, int* axis, float* position) const;

 Q_SIGNALS:
  // A click on the chart near a candidate (the quiz's sah-plane answer).
  void candidateClicked(int axis, float position);

 protected:
  bool eventFilter(QObject* watched, QEvent* event) override;

 private:
  struct Impl;
  std::unique_ptr<Impl> d_;
  std::shared_ptr<const SahCurve> curve_;
  std::shared_ptr<const BvhSahCurve> bvhCurve_;  // set with curve_ (its kd-shaped copy) for a BVH node
  std::shared_ptr<const BspSahCurve> bspCurve_;  // a BSP node (curve_ stays empty: no axis-shaped copy)
  void drawBspCurve();
  QComboBox* orientation_;  // the BSP picker (hidden for the kd-tree and the BVH)
  QScrollArea* scroll_;     // around text_
  QLabel* text_;
  QString lastPath_;  // setCurve's arguments, to draw again at another scale
  float lastTi_ = 0.f, lastTt_ = 0.f, lastBonus_ = 0.f;
  bool conceal_ = false;
  QString concealBuilder_ = "SAH";
};

}  // namespace raystep::viz
