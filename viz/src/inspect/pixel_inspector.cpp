#include "inspect/pixel_inspector.h"

#include <algorithm>
#include <cmath>

#include <QHBoxLayout>
#include <QHeaderView>
#include <QJsonArray>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QScrollArea>
#include <QShortcut>
#include <QSplitter>
#include <QTableWidget>
#include <QToolButton>
#include <QTreeWidget>
#include <QVBoxLayout>

#include "common/palette.h"
#include "raystep/io/image_io.h"
#include "raystep/render/image.h"
#include "raystep/render/pixel_filter.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/trace/trace_file.h"
#include "app/session.h"

namespace raystep::viz {
namespace {

QColor toQColor(const glm::vec3& linear) {
  return QColor(srgb_encode8(linear.r), srgb_encode8(linear.g), srgb_encode8(linear.b));
}

// The outline that keeps a sample visible on any colour: dark around a light sample, light around a dark one.
QColor outlineFor(const QColor& c) {
  return c.lightness() > 110 ? QColor(20, 20, 20) : QColor(235, 235, 235);
}

// Adaptive squares outlined by depth: depth 0 (the pixel) dark, deeper squares lighter on the ramp.
QColor depthColour(int depth, int maxDepth) {
  // Viridis from blue to green only: its yellow end is the current square's colour.
  glm::vec3 c = viridis(maxDepth > 0 ? 0.2f + 0.5f * float(depth) / float(maxDepth) : 0.7f);
  return QColor(srgb_encode8(c.r), srgb_encode8(c.g), srgb_encode8(c.b));
}

QString num(double v, int digits = 3) {
  return QString::number(v, 'f', digits);
}

QString rgbText(const glm::vec3& c, int digits = 3) {
  return QString("%1 %2 %3").arg(num(c.r, digits), num(c.g, digits), num(c.b, digits));
}

const char* outcomeName(const AdaptiveSquare& q) {
  switch (q.outcome) {
    case AdaptiveSquare::Outcome::agree:
      return "agree";
    case AdaptiveSquare::Outcome::depth_limit:
      return "depth limit";
    case AdaptiveSquare::Outcome::subdivided:
      return "split";
  }
  return "?";
}

float largestContrast(const AdaptiveSquare& q, int* channel) {
  int c = 0;
  for (int k = 1; k < 3; ++k)
    if (q.contrast[k] > q.contrast[c]) c = k;
  if (channel) *channel = c;
  return q.contrast[c];
}

// A sample's place inside its pixel, (0, 0) at the top left, (1, 1) at the bottom right.
QPointF inPixel(const PixelSampling& s, const PixelSample& p) {
  return QPointF(double(p.px) - s.x, double(p.py) - s.y);
}

// Screen pixels between neighbouring samples, for the size of their discs.
double spacing(const AntiAliasing& aa, double side) {
  switch (aa.mode) {
    case AntiAliasing::Mode::none:
      return side;
    case AntiAliasing::Mode::regular:
    case AntiAliasing::Mode::jitter:
      return side / std::max(1, aa.k);
    case AntiAliasing::Mode::random:
      return side / std::sqrt(double(std::max(1, aa.k)));
    case AntiAliasing::Mode::adaptive:
      return side / double(2 << aa.max_depth);
  }
  return side;
}

}  // namespace

namespace {

std::string describePattern(const AntiAliasing& aa) {
  const std::string k = std::to_string(aa.k);
  switch (aa.mode) {
    case AntiAliasing::Mode::none:
      return "none: 1 sample at the centre";
    case AntiAliasing::Mode::regular:
      return "regular " + k + " x " + k + ": " + std::to_string(aa.k * aa.k) +
             " samples at the strata's centres";
    case AntiAliasing::Mode::jitter:
      return "jittered " + k + " x " + k + ": one sample anywhere in each of the " +
             std::to_string(aa.k * aa.k) + " strata";
    case AntiAliasing::Mode::random:
      return "random: " + k + " samples anywhere in the pixel";
    case AntiAliasing::Mode::adaptive:
      return "adaptive: threshold " + QString::number(double(aa.threshold), 'g', 3).toStdString() +
             ", depth limit " + std::to_string(aa.max_depth);
  }
  return "?";
}

}  // namespace

std::string describeAntiAliasing(const AntiAliasing& aa) {
  return describePattern(aa) +
         (aa.filter == AntiAliasing::Filter::tent ? ", weighed by the tent filter over 3 x 3 pixels" : "");
}

std::string explainSquare(const TracePixel& pixel, int index) {
  const PixelSampling& s = pixel.sampling;
  if (index < 0 || index >= int(s.squares.size())) return "";
  const AdaptiveSquare& q = s.squares[size_t(index)];
  const QString where =
      q.depth == 0
          ? QString("The whole pixel")
          : QString("Square %1 (depth %2, side 1/%3 of the pixel)").arg(index).arg(q.depth).arg(1 << q.depth);
  int c = 0;
  const float contrast = largestContrast(q, &c);
  const char* channels[3] = {"red", "green", "blue"};
  // Name the channel only where the channels differ (on a grey scene "in red" would mislead).
  const bool oneValue = q.contrast.r == q.contrast.g && q.contrast.g == q.contrast.b;
  const QString inChannel = oneValue ? QString() : QString(" in the %1 channel").arg(channels[c]);
  const QString t = QString::number(double(s.aa.threshold), 'g', 3);
  const QString sampled =
      q.new_samples == 5 ? QString("all five samples are new")
      : q.new_samples == 0
          ? QString("all five samples were already taken by its neighbours (shared, not traced again)")
          : QString("%1 of the five samples are new, %2 shared with squares before it")
                .arg(q.new_samples)
                .arg(5 - q.new_samples);
  QString why;
  switch (q.outcome) {
    case AdaptiveSquare::Outcome::subdivided:
      why = QString(
                "%1: its four corners and centre are sampled (%2). The samples disagree: contrast %3 > "
                "threshold %4%5, so this square is split into four, and each quadrant is sampled the "
                "same way.")
                .arg(where, sampled, num(contrast, 2), t, inChannel);
      break;
    case AdaptiveSquare::Outcome::agree:
      why = QString(
                "%1: its four corners and centre are sampled (%2). The samples agree: contrast %3 <= "
                "threshold %4 in every channel, so one value stands for the square: the mean of its five "
                "samples, %5.")
                .arg(where, sampled, num(contrast, 2), t, rgbText(q.value));
      break;
    case AdaptiveSquare::Outcome::depth_limit:
      why = contrast > s.aa.threshold
                ? QString(
                      "%1: its four corners and centre are sampled (%2). Contrast %3 > threshold %4%5, "
                      "but "
                      "the depth limit %6 is reached: the square is not split further, and the mean of its "
                      "five "
                      "samples, %7, stands for it.")
                      .arg(where, sampled, num(contrast, 2), t, inChannel)
                      .arg(s.aa.max_depth)
                      .arg(rgbText(q.value))
                : QString(
                      "%1: its four corners and centre are sampled (%2). The depth limit %3 is reached "
                      "(contrast %4, "
                      "threshold %5): the mean of its five samples, %6, stands for the square.")
                      .arg(where, sampled)
                      .arg(s.aa.max_depth)
                      .arg(num(contrast, 2), t, rgbText(q.value));
      break;
  }
  if (q.depth == 0 && q.outcome == AdaptiveSquare::Outcome::subdivided)
    why += QString(" The pixel's value is the mean of its quadrants' values: %1.").arg(rgbText(q.value));
  return why.toStdString();
}

// ---- the canvas ----

PixelCanvas::PixelCanvas(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  setObjectName("pixelCanvas");
  setSizePolicy(QSizePolicy::Expanding, QSizePolicy::Expanding);
  connect(session_, &Session::traceChanged, this, qOverload<>(&QWidget::update));
  connect(session_, &Session::squareChanged, this, qOverload<>(&QWidget::update));
}

void PixelCanvas::setBackdrop(const QImage& image) {
  backdrop_ = image;
  update();
}

double PixelCanvas::viewReach(const AntiAliasing& aa) {
  return 0.5 * filter_reach(aa.filter);
}

QRectF PixelCanvas::pixelRect() const {
  const TracePixel* p = session_->pixel();
  const double reach = p ? viewReach(p->sampling.aa) : 0.0;
  const double view = std::max(20, std::min(width(), height()) - 28);  // room for the rings at the edges
  const double side = view / (1.0 + 2.0 * reach);
  return QRectF((width() - side) / 2.0, (height() - side) / 2.0, side, side);
}

QPointF PixelCanvas::toCanvas(const PixelSample& ps) const {
  const TracePixel* p = session_->pixel();
  const QRectF r = pixelRect();
  const QPointF f = inPixel(p->sampling, ps);
  return QPointF(r.left() + f.x() * r.width(), r.top() + f.y() * r.height());
}

QPointF PixelCanvas::samplePos(int i) const {
  const TracePixel* p = session_->pixel();
  if (!p || i < 0 || i >= int(p->sampling.samples.size())) return {-1, -1};
  return toCanvas(p->sampling.samples[size_t(i)]);
}

QPointF PixelCanvas::neighbourPos(int i) const {
  const TracePixel* p = session_->pixel();
  if (!p || i < 0 || i >= int(p->sampling.neighbours.size())) return {-1, -1};
  return toCanvas(p->sampling.neighbours[size_t(i)]);
}

void PixelCanvas::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.setRenderHint(QPainter::Antialiasing, true);
  p.fillRect(rect(), palette::background);
  const TracePixel* px = session_->pixel();
  if (!px) {
    p.setPen(Qt::lightGray);
    p.drawText(rect().adjusted(8, 8, -8, -8), Qt::AlignCenter | Qt::TextWordWrap,
               tr("Click a pixel of the picture to see its samples."));
    return;
  }
  const PixelSampling& s = px->sampling;
  const QRectF r = pixelRect();
  const double side = r.width();
  const bool tent = s.aa.filter == AntiAliasing::Filter::tent;
  const double reach = viewReach(s.aa);
  const QRectF view = r.adjusted(-reach * side, -reach * side, reach * side, reach * side);
  // The area the filter weighs, neutral grey, so that black and white samples both show; over it, faintly,
  // the scene there.
  p.fillRect(view, QColor(96, 96, 104));
  if (!backdrop_.isNull()) {
    p.setOpacity(0.45);
    p.setRenderHint(QPainter::SmoothPixmapTransform, true);  // an edge reads as a line, not a staircase
    p.drawImage(view, backdrop_);
    p.setOpacity(1.0);
  }
  if (tent) {
    // The tent's weight as light: full at the centre, falling to nothing at the view's edges (the
    // neighbours' centres); the neighbouring pixels' borders dashed.
    const int n = 64;
    QImage shade(n, n, QImage::Format_ARGB32);
    for (int j = 0; j < n; ++j)
      for (int i = 0; i < n; ++i) {
        const float u = 2.f * (float(i) + 0.5f) / float(n) - 1.f, v = 2.f * (float(j) + 0.5f) / float(n) - 1.f;
        shade.setPixel(i, j, qRgba(0, 0, 0, int(std::lround(170.0 * (1.0 - tent_weight(u, v))))));
      }
    p.setRenderHint(QPainter::SmoothPixmapTransform, true);
    p.drawImage(view, shade);
    p.setPen(QPen(QColor(200, 200, 210), 1, Qt::DashLine));
    p.setBrush(Qt::NoBrush);
    p.drawRect(view);
  }

