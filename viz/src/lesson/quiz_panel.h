// The quiz, in the lesson pane: "predict, then step". A step that asks a question shows its prompt and an
// input that fits the kind: the next cell typed as i,j,k (or picked by a click on the scene in the 3D view),
// the 3D-DDA's axis as x/y/z/none buttons, the first child as below/above with "far pushed?", the next node
// popped as an id or stop, the SAH's plane as axis,position (or a click on the chart: the nearest candidate),
// the adaptive subdivision as yes/no. Reveal shows the answer and why, marked right or wrong, and the score.
// "Predict" does the same for any ray the class picks: before each step forward, the next cell (grid) or node
// (tree), then the step is taken and the prediction marked. A view only: the presenter computes the answers.
#pragma once

#include <optional>

#include <QJsonObject>
#include <QWidget>

#include "raystep/lesson/question.h"

class QButtonGroup;
class QCheckBox;
class QLabel;
class QLineEdit;
class QPushButton;
class QRadioButton;

namespace raystep::viz {

class QuizPanel : public QWidget {
  Q_OBJECT
 public:
  explicit QuizPanel(QWidget* parent = nullptr);
  // The step's question (none: the quiz part hides, unless Predict is on).
  // walk: the structure asked about ("octree", "bsp": the prompt and inputs in its words; else the
  // kd-tree's).
  void setQuestion(std::optional<QuestionKind> kind, const std::string& walk = std::string());
  std::optional<QuestionKind> question() const { return kind_; }
  // A prediction filled in from elsewhere: a cell picked in the 3D view, a candidate clicked on the chart.
  void setPrediction(const QString& text);
  QString prediction() const;
  // After Reveal (or a Predict step): right or wrong (none: the form was not understood), and the text.
  void showResult(std::optional<bool> right, const QString& text);
  void setScore(int right, int asked);
  // Predict mode: "next cell" (grid) or "next node" (tree) is asked before each step forward.
  void setPredicting(bool on, const QString& unit);
  bool predicting() const;
  void setScale(double scale);
  QJsonObject dumpState() const;

 Q_SIGNALS:
  void revealRequested(const QString& prediction);
  void predictToggled(bool on);
  void predictStepRequested(const QString& prediction);

 private:
  void updateInputs();
  // A row of buttons, one per answer (object names namePrefix + answer): a click types it and reveals.
  QWidget* answerButtons(const QStringList& answers, const QString& namePrefix);
  std::optional<QuestionKind> kind_;
  std::string walk_;
  QLabel* prompt_;
  QLineEdit* input_;
  QWidget* axisButtons_;
  QWidget* childInputs_;
  QRadioButton* below_;
  QRadioButton* above_;
  QCheckBox* farPushed_;
  QWidget* yesNo_;
  QWidget* volumes_ = nullptr;  // bvol-kind: the four kinds
  QPushButton* reveal_;
  QLabel* result_;
  QLabel* score_;
  QCheckBox* predict_;
  QPushButton* predictStep_;
  QString unit_;
  std::optional<bool> lastRight_;
};

}  // namespace raystep::viz
