// The image view: the rendered picture, zoomable down to visible pixels (a pixel grid appears when a pixel
// is 8 screen pixels or more), with an optional heat-map overlay (cells visited, primitive tests or mailbox
// hits per pixel) and its colour bar. A click on a pixel asks for its rays to be traced.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <unordered_map>

#include <QImage>
#include <QWidget>

#include "raystep/render/pixel_samples.h"

#include "raystep/trace/heatmap.h"

class QComboBox;
class QCheckBox;
class QLabel;
class QSlider;

namespace raystep::viz {

class Session;

// The picture itself: pan (drag), zoom (wheel, keys + and -), click.
class ImageCanvas : public QWidget {
  Q_OBJECT
 public:
  explicit ImageCanvas(QWidget* parent = nullptr);
  void setImage(const QImage& image);
  void setHeat(const HeatMap* heat, double opacity);
  void setSelected(int x, int y);  // -1: none
  void setZoom(double zoom);       // screen pixels per image pixel; 0: fit
  double zoom() const;
  void centreOn(int x, int y);                  // pan so that pixel (x, y) is in the middle
  void resetPan();                              // the picture's centre in the middle
  double zoomSetting() const { return zoom_; }  // 0: fit
  // The picture's point (in its pixels) at the middle of the canvas: what the view is centred on.
  QPointF centre() const;
  // Where the centre of image pixel (x, y) is on the widget (for scripted clicks).
  QPoint widgetPosOf(int x, int y) const;
  // The sample pattern over each visible pixel, at 8x zoom and more: source gives a pixel's sampling (null:
  // none); only the visible pixels are asked for.
  using SampleSource = std::function<const PixelSampling*(int x, int y)>;
  void setSampleSource(SampleSource source) { sampleSource_ = std::move(source); }
  void setSampleOverlay(bool on);
  bool sampleOverlay() const { return sampleOverlay_; }
  int overlayPixelsDrawn() const { return overlayPixels_; }  // in the last paint, for the dump
  QSize sizeHint() const override { return {360, 300}; }

 Q_SIGNALS:
  void pixelClicked(int x, int y);

 protected:
  void paintEvent(QPaintEvent*) override;
  void wheelEvent(QWheelEvent*) override;
  void mousePressEvent(QMouseEvent*) override;
  void mouseMoveEvent(QMouseEvent*) override;
  void mouseReleaseEvent(QMouseEvent*) override;
  void resizeEvent(QResizeEvent*) override;

 private:
  QRectF imageRect() const;  // where the image is drawn, in widget coordinates
  QRect barRect() const;
  QImage image_, heatImage_;
  uint32_t heatMax_ = 0;
  double heatUnit_ = 1.0;
  QString heatLabel_;
  double heatOpacity_ = 0.7;
  int selX_ = -1, selY_ = -1;
  double zoom_ = 0.0;  // 0: fit to the widget
  QPointF pan_{0, 0};
  QPoint pressPos_;
  QPointF pressPan_;
  bool dragging_ = false, pressed_ = false;
  SampleSource sampleSource_;
  bool sampleOverlay_ = false;
  int overlayPixels_ = 0;
};

// The panel: anti-aliasing mode, heat map quantity and opacity, zoom, secondary rays, and the canvas.
class ImageView : public QWidget {
  Q_OBJECT
 public:
  explicit ImageView(Session* session, QWidget* parent = nullptr);
  QString antiAliasing() const;
  void setAntiAliasing(const QString& spec);
  // "off", "cells", "tests" or "mailbox".
  QString heatQuantity() const;
  void setHeatQuantity(const QString& q);
  bool secondaryRays() const;
  void setSecondaryRays(bool on);
  bool sampleOverlay() const;
  void setSampleOverlay(bool on);
  // Whether "error against the reference" can be chosen (the scene has an exact reference), and why not.
  bool errorHeatAvailable() const;
  QString errorHeatWhyNot() const;
  // What the heat map menu shows for it: whether the item can be chosen, and its tooltip.
  bool errorItemEnabled() const;
  QString errorItemToolTip() const;
  void setStatus(const QString& text);
  // Compact (presenter scales): the zoom buttons join the first row, the heat map's names are short.
  void setCompact(bool on);
  ImageCanvas* canvas() const { return canvas_; }

 Q_SIGNALS:
  void renderRequested();
  void heatRequested();
  void pixelClicked(int x, int y);

 private:
  void refreshHeat();
  void refreshErrorItem();
  const PixelSampling* overlaySampling(int x, int y);
  Session* session_;
  ImageCanvas* canvas_;
  QComboBox* aa_;
  QComboBox* heat_;
  QSlider* opacity_;
  QCheckBox* secondary_;
  QCheckBox* overlay_;
  // The overlay's samplings, per pixel, for what they were made for (structure, anti-aliasing, size).
  std::unordered_map<int64_t, PixelSampling> overlayCache_;
  std::string overlayKey_;
  QLabel* status_;
  QWidget* zoomBox_;
};

}  // namespace raystep::viz