  auto toScreen = [&](double fx, double fy) { return QPointF(r.left() + fx * side, r.top() + fy * side); };
  if (s.aa.mode == AntiAliasing::Mode::regular || s.aa.mode == AntiAliasing::Mode::jitter) {
    // The k x k strata: each holds one sample (its centre for regular, anywhere inside for jitter).
    p.setPen(QPen(QColor(200, 200, 210), 1, Qt::DashLine));
    for (int i = 1; i < s.aa.k; ++i) {
      const double f = double(i) / s.aa.k;
      p.drawLine(toScreen(f, 0), toScreen(f, 1));
      p.drawLine(toScreen(0, f), toScreen(1, f));
    }
  }
  const double lattice = double(2 << s.aa.max_depth);
  auto squareRect = [&](const AdaptiveSquare& q) {
    return QRectF(toScreen(q.i0 / lattice, q.j0 / lattice),
                  QSizeF(q.size / lattice * side, q.size / lattice * side));
  };
  if (s.aa.mode == AntiAliasing::Mode::adaptive) {
    // Every square visited, outlined by its depth (deeper squares are drawn last, over their parents' lines).
    for (int d = 0; d <= s.aa.max_depth; ++d)
      for (const AdaptiveSquare& q : s.squares)
        if (q.depth == d) {
          p.setPen(QPen(depthColour(d, s.aa.max_depth), d == 0 ? 2.0 : 1.5));
          p.setBrush(Qt::NoBrush);
          p.drawRect(squareRect(q));
        }
  }
  p.setPen(QPen(QColor(230, 230, 235), 2));
  p.setBrush(Qt::NoBrush);
  p.drawRect(r);

