#include "views/image_view.h"

#include <algorithm>
#include <cmath>

#include <QCheckBox>
#include <QComboBox>
#include <QHBoxLayout>
#include <QLabel>
#include <QMouseEvent>
#include <QPainter>
#include <QPushButton>
#include <QRegularExpression>
#include <QSlider>
#include <QStandardItemModel>
#include <QToolButton>
#include <QVBoxLayout>
#include <QWheelEvent>

#include "raystep/io/image_io.h"
#include "raystep/render/image.h"
#include "raystep/render/reference.h"
#include "raystep/scene/antialiasing_spec.h"
#include "app/session.h"

namespace raystep::viz {
namespace {

QColor rampColor(float t) {
  glm::vec3 c = viridis(t);
  return QColor(srgb_encode8(c.r), srgb_encode8(c.g), srgb_encode8(c.b));
}

}  // namespace

ImageCanvas::ImageCanvas(QWidget* parent) : QWidget(parent) {
  setMouseTracking(false);
  setFocusPolicy(Qt::ClickFocus);
  setObjectName("imageCanvas");
}

void ImageCanvas::setImage(const QImage& image) {
  image_ = image;
  update();
}

void ImageCanvas::setHeat(const HeatMap* heat, double opacity) {
  heatOpacity_ = opacity;
  if (!heat) {
    heatImage_ = QImage();
    update();
    return;
  }
  heatImage_ = QImage(heat->width, heat->height, QImage::Format_RGB888);
  float scale = heat->max_value ? 1.f / float(heat->max_value) : 0.f;
  for (int y = 0; y < heat->height; ++y) {
    uchar* row = heatImage_.scanLine(y);
    for (int x = 0; x < heat->width; ++x) {
      QColor c = rampColor(float(heat->values[size_t(y) * heat->width + x]) * scale);
      row[3 * x] = uchar(c.red());
      row[3 * x + 1] = uchar(c.green());
      row[3 * x + 2] = uchar(c.blue());
    }
  }
  heatMax_ = heat->max_value;
  heatUnit_ = heat->unit;
  heatLabel_ = heat_quantity_label(heat->quantity);
  // The bar's numbers are in the quantity's own unit (0.135, not 135 thousandths): the label says no unit.
  if (heat->unit != 1.0) heatLabel_.remove(QRegularExpression("\\s*\\(thousandths\\)"));
  update();
}

void ImageCanvas::setSampleOverlay(bool on) {
  sampleOverlay_ = on;
  update();
}

void ImageCanvas::setSelected(int x, int y) {
  selX_ = x;
  selY_ = y;
  update();
}

double ImageCanvas::zoom() const {
  if (zoom_ > 0.0) return zoom_;
  QSize s = image_.isNull() ? heatImage_.size() : image_.size();
  if (s.isEmpty()) return 1.0;
  int avail = width() - (heatImage_.isNull() ? 0 : barRect().width() + 72);
  return std::max(0.05, std::min(double(avail) / s.width(), double(height()) / s.height()));
}

void ImageCanvas::setZoom(double zoom) {
  zoom_ = zoom;
  if (zoom <= 0.0) pan_ = QPointF(0, 0);
  update();
}

QRectF ImageCanvas::imageRect() const {
  QSize s = image_.isNull() ? heatImage_.size() : image_.size();
  double z = zoom();
  int avail = width() - (heatImage_.isNull() ? 0 : barRect().width() + 72);
  QPointF topLeft((avail - s.width() * z) / 2.0, (height() - s.height() * z) / 2.0);
  return QRectF(topLeft + pan_, QSizeF(s.width() * z, s.height() * z));
}

QPointF ImageCanvas::centre() const {
  const QRectF r = imageRect();
  const int avail = width() - (heatImage_.isNull() ? 0 : barRect().width() + 72);
  const double z = zoom();
  return QPointF((avail / 2.0 - r.left()) / z, (height() / 2.0 - r.top()) / z);
}

void ImageCanvas::resetPan() {
  pan_ = QPointF(0, 0);
  update();
}

void ImageCanvas::centreOn(int x, int y) {
  pan_ = QPointF(0, 0);
  QPointF at = QPointF(widgetPosOf(x, y));
  int avail = width() - (heatImage_.isNull() ? 0 : barRect().width() + 72);
  pan_ = QPointF(avail / 2.0, height() / 2.0) - at;
  update();
}

QPoint ImageCanvas::widgetPosOf(int x, int y) const {
  QRectF r = imageRect();
  double z = zoom();
  return QPoint(int(std::floor(r.left() + (x + 0.5) * z)), int(std::floor(r.top() + (y + 0.5) * z)));
}

QRect ImageCanvas::barRect() const {
  return QRect(width() - 62, 16, 14, std::max(40, height() - 32));
}

void ImageCanvas::paintEvent(QPaintEvent*) {
  QPainter p(this);
  p.fillRect(rect(), QColor(40, 40, 44));
  if (image_.isNull() && heatImage_.isNull()) {
    p.setPen(Qt::lightGray);
    p.drawText(rect(), Qt::AlignCenter | Qt::TextWordWrap,
               tr("No picture.\nOpen a scene (a trace opened on its own replays without one)."));
    return;
  }
  QRectF r = imageRect();
  p.setRenderHint(QPainter::SmoothPixmapTransform, false);  // pixels stay square when zoomed in
  if (!image_.isNull()) p.drawImage(r, image_);
  if (!heatImage_.isNull()) {
    p.setOpacity(image_.isNull() ? 1.0 : heatOpacity_);
    p.drawImage(r, heatImage_);
    p.setOpacity(1.0);
  }
  double z = zoom();
  QSize s = image_.isNull() ? heatImage_.size() : image_.size();
  if (z >= 8.0) {  // the pixel grid
    p.setPen(QPen(QColor(0, 0, 0, 90), 0));
    int x0 = std::max(0, int(-r.left() / z)), x1 = std::min(s.width(), int((width() - r.left()) / z) + 1);
    int y0 = std::max(0, int(-r.top() / z)), y1 = std::min(s.height(), int((height() - r.top()) / z) + 1);
    for (int x = x0; x <= x1; ++x)
      p.drawLine(QPointF(r.left() + x * z, r.top() + y0 * z), QPointF(r.left() + x * z, r.top() + y1 * z));
    for (int y = y0; y <= y1; ++y)
      p.drawLine(QPointF(r.left() + x0 * z, r.top() + y * z), QPointF(r.left() + x1 * z, r.top() + y * z));
  }
  overlayPixels_ = 0;
  if (z >= 8.0 && sampleOverlay_ && sampleSource_) {  // each visible pixel's sample positions
    const int x0 = std::max(0, int(-r.left() / z)),
              x1 = std::min(s.width() - 1, int((width() - r.left()) / z));
    const int y0 = std::max(0, int(-r.top() / z)),
              y1 = std::min(s.height() - 1, int((height() - r.top()) / z));
    // Small dots in one colour that shows on black and on white (the picture stays readable beneath them).
    const double radius = std::clamp(z / 20.0, 1.0, 2.5);
    p.setRenderHint(QPainter::Antialiasing, true);
    p.setPen(Qt::NoPen);
    p.setBrush(QColor(255, 120, 0));
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const PixelSampling* ps = sampleSource_(x, y);
        if (!ps) continue;
        ++overlayPixels_;
        for (const PixelSample& smp : ps->samples)
          p.drawEllipse(QPointF(r.left() + double(smp.px) * z, r.top() + double(smp.py) * z), radius, radius);
      }
    p.setRenderHint(QPainter::Antialiasing, false);
  }
  if (selX_ >= 0) {  // the traced pixel: a box, and a cross-hair when it is small on screen
    QRectF px(r.left() + selX_ * z, r.top() + selY_ * z, z, z);
    p.setPen(QPen(QColor(0, 230, 255), 2));
    p.setBrush(Qt::NoBrush);
    p.drawRect(px.adjusted(-2, -2, 2, 2));
    if (z < 6.0) {
      QPointF c = px.center();
      p.drawLine(c - QPointF(14, 0), c - QPointF(5, 0));
      p.drawLine(c + QPointF(5, 0), c + QPointF(14, 0));
      p.drawLine(c - QPointF(0, 14), c - QPointF(0, 5));
      p.drawLine(c + QPointF(0, 5), c + QPointF(0, 14));
    }
  }
  if (!heatImage_.isNull()) {  // colour bar: bottom 0, top max
    QRect b = barRect();
    for (int y = 0; y < b.height(); ++y)
      p.fillRect(QRect(b.left(), b.top() + y, b.width(), 1),
                 rampColor(1.f - float(y) / float(b.height() - 1)));
    p.setPen(Qt::white);
    p.drawRect(b.adjusted(0, 0, -1, -1));
    // In the quantity's own unit (the error map counts thousandths: its top reads 0.135, not 135).
    p.drawText(QPoint(b.right() + 4, b.top() + 10),
               heatUnit_ == 1.0 ? QString::number(heatMax_) : QString::number(heatMax_ * heatUnit_, 'g', 3));
    p.drawText(QPoint(b.right() + 4, b.bottom()), "0");
    p.save();
    p.translate(b.left() - 4, b.center().y());
    p.rotate(-90);
    p.drawText(QRect(-150, -16, 300, 16), Qt::AlignCenter, heatLabel_);
    p.restore();
  }
}

