#include "inspect/sah_chart.h"

#include <algorithm>
#include <cmath>

#include <QComboBox>
#include <QHBoxLayout>
#include <QJsonArray>
#include <QLabel>
#include <QMouseEvent>
#include <QSaveFile>
#include <QScrollArea>
#include <QScrollBar>
#include <QVBoxLayout>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotLine.h>
#include <vtkPlotPoints.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>

#include "common/chart_util.h"
#include "common/palette.h"
#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/replay/replay_state.h"

namespace raystep::viz {
namespace {

using chartutil::addRow;
using chartutil::makeTable;

QJsonArray jsonColor(const QColor& c) {
  return QJsonArray{c.red(), c.green(), c.blue()};
}

const QColor& axisColor(int axis) {
  return axis == 0 ? palette::sahX : axis == 1 ? palette::sahY : palette::sahZ;
}

vtkPlot* addLine(vtkChartXY* chart, vtkTable* t, const QColor& c, float width, const std::string& label) {
  // One point is no line (VTK complains): a marker alone.
  vtkPlot* p = chart->AddPlot(t->GetNumberOfRows() >= 2 ? vtkChart::LINE : vtkChart::POINTS);
  p->SetInputData(t, 0, 1);
  p->SetColor((unsigned char)c.red(), (unsigned char)c.green(), (unsigned char)c.blue(), 255);
  p->SetWidth(width);
  p->SetLabel(label);
  return p;
}

QString fmt(double v) {
  return QString::number(std::abs(v) < 1e-30 ? 0.0 : v, 'g', 5);
}

// The x axis: across the node's box (kd-tree, BVH), or across the cell along each plane's normal (BSP).
void bottomTitle(vtkChartXY* chart, bool bsp) {
  chart->GetAxis(vtkAxis::BOTTOM)
      ->SetTitle(
          bsp ? "plane position along its normal (0: the cell's lowest point, 1: its highest)"
              : "split position across the node (0: box min, 1: box max)");
}

// A BSP candidate's orientation group: 0 the axes, 1 the face diagonals, 2 the body diagonals, 3 own planes.
int bspGroup(int direction) {
  return direction < 0 ? 3 : direction < 3 ? 0 : direction < 9 ? 1 : 2;
}
const char* const kBspGroupNames[4] = {"axes", "face diagonals", "body diagonals", "own planes"};
const char* const kBspGroupOne[4] = {"axis", "face diagonal", "body diagonal", "own plane"};

// The series' colour: the axes as the kd-tree's x, y, z; the other groups one hue, each direction of a group
// a shade of it when the group is shown alone.
QColor bspColor(int direction, bool shades) {
  const int group = bspGroup(direction);
  if (group == 0) return axisColor(direction);
  const QColor& base = group == 1   ? palette::sahFaceDiagonal
                       : group == 2 ? palette::sahBodyDiagonal
                                    : palette::sahOwnPlane;
  if (!shades || group == 3) return base;
  // From lighter to darker than the group's colour, never near the chosen plane's black.
  const int k = group == 1 ? direction - 3 : direction - 9, n = group == 1 ? 6 : 4;
  return base.lighter(150 - 85 * k / (n - 1));
}

QString vec(const glm::vec3& v) {
  return QString("(%1, %2, %3)").arg(fmt(v.x), fmt(v.y), fmt(v.z));
}

QString bspLeafReasonText(BspLeafReason r) {
  switch (r) {
    case BspLeafReason::few_primitives:
      return QObject::tr("N <= leaf size: no search");
    case BspLeafReason::max_depth:
      return QObject::tr("the depth limit: no search");
    case BspLeafReason::no_area:
      return QObject::tr("the cell has no area");
    case BspLeafReason::no_cheaper_split:
      return QObject::tr("no plane costs less than N t_i");
    case BspLeafReason::separates_nothing:
      return QObject::tr("the cheapest plane would leave every primitive on both sides");
    case BspLeafReason::budget:
      return QObject::tr("the reference budget is spent: the cheapest plane may cost less than N t_i");
  }
  return {};
}

QString leafReasonText(LeafReason r) {
  switch (r) {
    case LeafReason::few_primitives:
      return QObject::tr("N <= leaf size: no search");
    case LeafReason::max_depth:
      return QObject::tr("the depth limit: no search");
    case LeafReason::no_cheaper_split:
      return QObject::tr("no split costs less than N t_i");
    case LeafReason::no_candidate:
      return QObject::tr("no plane strictly inside the node");
    case LeafReason::budget:
      return QObject::tr("the reference budget is spent: the cheapest plane may cost less than N t_i");
  }
  return {};
}

}  // namespace

struct SahChart::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartXY> chart;
  vtkSmartPointer<vtkTable> axisTable[3];  // the candidates per axis, as plotted
  vtkSmartPointer<vtkTable> spatialTable[3];  // an SBVH node's spatial candidates per axis, as plotted
  // BSP: the candidates per direction (0..12, 13 the own planes) as plotted (null: none, or not shown), and
  // the series drawn (label, colour, points) for the state dump.
  vtkSmartPointer<vtkTable> bspTable[kBspKdopDirections + 1];
  QJsonArray bspSeries;
  double bspChosenX = -1.0;
  QString message;
  float scale = 1.f;
};

