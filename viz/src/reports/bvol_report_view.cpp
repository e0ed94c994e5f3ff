#include "reports/bvol_report_view.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QLocale>
#include <QProgressBar>
#include <QPushButton>
#include <QSplitter>
#include <QTableWidget>
#include <QVBoxLayout>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartMatrix.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkNew.h>
#include <vtkPlot.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkStringArray.h>
#include <vtkTable.h>
#include <vtkTextProperty.h>
#include <vtkVector.h>

#include "common/chart_util.h"
#include "raystep/util/error.h"
#include "app/session.h"

namespace raystep::viz {
namespace {

// The kinds in the report's order, as the lecture names them.
QString kindLabel(const std::string& kind) {
  if (kind == "bvol") return QObject::tr("box");
  if (kind == "bvol-sphere") return QObject::tr("sphere");
  if (kind == "bvol-kdop") return QObject::tr("14-DOP");
  if (kind == "bvol-obb") return QObject::tr("oriented box");
  return QString::fromStdString(kind);
}

// The four charts, bars per kind: each one or two quantities.
struct Quantity {
  const char* key;
  const char* label;
  QColor color;
  double (*value)(const BvolReportRow&);
};
struct Panel {
  const char* title;
  const char* yTitle;
  std::vector<Quantity> quantities;
};

const std::vector<Panel>& panels() {
  static const std::vector<Panel> p = {
      {"Volumes entered per ray, and entered in vain",
       "volumes per ray",
       {{"entered_per_ray", "entered", chartcolor::blue,
         [](const BvolReportRow& r) { return r.entered_per_ray; }},
        {"false_positives_per_ray", "in vain (object missed)", chartcolor::vermillion,
         [](const BvolReportRow& r) { return r.false_positives_per_ray; }}}},
      {"False-positive rate: entered volumes whose object the ray misses",
       "percent of entered volumes",
       {{"false_positive_percent", "false positives", chartcolor::vermillion,
         [](const BvolReportRow& r) { return 100.0 * r.false_positive_rate; }}}},
      {"Primitive tests per ray (what a false positive costs)",
       "tests per ray",
       {{"prim_tests_per_ray", "primitive tests", chartcolor::green,
         [](const BvolReportRow& r) { return r.prim_tests_per_ray; }}}},
      {"Time per ray: the volume tests and the primitive tests",
       "nanoseconds per ray",
       {{"ns_per_ray", "time", chartcolor::purple, [](const BvolReportRow& r) { return r.ns_per_ray; }}}},
  };
  return p;
}

}  // namespace

struct BvolReportView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartMatrix> matrix;
  vtkChartXY* charts[4] = {};
  std::map<std::string, vtkSmartPointer<vtkTable>> series;  // per quantity key: (kind index, value)
};

BvolReportView::BvolReportView(Session* session, QWidget* parent)
    : ReportWindow(parent), d_(new Impl), session_(session) {
  setObjectName("bvolReportView");
  cancellingText_ = tr("Cancelling: the report stops once its kinds are measured...");
  setWindowTitle(tr("raystep - kinds of bounding volumes"));
  resize(1040, 760);
  auto* layout = new QVBoxLayout(this);
  addHeader(layout, "bvolReport");
  auto* options = new QHBoxLayout;
  options->addStretch(1);
  addRunCancel(options, "bvolReport");
  layout->addLayout(options);
  addProgress(layout, "bvolReport");

  Impl& d = *d_;
  auto* split = new QSplitter(Qt::Vertical);
  d.widget = new QVTKOpenGLNativeWidget;
  d.widget->setMinimumSize(500, 360);
  chartutil::showContextView(d.widget, d.window, d.view);
  chartutil::addChartMatrix2x2(d.view, d.matrix, d.charts);
  for (int i = 0; i < 4; ++i) {
    const Panel& p = panels()[size_t(i)];
    chartutil::ChartStyle style;
    style.labelSize = 11;
    style.legend = p.quantities.size() > 1;
    style.legendAlignment = vtkChartLegend::RIGHT;
    chartutil::styleChart(d.charts[i], p.title, "kind of bounding volume", p.yTitle, style);
    d.charts[i]->SetBarWidthFraction(0.7f);
  }
  split->addWidget(d.widget);

  table_ = new QTableWidget(0, 10);
  table_->setObjectName("bvolReportTable");
  table_->setHorizontalHeaderLabels({tr("kind"), tr("objects"), tr("rays"), tr("volume tests / ray"),
                                     tr("volumes hit / ray"), tr("entered / ray"), tr("in vain / ray"),
                                     tr("false-positive rate"), tr("prim tests / ray"), tr("ns / ray")});
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->verticalHeader()->setVisible(false);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  split->addWidget(table_);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 1);
  split->setSizes({500, 170});
  layout->addWidget(split, 1);
  addStatus(layout, "bvolReport");

  connect(session_, &Session::sceneChanged, this, [this] {
    if (running()) cancel();
  });
  header_->setText(
      tr("One bounding volume per object: a ray tests every volume, and the object only when it enters "
         "the volume (T = B + p &middot; n &middot; I). Run measures four kinds on the scene's camera "
         "rays: a tighter volume is entered in vain less often (p) and costs more per test (B)."));
  status_->setText(tr("Which kind lets the fewest rays in vain, and which is fastest?"));
  redraw();
}

