#include "compare/compare_window.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <map>
#include <regex>

#include <QCheckBox>
#include <QComboBox>
#include <QDialog>
#include <QDialogButtonBox>
#include <QFileInfo>
#include <QGridLayout>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QPushButton>
#include <QScrollBar>
#include <QSignalBlocker>
#include <QSlider>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>

#include "common/chart_util.h"
#include "compare/cost_chart.h"
#include "common/palette.h"
#include "raystep/geometry/numerics.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/side_by_side.h"
#include "views/scene_view.h"
#include "app/session.h"

namespace raystep::viz {

namespace {

constexpr int kSliderSteps = 1000;

// One colour per structure, the same in its caption, its table row and its chart line (Okabe and Ito's set).
const QColor& walkColor(int i) {
  static const QColor colors[replay::kMaxSideBySide] = {chartcolor::blue, chartcolor::vermillion, chartcolor::green,
                                                  chartcolor::purple};
  return colors[i % replay::kMaxSideBySide];
}

QString structureTitle(const std::string& kind) {
  static const std::map<std::string, const char*> names = {
      {"grid", "uniform grid"},    {"kd", "kd-tree (SAH)"},          {"kd-median", "kd-tree (median)"},
      {"bvh", "BVH (binned SAH)"}, {"bvh-sweep", "BVH (sweep SAH)"}, {"bvh-median", "BVH (median)"},
      {"bvh4", "4-wide BVH"},      {"bvh8", "8-wide BVH"},           {"octree", "octree"},
      {"bsp", "general BSP tree"}};
  auto it = names.find(kind);
  return it == names.end() ? QString::fromStdString(kind) : QString(it->second);
}

QString swatch(const QColor& c, const QString& text) {
  return QString("<span style='background:%1'>&nbsp;&nbsp;&nbsp;&nbsp;</span>&nbsp;%2&nbsp;&nbsp; ")
      .arg(c.name(), text);
}

// Every colour the views use for these structures, once (the views have no legend of their own).
QString legendFor(const QStringList& kinds) {
  QString t = swatch(palette::currentCell, QObject::tr("cell or node at t")) +
              swatch(palette::visitedCell, QObject::tr("visited before")) +
              swatch(palette::stackNode, QObject::tr("waiting on the stack"));
  bool bvh = false, octree = false;
  for (const QString& k : kinds) {
    bvh = bvh || replay::is_bvh_kind(k.toStdString());
    octree = octree || k == "octree";
  }
  if (bvh || octree)
    t += swatch(palette::bvhChildFirst,
                bvh ? QObject::tr("first child (BVH: its box)") : QObject::tr("first child on the ray")) +
         swatch(palette::bvhChildOther, QObject::tr("the other children"));
  if (bvh) t += swatch(palette::bvhSkipped, QObject::tr("skipped (BVH)"));
  return t + swatch(palette::ray, QObject::tr("ray up to t")) +
         swatch(palette::rayAhead, QObject::tr("ray beyond t")) +
         swatch(palette::segment, QObject::tr("current [tmin, tmax]")) +
         swatch(palette::hitCandidate, QObject::tr("nearest hit so far")) +
         swatch(palette::hitFinal, QObject::tr("accepted hit"));
}

QString num(double v) {
  return std::isfinite(v) ? QString::number(v, 'f', 3) : QString(v > 0 ? "inf" : "-inf");
}

}  // namespace

struct CompareWindow::Pane {
  Session* session = nullptr;
  SceneView* view = nullptr;
  QLabel* caption = nullptr;
  QWidget* box = nullptr;
  std::string kind;
  WalkCost cost;
  replay::WalkAtT now;
};

QString CompareWindow::atTRule() {
  return tr(
      "At t each view shows its walk before it enters its first cell or node beyond t (entry t: a cell's "
      "t_enter, a node's t_min, the furthest so far), and before the pops that lead there; the counters "
      "and the cost are what it spent before it moved past t.");
}

CompareWindow::CompareWindow(QWidget* parent) : QWidget(parent, Qt::Window) {
  setObjectName("compareWindow");
  setWindowTitle(tr("The same ray, side by side"));
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 6, 6, 6);
  layout->setSpacing(4);
  header_ = new QLabel;
  header_->setObjectName("compareHeader");
  header_->setWordWrap(true);
  layout->addWidget(header_);

