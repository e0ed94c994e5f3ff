#include "reports/report_script.h"

#include <QApplication>
#include <QCommandLineParser>
#include <QJsonArray>
#include <QSaveFile>
#include <QThread>

#include "reports/aa_report_view.h"
#include "reports/bvol_report_view.h"
#include "reports/grid_sweep_view.h"
#include "app/main_window.h"
#include "raystep/util/error.h"
#include "app/session.h"
#include "app/settle.h"

namespace raystep::viz {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

constexpr int kReportTimeoutMs = 240000;

int parseCount(const QCommandLineParser& p, const QString& name, int lo, int hi) {
  bool ok = false;
  const int v = p.value(name).toInt(&ok);
  if (!ok || v < lo || v > hi)
    fail("--" + name.toStdString() + " '" + p.value(name).toStdString() + "': expected a whole number " +
         std::to_string(lo) + ".." + std::to_string(hi));
  return v;
}

// A window's picture as the screen shows it (the chart included), written atomically.
void saveWindow(QWidget* w, const QString& path) {
  QSaveFile file(path);
  if (!(file.open(QIODevice::WriteOnly) && w->grab().save(&file, "PNG") && file.commit()))
    fail("cannot write " + path.toStdString());
}

void settleWindow(QWidget*) {
  settleWindowSystem(10);
}

}  // namespace

void defineReportOptions(QCommandLineParser& p) {
  auto opt = [&](const QString& name, const QString& help, const QString& value = QString()) {
    p.addOption(QCommandLineOption(name, help, value));
  };
  opt("report",
      "Open a report window on the scene and run it: aa (anti-aliasing error against rays), grid-sweep "
      "(the grid's density d against cost) or bvol (the kinds of bounding volumes); several: aa,grid-sweep.",
      "LIST");
  opt("report-methods", "aa report: anti-aliasing specs, comma-separated (default: the report's).", "LIST");
  opt("report-reference", "aa report: auto, exact or jitter:K.", "REF");
  opt("report-size", "aa report: render size (default: the scene's).", "WxH");
  opt("report-seeds", "aa report: runs of each random method (default 5).", "N");
  opt("report-axis", "aa report: the chart's x axis, rays (per pixel) or time.", "AXIS");
  opt("report-cancel-after", "Cancel the report(s) right after row N, as the Cancel button does.", "N");
  opt("sweep-densities", "grid sweep: densities d, comma-separated (default 0.5 .. 8).", "LIST");
  opt("sweep-choose", "grid sweep: then move the slider to d (the main window rebuilds its grid).", "D");
  opt("screenshot-report", "Write a PNG of the anti-aliasing report window.", "FILE");
  opt("screenshot-sweep", "Write a PNG of the grid sweep window.", "FILE");
  opt("screenshot-bvol", "Write a PNG of the bounding-volume report window.", "FILE");
}

QStringList reportScriptOptions() {
  return {"report", "screenshot-report", "screenshot-sweep", "screenshot-bvol", "sweep-choose"};
}

