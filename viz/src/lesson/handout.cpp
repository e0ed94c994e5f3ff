#include "lesson/handout.h"

#include <QApplication>
#include <QDir>
#include <QFile>
#include <QFileInfo>
#include <QImage>
#include <QLayout>
#include <QPainter>
#include <QTemporaryDir>
#include <QThread>

#include "app/main_window.h"
#include "app/session.h"
#include "inspect/pixel_inspector.h"
#include "inspect/sah_chart.h"
#include "lesson/lesson_pane.h"
#include "lesson/presenter.h"
#include "lesson/tree_diagram.h"
#include "raystep/lesson/lesson_figure.h"
#include "raystep/replay/replay_state.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "raystep/web/lesson_page.h"
#include "reports/aa_report_view.h"
#include "reports/bvol_report_view.h"
#include "reports/grid_sweep_view.h"
#include "views/image_view.h"
#include "views/kd_tree_model.h"
#include "views/scene_view.h"
#include "views/state_panel.h"
#include "views/tree_view.h"

namespace raystep::viz {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

QString esc(const std::string& s) {
  return QString::fromStdString(s).toHtmlEscaped();
}

// Images side by side, top-aligned, on white: a figure and the panel that gives its numbers.
QImage besideEachOther(const std::vector<QImage>& parts) {
  int width = 0, height = 0;
  const int gap = 8;
  for (const QImage& p : parts) {
    width += p.width() + (width ? gap : 0);
    height = std::max(height, p.height());
  }
  QImage out(std::max(width, 1), std::max(height, 1), QImage::Format_RGB32);
  out.fill(Qt::white);
  QPainter painter(&out);
  int x = 0;
  for (const QImage& p : parts) {
    painter.drawImage(x, 0, p);
    x += p.width() + gap;
  }
  return out;
}

// The state panel's text (the figure's numbers), all of it, without the scroll area around it.
QImage statePanelImage(MainWindow& w) {
  QWidget* panel = w.statePanel();
  // Every group's layout again at the panel's width, so that a label whose text just grew gets its lines.
  for (QLayout* l : panel->findChildren<QLayout*>()) l->invalidate();
  for (QWidget* c : panel->findChildren<QWidget*>())
    if (c->layout()) c->layout()->activate();
  if (panel->layout()) panel->layout()->activate();
  for (int i = 0; i < 3; ++i) QApplication::processEvents();
  return panel->grab().toImage();
}

// One image above the other, left-aligned, on white: a wide figure and its panel.
QImage aboveEachOther(const QImage& top, const QImage& bottom) {
  const int gap = 8;
  QImage out(std::max(top.width(), bottom.width()), top.height() + gap + bottom.height(),
             QImage::Format_RGB32);
  out.fill(Qt::white);
  QPainter painter(&out);
  painter.drawImage(0, 0, top);
  painter.drawImage(0, top.height() + gap, bottom);
  return out;
}

// The figure the step is about (lesson_figure.h), drawn as the window shows it now: `show: 3d`, `tree`,
// `chart`, `picture` that view alone; `show: window` the figure the state names, with the state panel beside
// the 3D view or the tree when a ray is traced; `report` the first report window the step opens.
QImage figureOf(MainWindow& w, const LessonState& state, bool* withState) {
  *withState = false;
  const LessonFigure figure = lesson_figure(state);
  const bool named = state.show != "window";
  const bool ray = w.session()->ray() != nullptr;
  if (figure == LessonFigure::report) {
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
    if (!ray) return w.imageView()->canvas()->grab().toImage();
    *withState = true;
    return besideEachOther({w.grabMiddleView(), statePanelImage(w)});
  }
  switch (figure) {
    case LessonFigure::view3d: {
      // A 2D scene's middle view is the 2D view: its picture of the walk.
      const QImage view = w.grabMiddleView();  // a 2D scene's: the 2D view
      if (named || !ray) return view;
      *withState = true;
      return besideEachOther({view, statePanelImage(w)});
    }
    case LessonFigure::chart:
      return w.sahChart()->grabChart();
    case LessonFigure::tree: {
      // The tree drawn (tree_diagram.h) with the walk's marks, the state panel (its stack) beside it.
      const StructureData* structure = w.session()->structure();
      std::unique_ptr<TreeShape> shape = structure ? treeShapeOf(*structure) : nullptr;
      if (!shape) return w.treeView()->grab().toImage();
      TreeMarks marks;
      marks.selected = w.session()->selectedNode();
      if (const TracedRay* r = w.session()->ray()) {
        const replay::ReplayState& st = w.session()->state();
        if (st.node_event >= 0) marks.current = r->events[size_t(st.node_event)].node;
        for (const replay::StackEntry& e : st.stack) marks.stack.push_back(e.node);
        marks.visited = st.visited_nodes;
      }
      QImage tree = drawTreeDiagram(*shape, marks);
      if (!ray) return tree;
      *withState = true;
      // A wide tree: the panel below it, so that the page keeps the tree's boxes readable.
      return tree.width() > 1100 ? aboveEachOther(tree, statePanelImage(w))
                                 : besideEachOther({tree, statePanelImage(w)});
    }
    case LessonFigure::picture:
    default: {
      QImage picture = w.imageView()->canvas()->grab().toImage();
      if (!w.pixelInspectorVisible()) return picture;
      return besideEachOther({picture, w.pixelInspector()->grab().toImage()});
    }
  }
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
  TemporaryFolderOnSignal onSignal(tmp.path().toStdString());  // Ctrl-C removes it too

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
  html += "<p class=\"interactive\">To step through the walks yourself, in any browser and offline: "
          "<a href=\"interactive.html\">the interactive version</a> (the same steps and questions; the "
          "pictures below are for print).</p>\n";
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
    bool withState = false;
    QImage figure = figureOf(w, step.state, &withState);
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
            .arg(QString::fromUtf8(lesson_figure_name(lesson_figure(step.state))) +
                 (withState ? QStringLiteral(" and the state panel") : QString()));
    if (step.ask) {
      html += "<div class=\"question\">\n<p><b>Predict:</b> " +
              esc(question_prompt(*step.ask, step.state.accel)) + "</p>\n";
      if (const auto& a = presenter.answer())
        html += "<details><summary>Answer</summary>\n<p>" + esc(a->text) + "</p>\n<p>" +
                esc(a->why).replace("\n", "<br>\n") + "</p>\n</details>\n";
      html += "</div>\n";
    }
    html += "</section>\n";
  }
  html += "</body>\n</html>\n";
  // The browser player's page of the lesson (web/lesson_page.h): its walks, states and questions, offline.
  const std::string interactive = web::lesson_page(lesson);
  QFile player(tmp.path() + "/interactive.html");
  if (!player.open(QIODevice::WriteOnly | QIODevice::Truncate) ||
      player.write(interactive.data(), qint64(interactive.size())) < 0 || !player.flush())
    fail("cannot write " + player.fileName().toStdString());
  player.close();
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
