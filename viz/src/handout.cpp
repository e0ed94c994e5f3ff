#include "handout.h"

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QTemporaryDir>
#include <QThread>

#include "aa_report_view.h"
#include "bvol_report_view.h"
#include "grid_sweep_view.h"
#include "image_view.h"
#include "lesson_pane.h"
#include "main_window.h"
#include "presenter.h"
#include "raystep/util/error.h"
#include "sah_chart.h"
#include "scene_view.h"

namespace raystep::viz {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

QString esc(const std::string& s) {
  return QString::fromStdString(s).toHtmlEscaped();
}

// The figure the step's `show:` names, drawn as the window shows it now; `report`: the first report window
// the step opens (the window, when it opens none).
QImage figureOf(MainWindow& w, const LessonState& state) {
  const std::string& show = state.show;
  if (show == "report") {
    const std::string first = state.report.substr(0, state.report.find(','));
    ReportWindow* v = first == "aa"           ? static_cast<ReportWindow*>(w.aaReportView())
                      : first == "grid-sweep" ? static_cast<ReportWindow*>(w.gridSweepView())
                      : first == "bvol"       ? static_cast<ReportWindow*>(w.bvolReportView())
                                              : nullptr;
    if (v) {
      v->waitForFinished(240000);
      v->renderNow();
      return v->grab().toImage();
    }
  }
  if (show == "3d") return w.sceneView()->grabView();
  if (show == "chart") return w.sahChart()->grabChart();
  if (show == "picture") return w.imageView()->canvas()->grab().toImage();
  return w.grab().toImage();
}

}  // namespace

void exportHandout(MainWindow& w, Presenter& presenter, const QString& dir) {
  const Lesson& lesson = presenter.lesson();
  QFileInfo target(dir);
  const QString parent = target.absolutePath();
  if (!QDir().mkpath(parent)) fail("cannot make " + parent.toStdString());
  // Beside DIR (the same file system), so that the rename at the end is one step.
  QTemporaryDir tmp(parent + "/." + target.fileName() + ".tmp-XXXXXX");
  if (!tmp.isValid()) fail("cannot write in " + parent.toStdString());

  QString html;
  html += "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n<title>" +
          esc(lesson.title) +
          "</title>\n<style>\n"
          "body { font-family: sans-serif; max-width: 60em; margin: 2em auto; padding: 0 1em; line-height: "
          "1.45; }\n"
          "figure { margin: 1em 0; } figure img { max-width: 100%; border: 1px solid #bbb; }\n"
          "figcaption { color: #555; font-size: 90%; }\n"
          ".question { background: #eef3fb; padding: 0.6em 1em; border-left: 4px solid #3a6bc4; }\n"
          "details { margin-top: 0.5em; } summary { cursor: pointer; font-weight: bold; }\n"
          "code, pre { background: #f4f4f4; }\n</style>\n</head>\n<body>\n";
  html += "<h1>" + esc(lesson.title) + "</h1>\n";
  if (!lesson.intro.empty())
    html += "<div class=\"intro\">" + markdownToHtmlBody(QString::fromStdString(lesson.intro)) + "</div>\n";

  for (size_t i = 0; i < lesson.steps.size(); ++i) {
    const LessonStep& step = lesson.steps[i];
    presenter.goTo(int(i));
    for (int k = 0; k < 5; ++k) QApplication::processEvents();
    w.sceneView()->renderNow();
    w.sahChart()->renderNow();
    QApplication::processEvents();
    const QString png = QString("step-%1.png").arg(i + 1);
    QImage figure = figureOf(w, step.state);
    if (figure.isNull() || !figure.save(tmp.path() + "/" + png, "PNG"))
      fail("cannot write " + (tmp.path() + "/" + png).toStdString());

    html += QString("<section id=\"step-%1\">\n<h2>%1. %2</h2>\n").arg(i + 1).arg(esc(step.title));
    if (!QString::fromStdString(step.narration).trimmed().isEmpty())
      html += markdownToHtmlBody(QString::fromStdString(step.narration)) + "\n";
    html +=
        QString("<figure><img src=\"%1\" alt=\"Step %2: %3\"><figcaption>Step %2: %4</figcaption></figure>\n")
            .arg(png)
            .arg(i + 1)
            .arg(esc(step.title))
            .arg(QString::fromStdString(step.state.show == "3d"        ? "the 3D view"
                                        : step.state.show == "chart"   ? "the SAH chart"
                                        : step.state.show == "picture" ? "the picture"
                                        : step.state.show == "report"  ? "the report window"
                                                                       : "the debugger"));
    if (step.ask) {
      html += "<div class=\"question\">\n<p><b>Predict:</b> " +
              esc(question_prompt(*step.ask, step.state.accel)) + "</p>\n";
      if (const auto& a = presenter.answer())
        html += "<details><summary>Answer</summary>\n<p>" + esc(a->text) + "</p>\n<p>" + esc(a->why) +
                "</p>\n</details>\n";
      html += "</div>\n";
    }
    html += "</section>\n";
  }
  html += "</body>\n</html>\n";
  QFile index(tmp.path() + "/index.html");
  if (!index.open(QIODevice::WriteOnly | QIODevice::Truncate) || index.write(html.toUtf8()) < 0 ||
      !index.flush())
    fail("cannot write " + index.fileName().toStdString());
  index.close();

  // Over DIR: the old one moved aside first (a folder cannot be renamed over a full one), then removed.
  const QString path = target.absoluteFilePath();
  QString old;
  if (QFileInfo::exists(path)) {
    old = parent + "/." + target.fileName() + ".old-" + QString::number(QCoreApplication::applicationPid());
    QDir(old).removeRecursively();
    if (!QDir().rename(path, old)) fail("cannot replace " + path.toStdString());
  }
  if (!QDir().rename(tmp.path(), path)) {
    if (!old.isEmpty()) QDir().rename(old, path);
    fail("cannot write " + path.toStdString());
  }
  tmp.setAutoRemove(false);
  if (!old.isEmpty()) QDir(old).removeRecursively();
}

}  // namespace raystep::viz
