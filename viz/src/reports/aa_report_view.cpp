#include "reports/aa_report_view.h"

#include <algorithm>
#include <cmath>
#include <map>

#include <QComboBox>
#include <QFileInfo>
#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QLineEdit>
#include <QLocale>
#include <QProgressBar>
#include <QPushButton>
#include <QSpinBox>
#include <QSplitter>
#include <QTabBar>
#include <QTableWidget>
#include <QVBoxLayout>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkAxis.h>
#include <vtkChartLegend.h>
#include <vtkChartXY.h>
#include <vtkContextScene.h>
#include <vtkContextView.h>
#include <vtkDoubleArray.h>
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

#include "common/chart_util.h"
#include "raystep/util/error.h"
#include "app/session.h"

namespace raystep::viz {
namespace {

// The method families in the order of the legend; "none" is one point of its own.
const char* const kFamilies[] = {"regular", "jitter", "random", "adaptive", "regular+tent", "jitter+tent",
                                 "random+tent"};

// Without a Size, the report renders the scene at most this many pixels on its long side.
constexpr int kDefaultSide = 128;

const QColor& familyColor(const std::string& family) {
  static const std::map<std::string, QColor> colors = {{"regular", chartcolor::blue},
                                                       {"jitter", chartcolor::vermillion},
                                                       {"random", chartcolor::green},
                                                       {"adaptive", chartcolor::purple},
                                                       {"regular+tent", chartcolor::skyBlue},
                                                       {"jitter+tent", chartcolor::orange},
                                                       {"random+tent", chartcolor::grey},
                                                       {"none", chartcolor::black}};
  auto it = colors.find(family);
  return it != colors.end() ? it->second : chartcolor::grey;
}

QString familyLabel(const std::string& family) {
  if (family == "regular") return QObject::tr("regular k x k");
  if (family == "jitter") return QObject::tr("jittered k x k");
  if (family == "random") return QObject::tr("random N");
  if (family == "adaptive") return QObject::tr("adaptive (thresholds)");
  if (family == "none") return QObject::tr("none (1 ray, centre)");
  if (const size_t plus = family.find("+tent"); plus != std::string::npos)
    return familyLabel(family.substr(0, plus)) + QObject::tr(", tent filter");
  return QString::fromStdString(family);
}

QString num(double v, int digits = 3) {
  return QString::number(v, 'g', digits);
}

}  // namespace

struct AaReportView::Impl {
  QVTKOpenGLNativeWidget* widget = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkContextView> view;
  vtkNew<vtkChartXY> chart;
  // What is plotted, per series name ("regular", ..., "none", "theory -1/2", ...), sorted by x.
  std::map<std::string, vtkSmartPointer<vtkTable>> series;
  // The points in the order of the report's rows: series name, x, y.
  struct Point {
    std::string series;
    double x, y;
  };
  std::vector<Point> points;
  // After each row that came while the report ran: how many points the chart had (1, 2, 3, ...).
  std::vector<int> pointsAfterRow;
  double progress = 0.0;
};

AaReportView::AaReportView(Session* session, QWidget* parent)
    : ReportWindow(parent), d_(new Impl), session_(session) {
  setObjectName("aaReportView");
  cancellingText_ = tr("Cancelling: the report stops after the render under way...");
  setWindowTitle(tr("raystep - anti-aliasing report: error against rays"));
  resize(1040, 760);
  auto* layout = new QVBoxLayout(this);

  addHeader(layout, "aaReport");

  // The options of a run, as `raystep aa-report` takes them.
  auto* options = new QHBoxLayout;
  options->addWidget(new QLabel(tr("Methods:")));
  methods_ = new QLineEdit;
  methods_->setObjectName("aaReportMethods");
  methods_->setPlaceholderText(
      tr("default: none, regular:2..8, jitter:2..8, random:4..64, adaptive, +tent at regular:4, jitter:2..8"));
  methods_->setToolTip(
      tr("Comma-separated anti-aliasing specs, e.g. none,regular:4,jitter:4,random:16,adaptive:0.1:3"));
  options->addWidget(methods_, 1);
  options->addWidget(new QLabel(tr("Reference:")));
  reference_ = new QComboBox;
  reference_->setObjectName("aaReportReference");
  reference_->setEditable(true);
  reference_->addItems({"auto", "exact", "jitter:16", "jitter:32"});
  reference_->setToolTip(
      tr("auto: exact area coverage where the scene allows it (flat-coloured polygons seen "
         "orthographically), else a jittered render with many samples whose own error is estimated"));
  options->addWidget(reference_);
  options->addWidget(new QLabel(tr("Size:")));
  size_ = new QLineEdit;
  size_->setObjectName("aaReportSize");
  size_->setPlaceholderText(tr("scene's"));
  size_->setToolTip(tr("WxH, e.g. 64x48; empty: the scene's size, at most 128 pixels on its long side"));
  size_->setMaximumWidth(80);
  options->addWidget(size_);
  options->addWidget(new QLabel(tr("Seeds:")));
  seeds_ = new QSpinBox;
  seeds_->setObjectName("aaReportSeeds");
  seeds_->setRange(1, 50);
  seeds_->setValue(5);
  seeds_->setToolTip(tr("Runs of each random method (jitter, random): the table shows their spread"));
  options->addWidget(seeds_);
  addRunCancel(options, "aaReport");
  layout->addLayout(options);
  addProgress(layout, "aaReport");

  axisTabs_ = new QTabBar;
  axisTabs_->setObjectName("aaReportAxis");
  axisTabs_->addTab(tr("Error against rays"));
  axisTabs_->addTab(tr("Error against time"));
  axisTabs_->setExpanding(false);
  layout->addWidget(axisTabs_);

  auto* split = new QSplitter(Qt::Vertical);
  Impl& d = *d_;
  d.widget = new QVTKOpenGLNativeWidget;
  d.widget->setMinimumSize(400, 260);
  chartutil::showContextView(d.widget, d.window, d.view);
  d.view->GetScene()->AddItem(d.chart);
  chartutil::ChartStyle style;
  style.titleSize = 14;
  style.axisTitleSize = 12;
  style.labelSize = 11;
  style.legendSize = 12;
  style.legendAlignment = vtkChartLegend::RIGHT;
  chartutil::styleChart(d.chart, nullptr, nullptr, nullptr, style);
  d.chart->GetLegend()->SetInline(false);  // beside the plot, not over the points
  split->addWidget(d.widget);

  table_ = new QTableWidget(0, 9);
  table_->setObjectName("aaReportTable");
  table_->setHorizontalHeaderLabels({tr("method"), tr("spec"), tr("seeds"), tr("rays / pixel"),
                                     tr("rays cast"), tr("time / render"), tr("RMSE"), tr("RMSE min .. max"),
                                     tr("largest pixel error")});
  table_->horizontalHeaderItem(4)->setToolTip(
      tr("All rays one render cast: primary, shadow, reflected and refracted (mean over seeds)"));
  table_->horizontalHeaderItem(5)->setToolTip(tr("Median wall time of one render"));
  table_->horizontalHeaderItem(7)->setToolTip(tr("The spread of the RMSE over the seeds of a random method"));
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  table_->verticalHeader()->setVisible(false);
  table_->horizontalHeader()->setSectionResizeMode(QHeaderView::ResizeToContents);
  table_->horizontalHeader()->setStretchLastSection(true);
  split->addWidget(table_);
  split->setStretchFactor(0, 3);
  split->setStretchFactor(1, 1);
  split->setSizes({420, 230});
  layout->addWidget(split, 1);

  addStatus(layout, "aaReport");

  connect(axisTabs_, &QTabBar::currentChanged, this, [this] { redraw(); });
  connect(session_, &Session::sceneChanged, this, [this] {
    if (running()) cancel();
    updateHeader();
  });
  updateHeader();
  status_->setText(
      tr("Run renders the current scene with each method and measures its error against the "
         "reference; the chart fills in as each method is measured."));
  redraw();
}

AaReportView::~AaReportView() {
  stopWorker();
}

void AaReportView::setMethods(const QString& methods) {
  methods_->setText(methods);
}

void AaReportView::setReference(const QString& reference) {
  reference_->setCurrentText(reference);
}

void AaReportView::setReportSize(int width, int height) {
  size_->setText(width > 0 && height > 0 ? QString("%1x%2").arg(width).arg(height) : QString());
}

void AaReportView::setSeeds(int seeds) {
  seeds_->setValue(seeds);
}

void AaReportView::setXAxis(const QString& axis) {
  axisTabs_->setCurrentIndex(axis == "time" ? 1 : 0);
}

QString AaReportView::xAxis() const {
  return axisTabs_->currentIndex() == 1 ? "time" : "rays";
}

void AaReportView::updateHeader() {
  const SceneData* scene = session_->scene();
  QString now = scene ? QFileInfo(QString::fromStdString(scene->path)).fileName() : QString();
  QString t;
  if (!report_.rows.empty() || running()) {
    t = tr("<b>%1</b>, %2 x %3 pixels%4, rendered through the %5.")
            .arg(sceneName_)
            .arg(report_.width)
            .arg(report_.height)
            .arg(reducedFrom_.isEmpty()
                     ? QString()
                     : tr(" (the scene's %1 reduced, so that the report is quick: Size sets it)")
                           .arg(reducedFrom_))
            .arg(structureName_);
    if (!report_.reference_kind.empty())
      t += report_.reference_kind == "exact"
               ? tr(" Reference: <b>exact area coverage</b> (its error is 0: what you see is all the "
                    "method's).")
               : tr(" Reference: <b>%1</b>, a render with many samples; its own estimated RMSE is %2, "
                    "drawn as the dotted floor (errors near it are not measured).")
                     .arg(QString::fromStdString(report_.reference_kind))
                     .arg(num(report_.reference_rmse));
    for (size_t i = 1; i < report_.references.size(); ++i)
      t += tr(" The tent-filtered methods are measured against the scene pre-filtered by the same tent "
              "(<b>%1</b>).")
               .arg(QString::fromStdString(report_.references[i].kind));
    if (!now.isEmpty() && now != sceneName_) t += tr(" <i>The window now shows %1: Run again.</i>").arg(now);
  } else {
    t = scene ? tr("<b>%1</b>: Run measures each anti-aliasing method on this scene.").arg(now)
              : tr("Open a scene: the report renders it with each anti-aliasing method.");
  }
  header_->setText(t);
}

QString AaReportView::start() {
  stopForNewRun();
  reducedFrom_.clear();
  auto structure = session_->structureShared();
  try {
    if (!structure)
      throw InputError("", 0,
                       "open a scene first: the report renders the current scene through its structure");
    AaReportOptions o;
    for (const QString& m : methods_->text().split(',', Qt::SkipEmptyParts))
      if (!m.trimmed().isEmpty()) o.methods.push_back(m.trimmed().toStdString());
    if (!o.methods.empty()) parse_aa_methods(o.methods);  // a bad list is refused before anything runs
    o.reference = reference_->currentText().trimmed().toStdString();
    const QString size = size_->text().trimmed();
    if (!size.isEmpty()) {
      QStringList wh = size.split('x');
      bool okW = false, okH = false;
      if (wh.size() == 2) {
        o.width = wh[0].toInt(&okW);
        o.height = wh[1].toInt(&okH);
      }
      if (!okW || !okH || o.width < 1 || o.height < 1 || o.width > 4096 || o.height > 4096)
        throw InputError("", 0, "size '" + size.toStdString() + "': expected WxH with 1 <= W, H <= 4096");
    } else {
      // The scene's size, at most kDefaultSide on its long side: 27 methods over 5 seeds of a 320 x 320
      // scene with shadows take minutes; the chart should fill in while the student watches.
      const int sw = structure->scene->scene.render.width, sh = structure->scene->scene.render.height;
      const int longSide = std::max(sw, sh);
      if (longSide > kDefaultSide) {
        o.width = std::max(1, int(std::lround(double(sw) * kDefaultSide / longSide)));
        o.height = std::max(1, int(std::lround(double(sh) * kDefaultSide / longSide)));
        reducedFrom_ = QString("%1 x %2").arg(sw).arg(sh);
      }
    }
    o.seeds = seeds_->value();

    report_ = AaReport{};
    report_.width = o.width ? o.width : structure->scene->scene.render.width;
    report_.height = o.height ? o.height : structure->scene->scene.render.height;
    sceneName_ = QFileInfo(QString::fromStdString(structure->scene->path)).fileName();
    structureName_ = structure->grid() ? tr("uniform grid") : QString::fromStdString(structure->kind);
    table_->setRowCount(0);
    d_->points.clear();
    d_->pointsAfterRow.clear();
    d_->progress = 0.0;
    progress_->setValue(0);
    const int gen =
        beginRun(tr("Measuring... each method is rendered, timed and compared with the reference."));
    updateHeader();
    redraw();

    auto result = std::make_shared<AaReport>();
    auto work = [this, structure, o, gen, result] {
      AaReportHooks hooks;
      hooks.cancel = &cancel_;
      // Called on the worker: a copy of the row (and of the report's header) goes to the GUI thread.
      hooks.row_done = [this, gen](const AaReport& soFar, const AaReportRow& row) {
        AaReport head = soFar;
        head.rows.clear();
        toGui(gen, [this, head, row] { addRow(head, row); });
        rowDoneOnWorker();
      };
      hooks.progress = [this, gen](double f) {
        toGui(gen, [this, f] {
          d_->progress = f;
          progress_->setValue(int(std::lround(std::clamp(f, 0.0, 1.0) * 1000)));
        });
      };
      *result = run_aa_report(structure->scene->scene, *structure->accel, o, hooks);
    };
    runOnWorker(gen, work,
                [this, result](const QString& state, const QString& error) { done(*result, state, error); });
  } catch (const std::exception& e) {
    return refuseStart(e);
  }
  return lastError();
}

void AaReportView::addRow(const AaReport& soFar, const AaReportRow& row) {
  report_.reference_kind = soFar.reference_kind;
  report_.references = soFar.references;
  report_.reference_rmse = soFar.reference_rmse;
  report_.reference_seconds = soFar.reference_seconds;
  if (soFar.width > 0) report_.width = soFar.width, report_.height = soFar.height;
  report_.rows.push_back(row);

  const int r = table_->rowCount();
  table_->insertRow(r);
  QLocale l;
  const bool spread = row.seeds > 1;
  const QStringList cells = {
      QString::fromStdString(row.method),
      QString::fromStdString(row.spec),
      QString::number(row.seeds),
      num(row.rays_per_pixel, 4),
      l.toString(qulonglong(row.rays.total())),
      tr("%1 ms").arg(row.seconds * 1e3, 0, 'f', row.seconds < 0.01 ? 2 : 1),
      num(row.rmse, 4),
      spread ? QString("%1 .. %2").arg(num(row.rmse_min, 3), num(row.rmse_max, 3)) : tr("(one run)"),
      num(row.max_error, 3)};
  for (int c = 0; c < cells.size(); ++c) {
    auto* item = new QTableWidgetItem(cells[c]);
    if (c >= 2) item->setTextAlignment(Qt::AlignRight | Qt::AlignVCenter);
    if (c == 0) item->setForeground(familyColor(row.method));
    table_->setItem(r, c, item);
  }
  table_->scrollToBottom();
  updateHeader();
  redraw();
  d_->pointsAfterRow.push_back(int(d_->points.size()));
}

void AaReportView::done(const AaReport& report, const QString& state, const QString& error) {
  endRun(state, error);
  if (state != "failed" && report.rows.size() >= report_.rows.size()) {
    // The final report: the same rows, and the fitted slopes.
    const bool sameRows = report.rows.size() == report_.rows.size();
    report_ = report;
    if (!sameRows) {  // rows that never reached the chart (none should): the table from the report
      table_->setRowCount(0);
      std::vector<AaReportRow> rows;
      rows.swap(report_.rows);
      for (const AaReportRow& r : rows) addRow(report_, r);
    }
  }
  if (state == "done") progress_->setValue(1000);
  table_->scrollToTop();  // from "none" down, in the order measured
  QString t;
  if (state == "failed") {
    t = tr("<span style='color:#b00'>The report failed: %1</span>").arg(error.toHtmlEscaped());
  } else {
    t = state == "cancelled" ? tr("<b>Cancelled</b> after %1 methods.").arg(report_.rows.size())
                             : tr("<b>Done</b>: %1 methods measured.").arg(report_.rows.size());
    QStringList slopes;
    for (const auto& [method, slope] : report_.slopes) {
      if (!std::isfinite(slope)) continue;
      const std::string base = method.substr(0, method.find('+'));  // "+tent": the same samples' theory
      const QString theory = base == "jitter"     ? "-3/4"
                             : base == "regular"  ? "-1/2 along the pixel grid, -1 at slanted edges"
                             : base == "adaptive" ? QString()
                                                  : "-1/2";
      slopes << (theory.isEmpty() ? tr("%1 %2").arg(QString::fromStdString(method)).arg(slope, 0, 'f', 2)
                                  : tr("%1 %2 (theory %3)")
                                        .arg(QString::fromStdString(method))
                                        .arg(slope, 0, 'f', 2)
                                        .arg(theory));
    }
    if (!slopes.isEmpty())
      t += tr(" Fitted slopes of log RMSE against log rays: %1. A steeper (more negative) slope buys more "
              "accuracy per extra ray.")
               .arg(slopes.join(", "));
  }
  status_->setText(t);
  updateHeader();
  redraw();
  Q_EMIT finished();
}

void AaReportView::redraw() {
  Impl& d = *d_;
  vtkChartXY* chart = d.chart;
  chart->ClearPlots();
  d.series.clear();
  d.points.clear();
  const bool time = xAxis() == "time";
  auto xOf = [&](const AaReportRow& r) { return time ? r.seconds * 1e3 : r.rays_per_pixel; };

  // The rows per family, in the report's order (the points list keeps it). A family's line joins its
  // points by rays per pixel, the method's own order, on either axis (times measured on a busy machine
  // need not grow with the rays).
  std::map<std::string, std::vector<std::pair<double, double>>> byFamily;
  std::map<std::string, std::vector<std::pair<double, size_t>>> order;  // rays per pixel, index
  std::map<std::string, std::vector<std::string>> specs;                // per point, for the tooltips
  double xlo = HUGE_VAL, xhi = -HUGE_VAL, ylo = HUGE_VAL, yhi = -HUGE_VAL;
  for (const AaReportRow& r : report_.rows) {
    const double x = xOf(r), y = r.rmse;
    d.points.push_back({r.method, x, y});
    if (!(x > 0.0) || !(y > 0.0)) continue;  // a log axis has no place for 0 (an exact picture)
    order[r.method].push_back({r.rays_per_pixel, byFamily[r.method].size()});
    byFamily[r.method].push_back({x, y});
    specs[r.method].push_back(r.spec);
    xlo = std::min(xlo, x), xhi = std::max(xhi, x), ylo = std::min(ylo, y), yhi = std::max(yhi, y);
  }
  for (auto& [family, pts] : byFamily) {
    auto& o = order[family];
    std::stable_sort(o.begin(), o.end(), [](const auto& a, const auto& b) { return a.first < b.first; });
    std::vector<std::pair<double, double>> sorted;
    std::vector<std::string> sortedSpecs;
    for (const auto& [rays, i] : o) sorted.push_back(pts[i]), sortedSpecs.push_back(specs[family][i]);
    pts = sorted;
    specs[family] = sortedSpecs;
  }
  // Hovering a point names its method: "jitter:4: 16 rays per pixel, RMSE 0.0108".
  auto label = [&](vtkPlot* p, const std::string& family) {
    vtkNew<vtkStringArray> names;
    for (const std::string& spec : specs[family]) names->InsertNextValue(spec);
    p->SetIndexedLabels(names);
    p->SetTooltipLabelFormat(time ? "%i: %x ms per render, RMSE %y" : "%i: %x rays per pixel, RMSE %y");
  };
  auto add = [&](const std::string& name, const std::vector<std::pair<double, double>>& pts,
                 const QColor& color, float width, bool line, const QString& label) -> vtkPlot* {
    auto t = chartutil::makeTable("x", "y");
    for (const auto& [x, y] : pts) chartutil::addRow(t, x, y);
    d.series[name] = t;
    vtkPlot* p = chart->AddPlot(line && pts.size() >= 2 ? vtkChart::LINE : vtkChart::POINTS);
    p->SetInputData(t, 0, 1);
    p->SetColor(uchar(color.red()), uchar(color.green()), uchar(color.blue()), 255);
    p->SetWidth(width);
    p->SetLabel(label.toStdString());
    return p;
  };
  for (const char* family : kFamilies) {
    auto it = byFamily.find(family);
    if (it == byFamily.end()) continue;
    vtkPlot* p = add(family, it->second, familyColor(family), 2.f, true,
                     familyLabel(family) + QString(" (%1)").arg(it->second.size()));
    label(p, family);
    if (auto* pp = vtkPlotPoints::SafeDownCast(p)) {
      pp->SetMarkerStyle(vtkPlotPoints::CIRCLE);
      pp->SetMarkerSize(8.f);
    }
  }
  if (auto it = byFamily.find("none"); it != byFamily.end()) {
    auto* pp = vtkPlotPoints::SafeDownCast(
        add("none", it->second, familyColor("none"), 2.f, false, familyLabel("none")));
    if (pp) {
      label(pp, "none");
      pp->SetMarkerStyle(vtkPlotPoints::SQUARE);
      pp->SetMarkerSize(11.f);
    }
  }
  // The theory at edges, as guides a student compares slopes with: random sampling's error falls as N^-1/2,
  // jittered sampling's as N^-3/4, regular sampling's as N^-1 at slanted edges (N^-1/2 along the pixel
  // grid). Each guide runs parallel to its family, a little below it (on it, it would hide behind the data),
  // from the family's first point across the chart (the first point by rays: the vector is in rays' order).
  struct Theory {
    const char* name;
    double slope;
    const char* family;
    QString label;
  };
  const Theory theories[] = {{"theory -1/2", -0.5, "random", tr("N^-1/2: random's theory")},
                             {"theory -3/4", -0.75, "jitter", tr("N^-3/4: jittered's theory")},
                             {"theory -1", -1.0, "regular", tr("N^-1: regular's, slanted edges")}};
  const bool any = xhi > 0.0 && xhi >= xlo;
  for (const Theory& th : theories) {
    auto it = byFamily.find(th.family);
    if (time) break;  // the theory speaks of rays; the time tab shows what they cost on this machine
    if (!any || it == byFamily.end() || it->second.empty()) continue;
    const auto a = it->second.front();
    // At least two octaves long, so that the slope shows when the family has one point so far.
    const double xend = std::max(xhi, 4.0 * a.first);
    std::vector<std::pair<double, double>> pts;
    for (double x : {a.first, xend}) pts.push_back({x, 0.6 * a.second * std::pow(x / a.first, th.slope)});
    xhi = std::max(xhi, xend);
    ylo = std::min(ylo, pts.back().second);
    vtkPlot* p = add(th.name, pts, familyColor(th.family), 1.5f, true, th.label);
    p->GetPen()->SetLineType(vtkPen::DASH_LINE);
    if (auto* pp = vtkPlotPoints::SafeDownCast(p)) pp->SetMarkerStyle(vtkPlotPoints::NONE);
  }
  // The reference's own error: below it the measured error says little.
  if (any && report_.reference_rmse > 0.0) {
    const double y = report_.reference_rmse;
    vtkPlot* p = add("reference error", {{xlo, y}, {xhi > xlo ? xhi : xlo * 2, y}}, chartcolor::grey, 2.f,
                     true, tr("the reference's own error"));
    p->GetPen()->SetLineType(vtkPen::DOT_LINE);
    if (auto* pp = vtkPlotPoints::SafeDownCast(p)) pp->SetMarkerStyle(vtkPlotPoints::NONE);
    ylo = std::min(ylo, y);
    yhi = std::max(yhi, y);
  }

  // Log-log axes with a margin of a fifth of a decade, and ticks a student can read (1, 2, 5 x 10^k).
  if (!any) {
    xlo = time ? 0.1 : 1.0, xhi = time ? 1000.0 : 64.0, ylo = 1e-3, yhi = 0.3;
  }
  chartutil::setLogRange(chart->GetAxis(vtkAxis::BOTTOM), xlo, xhi);
  chartutil::setLogRange(chart->GetAxis(vtkAxis::LEFT), ylo, yhi);
  chart->GetAxis(vtkAxis::BOTTOM)
      ->SetTitle(time ? "time per render (milliseconds, log scale)" : "primary rays per pixel N (log scale)");
  chart->GetAxis(vtkAxis::LEFT)->SetTitle("RMSE against the reference (log scale)");
  chart->SetTitle(time ? "Error against time: which method is cheapest for a given error?"
                       : "Error against rays: how fast does each method's error fall?");
  chart->RecalculateBounds();
  renderNow();
}

void AaReportView::renderNow() {
  d_->window->Render();
}

QOpenGLWidget* AaReportView::chartWidget() const {
  return d_->widget;
}

QJsonObject AaReportView::dumpState() const {
  const Impl& d = *d_;
  QJsonObject o = dumpCommon();
  o["x_axis"] = xAxis();
  o["progress"] = d.progress;
  o["reference"] =
      QJsonObject{{"kind", QString::fromStdString(report_.reference_kind)}, {"rmse", report_.reference_rmse}};
  o["size"] = QJsonArray{report_.width, report_.height};
  QJsonArray rows;
  for (const AaReportRow& r : report_.rows)
    rows.append(QJsonObject{{"method", QString::fromStdString(r.method)},
                            {"spec", QString::fromStdString(r.spec)},
                            {"seeds", r.seeds},
                            {"rays_per_pixel", r.rays_per_pixel},
                            {"rays", double(r.rays.total())},
                            {"seconds", r.seconds},
                            {"rmse", r.rmse},
                            {"max_error", r.max_error}});
  o["rows"] = rows;
  QJsonArray points;
  for (const Impl::Point& p : d.points)
    points.append(QJsonObject{{"series", QString::fromStdString(p.series)}, {"x", p.x}, {"y", p.y}});
  o["points"] = points;  // one per row, in the rows' order
  QJsonArray filled;
  for (int n : d.pointsAfterRow) filled.append(n);
  o["points_after_each_row"] = filled;  // the chart as it filled in while the report ran
  QJsonObject colors;
  for (const char* f : {"regular", "jitter", "random", "adaptive", "none", "regular+tent", "jitter+tent"}) {
    const QColor& c = familyColor(f);
    colors[f] = QJsonArray{c.red(), c.green(), c.blue()};
  }
  o["colors"] = colors;
  QJsonObject series;
  for (const auto& [name, t] : d.series) {
    QJsonArray pts;
    for (vtkIdType i = 0; i < t->GetNumberOfRows(); ++i)
      pts.append(QJsonArray{t->GetValue(i, 0).ToDouble(), t->GetValue(i, 1).ToDouble()});
    series[QString::fromStdString(name)] = pts;
  }
  o["series"] = series;  // as plotted, by x
  o["plots"] = int(d.chart->GetNumberOfPlots());
  o["table_rows"] = table_->rowCount();
  o["log_axes"] = QJsonArray{d.chart->GetAxis(vtkAxis::BOTTOM)->GetLogScaleActive(),
                             d.chart->GetAxis(vtkAxis::LEFT)->GetLogScaleActive()};
  QJsonObject slopes;
  for (const auto& [method, slope] : report_.slopes)
    if (std::isfinite(slope)) slopes[QString::fromStdString(method)] = slope;
  o["slopes"] = slopes;
  return o;
}

}  // namespace raystep::viz