  // The views on the left, as tall as the window allows (the walk's cells are small); the counters and the
  // chart beside them; the timeline across the bottom, under everything it moves.
  auto* split = new QSplitter(Qt::Horizontal);
  viewsBox_ = new QWidget;
  viewsGrid_ = new QGridLayout(viewsBox_);
  viewsGrid_->setContentsMargins(0, 0, 0, 0);
  viewsGrid_->setSpacing(4);
  split->addWidget(viewsBox_);

  table_ = new QTableWidget(0, 7);
  table_->setObjectName("compareTable");
  table_->setHorizontalHeaderLabels({tr("structure"), tr("steps"), tr("prim.\ntests"), tr("mailbox\nhits"),
                                     tr("box\ntests"), tr("cost\nat t"), tr("total\ncost")});
  const QStringList tips = {tr("The structure walked"),
                            tr("Cells or nodes visited: at t / in the whole walk"),
                            tr("Ray-primitive tests: at t / in the whole walk"),
                            tr("Tests skipped by the mailbox (already tested): at t / in the whole walk"),
                            tr("BVH: children's bounding boxes tested: at t / in the whole walk"),
                            tr("t_t per step + t_i per primitive test, spent before the walk moved past t "
                               "(the cheapest in bold)"),
                            tr("The cost of the whole walk, to its hit or exit")};
  for (int c = 0; c < tips.size(); ++c) table_->horizontalHeaderItem(c)->setToolTip(tips[c]);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionMode(QAbstractItemView::NoSelection);
  table_->verticalHeader()->hide();
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->setVerticalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  table_->setSizePolicy(QSizePolicy::Preferred, QSizePolicy::Fixed);  // as tall as its rows (fillTable)
  auto* side = new QWidget;
  auto* sideLayout = new QVBoxLayout(side);
  sideLayout->setContentsMargins(0, 0, 0, 0);
  sideLayout->setSpacing(3);
  auto* countersTitle = new QLabel(
      tr("<b>Counters</b> at t / in the whole walk (steps: cells or nodes visited; the cheapest cost at t "
         "in bold)"));
  countersTitle->setWordWrap(true);
  sideLayout->addWidget(countersTitle);
  sideLayout->addWidget(table_);
  chart_ = new CostChart;
  chart_->setObjectName("compareChart");
  sideLayout->addWidget(chart_, 1);
  split->addWidget(side);
  split->setStretchFactor(0, 2);
  split->setStretchFactor(1, 1);
  split->setSizes({790, 480});  // the table's seven columns whole, beside views still wider than tall
  layout->addWidget(split, 1);

  legend_ = new QLabel;
  legend_->setObjectName("compareLegend");
  legend_->setWordWrap(true);
  layout->addWidget(legend_);

  // The timeline over t.
  auto* row = new QHBoxLayout;
  auto* tTitle = new QLabel(tr("<b>Ray parameter t</b>"));
  startLabel_ = new QLabel;
  endLabel_ = new QLabel;
  slider_ = new QSlider(Qt::Horizontal);
  slider_->setObjectName("compareSlider");
  slider_->setRange(0, kSliderSteps);
  slider_->setSingleStep(1);
  slider_->setPageStep(kSliderSteps / 20);
  slider_->setToolTip(atTRule());
  tLabel_ = new QLabel;
  tLabel_->setObjectName("compareT");
  tLabel_->setMinimumWidth(90);
  QFont big = tLabel_->font();
  big.setBold(true);
  big.setPointSizeF(big.pointSizeF() * 1.2);
  tLabel_->setFont(big);
  rayCombo_ = new QComboBox;
  rayCombo_->setObjectName("compareRay");
  rayCombo_->setToolTip(tr("The ray of the pixel's ray tree walked in every view"));
  row->addWidget(tTitle);
  row->addWidget(startLabel_);
  row->addWidget(slider_, 1);
  row->addWidget(endLabel_);
  row->addWidget(tLabel_);
  row->addWidget(rayCombo_);
  layout->addLayout(row);
  rule_ = new QLabel(atTRule());
  rule_->setObjectName("compareRule");
  rule_->setWordWrap(true);
  rule_->setStyleSheet("color: #555");
  layout->addWidget(rule_);

  connect(slider_, &QSlider::valueChanged, this, &CompareWindow::setSliderPosition);
  connect(rayCombo_, QOverload<int>::of(&QComboBox::currentIndexChanged), this, &CompareWindow::setRay);

  resize(1280, 800);
}

CompareWindow::~CompareWindow() {
  clearPanes();
}