void ImageCanvas::wheelEvent(QWheelEvent* e) {
  double z = zoom();
  double nz = std::clamp(z * (e->angleDelta().y() > 0 ? 1.25 : 0.8), 0.1, 64.0);
  // Keep the image point under the cursor where it is.
  QPointF m = e->position();
  QRectF r = imageRect();
  QPointF img = (m - r.topLeft()) / z;
  zoom_ = nz;
  pan_ = QPointF(0, 0);
  QRectF r2 = imageRect();
  pan_ = m - (r2.topLeft() + img * nz);
  update();
}

void ImageCanvas::mousePressEvent(QMouseEvent* e) {
  pressed_ = true;
  dragging_ = false;
  pressPos_ = e->pos();
  pressPan_ = pan_;
}

void ImageCanvas::mouseMoveEvent(QMouseEvent* e) {
  if (!pressed_) return;
  if ((e->pos() - pressPos_).manhattanLength() > 4) dragging_ = true;
  if (dragging_) {
    if (zoom_ <= 0.0) zoom_ = zoom();
    pan_ = pressPan_ + (e->pos() - pressPos_);
    update();
  }
}

void ImageCanvas::mouseReleaseEvent(QMouseEvent* e) {
  if (pressed_ && !dragging_ && e->button() == Qt::LeftButton) {
    QRectF r = imageRect();
    double z = zoom();
    QSize s = image_.isNull() ? heatImage_.size() : image_.size();
    int x = int(std::floor((e->pos().x() - r.left()) / z)), y = int(std::floor((e->pos().y() - r.top()) / z));
    if (x >= 0 && y >= 0 && x < s.width() && y < s.height()) Q_EMIT pixelClicked(x, y);
  }
  pressed_ = dragging_ = false;
}