  // The current square of the adaptive walk and its five samples.
  std::vector<int> squareSamples;
  if (const int sq = session_->square(); sq >= 0 && sq < int(s.squares.size())) {
    const AdaptiveSquare& q = s.squares[size_t(sq)];
    p.setPen(QPen(palette::currentCell, 3));
    p.drawRect(squareRect(q));
    squareSamples.assign(q.samples, q.samples + 5);
  }

  const double radius = std::clamp(spacing(s.aa, side) * 0.28, 4.0, 11.0);
  // With the tent, a disc's area is its weight: the centre's samples large, the far ones small.
  auto radiusOf = [&](const PixelSample& ps) {
    return tent ? std::max(2.0, radius * std::sqrt(double(ps.weight))) : radius;
  };
  for (size_t i = 0; i < s.neighbours.size(); ++i) {
    const QColor fill = toQColor(s.neighbours[i].colour);
    p.setPen(QPen(outlineFor(fill), 1.0, Qt::DotLine));
    p.setBrush(fill);
    p.drawEllipse(neighbourPos(int(i)), radiusOf(s.neighbours[i]), radiusOf(s.neighbours[i]));
  }
  for (size_t i = 0; i < s.samples.size(); ++i) {
    const QPointF c = samplePos(int(i));
    const double rs = radiusOf(s.samples[i]);
    const QColor fill = toQColor(s.samples[i].colour);
    if (std::find(squareSamples.begin(), squareSamples.end(), int(i)) != squareSamples.end()) {
      p.setPen(QPen(palette::currentCell, 3));
      p.setBrush(Qt::NoBrush);
      p.drawEllipse(c, rs + 4, rs + 4);
    }
    p.setPen(QPen(outlineFor(fill), 1.5));
    p.setBrush(fill);
    p.drawEllipse(c, rs, rs);
  }
  if (const int cur = session_->currentSample(); cur >= 0 && cur < int(s.samples.size())) {
    const QPointF c = samplePos(cur);
    p.setPen(QPen(palette::ray, 3));
    p.setBrush(Qt::NoBrush);
    p.drawEllipse(c, radius + 5, radius + 5);
    p.drawLine(c + QPointF(radius + 5, 0), c + QPointF(radius + 12, 0));
    p.drawLine(c - QPointF(radius + 5, 0), c - QPointF(radius + 12, 0));
  }
}

