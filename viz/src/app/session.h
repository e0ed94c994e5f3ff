// The debugger's document: the scene (or a trace opened on its own), the structure built over it (a grid or a
// kd-tree), the picture,
// the heat map, and the traced pixel with the current ray and step. Views read it and listen to its signals;
// only the main window changes it. The heavy work (build, render, heat map) is done by the free functions
// below, which take everything they need by shared pointer so that they can run on a worker thread.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include <QImage>
#include <QObject>

#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/structure_options.h"
#include <optional>

#include "raystep/accel/bvh_quality.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/render/render.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/heatmap.h"
#include "raystep/trace/trace_file.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/replayer.h"

namespace raystep::viz {

class SceneMesh;

struct SceneData {
  Scene scene;
  std::string path, hash;
  // The 3D view's mesh of the scene (scene_mesh.h), made with it on the loading worker; null: the view makes
  // it when it shows the scene.
  std::shared_ptr<const SceneMesh> mesh;
};

// Any accelerator that records events: "grid", "kd" (SAH), "kd-median", a BVH (bvh_names.h: "bvh", "bvh-sweep",
// "bvh-median", "bvh-sbvh", "bvh4", "bvh8", "bvh4-sbvh", "bvh8-sbvh"), "octree" or "bsp" (the general BSP tree).
struct StructureData {
  std::shared_ptr<const SceneData> scene;  // the structure points into its geometry: keep it alive
  std::string kind;
  std::unique_ptr<Accelerator> accel;
  double buildMs = 0.0;
  const UniformGrid* grid() const { return dynamic_cast<const UniformGrid*>(accel.get()); }
  const KdTree* kdTree() const { return dynamic_cast<const KdTree*>(accel.get()); }
  const Bvh* bvh() const { return dynamic_cast<const Bvh*>(accel.get()); }  // the binary BVH
  const Octree* octree() const { return dynamic_cast<const Octree*>(accel.get()); }
  const BspTree* bsp() const { return dynamic_cast<const BspTree*>(accel.get()); }
  const WideBvh* wideBvh() const { return dynamic_cast<const WideBvh*>(accel.get()); }  // bvh4, bvh8
  // The wide BVH's nodes as traces name them (WideBvh::describe), and each node's primitive count (its
  // subtree's): made with the build, for the tree view.
  std::shared_ptr<const WideBvhView> wideView;
  std::vector<uint32_t> wideViewPrims;
  // A BVH's (binary or wide) quality (SAH cost, EPO, leaf histograms: bvh_quality.h), measured with the
  // build on the worker, for the tree view's title and the structure line.
  std::optional<BvhQuality> quality;
};

// The debugger measures a BVH's EPO with its build up to this many primitives.
constexpr size_t kEpoTriangles = 250000;

// Each throws InputError on bad input; safe on any thread.
std::shared_ptr<const SceneData> loadSceneData(const std::string& path);
std::shared_ptr<const StructureData> buildStructureData(std::shared_ptr<const SceneData> scene,
                                                        const std::string& kind,
                                                        const StructureOptions& options);
// aaSpec "" or "scene": the scene file's anti-aliasing. rays (optional): the rays the render traced, by kind.
QImage renderPicture(const StructureData& s, const std::string& aaSpec, int width, int height, double* ms,
                     RayCounts* rays = nullptr);
// Traversal quantities count one centre ray per pixel; samples renders the picture with aaSpec and maps its
// samples per pixel.
HeatMap computeHeat(const StructureData& s, HeatQuantity q, const std::string& aaSpec, int width, int height,
                    double* ms);
// The anti-aliasing a picture's spec names: "" or "scene" is the scene file's own.
AntiAliasing antiAliasingOf(const Scene& scene, const std::string& aaSpec);
// Pixel (px, py) of a width x height picture sampled exactly as the renderer samples it (the scene's seed,
// the pixel's own random stream), with every sample's colour. positionsOnly: where the positions do not
// depend on what the samples see (every mode but adaptive), no ray is cast and the colours are black (the
// image view's sample overlay).
PixelSampling samplePixel(const StructureData& s, const AntiAliasing& aa, int width, int height, int px,
                          int py, bool positionsOnly = false);
// The rays of pixel (px, py) of a width x height picture, recorded through the structure. Without
// anti-aliasing the ray through the pixel's centre (and its secondaries), as `raystep trace --pixel` records
// it; with anti-aliasing every sample's ray tree (TracedRay::sample) and the pixel section (Trace::pixel: the
// samples, the adaptive squares, the value and the exact value where the scene has one).
Trace tracePixel(const StructureData& s, const AntiAliasing& aa, int width, int height, int px, int py,
                 bool secondary);
// What the scene shows inside pixel (px, py) and `reach` pixels beyond it on every side (the tent filter's
// 0.5: the square its weights cover): n x n rays through the centres of an n x n lattice, as an sRGB image
// (the pixel inspector's faint background, so that a student sees the edge the samples straddle).
QImage pixelBackdrop(const StructureData& s, int width, int height, int px, int py, int n = 64,
                     double reach = 0.0);
// The pixel section for a picture without anti-aliasing: one sample at the centre (the inspector shows it;
// the trace keeps version 1).
TracePixel centrePixel(const StructureData& s, int width, int height, int px, int py);

class Session : public QObject {
  Q_OBJECT
 public:
  explicit Session(QObject* parent = nullptr) : QObject(parent) {}