SahChart::SahChart(QWidget* parent) : QWidget(parent), d_(new Impl) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  auto* column = new QVBoxLayout;
  column->setContentsMargins(0, 0, 0, 0);
  // A BSP node's candidates come in 14 orientations: the picker shows them all (by group) or a few.
  orientation_ = new QComboBox;
  orientation_->setObjectName("bspOrientation");
  orientation_->setToolTip(tr("Which candidate planes the chart shows, by orientation"));
  orientation_->addItem(tr("all orientations"), QStringLiteral("all"));
  orientation_->addItem(tr("axes x, y, z (the kd-tree's)"), QStringLiteral("axes"));
  orientation_->addItem(tr("face diagonals (6)"), QStringLiteral("face"));
  orientation_->addItem(tr("body diagonals (4)"), QStringLiteral("body"));
  orientation_->addItem(tr("own planes (autopartition)"), QStringLiteral("own"));
  for (int i = 0; i < kBspKdopDirections; ++i)
    orientation_->addItem(tr("direction %1").arg(bsp_direction_name(i)), QString(bsp_direction_name(i)));
  orientation_->setFixedWidth(230);
  orientation_->hide();
  connect(orientation_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, [this] {
    if (bspCurve_) drawBspCurve();
  });
  column->addWidget(orientation_);
  text_ = new QLabel;
  text_->setObjectName("sahText");
  text_->setWordWrap(true);
  text_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  text_->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  text_->setFixedWidth(230);
  // Scrolled when the dock is short (a BSP node's text is longer than a kd node's).
  auto* scroll = new QScrollArea;
  scroll->setWidget(text_);
  scroll->setWidgetResizable(true);
  scroll->setFrameShape(QFrame::NoFrame);
  scroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  scroll->setFixedWidth(230 + scroll->verticalScrollBar()->sizeHint().width());
  scroll_ = scroll;
  column->addWidget(scroll, 1);
  layout->addLayout(column);

  Impl& d = *d_;
  d.widget = new QVTKOpenGLNativeWidget(this);
  d.widget->setMinimumSize(300, 180);
  d.window->SetMultiSamples(0);  // exact colours (the tests look for the series' colours)
  d.widget->setRenderWindow(d.window);
  d.view->SetRenderWindow(d.window);
  d.view->SetInteractor(d.widget->interactor());
  d.view->GetRenderer()->SetBackground(1.0, 1.0, 1.0);
  d.view->GetScene()->AddItem(d.chart);
  d.chart->SetShowLegend(true);
  // Beside the plot, not over the curves.
  d.chart->GetLegend()->SetInline(false);
  d.chart->GetLegend()->SetHorizontalAlignment(vtkChartLegend::RIGHT);
  d.chart->GetLegend()->SetVerticalAlignment(vtkChartLegend::TOP);
  d.chart->GetLegend()->GetLabelProperties()->SetFontSize(11);
  vtkAxis* bottom = d.chart->GetAxis(vtkAxis::BOTTOM);
  bottomTitle(d.chart, false);
  bottom->SetBehavior(vtkAxis::FIXED);
  bottom->SetRange(-0.02, 1.02);
  d.chart->GetAxis(vtkAxis::LEFT)->SetTitle("SAH cost C");
  for (vtkAxis* a : {bottom, d.chart->GetAxis(vtkAxis::LEFT)}) {
    a->GetTitleProperties()->SetFontSize(11);
    a->GetLabelProperties()->SetFontSize(10);
  }
  layout->addWidget(d.widget, 1);
  d.widget->installEventFilter(this);  // a click picks the nearest candidate
  showMessage(tr("Select a node in the tree (or click the scene in the 3D view) to see its SAH cost curve."));
}

SahChart::~SahChart() = default;

bool SahChart::eventFilter(QObject* watched, QEvent* event) {
  if (watched == d_->widget && event->type() == QEvent::MouseButtonRelease) {
    auto* e = static_cast<QMouseEvent*>(event);
    int axis = 0;
    float position = 0.f;
    if (e->button() == Qt::LeftButton && candidateAt(e->pos(), &axis, &position))
      Q_EMIT candidateClicked(axis, position);
  }
  return QWidget::eventFilter(watched, event);
}

bool SahChart::candidateAt(const QPoint& at, int* axis, float* position) const {
  const Impl& d = *d_;
  if (!curve_) return false;
  // The axes' ends in the scene's pixels (origin bottom left) map the chart's values to the widget.
  vtkAxis* bottom = d.chart->GetAxis(vtkAxis::BOTTOM);
  vtkAxis* left = d.chart->GetAxis(vtkAxis::LEFT);
  const float* b1 = bottom->GetPoint1();
  const float* b2 = bottom->GetPoint2();
  const float* l1 = left->GetPoint1();
  const float* l2 = left->GetPoint2();
  const double ratio = d.widget->devicePixelRatioF();
  const double px = at.x() * ratio, py = (d.widget->height() - at.y()) * ratio;
  const Bounds3& box = curve_->info.box;
  double best = 20.0 * ratio;
  bool found = false;
  for (const SahCandidate& c : curve_->candidates) {
    if (c.axis < 0 || c.axis > 2) continue;
    float extent = box.hi[c.axis] - box.lo[c.axis];
    double x = extent > 0.f ? double(c.position - box.lo[c.axis]) / double(extent) : 0.5;
    double sx =
        b1[0] + (x - bottom->GetMinimum()) / (bottom->GetMaximum() - bottom->GetMinimum()) * (b2[0] - b1[0]);
    double sy = l1[1] + (double(c.cost) - left->GetMinimum()) / (left->GetMaximum() - left->GetMinimum()) *
                            (l2[1] - l1[1]);
    double dist = std::hypot(sx - px, sy - py);
    if (dist < best) {
      best = dist;
      *axis = c.axis;
      *position = c.position;
      found = true;
    }
  }
  return found;
}

