#include "lesson/quiz_panel.h"

#include <QButtonGroup>
#include <QCheckBox>
#include <QHBoxLayout>
#include <QJsonArray>
#include <QLabel>
#include <QLineEdit>
#include <QPushButton>
#include <QRadioButton>
#include <QVBoxLayout>

namespace raystep::viz {
namespace {

QString placeholderOf(QuestionKind kind, const std::string& walk) {
  if (walk == "octree" && kind == QuestionKind::next_cell)
    return QObject::tr("octant (e.g. x+ y- z+; in 2D a quadrant: x+ y-), node id or stop");
  if (walk == "octree" && kind == QuestionKind::first_child)
    return QObject::tr("octant (e.g. x+ y- z+; in 2D a quadrant: x+ y-) or node id");
  switch (kind) {
    case QuestionKind::next_cell:
      return QObject::tr("i,j,k or stop (or click a cell in the 3D view)");
    case QuestionKind::dda_axis:
      return QObject::tr("x, y, z or none");
    case QuestionKind::first_child:
      return QObject::tr("below, above or a path (LR), then ,push or ,no push");
    case QuestionKind::next_pop:
      return QObject::tr("node id, path (LLR) or stop");
    case QuestionKind::sah_plane:
      return QObject::tr("axis,position in world units (x,-1.45) or across the node as the chart reads (x,51%), "
                         "or leaf; or click the chart");
    case QuestionKind::subdivide:
      return QObject::tr("yes or no");
    case QuestionKind::bvol_kind:
      return QObject::tr("box, sphere, 14-DOP or oriented box");
  }
  return {};
}

}  // namespace

QWidget* QuizPanel::answerButtons(const QStringList& answers, const QString& namePrefix) {
  auto* row = new QWidget;
  auto* box = new QHBoxLayout(row);
  box->setContentsMargins(0, 0, 0, 0);
  for (const QString& a : answers) {
    auto* b = new QPushButton(a);
    b->setObjectName(namePrefix + a);
    b->setFocusPolicy(Qt::NoFocus);
    connect(b, &QPushButton::clicked, this, [this, a] {
      input_->setText(a);
      Q_EMIT revealRequested(a);
    });
    box->addWidget(b);
  }
  return row;
}

QuizPanel::QuizPanel(QWidget* parent) : QWidget(parent) {
  setObjectName("quizPanel");
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 4, 0, 4);
  prompt_ = new QLabel;
  prompt_->setObjectName("quizPrompt");
  prompt_->setWordWrap(true);
  layout->addWidget(prompt_);

  auto* row = new QHBoxLayout;
  input_ = new QLineEdit;
  input_->setObjectName("quizInput");
  row->addWidget(input_, 1);
  reveal_ = new QPushButton(tr("Reveal"));
  reveal_->setObjectName("quizReveal");
  row->addWidget(reveal_);
  layout->addLayout(row);

  // dda-axis: one button per answer; a click answers at once.
  axisButtons_ = answerButtons({"x", "y", "z", "none"}, "quizAxis_");
  layout->addWidget(axisButtons_);

  // first-child: the side, and whether the far child waits on the stack.
  childInputs_ = new QWidget;
  auto* child = new QHBoxLayout(childInputs_);
  child->setContentsMargins(0, 0, 0, 0);
  below_ = new QRadioButton(tr("below"));
  above_ = new QRadioButton(tr("above"));
  farPushed_ = new QCheckBox(tr("far child pushed?"));
  for (QWidget* w :
       {static_cast<QWidget*>(below_), static_cast<QWidget*>(above_), static_cast<QWidget*>(farPushed_)}) {
    w->setFocusPolicy(Qt::NoFocus);
    child->addWidget(w);
  }
  auto composeChild = [this] {
    if (!below_->isChecked() && !above_->isChecked()) return;
    input_->setText(QString("%1,%2").arg(below_->isChecked() ? "below" : "above",
                                         farPushed_->isChecked() ? "push" : "no push"));
  };
  connect(below_, &QRadioButton::toggled, this, composeChild);
  connect(above_, &QRadioButton::toggled, this, composeChild);
  connect(farPushed_, &QCheckBox::toggled, this, composeChild);
  layout->addWidget(childInputs_);

  yesNo_ = answerButtons({"yes", "no"}, "quiz_");
  layout->addWidget(yesNo_);
  volumes_ = answerButtons({"box", "sphere", "14-DOP", "oriented box"}, "quiz_");
  layout->addWidget(volumes_);

  result_ = new QLabel;
  result_->setObjectName("quizResult");
  result_->setWordWrap(true);
  result_->setTextFormat(Qt::RichText);
  result_->setTextInteractionFlags(Qt::TextSelectableByMouse);
  layout->addWidget(result_);

