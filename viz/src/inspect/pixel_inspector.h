// The pixel inspector: one pixel's anti-aliasing as the renderer did it (render/pixel_samples.h). The pixel
// enlarged with its sample positions (the k x k strata of regular and jittered sampling, random samples,
// adaptive sampling's squares outlined by depth), each sample filled with its colour, the box-filtered
// average and, where the scene has one, the exact pre-filtered value and the average's error. Clicking a
// sample (on the canvas or in the table) replays its ray. For adaptive sampling, the subdivision as a tree,
// stepped through like a ray's walk (Ctrl+Right/Left, Ctrl+Home/End): the current square, its five samples,
// the contrast per channel against the threshold and the Why in the lecture's words.
#pragma once

#include <string>

#include <QImage>
#include <QJsonObject>
#include <QWidget>

class QLabel;
class QTableWidget;
class QTreeWidget;
class QTreeWidgetItem;
class QToolButton;
class QShortcut;

namespace raystep {
struct TracePixel;
struct AdaptiveSquare;
struct PixelSample;
struct AntiAliasing;
}  // namespace raystep

namespace raystep::viz {

class Session;

// "regular 4 x 4 (16 samples)", "adaptive, threshold 0.1, depth limit 3", "none (1 sample at the centre)".
std::string describeAntiAliasing(const AntiAliasing& aa);
// Why adaptive sampling did what it did with a square, with its numbers ("the corners disagree: contrast 0.83
// > threshold 0.1, so this square is split into four").
std::string explainSquare(const TracePixel& pixel, int square);

// The enlarged pixel: a square canvas. With the tent filter it shows the tent's whole square, the pixel and
// half of each neighbour, with the weight shading away from the centre and the neighbours' samples too.
class PixelCanvas : public QWidget {
  Q_OBJECT
 public:
  explicit PixelCanvas(Session* session, QWidget* parent = nullptr);
  // How far beyond the pixel, in pixels, the canvas shows for these settings: 0, or 0.5 for the tent.
  static double viewReach(const AntiAliasing& aa);
  // Where neighbour sample i's centre is drawn (tent filter), as samplePos.
  QPointF neighbourPos(int i) const;
  // Where sample i's centre is drawn (widget coordinates), for scripted clicks and tests.
  QPointF samplePos(int i) const;
  // The scene inside the pixel, drawn faintly under the samples (null: none, as for a trace without its
  // scene).
  void setBackdrop(const QImage& image);
  bool hasBackdrop() const { return !backdrop_.isNull(); }
  QSize sizeHint() const override { return {260, 260}; }
  QSize minimumSizeHint() const override { return {160, 160}; }
  bool hasHeightForWidth() const override { return true; }
  int heightForWidth(int w) const override { return w; }

 Q_SIGNALS:
  void sampleClicked(int sample);

 protected:
  void paintEvent(QPaintEvent*) override;
  void mouseReleaseEvent(QMouseEvent*) override;

 private:
  QRectF pixelRect() const;   // the pixel's own square on the canvas
  QPointF toCanvas(const PixelSample& p) const;
  Session* session_;
  QImage backdrop_;
};

class PixelInspector : public QWidget {
  Q_OBJECT
 public:
  explicit PixelInspector(Session* session, QWidget* parent = nullptr);
  PixelCanvas* canvas() const { return canvas_; }
  // The scene inside the pixel beneath the samples (null: none); the legend says what it is.
  void setBackdrop(const QImage& image);
  // What the inspector shows, for the scripted mode's --dump-state.
  QJsonObject dumpState() const;

 private:
  void refresh();        // a new pixel, or another ray of it
  void refreshSquare();  // the adaptive step
  void showSample();     // the current sample in the table and the canvas
  Session* session_;
  PixelCanvas* canvas_;
  QLabel* title_;
  QLabel* swatch_;
  QLabel* values_;
  QLabel* legend_;
  QTableWidget* table_;
  QWidget* adaptiveBox_;
  QTreeWidget* tree_;
  QLabel* squarePos_;
  QLabel* why_;
  bool syncing_ = false;
};

}  // namespace raystep::viz