void PixelCanvas::mouseReleaseEvent(QMouseEvent* e) {
  const TracePixel* px = session_->pixel();
  if (!px || e->button() != Qt::LeftButton) return;
  // The nearest sample within reach of the click.
  int best = -1;
  double bestD = 1e9;
  for (size_t i = 0; i < px->sampling.samples.size(); ++i) {
    const QPointF d = samplePos(int(i)) - e->pos();
    const double dist = std::hypot(d.x(), d.y());
    if (dist < bestD) {
      bestD = dist;
      best = int(i);
    }
  }
  if (best >= 0 && bestD <= 16) Q_EMIT sampleClicked(best);
}

// ---- the panel ----

PixelInspector::PixelInspector(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  setObjectName("pixelInspector");
  auto* split = new QSplitter(Qt::Horizontal);
  auto* layout = new QHBoxLayout(this);
  layout->setContentsMargins(2, 2, 2, 2);
  layout->addWidget(split);

  canvas_ = new PixelCanvas(session_);
  split->addWidget(canvas_);

  // The numbers: the mode, the average, the exact value and the error; the legend; the samples.
  auto* middle = new QWidget;
  auto* mid = new QVBoxLayout(middle);
  mid->setContentsMargins(4, 0, 4, 0);
  title_ = new QLabel;
  title_->setObjectName("pixelTitle");
  title_->setWordWrap(true);
  mid->addWidget(title_);
  auto* valueRow = new QHBoxLayout;
  swatch_ = new QLabel;
  swatch_->setObjectName("pixelSwatch");
  swatch_->setFixedSize(44, 44);
  swatch_->setFrameStyle(QFrame::Box);
  valueRow->addWidget(swatch_, 0, Qt::AlignTop);
  values_ = new QLabel;
  values_->setObjectName("pixelValues");
  values_->setWordWrap(true);
  values_->setTextFormat(Qt::RichText);
  valueRow->addWidget(values_, 1);
  mid->addLayout(valueRow);
  legend_ = new QLabel;
  legend_->setObjectName("pixelLegend");
  legend_->setWordWrap(true);
  legend_->setTextFormat(Qt::RichText);
  mid->addWidget(legend_);
  table_ = new QTableWidget(0, 3);
  table_->setObjectName("sampleTable");
  table_->setHorizontalHeaderLabels(
      {tr("sample (x, y) in the pixel"), tr("colour"), tr("stratum / lattice")});
  table_->verticalHeader()->setVisible(false);
  table_->verticalHeader()->setDefaultSectionSize(18);
  table_->horizontalHeader()->setStretchLastSection(true);
  table_->setSelectionBehavior(QAbstractItemView::SelectRows);
  table_->setSelectionMode(QAbstractItemView::SingleSelection);
  table_->setEditTriggers(QAbstractItemView::NoEditTriggers);
  mid->addWidget(table_, 1);
  // At presenter scale the numbers and the legend may need more height than the dock has: they scroll as one
  // column rather than squeeze each other off (a wrapped label keeps the height its width needs).
  table_->setMinimumHeight(4 * table_->verticalHeader()->defaultSectionSize() + 24);
  auto* middleScroll = new QScrollArea;
  middleScroll->setObjectName("pixelNumbers");
  middleScroll->setWidgetResizable(true);
  middleScroll->setFrameShape(QFrame::NoFrame);
  middleScroll->setHorizontalScrollBarPolicy(Qt::ScrollBarAlwaysOff);
  middleScroll->setWidget(middle);
  split->addWidget(middleScroll);

  // Adaptive sampling: the squares as a tree, stepped through; the Why.
  adaptiveBox_ = new QWidget;
  auto* right = new QVBoxLayout(adaptiveBox_);
  right->setContentsMargins(4, 0, 0, 0);
  auto* steps = new QHBoxLayout;
  auto button = [&](const QString& text, const QString& tip) {
    auto* b = new QToolButton;
    b->setText(text);
    b->setToolTip(tip);
    b->setFocusPolicy(Qt::NoFocus);
    steps->addWidget(b);
    return b;
  };
  steps->addWidget(new QLabel(tr("<b>Squares</b>")));
  QToolButton* first = button(tr("|<"), tr("The whole pixel (Ctrl+Home)"));
  QToolButton* back = button(tr("< Square"), tr("The square before (Ctrl+Left)"));
  QToolButton* fwd = button(tr("Square >"), tr("The next square, depth first (Ctrl+Right)"));
  QToolButton* last = button(tr(">|"), tr("The last square (Ctrl+End)"));
  squarePos_ = new QLabel;
  squarePos_->setObjectName("squarePosition");
  steps->addWidget(squarePos_);
  steps->addStretch();
  right->addLayout(steps);
  tree_ = new QTreeWidget;
  tree_->setObjectName("squareTree");
  tree_->setColumnCount(3);
  tree_->setHeaderLabels({tr("square"), tr("contrast r g b"), tr("outcome")});
  tree_->setUniformRowHeights(true);
  right->addWidget(tree_, 1);
  why_ = new QLabel;
  why_->setObjectName("squareWhy");
  why_->setWordWrap(true);
  why_->setTextFormat(Qt::RichText);
  why_->setMinimumHeight(64);
  why_->setAlignment(Qt::AlignTop | Qt::AlignLeft);
  right->addWidget(why_);
  split->addWidget(adaptiveBox_);
  split->setStretchFactor(0, 0);
  split->setStretchFactor(1, 1);
  split->setStretchFactor(2, 1);
  split->setSizes({270, 430, 520});

  connect(first, &QToolButton::clicked, this, [this] { session_->setSquare(0); });
  connect(last, &QToolButton::clicked, this, [this] { session_->setSquare(session_->squareCount() - 1); });
  connect(back, &QToolButton::clicked, this, [this] { session_->stepSquare(-1); });
  connect(fwd, &QToolButton::clicked, this, [this] { session_->stepSquare(1); });
  // The walk's keys with Ctrl: the plain ones step the replayed ray (and, in a lesson, the lesson).
  for (auto [key, fn] : {std::pair<int, int>{Qt::CTRL | Qt::Key_Right, 1},
                         {Qt::CTRL | Qt::Key_Left, -1},
                         {Qt::CTRL | Qt::Key_Home, -1000000},
                         {Qt::CTRL | Qt::Key_End, 1000000}}) {
    auto* s = new QShortcut(QKeySequence(key), this);
    s->setContext(Qt::WindowShortcut);
    connect(s, &QShortcut::activated, this, [this, fn = fn] {
      if (std::abs(fn) == 1)
        session_->stepSquare(fn);
      else
        session_->setSquare(fn < 0 ? 0 : session_->squareCount() - 1);
    });
  }
  connect(canvas_, &PixelCanvas::sampleClicked, session_, &Session::selectSample);
  connect(table_, &QTableWidget::currentCellChanged, this, [this](int row, int, int, int) {
    if (!syncing_ && row >= 0) session_->selectSample(row);
  });
  connect(tree_, &QTreeWidget::currentItemChanged, this, [this](QTreeWidgetItem* item, QTreeWidgetItem*) {
    if (!syncing_ && item) session_->setSquare(item->data(0, Qt::UserRole).toInt());
  });
  connect(session_, &Session::traceChanged, this, &PixelInspector::refresh);
  connect(session_, &Session::squareChanged, this, &PixelInspector::refreshSquare);
  refresh();
}