void SahChart::setConceal(bool on, const QString& builder) {
  if (on == conceal_ && builder == concealBuilder_) return;
  conceal_ = on;
  concealBuilder_ = builder;
  if (bspCurve_) drawBspCurve();
  if (bvhCurve_)
    setBvhCurve(bvhCurve_, lastPath_, lastTi_, lastTt_);
  else if (curve_)
    setCurve(curve_, lastPath_, lastTi_, lastTt_, lastBonus_);
}

void SahChart::setScale(double scale) {
  Impl& d = *d_;
  d.scale = float(scale);
  d.chart->GetLegend()->GetLabelProperties()->SetFontSize(int(std::lround(11 * scale)));
  for (vtkAxis* a : {d.chart->GetAxis(vtkAxis::BOTTOM), d.chart->GetAxis(vtkAxis::LEFT)}) {
    a->GetTitleProperties()->SetFontSize(int(std::lround(11 * scale)));
    a->GetLabelProperties()->SetFontSize(int(std::lround(10 * scale)));
  }
  d.chart->GetTitleProperties()->SetFontSize(int(std::lround(12 * scale)));
  text_->setFixedWidth(int(230 * scale));
  scroll_->setFixedWidth(int(230 * scale) + scroll_->verticalScrollBar()->sizeHint().width());
  orientation_->setFixedWidth(int(230 * scale));
  if (bspCurve_) {
    drawBspCurve();
  } else if (bvhCurve_) {
    setBvhCurve(bvhCurve_, QString(lastPath_), lastTi_, lastTt_);
  } else if (curve_) {
    QString path = lastPath_;
    setCurve(curve_, path, lastTi_, lastTt_, lastBonus_);
  } else {
    renderNow();
  }
}

void SahChart::showMessage(const QString& text) {
  curve_.reset();
  bvhCurve_.reset();
  bspCurve_.reset();
  orientation_->hide();
  for (auto& t : d_->bspTable) t = nullptr;
  d_->bspSeries = QJsonArray();
  d_->message = text;
  d_->chart->ClearPlots();
  for (auto& t : d_->axisTable) t = nullptr;
  for (auto& t : d_->spatialTable) t = nullptr;
  d_->chart->SetTitle("");
  text_->setText(text);
  renderNow();
}

