#include "reports/grid_sweep_view.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QProgressBar>
#include <QPushButton>
#include <QSlider>
#include <QSplitter>
#include <QTableWidget>
#include <QTimer>
#include <QVBoxLayout>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPen.h>
#include <vtkPlot.h>
#include <vtkPlotPoints.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

#include "app/session.h"
#include "common/chart_util.h"
#include "raystep/accel/grid.h"
#include "raystep/util/error.h"

namespace raystep::viz {
namespace {

constexpr int kSliderSteps = 240;

// The four charts, each a quantity against d; log: the quantity spans decades.
struct Quantity {
  const char* key;
  const char* label;
  QColor color;
  double (*value)(const GridSweepRow&);
};
struct Panel {
  const char* title;
  const char* yTitle;
  bool log;
  std::vector<Quantity> quantities;
};

const std::vector<Panel>& panels() {
  static const std::vector<Panel> p = {
      {"The walk: cells visited and primitives tested per ray",
       "mean per ray (log scale)",
       true,
       {{"cells_per_ray", "cells / ray", chartcolor::blue,
         [](const GridSweepRow& r) { return r.cells_per_ray; }},
        {"tests_per_ray", "tests / ray", chartcolor::vermillion,
         [](const GridSweepRow& r) { return r.tests_per_ray; }}}},
      {"References per primitive (cells each primitive is stored in)",
       "references per primitive",
       false,
       {{"references_per_prim", "references per primitive", chartcolor::green,
         [](const GridSweepRow& r) { return r.references_per_prim; }}}},
      // Linear from 0: where the walk's and the tests' costs balance, the time has its minimum.
      {"Trace time: all rays, median pass (the minimum is the best d)",
       "milliseconds",
       false,
       {{"trace_ms", "trace", chartcolor::purple,
         [](const GridSweepRow& r) { return r.trace_seconds * 1e3; }}}},
      {"Build time of the grid (memory: in the table)",
       "milliseconds (log scale)",
       true,
       {{"build_ms", "build", chartcolor::orange,
         [](const GridSweepRow& r) { return r.build_seconds * 1e3; }}}},
  };
  return p;
}

// Chart i of the 2 x 2 matrix: 0 top left, 1 top right, 2 bottom left, 3 bottom right (the matrix counts
// rows from the bottom).
QString resolutionText(const std::array<int, 3>& r) {
  return QString("%1 x %2 x %3").arg(r[0]).arg(r[1]).arg(r[2]);
}

}  // namespace

struct GridSweepView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartMatrix> matrix;
  vtkChartXY* charts[4] = {};
  std::map<std::string, vtkSmartPointer<vtkTable>> series;  // per quantity key, and "marker<i>"
  double progress = 0.0;
  float markerDensity = 0.f;  // where the charts mark the grid (0: nowhere)
};