  void setScene(std::shared_ptr<const SceneData> scene);  // clears structure, picture, heat map and trace
  void setStructure(std::shared_ptr<const StructureData> structure);  // clears the trace (of the old one)
  void setPicture(const QImage& image);
  void setHeat(std::shared_ptr<const HeatMap> heat);  // null: no overlay
  // pixel: the traced pixel's samples (null: the trace's own pixel section, if any). step: the first ray's
  // event shown (clamped to its events; a dragged ray keeps its step).
  void setTrace(std::shared_ptr<const Trace> trace, const QString& source,
                std::shared_ptr<const TracePixel> pixel = nullptr, int step = 0);
  void setImageSize(int width, int height);

  const SceneData* scene() const { return scene_.get(); }
  std::shared_ptr<const SceneData> sceneShared() const { return scene_; }
  const StructureData* structure() const { return structure_.get(); }
  std::shared_ptr<const StructureData> structureShared() const { return structure_; }
  const QImage& picture() const { return picture_; }
  const HeatMap* heat() const { return heat_.get(); }
  const Trace* trace() const { return trace_.get(); }
  QString traceSource() const { return traceSource_; }
  int imageWidth() const { return imageWidth_; }
  int imageHeight() const { return imageHeight_; }

  // The ray being replayed and its current event.
  int rayIndex() const { return ray_; }
  const TracedRay* ray() const;
  int step() const { return step_; }
  int eventCount() const;
  const replay::ReplayState& state() const { return state_; }

  void setRay(int index);
  void setStep(int step);  // clamped to the events
  void stepBy(int delta) { setStep(step_ + delta); }
  // Jump to the next (or previous) event of a type; false (and no change) when there is none.
  bool jumpTo(EventType type, bool forward);

  // The traced pixel's samples (null: none), the sample the current ray descends from (-1: none), and the
  // first ray of a sample's ray tree (its primary ray; -1: not in the trace). Without anti-aliasing the one
  // sample is the centre ray's, ray 0.
  const TracePixel* pixel() const { return pixel_.get(); }
  int currentSample() const;
  int rayOfSample(int sample) const;
  bool selectSample(int sample);  // replays the sample's primary ray; false when it has none
  // Adaptive sampling: the square being stepped through (index into the pixel's squares, depth first; -1:
  // none).
  int square() const { return square_; }
  int squareCount() const { return pixel_ ? int(pixel_->sampling.squares.size()) : 0; }
  void setSquare(int index);  // clamped to the squares
  void stepSquare(int delta) { setSquare(square_ + delta); }

  // The kd-tree node that the tree view, the SAH inspector and the 3D view show (-1: none). A new structure
  // clears it (the main window selects the same path again in the new tree).
  int selectedNode() const { return selectedNode_; }
  void setSelectedNode(int node);  // -1, or a node of the current kd-tree or binary BVH (others are ignored)

 Q_SIGNALS:
  void sceneChanged();
  void structureChanged();
  void pictureChanged();
  void heatChanged();
  void traceChanged();  // a new trace, or another ray of it
  void stepChanged();
  void selectedNodeChanged();
  void squareChanged();

 private:
  void replayRay();  // a new ray: its replayer, at its first event

  std::shared_ptr<const SceneData> scene_;
  std::shared_ptr<const StructureData> structure_;
  QImage picture_;
  std::shared_ptr<const HeatMap> heat_;
  std::shared_ptr<const Trace> trace_;
  QString traceSource_;
  int imageWidth_ = 0, imageHeight_ = 0;
  int ray_ = 0, step_ = 0;
  std::unique_ptr<replay::Replayer> replayer_;  // the current ray's, from checkpoints
  replay::ReplayState state_;
  int selectedNode_ = -1;
  std::shared_ptr<const TracePixel> pixel_;
  int square_ = -1;
};

}  // namespace raystep::viz