BvolReportView::~BvolReportView() {
  stopWorker();
}

QString BvolReportView::start() {
  stopForNewRun();
  auto scene = session_->sceneShared();
  try {
    if (!scene) throw InputError("", 0, "open a scene first: the report builds the volumes of its objects");
    rows_.clear();
    table_->setRowCount(0);
    sceneName_ = QFileInfo(QString::fromStdString(scene->path)).fileName();
    progress_->setRange(0, 0);  // one call measures every kind: a busy bar
    const int gen = beginRun(tr("Measuring... each kind built and traced with the same rays."));
    header_->setText(
        tr("<b>%1</b>: %2 objects, each in its own volume. Every ray tests every volume; it tests "
           "an object's primitives only when it enters the object's volume before its nearest hit "
           "so far. T = B + p &middot; n &middot; I: a tighter volume has a smaller p and a "
           "costlier test B.")
            .arg(sceneName_)
            .arg(scene->scene.geometry.objects().size()));
    redraw();
    auto result = std::make_shared<std::vector<BvolReportRow>>();
    auto work = [scene, result] { *result = run_bvol_report(scene->scene, BvolReportOptions{}); };
    runOnWorker(gen, work,
                [this, result](const QString& state, const QString& error) { done(*result, state, error); });
  } catch (const std::exception& e) {
    return refuseStart(e);
  }
  return lastError();
}

void BvolReportView::done(const std::vector<BvolReportRow>& rows, const QString& state,
                          const QString& error) {
  endRun(state, error);
  progress_->setRange(0, 1000);
  progress_->setValue(state == "done" ? 1000 : 0);
  if (state == "done") rows_ = rows;
  fillTable();
  if (state == "failed") {
    status_->setText(tr("<span style='color:#b00'>The report failed: %1</span>").arg(error.toHtmlEscaped()));
  } else if (state == "cancelled" || rows_.empty()) {
    status_->setText(tr("<b>Cancelled.</b>"));
  } else {
    auto fewest =
        std::min_element(rows_.begin(), rows_.end(), [](const BvolReportRow& a, const BvolReportRow& b) {
          return a.false_positive_rate < b.false_positive_rate;
        });
    auto fastest = std::min_element(
        rows_.begin(), rows_.end(),
        [](const BvolReportRow& a, const BvolReportRow& b) { return a.ns_per_ray < b.ns_per_ray; });
    uint64_t wrong = 0;
    for (const BvolReportRow& r : rows_) wrong += r.disagreements;
    status_->setText(
        tr("<b>Done</b>: %1 rays. Fewest entered in vain: <b>%2</b> (%3 %). Fastest: <b>%4</b> "
           "(%5 ns per ray, one thread; times vary from run to run). %6")
            .arg(QLocale().toString(qulonglong(rows_.front().rays)))
            .arg(kindLabel(fewest->kind))
            .arg(100.0 * fewest->false_positive_rate, 0, 'f', 1)
            .arg(kindLabel(fastest->kind))
            .arg(fastest->ns_per_ray, 0, 'f', 0)
            .arg(wrong == 0
                     ? tr("Every kind finds the same hits as brute force.")
                     : tr("<span style='color:#b00'>%1 rays differ from brute force!</span>").arg(wrong)));
  }
  redraw();
  Q_EMIT finished();
}

