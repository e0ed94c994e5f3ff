#include "views/timeline.h"

#include <algorithm>

#include <QApplication>
#include <QComboBox>
#include <QFontMetrics>
#include <QHBoxLayout>
#include <QLabel>
#include <QToolButton>
#include <QShortcut>
#include <QSlider>
#include <QSpinBox>
#include <QTimer>
#include <QVBoxLayout>

#include "app/session.h"

#include "raystep/replay/replay_state.h"

namespace raystep::viz {

std::vector<EventType> Timeline::typesOf(const QString& kind) {
  if (kind == "cell") return {EventType::cell};
  if (kind == "pushpop") return {EventType::push, EventType::pop};
  if (kind == "node") return {EventType::node};
  if (kind == "leaf") return {EventType::leaf};
  if (kind == "prim_test") return {EventType::prim_test};
  if (kind == "mailbox_hit") return {EventType::mailbox_hit};
  if (kind == "box_test") return {EventType::box_test};
  if (kind == "skip") return {EventType::skip};
  if (kind == "hit") return {EventType::hit_accepted};
  return {};
}

Timeline::Timeline(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(4, 2, 4, 2);
  auto* row = new QHBoxLayout;
  auto button = [&](const QString& text, const QString& tip) {
    auto* b = new QToolButton;
    b->setText(text);
    b->setToolButtonStyle(Qt::ToolButtonTextOnly);
    b->setToolTip(tip);
    b->setFocusPolicy(Qt::NoFocus);
    row->addWidget(b);
    return b;
  };
  QToolButton* first = button(tr("|<"), tr("First event (Home)"));
  QToolButton* back = button(tr("< Step"), tr("Step back (Left)"));
  play_ = button(tr("Play"), tr("Play / pause (Space)"));
  play_->setObjectName("playButton");
  QToolButton* fwd = button(tr("Step >"), tr("Step forward (Right)"));
  QToolButton* last = button(tr(">|"), tr("Last event (End)"));
  row->addWidget(new QLabel(tr("Speed")));
  speed_ = new QSpinBox;
  speed_->setRange(1, 200);
  speed_->setValue(4);
  speed_->setSuffix(tr(" ev/s"));
  row->addWidget(speed_);
  row->addSpacing(16);
  // Jump to: on the first row, or on the slider's row when the timeline is compact.
  jumpBox_ = new QWidget;
  auto* jumpRow = new QHBoxLayout(jumpBox_);
  jumpRow->setContentsMargins(0, 0, 0, 0);
  row->addWidget(jumpBox_);
  QHBoxLayout* buttons = row;
  row = jumpRow;
  row->addWidget(new QLabel(tr("Jump to")));
  QToolButton* prevKind = button(tr("< prev"), tr("Previous event of this kind"));
  kind_ = new QComboBox;
  kind_->setObjectName("jumpKind");
  kind_->addItem(tr("cell"), "cell");
  kind_->addItem(tr("node"), "node");
  kind_->addItem(tr("leaf"), "leaf");
  kind_->addItem(tr("push / pop"), "pushpop");
  kind_->addItem(tr("primitive test"), "prim_test");
  kind_->addItem(tr("mailbox hit"), "mailbox_hit");
  kind_->addItem(tr("box test (BVH)"), "box_test");
  kind_->addItem(tr("skip (BVH)"), "skip");
  kind_->addItem(tr("the hit"), "hit");
  kind_->setFocusPolicy(Qt::NoFocus);
  row->addWidget(kind_);
  QToolButton* nextKind = button(tr("next >"), tr("Next event of this kind"));
  // The ray's picker stays on the first row: on the slider's row it would squeeze the slider out.
  auto* rayBox = new QWidget;
  auto* rayRow = new QHBoxLayout(rayBox);
  rayRow->setContentsMargins(0, 0, 0, 0);
  buttons->addWidget(rayBox);
  row = rayRow;
  row->addSpacing(16);
  row->addWidget(new QLabel(tr("Ray")));
  ray_ = new QComboBox;
  ray_->setObjectName("rayCombo");
  ray_->setFocusPolicy(Qt::NoFocus);
  ray_->setSizeAdjustPolicy(QComboBox::AdjustToMinimumContentsLengthWithIcon);
  ray_->setMinimumContentsLength(14);
  row->addWidget(ray_);
  row = buttons;
  row->addStretch();
  layout->addLayout(row);
  auto* row2 = row2_ = new QHBoxLayout;
  position_ = new QLabel;
  position_->setObjectName("timelinePosition");
  position_->setMinimumWidth(230);
  slider_ = new QSlider(Qt::Horizontal);
  slider_->setObjectName("timelineSlider");
  slider_->setFocusPolicy(Qt::NoFocus);
  row2->addWidget(slider_, 1);
  row2->addWidget(position_);
  layout->addLayout(row2);

  timer_ = new QTimer(this);
  connect(timer_, &QTimer::timeout, this, [this] {
    if (session_->step() + 1 >= session_->eventCount()) setPlaying(false);
    else session_->stepBy(1);
  });
  connect(speed_, QOverload<int>::of(&QSpinBox::valueChanged), this, [this](int v) { timer_->setInterval(1000 / v); });
  timer_->setInterval(1000 / speed_->value());

  connect(first, &QToolButton::clicked, this, [this] { session_->setStep(0); });
  connect(last, &QToolButton::clicked, this, [this] { session_->setStep(session_->eventCount() - 1); });
  connect(back, &QToolButton::clicked, this, [this] { session_->stepBy(-1); });
  connect(fwd, &QToolButton::clicked, this, [this] { session_->stepBy(1); });
  connect(play_, &QToolButton::clicked, this, [this] { setPlaying(!playing()); });
  connect(prevKind, &QToolButton::clicked, this, [this] { jump(kind_->currentData().toString(), false); });
  connect(nextKind, &QToolButton::clicked, this, [this] { jump(kind_->currentData().toString(), true); });
  connect(slider_, &QSlider::valueChanged, this, [this](int v) { session_->setStep(v); });
  connect(ray_, QOverload<int>::of(&QComboBox::activated), this, [this](int i) { session_->setRay(i); });

  // Window-wide keys, so that they work whichever panel has the focus.
  QWidget* top = parent ? parent : this;
  auto key = [&](Qt::Key k, auto fn) {
    auto* s = new QShortcut(QKeySequence(k), top);
    s->setContext(Qt::WindowShortcut);
    connect(s, &QShortcut::activated, this, fn);
    return s;
  };
  forwardKey_ = key(Qt::Key_Right, [this] { session_->stepBy(1); });
  backKey_ = key(Qt::Key_Left, [this] { session_->stepBy(-1); });
  key(Qt::Key_Space, [this] { setPlaying(!playing()); });
  firstKey_ = key(Qt::Key_Home, [this] { session_->setStep(0); });
  lastKey_ = key(Qt::Key_End, [this] { session_->setStep(session_->eventCount() - 1); });
  periodKey_ = key(Qt::Key_Period, [this] { session_->stepBy(1); });
  commaKey_ = key(Qt::Key_Comma, [this] { session_->stepBy(-1); });
  periodKey_->setEnabled(false);
  commaKey_->setEnabled(false);

  connect(session_, &Session::traceChanged, this, [this] {
    setPlaying(false);
    ray_->clear();
    if (const Trace* t = session_->trace()) {
      const TracePixel* px = session_->pixel();
      for (size_t i = 0; i < t->rays.size(); ++i) {
        const TracedRay& r = t->rays[i];
        // An anti-aliased pixel's rays name their sample and where it lies in the pixel.
        QString sample;
        if (px && r.sample >= 0 && r.sample < int(px->sampling.samples.size())) {
          const PixelSample& ps = px->sampling.samples[size_t(r.sample)];
          sample = QString("sample %1 (%2, %3) ")
                       .arg(r.sample)
                       .arg(double(ps.px) - px->sampling.x, 0, 'f', 2)
                       .arg(double(ps.py) - px->sampling.y, 0, 'f', 2);
        }
        ray_->addItem(
            QString("%1: %2%3 (depth %4)").arg(i).arg(sample).arg(ray_kind_name(r.kind)).arg(r.depth));
      }
    }
    // Room for "12: sample 3 (0.62, 0.18) primary" when the rays name their samples.
    ray_->setMinimumContentsLength(session_->pixel() && session_->trace() && session_->trace()->pixel ? 34
                                                                                                      : 14);
    ray_->setCurrentIndex(session_->rayIndex());
    if (const TracedRay* r = session_->ray()) offerUnit(replay::is_tree_ray(*r));
    refresh();
  });
  connect(session_, &Session::stepChanged, this, &Timeline::refresh);
  // Before any ray, the unit of the structure that is built.
  connect(session_, &Session::structureChanged, this, [this] {
    if (!session_->ray() && session_->structure()) offerUnit(session_->structure()->kind != "grid");
  });
  refresh();
}

void Timeline::setCompact(bool on) {
  // The group moves between rows: at presenter scales one row of everything is wider than a projector.
  auto* row1 = static_cast<QBoxLayout*>(layout()->itemAt(0)->layout());
  row1->removeWidget(jumpBox_);
  row2_->removeWidget(jumpBox_);
  if (on) row2_->insertWidget(0, jumpBox_);
  else row1->insertWidget(row1->count() - 2, jumpBox_);  // before the ray's picker and the stretch
  // Room for the longest position at the application's font (the presenter scale's): never cut off.
  QFont bold = QApplication::font();
  bold.setBold(true);
  position_->setMinimumWidth(std::max(230, QFontMetrics(bold).horizontalAdvance("event 000 / 000: hit_deferred")));
}

void Timeline::setLessonKeys(bool on) {
  const Qt::KeyboardModifiers m = on ? Qt::ShiftModifier : Qt::NoModifier;
  forwardKey_->setKey(QKeySequence(int(m) | Qt::Key_Right));
  backKey_->setKey(QKeySequence(int(m) | Qt::Key_Left));
  firstKey_->setKey(QKeySequence(int(m) | Qt::Key_Home));
  lastKey_->setKey(QKeySequence(int(m) | Qt::Key_End));
  periodKey_->setEnabled(on);
  commaKey_->setEnabled(on);
}

bool Timeline::jump(const QString& kind, bool forward) {
  const TracedRay* r = session_->ray();
  if (!r) return false;
  int best = -1;
  for (EventType t : typesOf(kind)) {
    int i = replay::find_event(*r, session_->step(), t, forward);
    if (i >= 0 && (best < 0 || (forward ? i < best : i > best))) best = i;
  }
  if (best < 0) {  // say so, rather than doing nothing
    position_->setText(forward ? tr("no further <b>%1</b> event").arg(kind_->currentText())
                               : tr("no earlier <b>%1</b> event").arg(kind_->currentText()));
    return false;
  }
  session_->setStep(best);
  return true;
}

void Timeline::setPlaying(bool on) {
  if (on && session_->eventCount() == 0) on = false;
  if (on) {
    if (session_->step() + 1 >= session_->eventCount()) session_->setStep(0);
    timer_->start();
  } else {
    timer_->stop();
  }
  play_->setText(on ? tr("Pause") : tr("Play"));
}

bool Timeline::playing() const { return timer_->isActive(); }

void Timeline::offerUnit(bool tree) {
  QString k = kind_->currentData().toString();
  if (tree && k == "cell") kind_->setCurrentIndex(kind_->findData("node"));
  if (!tree && (k == "node" || k == "leaf" || k == "pushpop" || k == "box_test" || k == "skip"))
    kind_->setCurrentIndex(kind_->findData("cell"));
}

void Timeline::refresh() {
  int n = session_->eventCount();
  QSignalBlocker block(slider_);
  slider_->setRange(0, std::max(0, n - 1));
  slider_->setValue(session_->step());
  slider_->setEnabled(n > 0);
  const replay::ReplayState& s = session_->state();
  position_->setText(n ? tr("event %1 / %2: <b>%3</b>").arg(session_->step()).arg(n - 1).arg(event_type_name(s.event->type))
                       : tr("no trace: click a pixel"));
}

}  // namespace raystep::viz