void SahChart::setCurve(std::shared_ptr<const SahCurve> curve, const QString& path, float t_i, float t_t,
                        float empty_bonus) {
  Impl& d = *d_;
  curve_ = std::move(curve);
  bvhCurve_.reset();
  bspCurve_.reset();
  orientation_->hide();
  for (auto& t : d.bspTable) t = nullptr;
  d.bspSeries = QJsonArray();
  bottomTitle(d.chart, false);
  lastPath_ = path;
  lastTi_ = t_i;
  lastTt_ = t_t;
  lastBonus_ = empty_bonus;
  d.message.clear();
  d.chart->ClearPlots();
  for (auto& t : d.spatialTable) t = nullptr;
  const SahCurve& c = *curve_;
  const Bounds3& box = c.info.box;

  // The candidates per axis, by position (the builder's order is per sweep event); one point each.
  std::vector<const SahCandidate*> byAxis[3];
  for (const SahCandidate& s : c.candidates)
    if (s.axis >= 0 && s.axis < 3) byAxis[s.axis].push_back(&s);
  auto across = [&](int axis, float pos) {
    float extent = box.hi[axis] - box.lo[axis];
    return extent > 0.f ? double(pos - box.lo[axis]) / double(extent) : 0.5;
  };
  double lo = c.leaf_cost, hi = c.leaf_cost;
  for (int a = 0; a < 3; ++a) {
    std::stable_sort(byAxis[a].begin(), byAxis[a].end(),
                     [](const SahCandidate* x, const SahCandidate* y) { return x->position < y->position; });
    d.axisTable[a] = makeTable("position", "cost");
    for (const SahCandidate* s : byAxis[a]) {
      addRow(d.axisTable[a], across(a, s->position), s->cost);
      lo = std::min(lo, double(s->cost));
      hi = std::max(hi, double(s->cost));
    }
    if (byAxis[a].empty()) continue;  // an empty series draws nothing, but warns
    vtkPlot* p = addLine(d.chart, d.axisTable[a], axisColor(a), 2.f * d.scale,
                         std::string(replay::axis_name(a)) + " (" + std::to_string(byAxis[a].size()) + ")");
    if (auto* points = vtkPlotPoints::SafeDownCast(p)) {  // a line plot is a points plot with lines
      bool few = byAxis[a].size() <= 400;
      points->SetMarkerStyle(few || !vtkPlotLine::SafeDownCast(p) ? vtkPlotPoints::CIRCLE
                                                                  : vtkPlotPoints::NONE);
      points->SetMarkerSize((byAxis[a].size() == 1 ? 8.f : 5.f) * d.scale);
    }
  }
  // The leaf cost: a split is made only below this line.
  auto leaf = makeTable("position", "leaf cost");
  addRow(leaf, 0.0, c.leaf_cost);
  addRow(leaf, 1.0, c.leaf_cost);
  vtkPlot* leafPlot = addLine(d.chart, leaf, palette::sahLeafCost, 2.f * d.scale, "leaf cost N t_i");
  leafPlot->GetPen()->SetLineType(vtkPen::DASH_LINE);
  if (!c.leaf && c.axis >= 0 && !conceal_) {
    auto chosen = makeTable("position", "chosen");
    double x = across(c.axis, c.position);
    addRow(chosen, x, lo - 0.02 * (hi - lo));
    addRow(chosen, x, hi);
    addLine(d.chart, chosen, palette::sahChosen, 1.5f * d.scale, std::string("chosen: ") + replay::axis_name(c.axis));
  }
  vtkAxis* left = d.chart->GetAxis(vtkAxis::LEFT);
  double pad =
      hi > lo ? 0.05 * (hi - lo) : std::max(1.0, 0.1 * std::abs(hi));  // a lone leaf cost: a plain range
  left->SetBehavior(vtkAxis::FIXED);
  left->SetRange(lo - pad, hi + pad);
  d.chart->RecalculateBounds();

  // The text: which node, what it holds, what the builder decided and why.
  QString t =
      tr("<b>node %1</b> (path %2), depth %3<br>N = %4 primitives<br>box (%5, %6, %7)<br>"
         "&nbsp;&nbsp;.. (%8, %9, %10)<br>")
          .arg(c.node)
          .arg(path.isEmpty() ? tr("root") : path)
          .arg(c.info.depth)
          .arg(c.n_prims)
          .arg(fmt(box.lo.x), fmt(box.lo.y), fmt(box.lo.z), fmt(box.hi.x), fmt(box.hi.y), fmt(box.hi.z));
  t += tr("candidates: x %1, y %2, z %3<br>")
           .arg(byAxis[0].size())
           .arg(byAxis[1].size())
           .arg(byAxis[2].size());
  t += tr("leaf cost N t_i = %1 &times; %2 = %3<br>").arg(c.n_prims).arg(double(t_i)).arg(fmt(c.leaf_cost));
  const QString header = t;
  if (c.leaf) {
    t += tr("<b>leaf</b>: %1 (%2)").arg(leaf_reason_name(c.leaf_reason)).arg(leafReasonText(c.leaf_reason));
    if (!c.candidates.empty()) {
      auto best =
          std::min_element(c.candidates.begin(), c.candidates.end(),
                           [](const SahCandidate& a, const SahCandidate& b) { return a.cost < b.cost; });
      t += tr("; the cheapest plane (%1 = %2) costs %3")
               .arg(replay::axis_name(best->axis))
               .arg(fmt(best->position))
               .arg(fmt(best->cost));
    }
    d.chart->SetTitle("node " + std::to_string(c.node) + ": leaf (" + leaf_reason_name(c.leaf_reason) + ")");
  } else {
    // With an empty side and an empty bonus b, the cost is t_t + (1 - b)(p_a N_a + p_b N_b) t_i.
    const bool chosen_known = c.chosen >= 0 && size_t(c.chosen) < c.candidates.size();
    const bool bonus =
        empty_bonus > 0.f && chosen_known &&
        (c.candidates[size_t(c.chosen)].n_below == 0 || c.candidates[size_t(c.chosen)].n_above == 0);
    if (bonus)
      t +=
          tr("<b>split %1 = %2</b>, cost %3 = t_t + (1 &minus; b)(p_a N_a + p_b N_b) t_i (t_t = %4; an empty "
             "side earns the empty bonus b = %5)")
              .arg(replay::axis_name(c.axis))
              .arg(fmt(c.position))
              .arg(fmt(c.cost))
              .arg(double(t_t))
              .arg(double(empty_bonus));
    else
      t += tr("<b>split %1 = %2</b>, cost %3 = t_t + p_a N_a t_i + p_b N_b t_i (t_t = %4)")
               .arg(replay::axis_name(c.axis))
               .arg(fmt(c.position))
               .arg(fmt(c.cost))
               .arg(double(t_t));
    if (chosen_known) {
      const SahCandidate& s = c.candidates[size_t(c.chosen)];
      t += tr("<br>N below %1, above %2 (planar %3)").arg(s.n_below).arg(s.n_above).arg(s.n_planar);
    }
    d.chart->SetTitle("node " + std::to_string(c.node) + ": split " + replay::axis_name(c.axis) + " = " +
                      fmt(c.position).toStdString());
  }
  if (conceal_) {  // the quiz asks for this choice: the curves only, until the answer is revealed
    t = header + tr("<i>The %1's choice stays hidden until the answer is revealed.</i>").arg(concealBuilder_);
    d.chart->SetTitle("node " + std::to_string(c.node) + ": which plane does the " +
                      concealBuilder_.toStdString() + " choose?");
  }
  text_->setText(t);
  renderNow();
}

namespace {

}  // namespace