void CompareWindow::clearPanes() {
  for (auto& p : panes_) {
    delete p->box;  // the view before its session: it listens to it
    delete p->session;
  }
  panes_.clear();
}

SceneView* CompareWindow::view(int i) const {
  return i >= 0 && i < int(panes_.size()) ? panes_[size_t(i)]->view : nullptr;
}

void CompareWindow::setWalks(std::shared_ptr<const MultiTrace> walks, std::shared_ptr<const SceneData> scene,
                             std::vector<std::shared_ptr<const StructureData>> structures,
                             const QString& source) {
  clearPanes();
  walks_ = std::move(walks);
  scene_ = std::move(scene);
  structures_ = std::move(structures);
  const int n = walks_ ? int(walks_->walks.size()) : 0;
  // Two views one above the other, three or four in two rows of two: each wider than tall, as the scene's
  // camera frames it.
  const int columns = n <= 2 ? 1 : 2;
  QStringList names;
  std::vector<TracePrimitive> allPrimitives;
  if (!scene_) {
    std::map<int32_t, TracePrimitive> byId;
    for (const Trace& w : walks_->walks)
      for (const TracePrimitive& prim : w.primitives) byId.emplace(prim.id, prim);
    for (auto& [id, prim] : byId) allPrimitives.push_back(prim);
  }
  for (int i = 0; i < n; ++i) {
    const Trace& walk = walks_->walks[size_t(i)];
    auto pane = std::make_unique<Pane>();
    pane->kind = walk.structure.kind;
    names << QString::fromStdString(pane->kind);
    pane->session = new Session(this);
    pane->box = new QWidget;
    auto* v = new QVBoxLayout(pane->box);
    v->setContentsMargins(0, 0, 0, 0);
    v->setSpacing(1);
    pane->caption = new QLabel;
    pane->caption->setObjectName(QString("compareCaption%1").arg(i));
    pane->caption->setTextFormat(Qt::RichText);
    v->addWidget(pane->caption);
    pane->view = new SceneView(pane->session);
    pane->view->setObjectName(QString("compareView%1").arg(i));
    pane->view->setCompact(true);
    if (i > 0) pane->view->shareCamera(panes_.front()->view);
    v->addWidget(pane->view, 1);
    // Three views: the third under the first two, as wide as both (no empty corner).
    viewsGrid_->addWidget(pane->box, i / columns, i % columns, 1, n == 3 && i == 2 ? 2 : 1);
    // The walk's own trace shares the document's lifetime. Without the scene, a view draws the primitives its
    // trace names: every view gets those of all the walks, so that they show the same geometry.
    std::shared_ptr<const Trace> trace(walks_, &walk);
    if (!scene_ && n > 1) {
      auto withAll = std::make_shared<Trace>(walk);
      withAll->primitives = allPrimitives;
      trace = withAll;
    }
    if (scene_) pane->session->setScene(scene_);
    if (i < int(structures_.size())) pane->session->setStructure(structures_[size_t(i)]);
    pane->session->setTrace(trace, source);
    panes_.push_back(std::move(pane));
  }
  // One camera: a drag in any view draws them all.
  for (auto& p : panes_)
    connect(p->view, &SceneView::cameraMoved, this, [this, sender = p->view] {
      for (auto& q : panes_)
        if (q->view != sender) q->view->renderNow();
    });
  // Framed at the views' real size: now if the window is up, else when it is shown.
  needsFit_ = true;
  if (isVisible()) QTimer::singleShot(0, this, [this] { fitCamera(); });

  QString where;
  const TracedRay* r0 = n > 0 && !walks_->walks[0].rays.empty() ? &walks_->walks[0].rays[0] : nullptr;
  if (r0 && r0->has_pixel) where = tr("pixel (%1, %2) of ").arg(r0->pixel[0]).arg(r0->pixel[1]);
  header_->setText(
      tr("<b>The same ray through %1 structures:</b> %2 &nbsp; <span style='color:#555'>(%3%4; cost "
         "t_t = 1 per step, t_i = 80 per primitive test, the lecture's model)</span>")
          .arg(n)
          .arg(names.join(", "))
          .arg(where)
          .arg(QFileInfo(QString::fromStdString(walks_ ? walks_->scene_path : "")).fileName().isEmpty()
                   ? source
                   : QFileInfo(QString::fromStdString(walks_->scene_path)).fileName()));
  setWindowTitle(tr("The same ray, side by side: %1").arg(names.join(", ")));
  legend_->setText(legendFor(names));

  {
    const QSignalBlocker block(rayCombo_);
    rayCombo_->clear();
    const size_t rays = n > 0 ? walks_->walks[0].rays.size() : 0;
    for (size_t k = 0; k < rays; ++k) {
      const TracedRay& r = walks_->walks[0].rays[k];
      rayCombo_->addItem(tr("ray %1: %2 (depth %3)").arg(k).arg(ray_kind_name(r.kind)).arg(r.depth));
    }
    rayCombo_->setVisible(rays > 1);
  }
  ray_ = -1;
  setRay(0);
}

