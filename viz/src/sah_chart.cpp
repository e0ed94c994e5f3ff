#include "sah_chart.h"

#include <algorithm>
#include <cmath>

#include <QHBoxLayout>
#include <QJsonArray>
#include <QLabel>
#include <QMouseEvent>
#include <QSaveFile>
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

#include "chart_util.h"
#include "palette.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "replay.h"

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
  QString message;
  float scale = 1.f;
};

SahChart::SahChart(QWidget* parent) : QWidget(parent), d_(new Impl) {
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  text_ = new QLabel;
  text_->setObjectName("sahText");
  text_->setWordWrap(true);
  text_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  text_->setAlignment(Qt::AlignLeft | Qt::AlignTop);
  text_->setFixedWidth(230);
  layout->addWidget(text_);

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
  bottom->SetTitle("split position across the node (0 = box min, 1 = box max)");
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
  if (curve_) setCurve(curve_, lastPath_, lastTi_, lastTt_, lastBonus_);
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
  if (curve_) {
    QString path = lastPath_;
    setCurve(curve_, path, lastTi_, lastTt_, lastBonus_);
  } else {
    renderNow();
  }
}

void SahChart::showMessage(const QString& text) {
  curve_.reset();
  bvhCurve_.reset();
  d_->message = text;
  d_->chart->ClearPlots();
  for (auto& t : d_->axisTable) t = nullptr;
  d_->chart->SetTitle("");
  text_->setText(text);
  renderNow();
}

void SahChart::setCurve(std::shared_ptr<const SahCurve> curve, const QString& path, float t_i, float t_t,
                        float empty_bonus) {
  Impl& d = *d_;
  curve_ = std::move(curve);
  bvhCurve_.reset();
  lastPath_ = path;
  lastTi_ = t_i;
  lastTt_ = t_t;
  lastBonus_ = empty_bonus;
  d.message.clear();
  d.chart->ClearPlots();
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
                         std::string(axisName(a)) + " (" + std::to_string(byAxis[a].size()) + ")");
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
    addLine(d.chart, chosen, palette::sahChosen, 1.5f * d.scale, std::string("chosen: ") + axisName(c.axis));
  }
  vtkAxis* left = d.chart->GetAxis(vtkAxis::LEFT);
  double pad =
      hi > lo ? 0.05 * (hi - lo) : std::max(1.0, 0.1 * std::abs(hi));  // a lone leaf cost: a plain range
  left->SetBehavior(vtkAxis::FIXED);
  left->SetRange(lo - pad, hi + pad);
  d.chart->RecalculateBounds();

  // The text: which node, what it holds, what the builder decided and why.
  QString t =
      tr("<b>node %1</b> (path \"%2\"), depth %3<br>N = %4 primitives<br>box (%5, %6, %7)<br>"
         "&nbsp;&nbsp;.. (%8, %9, %10)<br>")
          .arg(c.node)
          .arg(path)
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
               .arg(axisName(best->axis))
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
              .arg(axisName(c.axis))
              .arg(fmt(c.position))
              .arg(fmt(c.cost))
              .arg(double(t_t))
              .arg(double(empty_bonus));
    else
      t += tr("<b>split %1 = %2</b>, cost %3 = t_t + p_a N_a t_i + p_b N_b t_i (t_t = %4)")
               .arg(axisName(c.axis))
               .arg(fmt(c.position))
               .arg(fmt(c.cost))
               .arg(double(t_t));
    if (chosen_known) {
      const SahCandidate& s = c.candidates[size_t(c.chosen)];
      t += tr("<br>N below %1, above %2 (planar %3)").arg(s.n_below).arg(s.n_above).arg(s.n_planar);
    }
    d.chart->SetTitle("node " + std::to_string(c.node) + ": split " + axisName(c.axis) + " = " +
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

LeafReason kdReasonOf(BvhLeafReason r) {
  switch (r) {
    case BvhLeafReason::few_primitives:
      return LeafReason::few_primitives;
    case BvhLeafReason::max_depth:
      return LeafReason::max_depth;
    case BvhLeafReason::no_cheaper_split:
      return LeafReason::no_cheaper_split;
    case BvhLeafReason::no_candidate:
      return LeafReason::no_candidate;
  }
  return LeafReason::few_primitives;
}

}  // namespace