void runReportActions(MainWindow& window, const QCommandLineParser& p) {
  if (!p.isSet("report")) {
    for (const char* o : {"report-methods", "report-reference", "report-size", "report-seeds", "report-axis",
                          "report-cancel-after", "sweep-densities", "sweep-choose", "screenshot-report",
                          "screenshot-sweep", "screenshot-bvol"})
      if (p.isSet(o)) fail(std::string("--") + o + " needs --report");
    return;
  }
  const QStringList reports = p.value("report").split(',', Qt::SkipEmptyParts);
  for (const QString& r : reports)
    if (r != "aa" && r != "grid-sweep" && r != "bvol")
      fail("--report '" + r.toStdString() + "': expected aa, grid-sweep or bvol");
  if (!window.session()->scene()) fail("--report: open a scene (a trace has none to render)");
  const int cancelAfter = p.isSet("report-cancel-after") ? parseCount(p, "report-cancel-after", 1, 1000) : 0;
  // The report windows beside the main window's size: a report window of its own size, on the same screen.
  if (reports.contains("aa")) {
    AaReportView* v = window.aaReportView();
    if (p.isSet("report-methods")) v->setMethods(p.value("report-methods"));
    if (p.isSet("report-reference")) v->setReference(p.value("report-reference"));
    if (p.isSet("report-size")) {
      const QStringList wh = p.value("report-size").split('x');
      bool okW = false, okH = false;
      const int w = wh.size() == 2 ? wh[0].toInt(&okW) : 0, h = wh.size() == 2 ? wh[1].toInt(&okH) : 0;
      if (!okW || !okH || w < 1 || h < 1 || w > 4096 || h > 4096)
        fail("--report-size '" + p.value("report-size").toStdString() +
             "': expected WxH with 1 <= W, H <= 4096");
      v->setReportSize(w, h);
    }
    if (p.isSet("report-seeds")) v->setSeeds(parseCount(p, "report-seeds", 1, 50));
    if (p.isSet("report-axis")) {
      const QString a = p.value("report-axis");
      if (a != "rays" && a != "time") fail("--report-axis '" + a.toStdString() + "': expected rays or time");
      v->setXAxis(a);
    }
    v->setCancelAfterRows(cancelAfter);
    v->show();
    settleWindow(v);
    const QString error = v->start();
    if (!error.isEmpty()) fail("--report aa: " + error.toStdString());
    if (!v->waitForFinished(kReportTimeoutMs)) fail("--report aa: the report did not finish in time");
    if (v->state() == "failed") fail("--report aa: " + v->lastError().toStdString());
    settleWindow(v);
  }
  if (reports.contains("grid-sweep")) {
    GridSweepView* v = window.gridSweepView();
    if (p.isSet("sweep-densities")) v->setDensities(p.value("sweep-densities"));
    v->setCancelAfterRows(cancelAfter);
    v->show();
    settleWindow(v);
    const QString error = v->start();
    if (!error.isEmpty()) fail("--report grid-sweep: " + error.toStdString());
    if (!v->waitForFinished(kReportTimeoutMs)) fail("--report grid-sweep: the sweep did not finish in time");
    if (v->state() == "failed") fail("--report grid-sweep: " + v->lastError().toStdString());
    if (p.isSet("sweep-choose")) {
      bool ok = false;
      const float d = p.value("sweep-choose").toFloat(&ok);
      if (!ok || !(d > 0.f) || d > 64.f)
        fail("--sweep-choose '" + p.value("sweep-choose").toStdString() + "': expected a density in (0, 64]");
      if (v->sweep().rows.empty()) fail("--sweep-choose: the sweep measured no density");
      v->chooseDensity(d);  // scripted: the grid is rebuilt in place
    }
    settleWindow(v);
  } else if (p.isSet("sweep-choose")) {
    fail("--sweep-choose needs --report grid-sweep");
  }
  if (reports.contains("bvol")) {
    BvolReportView* v = window.bvolReportView();
    v->setCancelAfterRows(cancelAfter);
    v->show();
    settleWindow(v);
    const QString error = v->start();
    if (!error.isEmpty()) fail("--report bvol: " + error.toStdString());
    if (!v->waitForFinished(kReportTimeoutMs)) fail("--report bvol: the report did not finish in time");
    if (v->state() == "failed") fail("--report bvol: " + v->lastError().toStdString());
    settleWindow(v);
  }
}

void writeReportOutputs(MainWindow& window, const QCommandLineParser& p) {
  if (p.isSet("screenshot-report")) {
    if (!p.value("report").split(',').contains("aa")) fail("--screenshot-report needs --report aa");
    window.aaReportView()->renderNow();
    saveWindow(window.aaReportView(), p.value("screenshot-report"));
  }
  if (p.isSet("screenshot-sweep")) {
    if (!p.value("report").split(',').contains("grid-sweep"))
      fail("--screenshot-sweep needs --report grid-sweep");
    window.gridSweepView()->renderNow();
    saveWindow(window.gridSweepView(), p.value("screenshot-sweep"));
  }
  if (p.isSet("screenshot-bvol")) {
    if (!p.value("report").split(',').contains("bvol")) fail("--screenshot-bvol needs --report bvol");
    window.bvolReportView()->renderNow();
    saveWindow(window.bvolReportView(), p.value("screenshot-bvol"));
  }
}

void addReportState(MainWindow& window, QJsonObject& o) {
  if (auto* v = window.findChild<AaReportView*>("aaReportView")) o["aa_report"] = v->dumpState();
  if (auto* v = window.findChild<GridSweepView*>("gridSweepView")) o["grid_sweep"] = v->dumpState();
  if (auto* v = window.findChild<BvolReportView*>("bvolReportView")) o["bvol_report"] = v->dumpState();
  const StructureData* s = window.session()->structure();
  if (const UniformGrid* g = s ? s->grid() : nullptr) {
    auto r = g->resolution();
    o["grid"] = QJsonObject{{"resolution", QJsonArray{r[0], r[1], r[2]}},
                            {"density", double(g->options().density)},
                            {"explicit_resolution", bool(g->options().resolution)},
                            {"coarsened", g->coarsened()},
                            {"primitives", double(g->geometry().size())}};
  }
}

}  // namespace raystep::viz