void PixelInspector::setBackdrop(const QImage& image) {
  canvas_->setBackdrop(image);
  refresh();
}

void PixelInspector::refresh() {
  const TracePixel* px = session_->pixel();
  QSignalBlocker blockTable(table_);
  QSignalBlocker blockTree(tree_);
  syncing_ = true;
  table_->setRowCount(0);
  tree_->clear();
  if (!px) {
    title_->setText(tr("<b>Pixel inspector</b>: click a pixel of the picture."));
    values_->clear();
    legend_->clear();
    swatch_->setStyleSheet("");
    adaptiveBox_->setVisible(false);
    why_->clear();
    syncing_ = false;
    canvas_->update();
    return;
  }
  const PixelSampling& s = px->sampling;
  title_->setText(tr("<b>Pixel (%1, %2)</b> of %3 x %4, anti-aliasing %5: <b>%6</b> cast.")
                      .arg(s.x)
                      .arg(s.y)
                      .arg(px->width)
                      .arg(px->height)
                      .arg(QString::fromStdString(describeAntiAliasing(s.aa)).toHtmlEscaped())
                      .arg(s.samples.size() == 1 ? tr("1 sample") : tr("%1 samples").arg(s.samples.size())));
  const QColor avg = toQColor(s.value);
  swatch_->setStyleSheet(QString("background: %1; border: 1px solid #ddd;").arg(avg.name()));
  const bool tent = s.aa.filter == AntiAliasing::Filter::tent;
  QString v;
  if (tent) {
    double own = 0, all = 0;
    for (const PixelSample& p : s.samples) own += p.weight;
    all = own;
    for (const PixelSample& p : s.neighbours) all += p.weight;
    v = tr("tent filter: <b>%1</b> (its own samples' average, the box's: %5)<br>its %2 samples and %3 of "
           "its neighbours', weighed by (1 - |dx|)(1 - |dy|); its own hold %4% of the weight")
            .arg(rgbText(s.value))
            .arg(s.samples.size())
            .arg(s.neighbours.size())
            .arg(all > 0 ? num(100.0 * own / all, 0) : QString("0"))
            .arg(rgbText(s.box_value));
  } else {
    v = (s.samples.size() == 1 ? tr("value (the one sample): <b>%1</b>") : tr("average (box filter): <b>%1</b>"))
            .arg(rgbText(s.value));
  }
  if (s.aa.mode == AntiAliasing::Mode::adaptive) v += tr("<br>(the leaf squares' values, weighted by area)");
  if (px->exact) {
    const glm::vec3 e = glm::abs(s.value - *px->exact);
    // The error per channel only where the channels differ (a grey scene has one number).
    const bool grey = e.r == e.g && e.g == e.b;
    const QString error = num(std::max({e.r, e.g, e.b}), 4);
    const QString channels = grey ? QString() : tr(" (largest channel of %1)").arg(rgbText(e, 4));
    if (tent)
      v += tr("<br>exact (the tent over the area covered): <b>%1</b>, error <b>%2</b>%3")
               .arg(rgbText(*px->exact), error, channels);
    else
      v += tr("<br>exact (area coverage): <b>%1</b><br>error of the %4: <b>%2</b>%3")
               .arg(rgbText(*px->exact), error, channels)
               .arg(s.samples.size() == 1 ? tr("value") : tr("average"));
  } else {
    v += session_->scene()
             ? tr("<br><i>no exact value for this scene: exact area coverage needs flat-coloured triangles "
                  "seen orthographically</i>")
             : tr("<br><i>the trace holds no exact value (open its scene to compute one)</i>");
  }
  values_->setText(v);
  QString legend =
      tr("<span>Each disc is a sample at its position, filled with the colour its "
         "ray brought back; the <span style='color:%1'>cyan ring</span> is the sample whose ray is "
         "replayed (click another).")
          .arg(palette::ray.darker(150).name());
  if (s.aa.mode == AntiAliasing::Mode::regular)
    legend += tr(" Dashed: the %1 x %1 strata; each sample sits at its stratum's centre.").arg(s.aa.k);
  if (s.aa.mode == AntiAliasing::Mode::jitter)
    legend +=
        tr(" Dashed: the %1 x %1 strata; each sample lies somewhere inside its own stratum.").arg(s.aa.k);
  if (s.aa.mode == AntiAliasing::Mode::random) legend += tr(" No strata: samples may clump or leave gaps.");
  if (s.aa.mode == AntiAliasing::Mode::adaptive) {
    legend += tr(" Squares outlined by depth:");
    for (int d = 0; d <= s.aa.max_depth; ++d)
      legend += QString(" <span style='color:%1'>&#9632; %2</span>")
                    .arg(depthColour(d, s.aa.max_depth).name())
                    .arg(d);
    legend += tr("; <span style='color:%1'>yellow</span>: the current square and its five samples.")
                  .arg(palette::currentCell.name());
  }
  if (s.aa.mode == AntiAliasing::Mode::none && !tent)
    legend += tr(" Without anti-aliasing the pixel is its centre ray.");
  if (tent)
    legend += tr(" Tent filter: the pixel (solid) and half of each neighbour (dashed), darker where the weight "
                 "falls; a disc's area is its weight; dotted: the neighbours' samples.");
  if (canvas_->hasBackdrop())
    legend += tent ? tr(" Faint beneath: the scene under the tent (64 x 64 extra rays, for reference only).")
                   : tr(" Faint beneath: the scene inside the pixel (64 x 64 extra rays, for reference only).");
  legend_->setText(legend + "</span>");

  table_->setRowCount(int(s.samples.size()));
  for (size_t i = 0; i < s.samples.size(); ++i) {
    const PixelSample& ps = s.samples[i];
    const QPointF f = inPixel(s, ps);
    auto* pos = new QTableWidgetItem(QString("%1: (%2, %3)").arg(i).arg(num(f.x(), 3)).arg(num(f.y(), 3)));
    auto* col = new QTableWidgetItem(rgbText(ps.colour));
    col->setData(Qt::DecorationRole, toQColor(ps.colour));
    QString where = ps.stratum[0] >= 0   ? QString("stratum (%1, %2)").arg(ps.stratum[0]).arg(ps.stratum[1])
                    : ps.lattice[0] >= 0 ? QString("lattice (%1, %2)").arg(ps.lattice[0]).arg(ps.lattice[1])
                                         : QString("-");
    if (tent) where += QString(", weight %1").arg(num(ps.weight, 3));
    table_->setItem(int(i), 0, pos);
    table_->setItem(int(i), 1, col);
    table_->setItem(int(i), 2, new QTableWidgetItem(where));
  }
  table_->resizeColumnToContents(0);
  table_->resizeColumnToContents(1);

  // The squares as a tree: the root is the pixel, each split square's children its quadrants.
  adaptiveBox_->setVisible(s.aa.mode == AntiAliasing::Mode::adaptive);
  std::vector<QTreeWidgetItem*> items(s.squares.size(), nullptr);
  for (size_t i = 0; i < s.squares.size(); ++i) {
    const AdaptiveSquare& q = s.squares[i];
    QTreeWidgetItem* item = q.parent >= 0 && items[size_t(q.parent)]
                                ? new QTreeWidgetItem(items[size_t(q.parent)])
                                : new QTreeWidgetItem(tree_);
    const double lattice = double(2 << s.aa.max_depth);
    item->setText(0, QString("%1: depth %2 at (%3, %4)")
                         .arg(i)
                         .arg(q.depth)
                         .arg(num(q.i0 / lattice, 3))
                         .arg(num(q.j0 / lattice, 3)));
    item->setText(1, rgbText(q.contrast, 2));
    item->setText(2, outcomeName(q));
    item->setData(0, Qt::UserRole, int(i));
    item->setForeground(0, depthColour(q.depth, s.aa.max_depth).lighter(130));
    items[i] = item;
  }
  tree_->expandAll();
  tree_->resizeColumnToContents(0);
  syncing_ = false;
  showSample();
  refreshSquare();
}