GridSweepView::GridSweepView(Session* session, QWidget* parent)
    : ReportWindow(parent), d_(new Impl), session_(session) {
  setObjectName("gridSweepView");
  cancellingText_ = tr("Cancelling: the sweep stops after the density under way...");
  setWindowTitle(tr("raystep - grid sweep: how fine should the grid be?"));
  resize(1040, 760);
  auto* layout = new QVBoxLayout(this);
  addHeader(layout, "gridSweep");

  auto* options = new QHBoxLayout;
  options->addWidget(new QLabel(tr("Densities d:")));
  densities_ = new QLineEdit;
  densities_->setObjectName("gridSweepDensities");
  densities_->setPlaceholderText(tr("default: 0.5, 0.75, 1, 1.5, 2, 3, 4, 6, 8"));
  options->addWidget(densities_, 1);
  addRunCancel(options, "gridSweep");
  layout->addLayout(options);
  addProgress(layout, "gridSweep");

  Impl& d = *d_;
  auto* split = new QSplitter(Qt::Vertical);
  d.widget = new QVTKOpenGLNativeWidget;
  d.widget->setMinimumSize(500, 360);
  chartutil::showContextView(d.widget, d.window, d.view);
  chartutil::addChartMatrix2x2(d.view, d.matrix, d.charts);
  for (int i = 0; i < 4; ++i) {
    const Panel& p = panels()[size_t(i)];
    // Short labels (the title says the rest), top centre, in head room the y axis leaves for it (redraw):
    // the curves cross everywhere else.
    chartutil::ChartStyle style;
    style.legend = p.quantities.size() > 1;
    style.legendAlignment = vtkChartLegend::CENTER;
    chartutil::styleChart(d.charts[i], p.title, "grid density d (log scale)", p.yTitle, style);
  }
  split->addWidget(d.widget);

  // The slider: d between the smallest and the largest measured, on a log scale like the charts.
  auto* below = new QWidget;
  auto* belowLayout = new QVBoxLayout(below);
  belowLayout->setContentsMargins(0, 0, 0, 0);
  auto* sliderRow = new QHBoxLayout;
  sliderRow->addWidget(new QLabel(tr("Rebuild the grid at d:")));
  slider_ = new QSlider(Qt::Horizontal);
  slider_->setObjectName("gridSweepSlider");
  slider_->setRange(0, kSliderSteps);
  slider_->setEnabled(false);
  slider_->setToolTip(
      tr("Drag to choose a density: the main window builds its grid with it (3D view, heat map)"));
  sliderRow->addWidget(slider_, 1);
  belowLayout->addLayout(sliderRow);
  chosenText_ = new QLabel;
  chosenText_->setObjectName("gridSweepChosen");
  chosenText_->setWordWrap(true);
  belowLayout->addWidget(chosenText_);
  table_ = new QTableWidget(0, 10);
  table_->setObjectName("gridSweepTable");
  table_->setHorizontalHeaderLabels({tr("d"), tr("resolution"), tr("cells"), tr("refs / primitive"),
                                     tr("cells / ray"), tr("tests / ray"), tr("trace"), tr("build"),
                                     tr("memory"), tr("Mrays/s")});
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->verticalHeader()->setVisible(false);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  belowLayout->addWidget(table_, 1);
  split->addWidget(below);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 1);
  split->setSizes({440, 230});
  layout->addWidget(split, 1);
  addStatus(layout, "gridSweep");

  rebuildTimer_ = new QTimer(this);
  rebuildTimer_->setSingleShot(true);
  rebuildTimer_->setInterval(300);  // a drag rebuilds once it rests, not at every step
  connect(rebuildTimer_, &QTimer::timeout, this, [this] { Q_EMIT densityChosen(chosen_); });
  connect(slider_, &QSlider::valueChanged, this, &GridSweepView::sliderMoved);
  connect(slider_, &QSlider::sliderReleased, this, [this] {
    rebuildTimer_->stop();
    Q_EMIT densityChosen(chosen_);
  });
  connect(session_, &Session::sceneChanged, this, [this] {
    if (running()) cancel();
  });
  // The built grid's density is marked when none was chosen here (or another was built in the panel).
  connect(session_, &Session::structureChanged, this, [this] {
    const StructureData* s = session_->structure();
    const UniformGrid* g = s ? s->grid() : nullptr;
    if (g && !g->options().resolution) {
      d_->markerDensity = g->options().density;
      if (std::abs(g->options().density - chosen_) > 1e-6f * chosen_) chosen_ = 0.f;
      updateChosenText();
      redraw();
    }
  });
  header_->setText(
      tr("Run builds the grid at each density d, with max(nx, ny, nz) = d &middot; "
         "&#8731;n, and traces the same rays through each: the lecture's rule put to the test."));
  status_->setText(
      tr("Fewer, larger cells: few cells per ray but many tests. More, smaller cells: few "
         "tests but many cells, more references and memory. Where is the minimum time?"));
  redraw();
}

GridSweepView::~GridSweepView() {
  stopWorker();
}

void GridSweepView::setDensities(const QString& densities) {
  densities_->setText(densities);
}