int CompareWindow::rayCount() const {
  return walks_ && !walks_->walks.empty() ? int(walks_->walks[0].rays.size()) : 0;
}

void CompareWindow::setRay(int index) {
  if (!walks_ || walks_->walks.empty()) return;
  const int rays = int(walks_->walks[0].rays.size());
  if (index < 0 || index >= rays || index == ray_) return;
  ray_ = index;
  {
    const QSignalBlocker block(rayCombo_);
    rayCombo_->setCurrentIndex(index);
  }
  std::vector<const TracedRay*> rs;
  std::vector<CostChart::Series> series;
  for (size_t i = 0; i < panes_.size(); ++i) {
    Pane& p = *panes_[i];
    p.session->setRay(index);
    const TracedRay& r = walks_->walks[i].rays[size_t(index)];
    rs.push_back(&r);
    p.cost = walk_cost(r, CostModel{});
  }
  const replay::TimelineRange range = replay::timeline_range(rs);
  tStart_ = range.start;
  tEnd_ = range.end;
  for (size_t i = 0; i < panes_.size(); ++i)
    series.push_back({QString::fromStdString(panes_[i]->kind), walkColor(int(i)),
                      replay::cost_staircase(panes_[i]->cost, range.start, range.end)});
  chart_->setSeries(series, tStart_, tEnd_, tr("cumulative cost: 1 per step + 80 per primitive test"));
  startLabel_->setText(num(tStart_));
  endLabel_->setText(num(tEnd_));
  startLabel_->setToolTip(tr("The first entry: where the first structure enters its first cell or node"));
  endLabel_->setToolTip(tr("The furthest end: the hit (or exit) of the walk that stops last"));
  t_ = tStart_ - 1.0;  // differs from any t: setT shows it
  setT(tStart_);
}

void CompareWindow::setSliderPosition(int position) {
  position = std::clamp(position, 0, kSliderSteps);
  const double t = position == kSliderSteps ? tEnd_ : tStart_ + (tEnd_ - tStart_) * position / kSliderSteps;
  setT(t);
}

void CompareWindow::setT(double t) {
  if (!std::isfinite(t)) return;
  t = std::clamp(t, tStart_, tEnd_);
  if (t == t_) return;
  t_ = t;
  {
    const QSignalBlocker block(slider_);
    slider_->setValue(int(std::lround((t - tStart_) / std::max(tEnd_ - tStart_, 1e-30) * kSliderSteps)));
  }
  showT();
  Q_EMIT tChanged(t_);
}

void CompareWindow::showT() {
  tLabel_->setText(tr("t = %1").arg(num(t_)));
  for (size_t i = 0; i < panes_.size(); ++i) {
    Pane& p = *panes_[i];
    const TracedRay* ray = p.session->ray();
    if (!ray) continue;
    p.now = replay::walk_at_t(*ray, float(t_), CostModel{});
    {
      const QSignalBlocker block(p.session);  // the view is drawn once, by setRayMark
      p.session->setStep(p.now.step);
    }
    p.view->setRayMark(float(t_));
    // The caption: the structure, and where its walk is at t.
    const replay::ReplayState& s = p.session->state();
    const Trace& walk = walks_->walks[i];
    QString where;
    if (s.ended && p.now.next == kInfinity) {
      const Event& end = ray->events.back();
      where = end.prim >= 0 ? tr("done: hit primitive %1 at t = %2").arg(end.prim).arg(num(end.t))
                            : tr("done: missed");
    } else if (s.cell_event >= 0 && walk.structure.kind == "grid") {
      const Event& e = ray->events[size_t(s.cell_event)];
      where = tr("in cell (%1, %2, %3), entered at t = %4")
                  .arg(e.cell[0])
                  .arg(e.cell[1])
                  .arg(e.cell[2])
                  .arg(num(e.t_enter));
    } else if (s.node_event >= 0) {
      const Event& e = ray->events[size_t(s.node_event)];
      const TraceNode* node = replay::find_node(walk, e.node);
      where = tr("at node %1 (depth %2%3), t_min = %4")
                  .arg(e.node)
                  .arg(e.depth)
                  .arg(node && node->leaf ? tr(", leaf") : QString())
                  .arg(num(e.t_min_node));
    } else {
      where = tr("not entered yet (its first step is at t = %1)").arg(num(p.now.next));
    }
    p.caption->setText(
        QString("<span style='background:%1'>&nbsp;&nbsp;&nbsp;</span> <b>%2</b> (%3): %4")
            .arg(walkColor(int(i)).name(), QString::fromStdString(p.kind), structureTitle(p.kind), where));
  }
  fillTable();
  chart_->setMarker(t_);
}

