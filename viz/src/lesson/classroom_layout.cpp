#include "lesson/classroom_layout.h"

#include <algorithm>

#include <QAbstractItemView>
#include <QApplication>
#include <QHeaderView>
#include <QTableView>
#include <QTreeView>
#include <QDockWidget>
#include <QFontMetrics>
#include <QJsonArray>
#include <QLayout>
#include <QMainWindow>
#include <QScreen>
#include <QScrollArea>
#include <QScrollBar>
#include <QSplitter>
#include <QStatusBar>
#include <QThread>

#include "lesson/lesson_pane.h"
#include "app/settle.h"

namespace raystep::viz {
namespace {

// The lesson pane's and the state column's shares of the window's width: the figure keeps at least half.
constexpr double kPaneShare = 0.25;
constexpr double kStateShare = 0.235;

QScreen* screenOf(const QWidget& w) {
  QScreen* s = w.screen();
  return s ? s : QGuiApplication::primaryScreen();
}

void settle() {  // the X server confirms sizes asynchronously
  settleWindowSystem();
}

int neededHeight(const QWidget* w) {
  return w->hasHeightForWidth() ? w->heightForWidth(w->width()) : w->minimumSizeHint().height();
}

QJsonArray rectIn(const QWidget* w, const QWidget* window) {
  const QPoint p = w->mapTo(window, QPoint(0, 0));
  return QJsonArray{p.x(), p.y(), w->width(), w->height()};
}

}  // namespace

void ClassroomLayout::arrange(LessonFigure figure, bool ray, bool mailbox, bool treePanel) {
  active_ = true;
  figure_ = figure;
  ray_ = ray;
  QScreen* screen = screenOf(window_);
  const QRect room = window_.isFullScreen() ? screen->geometry() : screen->availableGeometry();
  const int width = std::min(window_.width(), room.width());
  const int height = std::min(window_.height(), room.height());

  const int pane = narrationWindow_ ? 0 : int(width * kPaneShare);
  if (!narrationWindow_) parts_.lessonDock->widget()->setFixedWidth(pane);
  static_cast<LessonPane*>(parts_.lessonDock->widget())->setClassroom(true);
  const int stateWidth = int(width * kStateShare);
  const int figureWidth = width - pane - stateWidth;

  const bool chart = figure == LessonFigure::chart;
  const bool picture = figure == LessonFigure::picture;
  const bool tree = figure == LessonFigure::tree;
  window_.centralWidget()->setVisible(!chart);
  window_.statusBar()->hide();  // its timings are for the desk
  parts_.picture->setVisible(picture);
  parts_.view3d->setVisible(!picture && !chart);
  parts_.state->widget(1)->setVisible(mailbox);  // the mailbox table
  // Without a traced ray the state panel would only say "no ray yet", and with the pixel inspector open the
  // inspector gives the pixel's numbers: the figure takes its room.
  const bool inspector = parts_.pixelDock->isVisible();
  const bool state = ray && !(picture && inspector);
  parts_.state->setVisible(state);
  const int figureRoom = figureWidth + (state ? 0 : stateWidth);
  parts_.columns->setSizes({picture ? figureRoom : 0, picture ? 0 : figureRoom, state ? stateWidth : 0});

  // The tree with a ray: the tree below, the state panel above it in the 3D view's place
  // (its stack holds nodes of that tree). Else the dock below, the whole height for the chart.
  const bool dock = chart || tree || treePanel;
  const bool treeWithRay = tree && ray;
  parts_.treeDock->setVisible(dock);
  if (treeWithRay) {
    parts_.view3d->setVisible(false);
    parts_.columns->setSizes({0, 0, width - pane});
  }
  if (dock) {
    // The chart: the selected node's text beside it, the tree out of the way (the node is named).
    parts_.treeSplit->widget(0)->setVisible(!chart);
    // The tree alone, the whole width, unless the chart is the figure (it is a figure of its own).
    parts_.treeSplit->widget(1)->setVisible(chart);
    const int treeShare = chart ? 0 : width - pane;
    parts_.treeSplit->setSizes({treeShare, width - pane - treeShare});
    window_.resizeDocks({parts_.treeDock},
                        {chart ? height : int(height * (treeWithRay ? 0.29 : tree ? 0.5 : 0.36))}, Qt::Vertical);
    // The tree's columns as wide as their text at this scale (the desk's widths cut "split x = ..." off).
    if (auto* view = parts_.treeSplit->widget(0)->findChild<QTreeView*>()) {
      QApplication::processEvents();
      view->header()->resizeSections(QHeaderView::ResizeToContents);
    }
  }
  if (inspector) {
    const int dockHeight = int(height * 0.5);
    window_.resizeDocks({parts_.pixelDock}, {dockHeight}, Qt::Vertical);
    // The samples drawn as large as the dock is tall, the rows of its tables as tall as the text.
    if (auto* split = parts_.pixelDock->widget()->findChild<QSplitter*>()) {
      // The adaptive squares (a third column) take the larger share: their Why gives the numbers.
      const int rest = std::max(0, width - pane - dockHeight);
      const bool squares = split->count() > 2 && split->widget(2)->isVisibleTo(split);
      const int middle = squares ? rest * 2 / 5 : rest;
      split->setSizes({dockHeight, middle, rest - middle});
    }
    const int row = QFontMetrics(QApplication::font()).height() + 6;
    for (QTableView* t : parts_.pixelDock->widget()->findChildren<QTableView*>())
      t->verticalHeader()->setDefaultSectionSize(row);
  }
  window_.resize(width, height);
  settle();
  // The structure line as tall as its text at the column's width (it wraps to more lines after a build).
  if (picture) {
    auto* left = static_cast<QSplitter*>(parts_.picture);
    const int top = neededHeight(parts_.structure);
    left->setSizes({top, std::max(1, left->height() - top)});
  }
  // The state column: the panel first, the event list the rest.
  // The event list gives its room to the state panel: the class follows one event at a time (the panel and
  // the timeline name it), and the mailbox table lists the tests when the step is about them.
  parts_.state->widget(2)->setVisible(false);
  auto* table = parts_.state->widget(1)->findChild<QTableView*>();
  const int rows = table ? std::clamp(table->model()->rowCount(), 1, 3) : 2;
  const int tableHeight = table ? table->horizontalHeader()->height() + rows * table->verticalHeader()->defaultSectionSize() +
                                      QFontMetrics(QApplication::font()).height() + 16
                                : 0;
  const int total = parts_.state->height();
  parts_.state->setSizes({mailbox ? total - tableHeight : total, mailbox ? tableHeight : 0, 0});
  window_.resize(width, height);  // again: the parts hidden above may have held the window wider
  settle();
  // Where the panel is still taller than its room, the stack (a tree's walk) stays in view.
  auto* scroll = static_cast<QScrollArea*>(parts_.state->widget(0));
  if (QWidget* stack = scroll->widget()->findChild<QWidget*>("stackTable"); stack && stack->isVisible())
    scroll->ensureWidgetVisible(stack, 0, 0);
}

void ClassroomLayout::release() {
  if (!active_) return;
  active_ = false;
  window_.centralWidget()->show();
  window_.statusBar()->show();
  parts_.picture->show();
  parts_.view3d->show();
  parts_.state->show();
  parts_.state->widget(1)->show();
  parts_.state->widget(2)->show();
  parts_.treeSplit->widget(0)->show();
  parts_.treeSplit->widget(1)->show();
  static_cast<LessonPane*>(parts_.lessonDock->widget())->setClassroom(false);
  if (!narrationWindow_) {
    parts_.lessonDock->widget()->setMinimumWidth(200);
    parts_.lessonDock->widget()->setMaximumWidth(QWIDGETSIZE_MAX);
  }
}

void ClassroomLayout::setNarrationWindow(bool on) {
  narrationWindow_ = on;
  QDockWidget* dock = parts_.lessonDock;
  QWidget* pane = dock->widget();
  if (on) {
    pane->setMinimumWidth(200);
    pane->setMaximumWidth(QWIDGETSIZE_MAX);
    dock->setFloating(true);
    // The instructor's laptop: the screen the window is not on, when there are two.
    const QList<QScreen*> screens = QGuiApplication::screens();
    QScreen* here = screenOf(window_);
    QScreen* other = here;
    for (QScreen* s : screens)
      if (s != here) other = s;
    const QRect r = other->availableGeometry();
    dock->resize(std::min(r.width(), 720), std::min(r.height(), 1000));
    dock->move(r.topLeft() + (other == here ? QPoint(r.width() - dock->width(), 0) : QPoint(0, 0)));
  } else {
    dock->setFloating(false);
  }
  if (active_) arrange(figure_, ray_, parts_.state->widget(1)->isVisible(), parts_.treeDock->isVisible());
}

QJsonObject ClassroomLayout::dumpState() const {
  QJsonObject o;
  o["active"] = active_;
  o["narration_window"] = narrationWindow_;
  o["figure"] = lesson_figure_name(figure_);
  const QRect screen = screenOf(window_)->geometry();
  o["screen"] = QJsonArray{screen.width(), screen.height()};
  o["window"] = QJsonArray{window_.width(), window_.height()};
  o["window_min"] = QJsonArray{window_.minimumSizeHint().width(), window_.centralWidget()->minimumSizeHint().width(),
                               parts_.columns->minimumSizeHint().width(), parts_.state->minimumSizeHint().width(),
                               parts_.lessonDock->minimumSizeHint().width(), parts_.view3d->minimumSizeHint().width()};
  o["font_px"] = QFontMetrics(QApplication::font()).height();
  QJsonObject parts;
  auto put = [&](const char* name, const QWidget* w) {
    if (w->isVisible()) parts[name] = rectIn(w, &window_);
  };
  put("picture", parts_.picture);
  put("3d", parts_.view3d);
  put("state", parts_.state);
  put("mailbox", parts_.state->widget(1));
  put("tree_dock", parts_.treeDock);
  if (parts_.treeDock->isVisible()) {
    if (parts_.treeSplit->widget(0)->isVisible()) put("tree", parts_.treeSplit->widget(0));
    if (parts_.treeSplit->widget(1)->isVisible()) put("chart", parts_.treeSplit->widget(1));
  }
  put("pixel_dock", parts_.pixelDock);
  if (!narrationWindow_) put("lesson", parts_.lessonDock);
  o["parts"] = parts;
  // Cut off: the state panel wider or taller than the room its scroll area gives it, the structure line
  // shorter than its wrapped text.
  auto* scroll = static_cast<QScrollArea*>(parts_.state->widget(0));
  if (parts_.state->isVisible()) {
  const QWidget* panel = scroll->widget();
  const QSize need = panel->minimumSizeHint();
  o["state_need"] = QJsonArray{need.width(), panel->hasHeightForWidth()
                                                  ? panel->heightForWidth(scroll->viewport()->width())
                                                  : panel->sizeHint().height()};
  o["state_room"] = QJsonArray{scroll->viewport()->width(), scroll->viewport()->height()};
  o["state_scrolls"] = scroll->verticalScrollBar()->maximum() > 0 || scroll->horizontalScrollBar()->maximum() > 0;
  if (const QWidget* stack = panel->findChild<QWidget*>("stackTable"); stack && stack->isVisible()) {
    const QRect r(stack->mapTo(scroll->viewport(), QPoint(0, 0)), stack->size());
    o["stack_in_view"] = scroll->viewport()->rect().contains(r);
  }
  }
  if (parts_.structure->isVisible())
    o["structure_clipped"] = parts_.structure->height() < neededHeight(parts_.structure);
  return o;
}

}  // namespace raystep::viz
