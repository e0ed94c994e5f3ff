// The lesson's layout for a lecture hall (a lesson presented at a scale above 1): the step's figure
// (lesson_figure.h) takes the room, the state panel beside it gives the figure's numbers, the lesson pane on
// the right (or in a window of its own, for the instructor's laptop) and every other panel out of the way.
// The window stays within the screen. A view arrangement only: the presenter says which figure, the main
// window owns the parts.
#pragma once

#include <QJsonObject>

#include "raystep/lesson/lesson_figure.h"

class QDockWidget;
class QMainWindow;
class QSplitter;
class QWidget;

namespace raystep::viz {

struct ClassroomParts {
  QWidget* picture = nullptr;     // the structure panel and the picture (a column)
  QWidget* structure = nullptr;   // the structure panel, at the top of that column
  QWidget* view3d = nullptr;      // the 3D view
  QSplitter* state = nullptr;     // the state panel, the mailbox table, the event list (a column)
  QSplitter* columns = nullptr;   // the three columns
  QDockWidget* treeDock = nullptr;  // the tree and the SAH chart
  QSplitter* treeSplit = nullptr;   // inside it: the tree | the chart
  QDockWidget* pixelDock = nullptr;
  QDockWidget* lessonDock = nullptr;
};

class ClassroomLayout {
 public:
  ClassroomLayout(QMainWindow& window, const ClassroomParts& parts) : window_(window), parts_(parts) {}
  // Shows the figure and what it needs. `ray`: a ray is traced (its state panel is shown); `mailbox`: the current
  // event is a primitive's test (the mailbox table lists the ray's tests); `treePanel`: the step opened the tree dock
  // (shown below the 3D view when the figure is not the tree or the chart).
  void arrange(LessonFigure figure, bool ray, bool mailbox, bool treePanel);
  // The debugger's own arrangement back (every column shown).
  void release();
  bool active() const { return active_; }
  // The narration (the lesson pane) in a window of its own, on the second screen when there is one.
  void setNarrationWindow(bool on);
  bool narrationWindow() const { return narrationWindow_; }
  // For --dump-state: the screen, the window, each part's place and size (absent when hidden), the font's
  // line height, whether the state panel and the structure line need more room than they have.
  QJsonObject dumpState() const;

 private:
  QMainWindow& window_;
  ClassroomParts parts_;
  bool active_ = false;
  bool narrationWindow_ = false;
  bool ray_ = false;
  LessonFigure figure_ = LessonFigure::view3d;
};

}  // namespace raystep::viz