void SahChart::setBvhCurve(std::shared_ptr<const BvhSahCurve> curve, const QString& path, float t_i,
                           float t_t) {
  // The chart draws candidates against their plane's position across the node's box: a BVH object candidate
  // is the plane between two bins of centroids, N left and right its sides' counts (no planar primitives:
  // each primitive goes to one side by its centroid). An SBVH node's spatial candidates (planes that cut the
  // primitives crossing them) are drawn as their own dashed series per axis, in the axis's colour.
  const BvhSahCurve& b = *curve;
  auto c = std::make_shared<SahCurve>(as_kd_curve(b, false));
  std::vector<const BvhCandidate*> spatial[3];
  for (const BvhCandidate& k : b.candidates)
    if (k.spatial && k.axis >= 0 && k.axis < 3) spatial[k.axis].push_back(&k);
  const bool chosenKnown = !b.leaf && b.chosen >= 0 && size_t(b.chosen) < b.candidates.size();
  const BvhCandidate* chosen = chosenKnown ? &b.candidates[size_t(b.chosen)] : nullptr;
  if (chosen && chosen->spatial) c->axis = -1;  // its line is drawn below, over the spatial costs too
  setCurve(c, path, t_i, t_t);
  bvhCurve_ = std::move(curve);
  Impl& d = *d_;
  const Bounds3& box = b.bvh_node.box;
  auto across = [&](int a, float pos) {
    const float extent = box.hi[a] - box.lo[a];
    return extent > 0.f ? double(pos - box.lo[a]) / double(extent) : 0.5;
  };
  size_t spatialCount = 0;
  for (int a = 0; a < 3; ++a) spatialCount += spatial[a].size();
  if (spatialCount > 0) {
    double lo = b.leaf_cost, hi = b.leaf_cost;
    for (const BvhCandidate& k : b.candidates) {
      lo = std::min(lo, double(k.cost));
      hi = std::max(hi, double(k.cost));
    }
    for (int a = 0; a < 3; ++a) {
      if (spatial[a].empty()) continue;
      d.spatialTable[a] = makeTable("position", "spatial cost");
      for (const BvhCandidate* k : spatial[a]) addRow(d.spatialTable[a], across(a, k->position), k->cost);
      vtkPlot* p = addLine(d.chart, d.spatialTable[a], axisColor(a), 2.f * d.scale,
                           std::string(replay::axis_name(a)) + " spatial (" + std::to_string(spatial[a].size()) +
                               ")");
      p->GetPen()->SetLineType(vtkPen::DASH_LINE);
    }
    if (chosen && chosen->spatial && !conceal_) {
      auto line = makeTable("position", "chosen");
      addRow(line, across(chosen->axis, chosen->position), lo - 0.02 * (hi - lo));
      addRow(line, across(chosen->axis, chosen->position), hi);
      addLine(d.chart, line, palette::sahChosen, 1.5f * d.scale,
              std::string("chosen: ") + replay::axis_name(chosen->axis) + " spatial");
    }
    const double pad = hi > lo ? 0.05 * (hi - lo) : std::max(1.0, 0.1 * std::abs(hi));
    d.chart->GetAxis(vtkAxis::LEFT)->SetRange(lo - pad, hi + pad);
    d.chart->RecalculateBounds();
  }
  const QString spatialWords =
      spatialCount == 0
          ? QString()
          : tr("<br>spatial candidates (dashed): x %1, y %2, z %3, planes across the node's box that cut the "
               "primitives crossing them, each side keeping its part")
                .arg(spatial[0].size())
                .arg(spatial[1].size())
                .arg(spatial[2].size());
  if (conceal_ || !chosen) {
    text_->setText(text_->text() + spatialWords);
    renderNow();
    return;
  }
  // The decision in the BVH's terms: the bin, the counts and the areas of each side's box.
  const BvhCandidate& k = *chosen;
  QString t = text_->text();
  const int cut = t.indexOf("<b>split");
  if (cut >= 0) t.truncate(cut);
  if (k.spatial)
    t += tr("<b>spatial split at %1 = %2</b> (bin %3), cost %4 = t_t + (S_l N_l + S_r N_r) t_i / S_node (t_t = "
            "%5)<br>N left %6, right %7 of %8: the %9 primitives crossing the plane are referenced on both "
            "sides, each side's box holding only its part, so the two boxes meet at the plane and do not "
            "overlap")
             .arg(replay::axis_name(k.axis))
             .arg(fmt(k.position))
             .arg(k.bin)
             .arg(fmt(k.cost))
             .arg(double(t_t))
             .arg(k.n_left)
             .arg(k.n_right)
             .arg(b.info.prims)
             .arg(k.n_left + k.n_right - b.info.prims);
  else
    t += tr("<b>bin %1 on %2</b> (plane %2 = %3), cost %4 = t_t + (S_l N_l + S_r N_r) t_i / S_node (t_t = %5)"
            "<br>N left %6, right %7; each side's box is tight around its primitives and may overlap the other")
             .arg(k.bin)
             .arg(replay::axis_name(k.axis))
             .arg(fmt(k.position))
             .arg(fmt(k.cost))
             .arg(double(t_t))
             .arg(k.n_left)
             .arg(k.n_right);
  text_->setText(t + spatialWords);
  d.chart->SetTitle("node " + std::to_string(b.node) + ": " +
                    (k.spatial ? std::string("spatial split") : "bin " + std::to_string(k.bin)) + " on " +
                    replay::axis_name(k.axis));
  renderNow();
}

