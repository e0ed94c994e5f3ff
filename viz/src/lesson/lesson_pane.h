// The lesson pane, beside the debugger in presenter mode: the lesson's title, its steps as a list, the
// current step's narration (Markdown, QTextDocument::setMarkdown), Previous/Next, "Back to the lesson" once
// the class has left the step (a click on a pixel, a step of the walk), the keys, and the quiz below
// (quiz_panel.h). A view only: the presenter (presenter.h) decides what it shows and acts on its signals.
#pragma once

#include <QJsonObject>
#include <QWidget>

class QLabel;
class QListWidget;
class QPushButton;
class QTextBrowser;

namespace raystep {
struct Lesson;
}

namespace raystep::viz {

class QuizPanel;

class LessonPane : public QWidget {
  Q_OBJECT
 public:
  explicit LessonPane(QWidget* parent = nullptr);
  void setLesson(const Lesson& lesson);
  // The step (0-based): its narration (the lesson's introduction above the first step's), the list's row.
  void showStep(const Lesson& lesson, int index);
  // The window no longer shows the step as the lesson set it: offer the way back.
  void setAway(bool away);
  void setScale(double scale);
  // The lecture hall's pane (classroom_layout.h): the step's title, narration and quiz only; the list of
  // steps and the keys' help give their room to the narration.
  void setClassroom(bool on);
  QuizPanel* quiz() const { return quiz_; }
  // What the pane shows, for the scripted mode's --dump-state.
  QJsonObject dumpState() const;

 Q_SIGNALS:
  void stepChosen(int index);
  void nextRequested();
  void previousRequested();
  void backRequested();

 private:
  QLabel* title_;
  QListWidget* steps_;
  QLabel* position_;
  QTextBrowser* narration_;
  QuizPanel* quiz_;
  QPushButton* previous_;
  QPushButton* next_;
  QPushButton* back_;
  QLabel* keys_;
  bool syncing_ = false;
};

// The pane's Markdown as HTML, the body only (for the handout, which puts many of them on one page).
QString markdownToHtmlBody(const QString& markdown);

}  // namespace raystep::viz