void BvolReportView::fillTable() {
  table_->setRowCount(0);
  for (const BvolReportRow& row : rows_) {
    const int r = table_->rowCount();
    table_->insertRow(r);
    const QStringList cells = {kindLabel(row.kind),
                               QString::number(qulonglong(row.objects)),
                               QString::number(qulonglong(row.rays)),
                               QString::number(row.volume_tests_per_ray, 'f', 2),
                               QString::number(row.volume_hits_per_ray, 'f', 2),
                               QString::number(row.entered_per_ray, 'f', 2),
                               QString::number(row.false_positives_per_ray, 'f', 2),
                               tr("%1 %").arg(100.0 * row.false_positive_rate, 0, 'f', 1),
                               QString::number(row.prim_tests_per_ray, 'f', 2),
                               QString::number(row.ns_per_ray, 'f', 0)};
    for (int c = 0; c < cells.size(); ++c) {
      auto* item = new QTableWidgetItem(cells[c]);
      item->setTextAlignment((c == 0 ? Qt::AlignLeft : Qt::AlignRight) | Qt::AlignVCenter);
      table_->setItem(r, c, item);
    }
  }
}

void BvolReportView::redraw() {
  Impl& d = *d_;
  d.series.clear();
  // The kinds at x = 1..4, named by custom ticks.
  vtkNew<vtkDoubleArray> ticks;
  vtkNew<vtkStringArray> names;
  for (size_t k = 0; k < rows_.size(); ++k) {
    ticks->InsertNextValue(double(k + 1));
    names->InsertNextValue(kindLabel(rows_[k].kind).toStdString());
  }
  for (int i = 0; i < 4; ++i) {
    vtkChartXY* c = d.charts[i];
    c->ClearPlots();
    const Panel& p = panels()[size_t(i)];
    double yhi = 0.0;
    for (const Quantity& q : p.quantities) {
      auto t = chartutil::makeTable("kind", q.key);
      for (size_t k = 0; k < rows_.size(); ++k) {
        const double y = q.value(rows_[k]);
        chartutil::addRow(t, double(k + 1), std::isfinite(y) ? y : 0.0);
        if (std::isfinite(y)) yhi = std::max(yhi, y);
      }
      d.series[q.key] = t;
      if (rows_.empty()) continue;
      vtkPlot* plot = c->AddPlot(vtkChart::BAR);
      plot->SetInputData(t, 0, 1);
      plot->SetColor(uchar(q.color.red()), uchar(q.color.green()), uchar(q.color.blue()), 255);
      plot->SetLabel(q.label);
      plot->SetTooltipLabelFormat(std::string(q.label) + " = %y");
    }
    vtkAxis* x = c->GetAxis(vtkAxis::BOTTOM);
    x->SetBehavior(vtkAxis::FIXED);
    x->SetRange(0.4, std::max<double>(1.0, double(rows_.size())) + 0.6);
    if (rows_.empty())
      x->SetCustomTickPositions(nullptr, nullptr);
    else
      x->SetCustomTickPositions(ticks, names);
    // Head room for the legend above the bars.
    chartutil::setLinearRange(c->GetAxis(vtkAxis::LEFT), 0.0,
                              yhi > 0.0 ? yhi * (p.quantities.size() > 1 ? 1.35 : 1.1) : 1.0);
    c->RecalculateBounds();
  }
  renderNow();
}

void BvolReportView::renderNow() {
  d_->window->Render();
}

QOpenGLWidget* BvolReportView::chartWidget() const {
  return d_->widget;
}

QJsonObject BvolReportView::dumpState() const {
  QJsonObject o = dumpCommon();
  o["scene"] = sceneName_;
  QJsonArray rows;
  for (const BvolReportRow& r : rows_)
    rows.append(QJsonObject{{"kind", QString::fromStdString(r.kind)},
                            {"objects", double(r.objects)},
                            {"rays", double(r.rays)},
                            {"volume_tests_per_ray", r.volume_tests_per_ray},
                            {"entered_per_ray", r.entered_per_ray},
                            {"false_positives_per_ray", r.false_positives_per_ray},
                            {"false_positive_rate", r.false_positive_rate},
                            {"prim_tests_per_ray", r.prim_tests_per_ray},
                            {"ns_per_ray", r.ns_per_ray},
                            {"disagreements", double(r.disagreements)}});
  o["rows"] = rows;
  QJsonObject series;
  for (const auto& [name, t] : d_->series) {
    QJsonArray pts;
    for (vtkIdType i = 0; i < t->GetNumberOfRows(); ++i)
      pts.append(QJsonArray{t->GetValue(i, 0).ToDouble(), t->GetValue(i, 1).ToDouble()});
    series[QString::fromStdString(name)] = pts;
  }
  o["series"] = series;
  o["table_rows"] = table_->rowCount();
  return o;
}

}  // namespace raystep::viz
