#include "lesson/lesson_pane.h"

#include <QHBoxLayout>
#include <QJsonArray>
#include <QLabel>
#include <QListWidget>
#include <QPushButton>
#include <QRegularExpression>
#include <QTextBrowser>
#include <QTextBlock>
#include <QTextCursor>
#include <QTextDocument>
#include <QFontInfo>
#include <QVBoxLayout>

#include "lesson/quiz_panel.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/markdown_fence.h"

namespace raystep::viz {

namespace {

// Markdown prose as HTML, the body only.
QString proseToHtml(const QString& markdown) {
  if (markdown.trimmed().isEmpty()) return QString();
  QTextDocument doc;
  doc.setMarkdown(markdown);
  QString html = doc.toHtml();
  // toHtml writes a whole document: keep what is inside <body ...> ... </body>.
  int open = html.indexOf("<body");
  int start = open >= 0 ? html.indexOf('>', open) + 1 : 0;
  int end = html.lastIndexOf("</body>");
  QString body = html.mid(start, end > start ? end - start : -1).trimmed();
  // Qt's own style properties mean nothing to a browser, and its paragraph margins and zero indents are what
  // a browser does anyway.
  static const QRegularExpression qtOnly(
      R"((-qt-[a-z-]+:[^;"]*;|margin-(top|bottom):[^;"]*;|margin-(left|right):0px;|text-indent:0px;)\s*)");
  body.remove(qtOnly);
  body.remove(QRegularExpression(R"( style="\s*")"));
  return body;
}

}  // namespace

QString markdownToHtmlBody(const QString& markdown) {
  // Fenced code (the lessons' pseudocode) as <pre>, line for line with its indentation; the prose between
  // the fences through Qt's Markdown reader.
  QString out, prose, code;
  Fence open;
  bool inCode = false;
  for (const QString& line : markdown.split('\n')) {
    const std::string text = line.toStdString();
    if (!inCode && fence_of(text, &open)) {
      out += proseToHtml(prose);
      prose.clear();
      inCode = true;
      continue;
    }
    if (inCode) {
      if (fence_closes(open, text)) {
        out += "\n<pre><code>" + code.toHtmlEscaped() + "</code></pre>\n";
        code.clear();
        inCode = false;
      } else {
        code += line + "\n";
      }
      continue;
    }
    prose += line + "\n";
  }
  if (inCode) out += "\n<pre><code>" + code.toHtmlEscaped() + "</code></pre>\n";
  out += proseToHtml(prose);
  return out.trimmed();
}

LessonPane::LessonPane(QWidget* parent) : QWidget(parent) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(6, 4, 6, 4);
  title_ = new QLabel;
  title_->setObjectName("lessonTitle");
  title_->setWordWrap(true);
  layout->addWidget(title_);

  // The steps, all of them in view (a lesson has 4 to 10): the room sees where the lecture is.
  steps_ = new QListWidget;
  steps_->setObjectName("lessonSteps");
  steps_->setFocusPolicy(Qt::NoFocus);  // the arrow keys belong to the presenter, not to the list
  steps_->setVerticalScrollBarPolicy(Qt::ScrollBarAsNeeded);
  steps_->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  steps_->setWordWrap(true);
  layout->addWidget(steps_);

  position_ = new QLabel;
  position_->setObjectName("lessonPosition");
  position_->setWordWrap(true);
  layout->addWidget(position_);
  narration_ = new QTextBrowser;
  narration_->setObjectName("lessonNarration");
  narration_->setFocusPolicy(Qt::NoFocus);
  narration_->setOpenExternalLinks(true);
  layout->addWidget(narration_, 1);

  quiz_ = new QuizPanel;
  layout->addWidget(quiz_);