void SahChart::setBspCurve(std::shared_ptr<const BspSahCurve> curve, const QString& path, float t_i,
                           float t_t) {
  curve_.reset();
  bvhCurve_.reset();
  bspCurve_ = std::move(curve);
  lastPath_ = path;
  lastTi_ = t_i;
  lastTt_ = t_t;
  lastBonus_ = 0.f;
  d_->message.clear();
  for (auto& t : d_->axisTable) t = nullptr;
  for (auto& t : d_->spatialTable) t = nullptr;
  orientation_->show();
  drawBspCurve();
}

bool SahChart::setBspOrientation(const QString& name) {
  const int i = orientation_->findData(name);
  if (i < 0) return false;
  orientation_->setCurrentIndex(i);  // redraws a BSP curve
  return true;
}

void SahChart::drawBspCurve() {
  Impl& d = *d_;
  const BspSahCurve& c = *bspCurve_;
  d.chart->ClearPlots();
  for (auto& t : d.bspTable) t = nullptr;
  d.bspSeries = QJsonArray();
  d.bspChosenX = -1.0;
  bottomTitle(d.chart, true);
  const QString filter = orientation_->currentData().toString();
  const bool all = filter == "all";
  auto shown = [&](int direction) {
    const int g = bspGroup(direction);
    return all || (filter == "axes" && g == 0) || (filter == "face" && g == 1) ||
           (filter == "body" && g == 2) || (filter == "own" && g == 3) ||
           filter == bsp_direction_name(direction);
  };
  auto across = [](const BspCandidate& k) {
    const double w = k.cell_max - k.cell_min;
    return w > 0.0 ? (double(k.plane.offset) - k.cell_min) / w : 0.5;
  };

  // The candidates per direction (13: the own planes), by position across the cell.
  std::vector<const BspCandidate*> per[kBspKdopDirections + 1];
  for (const BspCandidate& k : c.candidates)
    per[k.direction < 0 ? kBspKdopDirections : k.direction].push_back(&k);
  int groupCount[4] = {0, 0, 0, 0};
  for (int i = 0; i <= kBspKdopDirections; ++i)
    groupCount[bspGroup(i < kBspKdopDirections ? i : -1)] += int(per[i].size());
  // The chosen candidate: a black disc drawn first, so that its own series' marker shows inside it.
  const bool chosenKnown = !c.leaf && c.chosen >= 0 && size_t(c.chosen) < c.candidates.size();
  const BspCandidate* chosen = chosenKnown ? &c.candidates[size_t(c.chosen)] : nullptr;
  if (chosen && !conceal_ && shown(chosen->direction)) {
    auto mark = makeTable("position", "chosen cost");
    addRow(mark, across(*chosen), chosen->cost);
    vtkPlot* m = d.chart->AddPlot(vtkChart::POINTS);
    m->SetInputData(mark, 0, 1);
    m->SetColor(0, 0, 0, 255);
    m->SetLegendVisibility(false);
    if (auto* points = vtkPlotPoints::SafeDownCast(m)) {
      points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      points->SetMarkerSize(15.f * d.scale);
    }
  }
  double lo = c.leaf_cost, hi = c.leaf_cost;
  bool groupLabelled[4] = {false, false, false, false};
  for (int i = 0; i <= kBspKdopDirections; ++i) {
    const int direction = i < kBspKdopDirections ? i : -1;
    if (per[i].empty() || !shown(direction)) continue;
    std::stable_sort(per[i].begin(), per[i].end(),
                     [&](const BspCandidate* a, const BspCandidate* b) { return across(*a) < across(*b); });
    d.bspTable[i] = makeTable("position", "cost");
    for (const BspCandidate* k : per[i]) {
      addRow(d.bspTable[i], across(*k), k->cost);
      lo = std::min(lo, k->cost);
      hi = std::max(hi, k->cost);
    }
    // All orientations: one legend entry per group (the axes each their own, as in the kd-tree's chart);
    // a group or a direction alone: one per direction.
    const int g = bspGroup(direction);
    const QColor color = bspColor(direction, !all);
    std::string label = bsp_direction_name(direction);
    if (all && g != 0) label = std::string(kBspGroupNames[g]);
    label += " (" + std::to_string(all && g != 0 ? groupCount[g] : int(per[i].size())) + ")";
    const bool legend = !(all && g != 0 && groupLabelled[g]);
    groupLabelled[g] = true;
    vtkPlot* p;
    if (direction < 0) {  // each own plane has its own normal: points, not a curve
      p = d.chart->AddPlot(vtkChart::POINTS);
      p->SetInputData(d.bspTable[i], 0, 1);
      p->SetColor((unsigned char)color.red(), (unsigned char)color.green(), (unsigned char)color.blue(), 255);
      p->SetWidth(2.f * d.scale);
      p->SetLabel(label);
      if (auto* points = vtkPlotPoints::SafeDownCast(p)) {
        points->SetMarkerStyle(vtkPlotPoints::DIAMOND);
        points->SetMarkerSize(9.f * d.scale);
      }
    } else {
      p = addLine(d.chart, d.bspTable[i], color, (g == 0 ? 2.f : 1.5f) * d.scale, label);
      if (auto* points = vtkPlotPoints::SafeDownCast(p)) {
        points->SetMarkerStyle(vtkPlotPoints::CIRCLE);
        points->SetMarkerSize((per[i].size() == 1 ? 8.f : 4.f) * d.scale);
      }
    }
    p->SetLegendVisibility(legend);
    d.bspSeries.append(QJsonObject{{"direction", direction},
                                   {"name", bsp_direction_name(direction)},
                                   {"label", QString::fromStdString(label)},
                                   {"legend", legend},
                                   {"color", jsonColor(color)},
                                   {"points", int(per[i].size())}});
  }
  auto leaf = makeTable("position", "leaf cost");
  addRow(leaf, 0.0, c.leaf_cost);
  addRow(leaf, 1.0, c.leaf_cost);
  vtkPlot* leafPlot = addLine(d.chart, leaf, palette::sahLeafCost, 2.f * d.scale, "leaf cost N t_i");
  leafPlot->GetPen()->SetLineType(vtkPen::DASH_LINE);
  if (chosen && !conceal_ && shown(chosen->direction)) {
    // The chosen plane: a vertical line at its position (its marker was drawn first).
    d.bspChosenX = across(*chosen);
    auto line = makeTable("position", "chosen");
    addRow(line, d.bspChosenX, lo - 0.02 * (hi - lo));
    addRow(line, d.bspChosenX, hi);
    addLine(d.chart, line, palette::sahChosen, 1.5f * d.scale,
            std::string("chosen: ") + bsp_direction_name(chosen->direction));
  }
  vtkAxis* left = d.chart->GetAxis(vtkAxis::LEFT);
  const double pad = hi > lo ? 0.05 * (hi - lo) : std::max(1.0, 0.1 * std::abs(hi));
  left->SetBehavior(vtkAxis::FIXED);
  left->SetRange(lo - pad, hi + pad);
  d.chart->RecalculateBounds();

  // The text, short enough for the dock's height: the node, its cell, the candidates by orientation, the
  // decision in the BSP's terms and, first after it, what the best axis plane (a kd-tree's only choice) would
  // have cost. The cell's bounding box is in the tree view's tooltip.
  // (The candidates per group are in the legend.)
  QString t = tr("<b>node %1</b> (path %2), depth %3, N = %4; its cell, a convex polytope, has area S = "
                 "%5<br>")
                  .arg(c.node)
                  .arg(lastPath_.isEmpty() ? tr("root") : lastPath_)
                  .arg(c.info.depth)
                  .arg(c.n_prims)
                  .arg(fmt(c.info.area));
  t += tr("leaf cost N t_i = %1 &times; %2 = %3<br>")
           .arg(c.n_prims)
           .arg(double(lastTi_))
           .arg(fmt(c.leaf_cost));
  const QString header = t;
  const BspCandidate* bestAxis = nullptr;
  for (const BspCandidate& k : c.candidates)
    if (k.direction >= 0 && k.direction < 3 && (!bestAxis || k.cost < bestAxis->cost)) bestAxis = &k;
  if (c.leaf) {
    t += tr("<b>leaf</b>: %1 (%2)")
             .arg(bsp_leaf_reason_name(c.leaf_reason))
             .arg(bspLeafReasonText(c.leaf_reason));
    d.chart->SetTitle("node " + std::to_string(c.node) + ": leaf (" + bsp_leaf_reason_name(c.leaf_reason) +
                      ")");
  } else if (chosen) {
    const QString which = chosen->direction >= 0 ? tr("the %1 plane (%2)")
                                                       .arg(bsp_direction_name(chosen->direction))
                                                       .arg(tr(kBspGroupOne[bspGroup(chosen->direction)]))
                                                 : tr("the own plane of triangle %1").arg(chosen->prim);
    t += tr("<b>split by %1</b>, cost %4: n&middot;p = d, n = %2, d = %3<br>")
             .arg(which)
             .arg(vec(chosen->plane.normal))
             .arg(fmt(chosen->plane.offset))
             .arg(fmt(chosen->cost));
    if (chosen->direction >= 3 || chosen->direction < 0) {
      if (bestAxis)
        t += tr("<b>the best axis plane</b> (the kd-tree's choice), %1 = %2, costs %3: %4% more<br>")
                 .arg(bsp_direction_name(bestAxis->direction))
                 .arg(fmt(bestAxis->plane.offset))
                 .arg(fmt(bestAxis->cost))
                 .arg(100.0 * (bestAxis->cost / chosen->cost - 1.0), 0, 'f', 0);
    } else {
      t += tr("an axis plane: a kd-tree could have chosen it too<br>");
    }
    t += tr("C = t_t + t_i (S_b N_b + S_a N_a) / S; N below %1, above %2 (a primitive the plane cuts is on "
            "both sides)")
             .arg(c.n_below)
             .arg(c.n_above);
    if (!shown(chosen->direction))
      t += tr("<br><i>(the chosen plane's orientation is not shown: pick it above)</i>");
    d.chart->SetTitle("node " + std::to_string(c.node) + ": split by " +
                      (chosen->direction >= 0
                           ? std::string("the ") + bsp_direction_name(chosen->direction) + " plane"
                           : "triangle " + std::to_string(chosen->prim) + "'s own plane") +
                      ", d = " + fmt(chosen->plane.offset).toStdString());
  }
  if (conceal_) {
    t = header + tr("<i>The %1's choice stays hidden until the answer is revealed.</i>").arg(concealBuilder_);
    d.chart->SetTitle("node " + std::to_string(c.node) + ": which plane does the " +
                      concealBuilder_.toStdString() + " choose?");
  }
  text_->setText(t);
  renderNow();
}