void ImageCanvas::resizeEvent(QResizeEvent*) {
  update();
}

ImageView::ImageView(Session* session, QWidget* parent) : QWidget(parent), session_(session) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(2);
  auto* row1 = new QHBoxLayout;
  row1->addWidget(new QLabel(tr("<b>Image</b>")));
  row1->addStretch();
  overlay_ = new QCheckBox(tr("samples"));
  overlay_->setObjectName("sampleOverlay");
  overlay_->setToolTip(
      tr("Zoomed to 8x and more: each pixel's sample positions, as the renderer placed them"));
  row1->addWidget(overlay_);
  row1->addWidget(new QLabel(tr("AA")));
  aa_ = new QComboBox;
  aa_->setObjectName("aaCombo");
  aa_->setEditable(true);
  aa_->addItems(
      {"scene", "none", "regular:2", "regular:4", "jitter:4", "random:16", "adaptive:0.1", "regular:4+tent"});
  aa_->setToolTip(tr("scene (the scene file's) | none | regular:K | jitter:K | random:N | adaptive:T[:D]; "
                     "+tent after any but adaptive: the tent filter over the neighbours' samples too"));
  row1->addWidget(aa_);
  auto* render = new QPushButton(tr("Render"));
  row1->addWidget(render);
  layout->addLayout(row1);

  auto* row2 = new QHBoxLayout;
  row2->addWidget(new QLabel(tr("Heat map")));
  heat_ = new QComboBox;
  heat_->setObjectName("heatCombo");
  heat_->addItem(tr("off"), "off");
  heat_->addItem(tr("cells or nodes visited"), "cells");
  heat_->addItem(tr("primitive tests"), "tests");
  heat_->addItem(tr("mailbox hits"), "mailbox");
  heat_->addItem(tr("box tests (BVH)"), "boxes");
  heat_->addItem(tr("samples per pixel"), "samples");
  heat_->addItem(tr("error against the reference"), "error");
  row2->addWidget(heat_);
  opacity_ = new QSlider(Qt::Horizontal);
  opacity_->setRange(0, 100);
  opacity_->setValue(75);
  opacity_->setFixedWidth(50);
  opacity_->setToolTip(tr("Heat map opacity"));
  row2->addWidget(opacity_);
  secondary_ = new QCheckBox(tr("2nd rays"));
  secondary_->setToolTip(tr("A click traces the pixel's shadow, reflected and refracted rays too"));
  row2->addWidget(secondary_);
  row2->addStretch();
  zoomBox_ = new QWidget;
  auto* zoom = new QHBoxLayout(zoomBox_);
  zoom->setContentsMargins(0, 0, 0, 0);
  for (auto [text, z] : {std::pair{"Fit", 0.0}, std::pair{"1:1", 1.0}, std::pair{"8x", 8.0}}) {
    auto* b = new QToolButton;
    b->setText(tr(text));
    connect(b, &QPushButton::clicked, this, [this, z = z] { canvas_->setZoom(z); });
    zoom->addWidget(b);
  }
  row2->addWidget(zoomBox_);
  layout->addLayout(row2);

  canvas_ = new ImageCanvas;
  layout->addWidget(canvas_, 1);
  status_ = new QLabel;
  status_->setObjectName("imageStatus");
  status_->setWordWrap(true);
  layout->addWidget(status_);

  connect(render, &QPushButton::clicked, this, &ImageView::renderRequested);
  connect(aa_, QOverload<int>::of(&QComboBox::activated), this, &ImageView::renderRequested);
  connect(heat_, QOverload<int>::of(&QComboBox::activated), this, &ImageView::heatRequested);
  connect(opacity_, &QSlider::valueChanged, this, &ImageView::refreshHeat);
  connect(canvas_, &ImageCanvas::pixelClicked, this, &ImageView::pixelClicked);
  connect(session_, &Session::pictureChanged, this, [this] {
    canvas_->setImage(session_->picture());
    refreshErrorItem();
  });
  connect(session_, &Session::structureChanged, this, &ImageView::refreshErrorItem);
  connect(overlay_, &QCheckBox::toggled, canvas_, &ImageCanvas::setSampleOverlay);
  canvas_->setSampleSource([this](int x, int y) { return overlaySampling(x, y); });
  refreshErrorItem();
  connect(session_, &Session::heatChanged, this, &ImageView::refreshHeat);
  connect(session_, &Session::traceChanged, this, [this] {
    const Trace* t = session_->trace();
    bool mine = t && !t->rays.empty() && t->rays[0].has_pixel && session_->scene();
    canvas_->setSelected(mine ? t->rays[0].pixel[0] : -1, mine ? t->rays[0].pixel[1] : -1);
  });
}