  auto* bottom = new QHBoxLayout;
  predict_ = new QCheckBox(tr("Predict"));
  predict_->setObjectName("quizPredict");
  predict_->setToolTip(
      tr("Before each step forward, predict the next cell (grid) or node (tree), then step"));
  predict_->setFocusPolicy(Qt::NoFocus);
  predictStep_ = new QPushButton(tr("Step and check"));
  predictStep_->setObjectName("quizPredictStep");
  score_ = new QLabel;
  score_->setObjectName("quizScore");
  bottom->addWidget(predict_);
  bottom->addWidget(predictStep_);
  bottom->addStretch();
  bottom->addWidget(score_);
  layout->addLayout(bottom);

  connect(reveal_, &QPushButton::clicked, this, [this] { Q_EMIT revealRequested(input_->text()); });
  connect(input_, &QLineEdit::returnPressed, this, [this] {
    if (predicting() && !kind_)
      Q_EMIT predictStepRequested(input_->text());
    else
      Q_EMIT revealRequested(input_->text());
  });
  connect(predict_, &QCheckBox::toggled, this, [this](bool on) {
    updateInputs();
    Q_EMIT predictToggled(on);
  });
  connect(predictStep_, &QPushButton::clicked, this, [this] { Q_EMIT predictStepRequested(input_->text()); });
  setScore(0, 0);
  updateInputs();
}

void QuizPanel::setQuestion(std::optional<QuestionKind> kind, const std::string& walk) {
  kind_ = kind;
  walk_ = walk;
  input_->clear();
  result_->clear();
  lastRight_.reset();
  for (QRadioButton* b : {below_, above_}) {
    b->setAutoExclusive(false);
    b->setChecked(false);
    b->setAutoExclusive(true);
  }
  farPushed_->setChecked(false);
  updateInputs();
}

void QuizPanel::updateInputs() {
  const bool asking = kind_.has_value();
  const bool predicting = predict_->isChecked() && !asking;
  prompt_->setVisible(asking || predicting);
  if (asking) {
    prompt_->setText(
        QString("<b>%1</b> %2").arg(tr("Predict:"), QString(question_prompt(*kind_, walk_)).toHtmlEscaped()));
    input_->setPlaceholderText(placeholderOf(*kind_, walk_));
  } else if (predicting) {
    prompt_->setText(
        tr("<b>Predict:</b> the %1 the walk goes to next, then <i>Step and check</i>.").arg(unit_));
    input_->setPlaceholderText(unit_ == "node" ? tr("node id or stop") : tr("i,j,k or stop"));
  }
  input_->setVisible(asking || predicting);
  reveal_->setVisible(asking);
  axisButtons_->setVisible(asking && *kind_ == QuestionKind::dda_axis);
  // An octree's first child is a cell of eight, not a side of a plane: typed (octant or id).
  childInputs_->setVisible(asking && *kind_ == QuestionKind::first_child && walk_ != "octree");
  yesNo_->setVisible(asking && *kind_ == QuestionKind::subdivide);
  volumes_->setVisible(asking && *kind_ == QuestionKind::bvol_kind);
  predictStep_->setVisible(predicting);
  result_->setVisible(!result_->text().isEmpty());
}

void QuizPanel::setPrediction(const QString& text) {
  input_->setText(text);
}
QString QuizPanel::prediction() const {
  return input_->text();
}

void QuizPanel::showResult(std::optional<bool> right, const QString& text) {
  lastRight_ = right;
  // Right and wrong are said in words and marks, not by colour alone (colour-blind viewers, projectors).
  QString mark = !right   ? QString()
                 : *right ? tr("<b>&#10004; Right.</b> ")
                          : tr("<b>&#10008; Not quite.</b> ");
  result_->setText(mark + text);
  result_->setVisible(true);
}

void QuizPanel::setScore(int right, int asked) {
  score_->setText(tr("Score: %1 / %2").arg(right).arg(asked));
}

void QuizPanel::setPredicting(bool on, const QString& unit) {
  unit_ = unit;
  QSignalBlocker block(predict_);
  predict_->setChecked(on);
  updateInputs();
}

bool QuizPanel::predicting() const {
  return predict_->isChecked();
}

void QuizPanel::setScale(double) {
  updateInputs();
}

QJsonObject QuizPanel::dumpState() const {
  QJsonObject o;
  o["question"] = kind_ ? question_kind_name(*kind_) : "";
  o["prompt"] = prompt_->isVisibleTo(this) ? prompt_->text() : "";
  o["prediction"] = input_->text();
  o["result"] = result_->text();
  o["right"] = lastRight_ ? QJsonValue(*lastRight_) : QJsonValue();
  o["score"] = score_->text();
  o["predicting"] = predict_->isChecked();
  return o;
}

}  // namespace raystep::viz