void SahChart::renderNow() {
  d_->window->Render();
}

QImage SahChart::grabChart() {
  return d_->widget->grabFramebuffer();
}

bool SahChart::saveChart(const QString& path) {
  QSaveFile file(path);
  return file.open(QIODevice::WriteOnly) && grabChart().save(&file, "PNG") && file.commit();
}

QJsonObject SahChart::dumpState() const {
  const Impl& d = *d_;
  QJsonObject o;
  QWidget* win = window();
  QPoint off = d.widget->mapTo(win, QPoint(0, 0));
  o["viewport"] = QJsonArray{off.x(), off.y(), d.widget->width(), d.widget->height()};
  o["visible"] = d.widget->isVisible();
  o["colors"] = QJsonObject{{"x", jsonColor(palette::sahX)},
                            {"y", jsonColor(palette::sahY)},
                            {"z", jsonColor(palette::sahZ)},
                            {"leaf_cost", jsonColor(palette::sahLeafCost)},
                            {"chosen", jsonColor(palette::sahChosen)}};
  o["message"] = d.message;
  o["concealed"] = conceal_;
  if (bspCurve_) {
    const BspSahCurve& c = *bspCurve_;
    o["structure"] = "bsp";
    o["node"] = int(c.node);
    o["depth"] = c.info.depth;
    o["n_prims"] = int(c.n_prims);
    o["leaf_cost"] = c.leaf_cost;
    o["leaf"] = c.leaf;
    o["candidates"] = int(c.candidates.size());
    o["orientation"] = orientation_->currentData().toString();
    o["orientation_picker_visible"] = orientation_->isVisible();
    o["text"] = text_->text();
    o["title"] = QString::fromStdString(d.chart->GetTitle());
    o["colors"] = QJsonObject{{"x", jsonColor(palette::sahX)},
                              {"y", jsonColor(palette::sahY)},
                              {"z", jsonColor(palette::sahZ)},
                              {"face_diagonals", jsonColor(palette::sahFaceDiagonal)},
                              {"body_diagonals", jsonColor(palette::sahBodyDiagonal)},
                              {"own_planes", jsonColor(palette::sahOwnPlane)},
                              {"leaf_cost", jsonColor(palette::sahLeafCost)},
                              {"chosen", jsonColor(palette::sahChosen)}};
    QJsonObject points;  // as plotted, per direction name ("own plane" for the own planes)
    for (int i = 0; i <= kBspKdopDirections; ++i)
      points[bsp_direction_name(i < kBspKdopDirections ? i : -1)] =
          d.bspTable[i] ? int(d.bspTable[i]->GetNumberOfRows()) : 0;
    o["points"] = points;
    o["series"] = d.bspSeries;
    o["plots"] = int(d.chart->GetNumberOfPlots());
    if (c.leaf) {
      o["leaf_reason"] = bsp_leaf_reason_name(c.leaf_reason);
    } else if (c.chosen >= 0 && size_t(c.chosen) < c.candidates.size()) {
      const BspCandidate& k = c.candidates[size_t(c.chosen)];
      o["chosen"] = QJsonObject{{"index", c.chosen},
                                {"direction", k.direction},
                                {"name", bsp_direction_name(k.direction)},
                                {"source", bsp_plane_source_name(k.source)},
                                {"normal", QJsonArray{k.plane.normal.x, k.plane.normal.y, k.plane.normal.z}},
                                {"offset", k.plane.offset},
                                {"cost", k.cost},
                                {"x", d.bspChosenX},  // -1: not drawn (hidden by the picker or concealed)
                                {"n_below", int(c.n_below)},
                                {"n_above", int(c.n_above)}};
    }
    return o;
  }
  if (!curve_) return o;
  const SahCurve& c = *curve_;
  o["node"] = int(c.node);
  o["depth"] = c.info.depth;
  o["n_prims"] = int(c.n_prims);
  o["leaf_cost"] = c.leaf_cost;
  o["leaf"] = c.leaf;
  if (c.leaf)
    o["leaf_reason"] = leaf_reason_name(c.leaf_reason);
  else
    o["chosen"] = QJsonObject{
        {"axis", replay::axis_name(c.axis)}, {"position", c.position}, {"cost", c.cost}, {"index", c.chosen}};
  QJsonObject points;
  for (int a = 0; a < 3; ++a)
    points[replay::axis_name(a)] = d.axisTable[a] ? int(d.axisTable[a]->GetNumberOfRows()) : 0;
  o["points"] = points;  // as plotted: one per candidate
  o["plots"] = int(d.chart->GetNumberOfPlots());
  o["candidates"] = int(c.candidates.size());
  o["structure"] = bvhCurve_ ? "bvh" : "kd";
  if (bvhCurve_ && bvhCurve_->chosen >= 0 && size_t(bvhCurve_->chosen) < bvhCurve_->candidates.size()) {
    o["chosen_bin"] = bvhCurve_->candidates[size_t(bvhCurve_->chosen)].bin;
    o["chosen_kind"] = bvhCurve_->candidates[size_t(bvhCurve_->chosen)].spatial ? "spatial" : "object";
  }
  QJsonObject spatialPoints;
  for (int a = 0; a < 3; ++a)
    spatialPoints[replay::axis_name(a)] = d.spatialTable[a] ? int(d.spatialTable[a]->GetNumberOfRows()) : 0;
  o["spatial_points"] = spatialPoints;
  return o;
}

}  // namespace raystep::viz
