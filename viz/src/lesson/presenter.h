// Presenter mode: a lesson (core's parsed Lesson) shown step by step in the window. Entering a step puts its
// whole state into the debugger (lesson_enter.h) and its narration and question into the lesson pane; the
// class may then click pixels and step freely, and "Back to the lesson" enters the step again. Keys, as a
// clicker sends them: PageDown/Right next step, PageUp/Left previous, Home/End first/last, F5 full screen;
// the walk's own keys move to Shift+Right/Shift+Left (and . ,). The quiz: the step's question answered by
// core from the walk or the build when the step is entered, a prediction marked by core, a score; and
// "Predict" for any ray: the next cell or node, then the step. Not a view: it drives the window and the pane.
#pragma once

#include <functional>
#include <optional>

#include <QJsonObject>
#include <QObject>

#include "raystep/lesson/lesson.h"
#include "raystep/lesson/question.h"

class QShortcut;

namespace raystep::viz {

class LessonPane;
class MainWindow;

class Presenter : public QObject {
  Q_OBJECT
 public:
  Presenter(MainWindow& window, LessonPane* pane, Lesson lesson);
  ~Presenter() override;

  const Lesson& lesson() const { return lesson_; }
  int current() const { return current_; }  // 0-based; -1 before the first step is entered
  // Enters step `index` (0-based). Throws InputError(lesson file, line of the step's heading or question,
  // what) when the step cannot be reached; goToReportingErrors shows that in a dialog instead.
  void goTo(int index);
  void goToReportingErrors(int index);
  // The window no longer shows the step as the lesson sets it (the class clicked, stepped, picked a node).
  bool away() const { return away_; }

  // The current step's answer (computed on entering; none without a question).
  const std::optional<Answer>& answer() const { return answer_; }
  // Marks a prediction for the step's question, shows the answer and why, steps the walk to what was
  // predicted (with the debugger's Why there) and counts the score.
  void predictAndReveal(const QString& prediction);
  // Predict mode: the next cell (grid) or node (tree) of the current ray, marked, then the step taken.
  void predictNext(const QString& prediction);
  int right() const { return right_; }
  int asked() const { return asked_; }
  QJsonObject dumpState() const;
  // While a step is shown, build the next step's structure in the background (same scene, other structure or
  // options), so that Next does not wait for the build. On when presenting; scripted runs enter steps alone.
  void setPrefetch(bool on) { prefetch_ = on; }

 private:
  void setLessonKeys(bool on);
  void markAway();
  void concealWalk(bool on);  // the Why text, the next axis and the events to come, at a walk question
  void showScore();
  MainWindow& window_;
  LessonPane* pane_;
  Lesson lesson_;
  int current_ = -1;
  bool entering_ = false, away_ = false, revealed_ = false, prefetch_ = true;
  std::optional<Answer> answer_;
  int right_ = 0, asked_ = 0;
  std::vector<QShortcut*> keys_;
};

}  // namespace raystep::viz
