#include "lesson/presenter.h"

#include <QShortcut>

#include "app/main_window.h"
#include "app/session.h"
#include "inspect/sah_chart.h"
#include "lesson/lesson_enter.h"
#include "lesson/lesson_pane.h"
#include "lesson/quiz_answers.h"
#include "lesson/quiz_panel.h"
#include "raystep/replay/explain.h"
#include "raystep/replay/replay_state.h"
#include "raystep/util/error.h"
#include "views/event_list.h"
#include "views/scene_view.h"
#include "views/state_panel.h"
#include "views/timeline.h"

namespace raystep::viz {
namespace {

// Messages of the scripted mode name options ("--pixel 400,1: ..."); in a lesson they are settings.
std::string asSetting(std::string what) {
  if (what.rfind("--", 0) == 0) what.erase(0, 2);
  return what;
}

QString html(const std::string& text) {
  return QString::fromStdString(text).toHtmlEscaped();
}

// The event a prediction is about: the next cell event (grid), or the next node the walk is at (a node, leaf
// or pop event: tree); -1 when the walk stops first.
int nextUnitEvent(const TracedRay& ray, int step, bool tree) {
  if (!tree) return replay::find_event(ray, step, EventType::cell, true);
  int best = -1;
  for (EventType t : {EventType::node, EventType::leaf, EventType::pop}) {
    int i = replay::find_event(ray, step, t, true);
    if (i >= 0 && (best < 0 || i < best)) best = i;
  }
  return best;
}

}  // namespace

Presenter::Presenter(MainWindow& window, LessonPane* pane, Lesson lesson)
    : QObject(&window), window_(window), pane_(pane), lesson_(std::move(lesson)) {
  pane_->setLesson(lesson_);
  connect(pane_, &LessonPane::stepChosen, this, &Presenter::goToReportingErrors);
  connect(pane_, &LessonPane::nextRequested, this, [this] { goToReportingErrors(current_ + 1); });
  connect(pane_, &LessonPane::previousRequested, this, [this] { goToReportingErrors(current_ - 1); });
  connect(pane_, &LessonPane::backRequested, this, [this] { goToReportingErrors(current_); });
  QuizPanel* quiz = pane_->quiz();
  connect(quiz, &QuizPanel::revealRequested, this, &Presenter::predictAndReveal);
  connect(quiz, &QuizPanel::predictStepRequested, this, &Presenter::predictNext);
  connect(quiz, &QuizPanel::predictToggled, this, [this](bool on) {
    const TracedRay* r = window_.session()->ray();
    bool tree = r ? replay::is_tree_ray(*r)
                  : window_.session()->structure() && window_.session()->structure()->kind != "grid";
    pane_->quiz()->setPredicting(on, tree ? tr("node") : tr("cell"));
  });
  // A cell picked in the 3D view answers "which cell next" (the cell holding the picked point).
  connect(window_.sceneView(), &SceneView::pointPicked, this, [this](float x, float y, float z) {
    const StructureData* s = window_.session()->structure();
    const UniformGrid* grid = s ? s->grid() : nullptr;
    QuizPanel* q = pane_->quiz();
    bool wantsCell = q->question() == QuestionKind::next_cell || (!q->question() && q->predicting());
    if (!grid || !wantsCell) return;
    const float p[3] = {x, y, z};
    q->setPrediction(QString("%1,%2,%3")
                         .arg(grid->cell_of(p[0], 0))
                         .arg(grid->cell_of(p[1], 1))
                         .arg(grid->cell_of(p[2], 2)));
  });
  // A candidate clicked on the SAH chart answers "which plane" (axis,position).
  connect(window_.sahChart(), &SahChart::candidateClicked, this, [this](int axis, float position) {
    if (pane_->quiz()->question() == QuestionKind::sah_plane)
      pane_->quiz()->setPrediction(QString("%1,%2").arg(QChar("xyz"[axis])).arg(double(position), 0, 'g', 7));
  });
  // Anything that changes the walk or the selection outside entering a step leaves the step.
  Session* s = window_.session();
  for (auto signal : {&Session::traceChanged, &Session::stepChanged, &Session::selectedNodeChanged,
                      &Session::structureChanged})
    connect(s, signal, this, &Presenter::markAway);
  setLessonKeys(true);
  showScore();
}

Presenter::~Presenter() {
  setLessonKeys(false);
}

void Presenter::setLessonKeys(bool on) {
  window_.timeline()->setLessonKeys(on);
  for (QShortcut* k : keys_) delete k;
  keys_.clear();
  if (!on) return;
  auto key = [this](QKeySequence seq, auto fn) {
    auto* s = new QShortcut(seq, &window_);
    s->setContext(Qt::WindowShortcut);
    connect(s, &QShortcut::activated, this, fn);
    keys_.push_back(s);
  };
  // A clicker sends PageDown/PageUp (some send Right/Left): both move between steps.
  for (Qt::Key k : {Qt::Key_PageDown, Qt::Key_Right})
    key(QKeySequence(k), [this] { goToReportingErrors(current_ + 1); });
  for (Qt::Key k : {Qt::Key_PageUp, Qt::Key_Left})
    key(QKeySequence(k), [this] { goToReportingErrors(current_ - 1); });
  key(QKeySequence(Qt::Key_Home), [this] { goToReportingErrors(0); });
  key(QKeySequence(Qt::Key_End), [this] { goToReportingErrors(int(lesson_.steps.size()) - 1); });
}

void Presenter::goTo(int index) {
  if (index < 0 || index >= int(lesson_.steps.size())) return;
  const LessonStep& step = lesson_.steps[size_t(index)];
  current_ = index;
  answer_.reset();
  revealed_ = false;
  pane_->showStep(lesson_, index);
  pane_->quiz()->setQuestion(step.ask, step.state.accel);
  window_.sahChart()->setConceal(step.ask == QuestionKind::sah_plane,
                                 step.state.accel == "kd-median" ? "median builder" : "SAH");
  concealWalk(false);
  entering_ = true;
  try {
    enterState(window_, step.state);
  } catch (const std::exception& e) {
    entering_ = false;
    away_ = true;
    pane_->setAway(true);
    throw InputError(lesson_.path, step.line, asSetting(e.what()));
  }
  entering_ = false;
  away_ = false;
  pane_->setAway(false);
  if (prefetch_ && index + 1 < int(lesson_.steps.size())) {
    const LessonState& next = lesson_.steps[size_t(index) + 1].state;
    if (next.scene == step.state.scene) window_.prefetchStructure(next.accel, next.structure);
  }
  // A question about the walk's next move: the panels that say it wait for Reveal.
  const bool walkQuestion = step.ask && *step.ask != QuestionKind::sah_plane &&
                            *step.ask != QuestionKind::subdivide && *step.ask != QuestionKind::bvol_kind;
  concealWalk(walkQuestion);
  window_.arrangeForStep(step.state);
  if (step.ask) {
    Session* s = window_.session();
    QuestionContext c;
    c.scene = s->scene() ? &s->scene()->scene : nullptr;
    c.accel = s->structure() ? s->structure()->accel.get() : nullptr;
    c.trace = s->trace();
    c.ray = s->rayIndex();
    c.step = s->step();
    c.node = s->selectedNode();
    c.aa = step.state.aa;
    c.width = s->imageWidth();
    c.height = s->imageHeight();
    if (step.state.pixel) c.pixel = *step.state.pixel;
    try {
      answer_ = computeAnswer(*step.ask, c);
    } catch (const std::exception& e) {
      throw InputError(lesson_.path, step.ask_line, asSetting(e.what()));
    }
  }
}

void Presenter::goToReportingErrors(int index) {
  try {
    goTo(index);
  } catch (const std::exception& e) {
    window_.reportError(QString::fromStdString(e.what()));
  }
}

void Presenter::concealWalk(bool on) {
  window_.statePanel()->setConceal(on);
  window_.sceneView()->setConceal(on);
  window_.eventList()->setConcealAfter(on ? window_.session()->step() : -1);
}

void Presenter::markAway() {
  if (entering_ || away_ || current_ < 0) return;
  concealWalk(false);  // the class walks on: nothing is left to predict here
  away_ = true;
  pane_->setAway(true);
}

void Presenter::showScore() {
  pane_->quiz()->setScore(right_, asked_);
}

void Presenter::predictAndReveal(const QString& prediction) {
  QuizPanel* quiz = pane_->quiz();
  if (!answer_) {
    quiz->showResult(std::nullopt, tr("This step asks no question."));
    return;
  }
  bool ok = false;
  try {
    ok = predictionMatches(*answer_, prediction.toStdString());
  } catch (const std::exception& e) {
    quiz->showResult(std::nullopt, tr("Not understood: %1").arg(html(asSetting(e.what()))));
    return;
  }
  window_.sahChart()->setConceal(false);
  concealWalk(false);
  quiz->setPrediction(prediction);
  if (!revealed_) {  // the first answer counts; trying again after the reveal does not
    revealed_ = true;
    ++asked_;
    right_ += ok;
  }
  // A wrong answer first gets a sentence aimed at its likely misconception, then the answer and its reasons.
  QString text;
  if (!ok) text = "<i>" + html(predictionFeedback(*answer_, prediction.toStdString())) + "</i><br>";
  text += tr("Answer: ") + html(answer_->text) + "<br>" + html(answer_->why).replace("\n", "<br>");
  // Then the walk goes where the question looked: the debugger's own Why there says it once more, labelled
  // as the walk's next step (not as a verdict on the prediction).
  Session* s = window_.session();
  if (const TracedRay* r = s->ray()) {
    int to = -1;
    switch (answer_->kind) {
      case QuestionKind::next_cell:
      case QuestionKind::dda_axis:
        to = replay::find_event(*r, s->step(), EventType::cell, true);
        break;
      case QuestionKind::first_child:
        to = nextUnitEvent(*r, s->step(), true);
        break;
      case QuestionKind::next_pop:
        to = replay::find_event(*r, s->step(), EventType::pop, true);
        break;
      default:
        break;
    }
    bool walks = answer_->kind == QuestionKind::next_cell || answer_->kind == QuestionKind::dda_axis ||
                 answer_->kind == QuestionKind::first_child || answer_->kind == QuestionKind::next_pop;
    if (walks) {
      s->setStep(to >= 0 ? to : s->eventCount() - 1);
      text += "<br><i>" + tr("Debugger, at the walk's next step:") + "</i> " +
              html(replay::explain_rule(s->trace(), *r, s->state()));
    }
  }
  quiz->showResult(ok, text);
  showScore();
}

void Presenter::predictNext(const QString& prediction) {
  QuizPanel* quiz = pane_->quiz();
  Session* s = window_.session();
  const TracedRay* r = s->ray();
  if (!quiz->predicting()) quiz->setPredicting(true, r && replay::is_tree_ray(*r) ? tr("node") : tr("cell"));
  if (!r) {
    quiz->showResult(std::nullopt, tr("Click a pixel first: Predict follows its ray."));
    return;
  }
  const bool tree = replay::is_tree_ray(*r);
  const QString p = prediction.trimmed().toLower();
  // What the student said: a cell i,j,k or a node id, or that the walk stops.
  bool stop = p == "stop", understood = stop;
  int cell[3] = {0, 0, 0}, node = -1;
  if (!stop && !tree) {
    QStringList parts = p.split(',');
    understood = parts.size() == 3;
    for (int k = 0; k < 3 && understood; ++k) cell[k] = parts[k].trimmed().toInt(&understood);
  } else if (!stop) {
    node = p.toInt(&understood);
  }
  if (!understood) {
    quiz->showResult(std::nullopt, tree ? tr("Type a node id or stop.") : tr("Type i,j,k or stop."));
    return;
  }
  const int to = nextUnitEvent(*r, s->step(), tree);
  bool ok = false;
  QString truth;
  if (to < 0) {
    ok = stop;
    truth = tr("The walk stops here.");
  } else {
    const Event& e = r->events[size_t(to)];
    ok = !stop &&
         (tree ? node == e.node : (cell[0] == e.cell[0] && cell[1] == e.cell[1] && cell[2] == e.cell[2]));
    truth = tree ? tr("The walk goes to node %1.").arg(e.node)
                 : tr("The walk enters cell (%1, %2, %3).").arg(e.cell[0]).arg(e.cell[1]).arg(e.cell[2]);
  }
  ++asked_;
  right_ += ok;
  s->setStep(to >= 0 ? to : s->eventCount() - 1);
  quiz->setPrediction(QString());
  quiz->showResult(ok, truth + "<br><i>" + tr("Debugger:") + "</i> " +
                           html(replay::explain_rule(s->trace(), *s->ray(), s->state())));
  showScore();
}

QJsonObject Presenter::dumpState() const {
  QJsonObject o;
  o["file"] = QString::fromStdString(lesson_.path);
  o["title"] = QString::fromStdString(lesson_.title);
  o["step"] = current_ + 1;
  o["steps"] = int(lesson_.steps.size());
  o["away"] = away_;
  if (answer_)
    o["answer"] = QJsonObject{{"text", QString::fromStdString(answer_->text)},
                              {"why", QString::fromStdString(answer_->why)}};
  o["right"] = right_;
  o["asked"] = asked_;
  o["pane"] = pane_->dumpState();
  return o;
}

}  // namespace raystep::viz