void CompareWindow::fillTable() {
  const bool resize = table_->rowCount() != int(panes_.size());
  table_->setRowCount(int(panes_.size()));
  double cheapest = HUGE_VAL;
  for (const auto& p : panes_) cheapest = std::min(cheapest, p->now.cost);
  for (size_t i = 0; i < panes_.size(); ++i) {
    const Pane& p = *panes_[i];
    const QStringList cells = {QString::fromStdString(p.kind),
                               QString("%1 / %2").arg(p.now.steps).arg(p.cost.steps),
                               QString("%1 / %2").arg(p.now.prim_tests).arg(p.cost.prim_tests),
                               QString("%1 / %2").arg(p.now.mailbox_hits).arg(p.cost.mailbox_hits),
                               QString("%1 / %2").arg(p.now.box_tests).arg(p.cost.box_tests),
                               QString::number(p.now.cost, 'f', 0),
                               QString::number(p.cost.total, 'f', 0)};
    for (int c = 0; c < cells.size(); ++c) {
      auto* item = new QTableWidgetItem(cells[c]);
      if (c > 0) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
      if (c == 0) item->setForeground(walkColor(int(i)));
      if (c == 0 || (c == 5 && p.now.cost == cheapest)) {
        QFont f = item->font();
        f.setBold(true);
        item->setFont(f);
      }
      table_->setItem(int(i), c, item);
    }
  }
  if (resize) {
    table_->resizeColumnsToContents();
    table_->resizeRowsToContents();
  }
  int h = table_->horizontalHeader()->sizeHint().height() + 2 * table_->frameWidth();
  for (int r = 0; r < table_->rowCount(); ++r) h += table_->rowHeight(r);
  if (table_->horizontalScrollBar()->isVisible()) h += table_->horizontalScrollBar()->height();
  table_->setFixedHeight(h);
}

void CompareWindow::showEvent(QShowEvent* event) {
  QWidget::showEvent(event);
  if (needsFit_) QTimer::singleShot(0, this, [this] { fitCamera(); });
}

void CompareWindow::fitCamera() {
  needsFit_ = false;
  if (panes_.empty()) return;
  panes_.front()->view->fitCamera();
  renderNow();
}

void CompareWindow::renderNow() {
  for (auto& p : panes_) p->view->renderNow();
  chart_->renderNow();
}