void PixelInspector::showSample() {
  syncing_ = true;
  const int cur = session_->currentSample();
  if (cur >= 0 && cur < table_->rowCount()) {
    table_->setCurrentCell(cur, 0);
    table_->scrollToItem(table_->item(cur, 0));
  } else {
    table_->clearSelection();
  }
  syncing_ = false;
  canvas_->update();
}

void PixelInspector::refreshSquare() {
  const TracePixel* px = session_->pixel();
  const int sq = session_->square();
  canvas_->update();
  if (!px || sq < 0) {
    squarePos_->clear();
    why_->clear();
    return;
  }
  const PixelSampling& s = px->sampling;
  squarePos_->setText(tr("square %1 of %2").arg(sq).arg(s.squares.size() - 1));
  syncing_ = true;
  std::function<QTreeWidgetItem*(QTreeWidgetItem*)> find = [&](QTreeWidgetItem* item) -> QTreeWidgetItem* {
    if (item->data(0, Qt::UserRole).toInt() == sq) return item;
    for (int i = 0; i < item->childCount(); ++i)
      if (QTreeWidgetItem* f = find(item->child(i))) return f;
    return nullptr;
  };
  for (int i = 0; i < tree_->topLevelItemCount(); ++i)
    if (QTreeWidgetItem* f = find(tree_->topLevelItem(i))) {
      tree_->setCurrentItem(f);
      tree_->scrollToItem(f);
    }
  syncing_ = false;
  const AdaptiveSquare& q = s.squares[size_t(sq)];
  QString samples;
  for (int k = 0; k < 5; ++k) {
    const int i = q.samples[k];
    if (i < 0 || i >= int(s.samples.size())) continue;
    samples += QString("%1%2 %3").arg(k ? ", " : "").arg(k < 4 ? tr("corner") : tr("centre")).arg(i);
  }
  why_->setText(
      tr("<b>Why:</b> %1<br><span style='color:#555'>samples: %2; contrast per channel (max - min) / "
         "(max + min): r %3, g %4, b %5</span>")
          .arg(QString::fromStdString(explainSquare(*px, sq)).toHtmlEscaped())
          .arg(samples)
          .arg(num(q.contrast.r, 3), num(q.contrast.g, 3), num(q.contrast.b, 3)));
}