QString GridSweepView::start() {
  stopForNewRun();
  auto scene = session_->sceneShared();
  try {
    if (!scene) throw InputError("", 0, "open a scene first: the sweep builds grids over the current scene");
    GridSweepOptions o;
    for (const QString& part : densities_->text().split(',', Qt::SkipEmptyParts)) {
      if (part.trimmed().isEmpty()) continue;
      bool ok = false;
      const float v = part.trimmed().toFloat(&ok);
      if (!ok || !(v > 0.f) || v > 64.f)
        throw InputError("", 0,
                         "density '" + part.trimmed().toStdString() + "': expected a number in (0, 64]");
      o.densities.push_back(v);
    }
    sweep_ = GridSweep{};
    sweep_.primitives = scene->scene.geometry.size();
    sceneName_ = QFileInfo(QString::fromStdString(scene->path)).fileName();
    table_->setRowCount(0);
    d_->progress = 0.0;
    progress_->setValue(0);
    progress_->setRange(0, std::max<int>(1, int(o.densities.empty() ? 9 : o.densities.size())));
    const int gen = beginRun(tr("Sweeping... each density's grid is built and traced."));
    slider_->setEnabled(false);
    const double n = double(std::max<size_t>(1, sweep_.primitives));
    header_->setText(tr("<b>%1</b>: n = %2 primitives, so the grid's longest axis has d &middot; &#8731;n = "
                        "d &times; %3 cells. Each density: the grid built, then the same rays traced "
                        "through it.")
                         .arg(sceneName_)
                         .arg(sweep_.primitives)
                         .arg(std::cbrt(n), 0, 'f', 2));
    redraw();

    auto result = std::make_shared<GridSweep>();
    auto work = [this, scene, o, gen, result] {
      auto rowDone = [this, gen](const GridSweepRow& row) {
        toGui(gen, [this, row] { addRow(row); });
        rowDoneOnWorker();
      };
      *result = run_grid_sweep(scene->scene, o, rowDone, &cancel_);
    };
    runOnWorker(gen, work,
                [this, result](const QString& state, const QString& error) { done(*result, state, error); });
  } catch (const std::exception& e) {
    return refuseStart(e);
  }
  return lastError();
}

void GridSweepView::addRow(const GridSweepRow& row) {
  sweep_.rows.push_back(row);
  progress_->setValue(int(sweep_.rows.size()));
  const int r = table_->rowCount();
  table_->insertRow(r);
  QLocale l;
  const QStringList cells = {
      QString::number(double(row.density), 'g', 3),
      resolutionText(row.resolution) + (row.coarsened ? tr(" (coarsened)") : QString()),
      l.toString(qulonglong(row.cells)),
      QString::number(row.references_per_prim, 'f', 2),
      QString::number(row.cells_per_ray, 'f', 2),
      QString::number(row.tests_per_ray, 'f', 2),
      tr("%1 ms").arg(row.trace_seconds * 1e3, 0, 'f', 2),
      tr("%1 ms").arg(row.build_seconds * 1e3, 0, 'f', 2),
      tr("%1 KiB").arg(row.bytes / 1024.0, 0, 'f', 1),
      QString::number(row.mrays_per_second, 'f', 2)};
  for (int c = 0; c < cells.size(); ++c) {
    auto* item = new QTableWidgetItem(cells[c]);
    item->setTextAlignment((c == 1 ? Qt::AlignLeft : Qt::AlignRight) | Qt::AlignVCenter);
    table_->setItem(r, c, item);
  }
  table_->scrollToBottom();
  redraw();
}