QJsonObject CompareWindow::dumpState() const {
  QJsonObject o;
  o["t"] = t_;
  o["t_start"] = tStart_;
  o["t_end"] = tEnd_;
  o["slider"] = slider_->value();
  o["slider_steps"] = kSliderSteps;
  o["ray"] = ray_;
  o["rays"] = walks_ && !walks_->walks.empty() ? int(walks_->walks[0].rays.size()) : 0;
  o["t_label"] = tLabel_->text();
  o["rule"] = rule_->text();
  o["slider_tooltip"] = slider_->toolTip();
  o["header"] = header_->text();
  QJsonArray views;
  for (size_t i = 0; i < panes_.size(); ++i) {
    const Pane& p = *panes_[i];
    const replay::ReplayState& s = p.session->state();
    QJsonObject v{
        {"structure", QString::fromStdString(p.kind)},
        {"step", p.now.step},
        {"session_step", p.session->step()},
        {"events", p.session->eventCount()},
        {"event_type", s.event ? event_type_name(s.event->type) : ""},
        {"entered", std::isfinite(p.now.entered) ? QJsonValue(double(p.now.entered)) : QJsonValue()},
        {"next", std::isfinite(p.now.next) ? QJsonValue(double(p.now.next)) : QJsonValue()},
        {"caption", p.caption->text()},
        {"color", QJsonArray{walkColor(int(i)).red(), walkColor(int(i)).green(), walkColor(int(i)).blue()}}};
    v["at_t"] = QJsonObject{{"steps", int(p.now.steps)},
                            {"prim_tests", int(p.now.prim_tests)},
                            {"mailbox_hits", int(p.now.mailbox_hits)},
                            {"box_tests", int(p.now.box_tests)},
                            {"cost", p.now.cost},
                            {"cost_at", cost_at(p.cost, float(t_))}};
    v["total"] = QJsonObject{{"steps", int(p.cost.steps)},
                             {"prim_tests", int(p.cost.prim_tests)},
                             {"mailbox_hits", int(p.cost.mailbox_hits)},
                             {"box_tests", int(p.cost.box_tests)},
                             {"cost", p.cost.total},
                             {"hit", p.cost.hit},
                             {"t_hit", double(p.cost.t_hit)}};
    v["view"] = p.view->dumpState();
    views.append(v);
  }
  o["views"] = views;
  QJsonArray rows;
  for (int r = 0; r < table_->rowCount(); ++r) {
    QJsonArray row;
    for (int c = 0; c < table_->columnCount(); ++c)
      row.append(table_->item(r, c) ? table_->item(r, c)->text() : QString());
    rows.append(row);
  }
  o["table"] = rows;
  o["chart"] = chart_->dumpState();
  o["window"] = QJsonArray{width(), height()};
  return o;
}

std::shared_ptr<const MultiTrace> recordComparePixel(
    const std::vector<std::shared_ptr<const StructureData>>& structures, int width, int height, int px,
    int py, bool secondary) {
  const SceneData& sd = *structures.front()->scene;
  std::vector<const Accelerator*> accels;
  for (const auto& s : structures) accels.push_back(s->accel.get());
  // The pixel's rays are spawned once, by the first structure: every structure walks exactly those.
  const std::vector<RayRequest> requests =
      pixel_rays(sd.scene, *accels.front(), width, height, px, py, secondary);
  return std::make_shared<const MultiTrace>(
      record_walks(sd.scene.geometry, accels, requests, sd.path, sd.hash));
}

bool isMultiTraceFile(const QString& path) {
  std::ifstream in(path.toStdString(), std::ios::binary);
  std::string head(4096, '\0');
  in.read(&head[0], long(head.size()));
  head.resize(size_t(in.gcount()));
  static const std::regex version("\"version\"\\s*:\\s*5[^0-9]");
  return head.find("\"raystep-trace\"") != std::string::npos && std::regex_search(head, version);
}

QStringList pickCompareStructures(QWidget* parent, const QStringList& checked) {
  QDialog dialog(parent);
  dialog.setWindowTitle(QObject::tr("Compare structures side by side"));
  auto* layout = new QVBoxLayout(&dialog);
  layout->addWidget(new QLabel(QObject::tr("The same ray through 2 to 4 structures (then click a pixel):")));
  const QStringList kinds = {"grid",       "kd",   "kd-median", "bvh",    "bvh-sweep",
                             "bvh-median", "bvh4", "bvh8",      "octree", "bsp"};
  std::vector<QCheckBox*> boxes;
  for (const QString& k : kinds) {
    auto* box = new QCheckBox(QString("%1  (%2)").arg(k, structureTitle(k.toStdString())));
    box->setObjectName("compare_" + k);
    box->setChecked(checked.contains(k));
    layout->addWidget(box);
    boxes.push_back(box);
  }
  auto* buttons = new QDialogButtonBox(QDialogButtonBox::Ok | QDialogButtonBox::Cancel);
  layout->addWidget(buttons);
  auto update = [&] {
    int n = 0;
    for (QCheckBox* b : boxes) n += b->isChecked();
    buttons->button(QDialogButtonBox::Ok)->setEnabled(n >= replay::kMinSideBySide && n <= replay::kMaxSideBySide);
  };
  for (QCheckBox* b : boxes) QObject::connect(b, &QCheckBox::toggled, &dialog, update);
  update();
  QObject::connect(buttons, &QDialogButtonBox::accepted, &dialog, &QDialog::accept);
  QObject::connect(buttons, &QDialogButtonBox::rejected, &dialog, &QDialog::reject);
  if (dialog.exec() != QDialog::Accepted) return {};
  QStringList out;
  for (size_t i = 0; i < boxes.size(); ++i)
    if (boxes[i]->isChecked()) out << kinds[int(i)];
  return out;
}

}  // namespace raystep::viz