  auto* nav = new QHBoxLayout;
  previous_ = new QPushButton(tr("< Previous"));
  previous_->setObjectName("lessonPrevious");
  previous_->setToolTip(tr("Previous step (PageUp or Left)"));
  next_ = new QPushButton(tr("Next >"));
  next_->setObjectName("lessonNext");
  next_->setToolTip(tr("Next step (PageDown or Right)"));
  back_ = new QPushButton(tr("Back to the lesson"));
  back_->setObjectName("lessonBack");
  back_->setToolTip(tr("Show the step again as the lesson sets it"));
  for (QPushButton* b : {previous_, next_, back_}) b->setFocusPolicy(Qt::NoFocus);
  nav->addWidget(previous_);
  nav->addWidget(next_);
  nav->addStretch();
  nav->addWidget(back_);
  layout->addLayout(nav);
  keys_ =
      new QLabel(tr("Steps: PageDown / Right, PageUp / Left, Home, End. The walk: Shift+Right / Shift+Left "
                    "or . and , (one event). F5: full screen."));
  keys_->setObjectName("lessonKeys");
  keys_->setWordWrap(true);
  layout->addWidget(keys_);

  connect(steps_, &QListWidget::currentRowChanged, this, [this](int row) {
    if (!syncing_ && row >= 0) Q_EMIT stepChosen(row);
  });
  connect(previous_, &QPushButton::clicked, this, &LessonPane::previousRequested);
  connect(next_, &QPushButton::clicked, this, &LessonPane::nextRequested);
  connect(back_, &QPushButton::clicked, this, &LessonPane::backRequested);
  setAway(false);
  setScale(1.0);
}

void LessonPane::setLesson(const Lesson& lesson) {
  syncing_ = true;
  title_->setText(QString("<b>%1</b>").arg(QString::fromStdString(lesson.title).toHtmlEscaped()));
  steps_->clear();
  for (size_t i = 0; i < lesson.steps.size(); ++i)
    steps_->addItem(QString("%1. %2").arg(i + 1).arg(QString::fromStdString(lesson.steps[i].title)));
  syncing_ = false;
}

void LessonPane::showStep(const Lesson& lesson, int index) {
  syncing_ = true;
  steps_->setCurrentRow(index);
  syncing_ = false;
  const LessonStep& step = lesson.steps[size_t(index)];
  position_->setText(tr("<b>Step %1 of %2: %3</b>")
                         .arg(index + 1)
                         .arg(lesson.steps.size())
                         .arg(QString::fromStdString(step.title).toHtmlEscaped()));
  QString text = QString::fromStdString(step.narration);
  if (index == 0 && !lesson.intro.empty()) text = QString::fromStdString(lesson.intro) + "\n\n" + text;
  narration_->setMarkdown(text);
  // Code (the lessons' pseudocode) keeps its lines: scrolled sideways in a narrow pane, never re-wrapped.
  for (QTextBlock b = narration_->document()->begin(); b.isValid(); b = b.next()) {
    QTextBlockFormat f = b.blockFormat();
    if (f.hasProperty(QTextFormat::BlockCodeFence) || b.charFormat().fontFixedPitch() ||
        QFontInfo(b.charFormat().font()).fixedPitch()) {
      f.setNonBreakableLines(true);
      QTextCursor(b).setBlockFormat(f);
    }
  }
  previous_->setEnabled(index > 0);
  next_->setEnabled(index + 1 < int(lesson.steps.size()));
}

void LessonPane::setAway(bool away) {
  back_->setEnabled(away);
}

void LessonPane::setScale(double scale) {
  // The title a little larger than the text; the list as tall as its rows (no scrolling for 10 steps).
  QFont f = font();
  f.setPointSizeF(f.pointSizeF() * 1.25);
  title_->setFont(f);
  const int rows = std::max(4, steps_->count());
  steps_->setFixedHeight(rows * steps_->fontMetrics().height() * 13 / 10 + 8);
  quiz_->setScale(scale);
}

void LessonPane::setClassroom(bool on) {
  steps_->setVisible(!on);
  keys_->setVisible(!on);
  back_->setText(on ? tr("Back to the step") : tr("Back to the lesson"));
}

QJsonObject LessonPane::dumpState() const {
  QJsonObject o;
  o["title"] = title_->text();
  o["position"] = position_->text();
  o["step_row"] = steps_->currentRow();
  o["narration"] = narration_->toPlainText();
  o["back_enabled"] = back_->isEnabled();
  o["quiz"] = quiz_->dumpState();
  return o;
}

}  // namespace raystep::viz