void GridSweepView::done(const GridSweep& sweep, const QString& state, const QString& error) {
  endRun(state, error);
  if (state != "failed" && sweep.rows.size() >= sweep_.rows.size()) {
    const bool sameRows = sweep.rows.size() == sweep_.rows.size();
    if (!sameRows) {
      sweep_.rows.clear();
      table_->setRowCount(0);
      for (const GridSweepRow& r : sweep.rows) addRow(r);
    }
    sweep_ = sweep;
  }
  if (state == "done") progress_->setValue(progress_->maximum());
  table_->scrollToTop();
  if (state == "failed") {
    status_->setText(tr("<span style='color:#b00'>The sweep failed: %1</span>").arg(error.toHtmlEscaped()));
  } else {
    QString t = state == "cancelled" ? tr("<b>Cancelled</b> after %1 densities.").arg(sweep_.rows.size())
                                     : tr("<b>Done</b>: %1 densities, %2 rays each.")
                                           .arg(sweep_.rows.size())
                                           .arg(QLocale().toString(qulonglong(sweep_.rays)));
    if (!sweep_.rows.empty()) {
      auto fastest = std::min_element(
          sweep_.rows.begin(), sweep_.rows.end(),
          [](const GridSweepRow& a, const GridSweepRow& b) { return a.trace_seconds < b.trace_seconds; });
      t += tr(" Fastest trace at d = %1 (%2 cells, %3 cells and %4 tests per ray). Drag the slider to "
              "rebuild the main window's grid at any d and watch the 3D view and the heat map.")
               .arg(double(fastest->density), 0, 'g', 3)
               .arg(resolutionText(fastest->resolution))
               .arg(fastest->cells_per_ray, 0, 'f', 1)
               .arg(fastest->tests_per_ray, 0, 'f', 1);
    }
    status_->setText(t);
  }
  updateSlider();
  redraw();
  Q_EMIT finished();
}

float GridSweepView::densityAt(int v) const {
  if (sweep_.rows.empty()) return 0.f;
  float lo = sweep_.rows.front().density, hi = lo;
  for (const GridSweepRow& r : sweep_.rows) lo = std::min(lo, r.density), hi = std::max(hi, r.density);
  if (!(hi > lo)) return lo;
  const double t = double(v) / kSliderSteps;
  double dd = std::exp(std::log(lo) + t * (std::log(hi) - std::log(lo)));
  // Near a measured density (within a slider step and a half), the measured one.
  const double step = (std::log(hi) - std::log(lo)) / kSliderSteps;
  for (const GridSweepRow& r : sweep_.rows)
    if (std::abs(std::log(dd) - std::log(double(r.density))) < 1.5 * step) return r.density;
  return float(std::round(dd * 100.0) / 100.0);  // two decimals, as the structure panel shows d
}

int GridSweepView::sliderAt(float density) const {
  if (sweep_.rows.empty()) return 0;
  float lo = sweep_.rows.front().density, hi = lo;
  for (const GridSweepRow& r : sweep_.rows) lo = std::min(lo, r.density), hi = std::max(hi, r.density);
  if (!(hi > lo)) return 0;
  const double t = (std::log(std::clamp(density, lo, hi)) - std::log(lo)) / (std::log(hi) - std::log(lo));
  return int(std::lround(t * kSliderSteps));
}

void GridSweepView::updateSlider() {
  slider_->setEnabled(sweep_.rows.size() >= 1 && !running());
  settingSlider_ = true;
  slider_->setValue(sliderAt(chosen_ > 0.f ? chosen_ : d_->markerDensity));
  settingSlider_ = false;
  updateChosenText();
}

void GridSweepView::sliderMoved(int value) {
  if (settingSlider_) return;
  chosen_ = densityAt(value);
  d_->markerDensity = chosen_;
  updateChosenText();
  redraw();
  rebuildTimer_->start();
}

void GridSweepView::chooseDensity(float density) {
  if (sweep_.rows.empty()) return;
  float lo = sweep_.rows.front().density, hi = lo;
  for (const GridSweepRow& r : sweep_.rows) lo = std::min(lo, r.density), hi = std::max(hi, r.density);
  chosen_ = std::clamp(density, lo, hi);
  d_->markerDensity = chosen_;
  settingSlider_ = true;
  slider_->setValue(sliderAt(chosen_));
  settingSlider_ = false;
  updateChosenText();
  redraw();
  rebuildTimer_->stop();
  Q_EMIT densityChosen(chosen_);
}