void ImageView::setCompact(bool on) {
  auto* row1 = static_cast<QBoxLayout*>(layout()->itemAt(0)->layout());
  auto* row2 = static_cast<QBoxLayout*>(layout()->itemAt(1)->layout());
  row1->removeWidget(zoomBox_);
  row2->removeWidget(zoomBox_);
  (on ? row1 : row2)->addWidget(zoomBox_);
  heat_->setItemText(1, on ? tr("cells/nodes") : tr("cells or nodes visited"));
  heat_->setItemText(2, on ? tr("tests") : tr("primitive tests"));
  heat_->setItemText(4, on ? tr("samples") : tr("samples per pixel"));
  heat_->setItemText(5, on ? tr("error") : tr("error against the reference"));
}

const PixelSampling* ImageView::overlaySampling(int x, int y) {
  const StructureData* s = session_->structure();
  if (!s) return nullptr;
  const int w = session_->imageWidth(), h = session_->imageHeight();
  if (x >= w || y >= h) return nullptr;
  AntiAliasing aa;
  try {
    aa = antiAliasingOf(s->scene->scene, antiAliasing().toStdString());
  } catch (const std::exception&) {  // a spec being typed: nothing to show yet
    return nullptr;
  }
  // What the cached samplings were made for: another structure, anti-aliasing or size starts afresh.
  const std::string key = std::to_string(reinterpret_cast<uintptr_t>(s)) + " " + to_string(aa) + " " +
                          std::to_string(w) + "x" + std::to_string(h);
  if (key != overlayKey_ || overlayCache_.size() > 200000) {
    overlayCache_.clear();
    overlayKey_ = key;
  }
  const int64_t k = int64_t(y) * w + x;
  auto it = overlayCache_.find(k);
  if (it == overlayCache_.end()) it = overlayCache_.emplace(k, samplePixel(*s, aa, w, h, x, y, true)).first;
  return &it->second;
}

