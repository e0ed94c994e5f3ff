// The debugger's document: the scene (or a trace opened on its own), the structure built over it (a grid or a
// kd-tree), the picture,
// the heat map, and the traced pixel with the current ray and step. Views read it and listen to its signals;
// only the main window changes it. The heavy work (build, render, heat map) is done by the free functions
// below, which take everything they need by shared pointer so that they can run on a worker thread.
#pragma once

#include <memory>
#include <string>

#include <QImage>
#include <QObject>

#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/structure_options.h"
#include "raystep/render/render.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/heatmap.h"
#include "raystep/trace/trace_file.h"
#include "replay.h"

namespace raystep::viz {

struct SceneData {
  Scene scene;
  std::string path, hash;
};

// Any accelerator that records events: "grid", "kd" (SAH) or "kd-median".
struct StructureData {
  std::shared_ptr<const SceneData> scene;  // the structure points into its geometry: keep it alive
  std::string kind;
  std::unique_ptr<Accelerator> accel;
  double buildMs = 0.0;
  const UniformGrid* grid() const { return dynamic_cast<const UniformGrid*>(accel.get()); }
  const KdTree* kdTree() const { return dynamic_cast<const KdTree*>(accel.get()); }
};

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
// The rays of pixel (px, py) of a width x height picture, recorded through the structure.
Trace tracePixel(const StructureData& s, int width, int height, int px, int py, bool secondary);

class Session : public QObject {
  Q_OBJECT
 public:
  explicit Session(QObject* parent = nullptr) : QObject(parent) {}

  void setScene(std::shared_ptr<const SceneData> scene);  // clears structure, picture, heat map and trace
  void setStructure(std::shared_ptr<const StructureData> structure);  // clears the trace (of the old one)
  void setPicture(const QImage& image);
  void setHeat(std::shared_ptr<const HeatMap> heat);  // null: no overlay
  void setTrace(std::shared_ptr<const Trace> trace, const QString& source);
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
  const ReplayState& state() const { return state_; }

  void setRay(int index);
  void setStep(int step);  // clamped to the events
  void stepBy(int delta) { setStep(step_ + delta); }
  // Jump to the next (or previous) event of a type; false (and no change) when there is none.
  bool jumpTo(EventType type, bool forward);

  // The kd-tree node that the tree view, the SAH inspector and the 3D view show (-1: none). A new structure
  // clears it (the main window selects the same path again in the new tree).
  int selectedNode() const { return selectedNode_; }
  void setSelectedNode(int node);  // -1, or a node of the current kd-tree (others are ignored)

 Q_SIGNALS:
  void sceneChanged();
  void structureChanged();
  void pictureChanged();
  void heatChanged();
  void traceChanged();  // a new trace, or another ray of it
  void stepChanged();
  void selectedNodeChanged();

 private:
  std::shared_ptr<const SceneData> scene_;
  std::shared_ptr<const StructureData> structure_;
  QImage picture_;
  std::shared_ptr<const HeatMap> heat_;
  std::shared_ptr<const Trace> trace_;
  QString traceSource_;
  int imageWidth_ = 0, imageHeight_ = 0;
  int ray_ = 0, step_ = 0;
  ReplayState state_;
  int selectedNode_ = -1;
};

}  // namespace raystep::viz