void GridSweepView::updateChosenText() {
  const float dd = chosen_ > 0.f ? chosen_ : d_->markerDensity;
  const SceneData* scene = session_->scene();
  if (!(dd > 0.f) || !scene || sweep_.rows.empty()) {
    chosenText_->setText(
        tr("After the sweep, the slider chooses d; the charts mark it with a dashed vertical line."));
    return;
  }
  const Geometry& g = scene->scene.geometry;
  const auto res = UniformGrid::resolution_for(g.bounds(), g.size(), dd, g.split_space());
  const GridSweepRow* measured = nullptr;
  for (const GridSweepRow& r : sweep_.rows)
    if (r.density == dd) measured = &r;
  QString t = tr("<b>d = %1</b> (the dashed line): max(nx, ny, nz) = round(%1 &times; %2) = %3, so the grid "
                 "is %4 cells")
                  .arg(double(dd), 0, 'g', 3)
                  .arg(std::cbrt(double(std::max<size_t>(1, g.size()))), 0, 'f', 2)
                  .arg(std::max({res[0], res[1], res[2]}))
                  .arg(resolutionText(res));
  t += measured ? tr(" (a measured density: its row is selected below).")
                : tr(" (between the measured densities: the main window's grid shows it, the charts "
                     "have no point there).");
  if (chosen_ <= 0.f) t += tr(" This is the grid the main window has built now.");
  chosenText_->setText(t);
  table_->clearSelection();
  for (int i = 0; i < int(sweep_.rows.size()); ++i)
    if (&sweep_.rows[size_t(i)] == measured) table_->selectRow(i);
}