void ImageView::refreshErrorItem() {
  auto* model = qobject_cast<QStandardItemModel*>(heat_->model());
  const int i = heat_->findData("error");
  if (!model || i < 0) return;
  const QString why = errorHeatWhyNot();
  model->item(i)->setEnabled(why.isEmpty());
  heat_->setItemData(i,
                     why.isEmpty()
                         ? tr("Per pixel, the largest channel's error against the exact pre-filtered "
                              "picture (area coverage), in the picture's units (0 to 1)")
                         : tr("No exact reference: %1").arg(why),
                     Qt::ToolTipRole);
}

bool ImageView::errorItemEnabled() const {
  auto* model = qobject_cast<QStandardItemModel*>(heat_->model());
  const int i = heat_->findData("error");
  return model && i >= 0 && model->item(i)->isEnabled();
}

QString ImageView::errorItemToolTip() const {
  const int i = heat_->findData("error");
  return i >= 0 ? heat_->itemData(i, Qt::ToolTipRole).toString() : QString();
}

bool ImageView::errorHeatAvailable() const {
  return errorHeatWhyNot().isEmpty();
}

QString ImageView::errorHeatWhyNot() const {
  const SceneData* scene = session_->scene();
  if (!scene) return tr("open a scene");
  const int w = session_->imageWidth() > 0 ? session_->imageWidth() : scene->scene.render.width;
  const int h = session_->imageHeight() > 0 ? session_->imageHeight() : scene->scene.render.height;
  return QString::fromStdString(exact_coverage_unavailable(scene->scene, w, h));
}

bool ImageView::sampleOverlay() const {
  return overlay_->isChecked();
}
void ImageView::setSampleOverlay(bool on) {
  overlay_->setChecked(on);
}

void ImageView::refreshHeat() {
  canvas_->setHeat(session_->heat(), opacity_->value() / 100.0);
}

QString ImageView::antiAliasing() const {
  return aa_->currentText();
}
void ImageView::setAntiAliasing(const QString& spec) {
  aa_->setCurrentText(spec);
}
QString ImageView::heatQuantity() const {
  return heat_->currentData().toString();
}
void ImageView::setHeatQuantity(const QString& q) {
  int i = heat_->findData(q);
  if (i >= 0) heat_->setCurrentIndex(i);
}
bool ImageView::secondaryRays() const {
  return secondary_->isChecked();
}
void ImageView::setSecondaryRays(bool on) {
  secondary_->setChecked(on);
}
void ImageView::setStatus(const QString& text) {
  status_->setText(text);
}

}  // namespace raystep::viz