QJsonObject PixelInspector::dumpState() const {
  QJsonObject o;
  o["visible"] = isVisible();
  const TracePixel* px = session_->pixel();
  if (!px) return o;
  const PixelSampling& s = px->sampling;
  auto rgb = [](const glm::vec3& c) { return QJsonArray{double(c.r), double(c.g), double(c.b)}; };
  o["pixel"] = QJsonArray{s.x, s.y};
  o["aa"] = QString::fromStdString(describeAntiAliasing(s.aa));
  QJsonArray samples;
  for (const PixelSample& p : s.samples)
    samples.append(
        QJsonArray{double(p.px), double(p.py), double(p.colour.r), double(p.colour.g), double(p.colour.b)});
  o["samples"] = samples;
  o["value"] = rgb(s.value);
  o["filter"] = s.aa.filter == AntiAliasing::Filter::tent ? "tent" : "box";
  o["box_value"] = rgb(s.box_value);
  o["neighbours"] = int(s.neighbours.size());
  if (px->exact) o["exact"] = rgb(*px->exact);
  QJsonArray squares;
  for (const AdaptiveSquare& q : s.squares)
    squares.append(QJsonObject{{"depth", q.depth},
                               {"i0", q.i0},
                               {"j0", q.j0},
                               {"size", q.size},
                               {"outcome", outcomeName(q)},
                               {"contrast", rgb(q.contrast)}});
  o["squares"] = squares;
  o["backdrop"] = canvas_->hasBackdrop();
  o["legend"] = legend_->text();
  o["square"] = session_->square();
  o["sample"] = session_->currentSample();
  o["title"] = title_->text();
  o["values"] = values_->text();
  o["why"] = why_->text();
  o["table_row"] = table_->currentRow();
  if (session_->square() >= 0) {
    QTreeWidgetItem* cur = tree_->currentItem();
    o["tree_current"] = cur ? cur->data(0, Qt::UserRole).toInt() : -1;
  }
  if (const int cur = session_->currentSample(); cur >= 0 && isVisible()) {  // where it is drawn, when it is
    const QPointF at = canvas_->mapTo(window(), canvas_->samplePos(cur).toPoint());
    o["sample_on_window"] = QJsonArray{at.x(), at.y()};
  }
  return o;
}

}  // namespace raystep::viz