void GridSweepView::redraw() {
  Impl& d = *d_;
  d.series.clear();
  double xlo = HUGE_VAL, xhi = -HUGE_VAL;
  for (const GridSweepRow& r : sweep_.rows)
    if (r.density > 0.f) xlo = std::min(xlo, double(r.density)), xhi = std::max(xhi, double(r.density));
  if (!(xhi >= xlo)) xlo = 0.5, xhi = 8.0;
  const double mark = d.markerDensity;
  for (int i = 0; i < 4; ++i) {
    vtkChartXY* c = d.charts[i];
    c->ClearPlots();
    const Panel& p = panels()[size_t(i)];
    double ylo = HUGE_VAL, yhi = -HUGE_VAL;
    for (const Quantity& q : p.quantities) {
      std::vector<std::pair<double, double>> pts;
      std::vector<std::pair<double, std::string>> names;  // hovering a point names its grid
      for (const GridSweepRow& r : sweep_.rows) {
        const double y = q.value(r);
        if (!(r.density > 0.f) || !std::isfinite(y) || (p.log && !(y > 0.0))) continue;
        pts.push_back({double(r.density), y});
        names.push_back({double(r.density), "d = " + chartutil::tickLabel(r.density) + ", grid " +
                                                resolutionText(r.resolution).toStdString()});
      }
      std::stable_sort(pts.begin(), pts.end());
      std::stable_sort(names.begin(), names.end(),
                       [](const auto& a, const auto& b) { return a.first < b.first; });
      auto t = chartutil::makeTable("d", q.key);
      for (const auto& [x, y] : pts) {
        chartutil::addRow(t, x, y);
        ylo = std::min(ylo, y), yhi = std::max(yhi, y);
      }
      d.series[q.key] = t;
      if (pts.empty()) continue;
      vtkPlot* plot = c->AddPlot(pts.size() >= 2 ? vtkChart::LINE : vtkChart::POINTS);
      plot->SetInputData(t, 0, 1);
      plot->SetColor(uchar(q.color.red()), uchar(q.color.green()), uchar(q.color.blue()), 255);
      plot->SetWidth(2.f);
      plot->SetLabel(q.label);
      vtkNew<vtkStringArray> labels;
      for (const auto& n : names) labels->InsertNextValue(n.second);
      plot->SetIndexedLabels(labels);
      plot->SetTooltipLabelFormat(std::string("%i: ") + q.label + " = %y");
      if (auto* pp = vtkPlotPoints::SafeDownCast(plot)) {
        pp->SetMarkerStyle(vtkPlotPoints::CIRCLE);
        pp->SetMarkerSize(7.f);
      }
    }
    if (!(yhi >= ylo)) ylo = p.log ? 1.0 : 0.0, yhi = p.log ? 10.0 : 1.0;
    if (p.log) {
      // About a third of the height above the data for the legend.
      const double decades = std::log10(yhi / ylo);
      const double room = p.quantities.size() > 1 ? std::pow(10.0, std::max(0.5, 0.55 * decades)) : 1.0;
      chartutil::setLogRange(c->GetAxis(vtkAxis::LEFT), ylo, yhi * room);
    } else {
      chartutil::setLinearRange(c->GetAxis(vtkAxis::LEFT), std::min(0.0, ylo), yhi);
    }
    chartutil::setLogRange(c->GetAxis(vtkAxis::BOTTOM), xlo, xhi);
    // The chosen (or built) density: a dashed vertical line across the chart.
    if (mark > 0.0 && !sweep_.rows.empty()) {
      double range[2];
      c->GetAxis(vtkAxis::LEFT)->GetUnscaledRange(range);
      auto t = chartutil::makeTable("d", "marker");
      const double lo = p.log ? range[0] * 1.05 : range[0], hi = p.log ? range[1] / 1.05 : range[1];
      chartutil::addRow(t, mark, lo);
      chartutil::addRow(t, mark, hi);
      d.series["marker" + std::to_string(i)] = t;
      vtkPlot* plot = c->AddPlot(vtkChart::LINE);
      plot->SetInputData(t, 0, 1);
      plot->SetColor(0, 0, 0, 255);
      plot->SetWidth(1.5f);
      plot->GetPen()->SetLineType(vtkPen::DASH_LINE);
      plot->SetLabel(QString("d = %1").arg(mark, 0, 'g', 3).toStdString());
      plot->SetLegendVisibility(false);  // the text under the slider says what the dashed line is
      if (auto* pp = vtkPlotPoints::SafeDownCast(plot)) pp->SetMarkerStyle(vtkPlotPoints::NONE);
    }
    c->RecalculateBounds();
  }
  renderNow();
}

void GridSweepView::renderNow() {
  d_->window->Render();
}

QOpenGLWidget* GridSweepView::chartWidget() const {
  return d_->widget;
}

QJsonObject GridSweepView::dumpState() const {
  const Impl& d = *d_;
  QJsonObject o = dumpCommon();
  o["primitives"] = double(sweep_.primitives);
  QJsonArray rows;
  for (const GridSweepRow& r : sweep_.rows)
    rows.append(QJsonObject{{"density", double(r.density)},
                            {"resolution", QJsonArray{r.resolution[0], r.resolution[1], r.resolution[2]}},
                            {"cells_per_ray", r.cells_per_ray},
                            {"tests_per_ray", r.tests_per_ray},
                            {"references_per_prim", r.references_per_prim},
                            {"trace_seconds", r.trace_seconds}});
  o["rows"] = rows;
  QJsonObject series;
  for (const auto& [name, t] : d.series) {
    QJsonArray pts;
    for (vtkIdType i = 0; i < t->GetNumberOfRows(); ++i)
      pts.append(QJsonArray{t->GetValue(i, 0).ToDouble(), t->GetValue(i, 1).ToDouble()});
    series[QString::fromStdString(name)] = pts;
  }
  o["series"] = series;
  o["chosen_density"] = double(chosen_);
  o["marker_density"] = double(d.markerDensity);
  o["slider"] = QJsonObject{{"value", slider_->value()}, {"enabled", slider_->isEnabled()}};
  o["table_rows"] = table_->rowCount();
  return o;
}

}  // namespace raystep::viz