void SahChart::setBvhCurve(std::shared_ptr<const BvhSahCurve> curve, const QString& path, float t_i,
                           float t_t) {
  // The chart draws candidates against their plane's position across the node's box: a BVH candidate is the
  // plane between two bins of centroids, N left and right its sides' counts (no planar primitives: each
  // primitive goes to one side by its centroid).
  const BvhSahCurve& b = *curve;
  auto c = std::make_shared<SahCurve>();
  c->node = b.node;
  c->info.box = b.bvh_node.box;
  c->info.parent = b.info.parent;
  c->info.depth = b.info.depth;
  c->info.cost = b.info.cost;
  c->n_prims = b.info.prims;
  c->leaf_cost = b.leaf_cost;
  c->leaf = b.leaf;
  c->leaf_reason = kdReasonOf(b.leaf_reason);
  c->chosen = b.chosen;
  for (const BvhCandidate& k : b.candidates) {
    SahCandidate s;
    s.axis = k.axis;
    s.position = k.position;
    s.n_below = k.n_left;
    s.n_above = k.n_right;
    s.area_below = k.area_left;
    s.area_above = k.area_right;
    s.area_node = k.area_node;
    s.cost = k.cost;
    c->candidates.push_back(s);
  }
  const bool chosenKnown = b.chosen >= 0 && size_t(b.chosen) < b.candidates.size();
  if (!b.leaf && chosenKnown) {
    const BvhCandidate& k = b.candidates[size_t(b.chosen)];
    c->axis = k.axis;
    c->position = k.position;
    c->cost = k.cost;
  }
  setCurve(c, path, t_i, t_t);
  bvhCurve_ = std::move(curve);
  if (conceal_ || b.leaf || !chosenKnown) return;
  // The decision in the BVH's terms: the bin, the counts and the areas of each side's tight box.
  const BvhCandidate& k = b.candidates[size_t(b.chosen)];
  QString t = text_->text();
  const int cut = t.indexOf("<b>split");
  if (cut >= 0) t.truncate(cut);
  t += tr("<b>bin %1 on %2</b> (plane %2 = %3), cost %4 = t_t + (S_l N_l + S_r N_r) t_i / S_node (t_t = %5)"
          "<br>N left %6, right %7; each side's box is tight around its primitives and may overlap the other")
           .arg(k.bin)
           .arg(axisName(k.axis))
           .arg(fmt(k.position))
           .arg(fmt(k.cost))
           .arg(double(t_t))
           .arg(k.n_left)
           .arg(k.n_right);
  text_->setText(t);
  d_->chart->SetTitle("node " + std::to_string(b.node) + ": bin " + std::to_string(k.bin) + " on " +
                      axisName(k.axis));
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
        {"axis", axisName(c.axis)}, {"position", c.position}, {"cost", c.cost}, {"index", c.chosen}};
  QJsonObject points;
  for (int a = 0; a < 3; ++a)
    points[axisName(a)] = d.axisTable[a] ? int(d.axisTable[a]->GetNumberOfRows()) : 0;
  o["points"] = points;  // as plotted: one per candidate
  o["plots"] = int(d.chart->GetNumberOfPlots());
  o["candidates"] = int(c.candidates.size());
  o["structure"] = bvhCurve_ ? "bvh" : "kd";
  if (bvhCurve_ && bvhCurve_->chosen >= 0 && size_t(bvhCurve_->chosen) < bvhCurve_->candidates.size())
    o["chosen_bin"] = bvhCurve_->candidates[size_t(bvhCurve_->chosen)].bin;
  return o;
}

}  // namespace raystep::viz
