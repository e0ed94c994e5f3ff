#include "session.h"

#include <chrono>

#include "raystep/io/image_io.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/scene/scene_loader.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"

namespace raystep::viz {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace

std::shared_ptr<const SceneData> loadSceneData(const std::string& path) {
  auto data = std::make_shared<SceneData>();
  data->scene = load_scene(path);
  data->path = path;
  data->hash = file_content_hash(path);
  return data;
}

std::shared_ptr<const StructureData> buildStructureData(std::shared_ptr<const SceneData> scene,
                                                        const std::string& kind,
                                                        const StructureOptions& options) {
  auto data = std::make_shared<StructureData>();
  data->scene = std::move(scene);
  data->kind = kind;
  data->accel = make_accelerator(kind, options);
  auto t0 = std::chrono::steady_clock::now();
  data->accel->build(data->scene->scene.geometry);
  data->buildMs = msSince(t0);
  return data;
}

namespace {

RenderResult renderWith(const StructureData& s, const std::string& aaSpec, int width, int height) {
  const Scene& scene = s.scene->scene;
  RenderOptions opt = render_options(scene.render);
  // "scene" (the default, as in a lesson's `aa: scene`): the scene file's own anti-aliasing.
  if (!aaSpec.empty() && aaSpec != "scene") opt.aa = parse_antialiasing(aaSpec);
  opt.width = width;
  opt.height = height;
  return render_image(scene, *s.accel, opt);
}

}  // namespace

QImage renderPicture(const StructureData& s, const std::string& aaSpec, int width, int height, double* ms,
                     RayCounts* rays) {
  RenderResult r = renderWith(s, aaSpec, width, height);
  if (ms) *ms = r.seconds * 1e3;
  if (rays) *rays = r.rays;
  QImage img(width, height, QImage::Format_RGB888);
  for (int y = 0; y < height; ++y) {
    uchar* row = img.scanLine(y);
    for (int x = 0; x < width; ++x) {
      const glm::vec3& c = r.image.at(x, y);
      row[3 * x] = srgb_encode8(c.r);
      row[3 * x + 1] = srgb_encode8(c.g);
      row[3 * x + 2] = srgb_encode8(c.b);
    }
  }
  return img;
}

HeatMap computeHeat(const StructureData& s, HeatQuantity q, const std::string& aaSpec, int width, int height,
                    double* ms) {
  auto t0 = std::chrono::steady_clock::now();
  HeatMap h = q == HeatQuantity::samples
                  ? samples_heatmap(renderWith(s, aaSpec, width, height).samples, width, height)
                  : compute_heatmap(s.scene->scene.camera, *s.accel, width, height, q, 0);
  if (ms) *ms = msSince(t0);
  return h;
}

Trace tracePixel(const StructureData& s, int width, int height, int px, int py, bool secondary) {
  const SceneData& sd = *s.scene;
  std::vector<RayRequest> requests = pixel_rays(sd.scene, *s.accel, width, height, px, py, secondary);
  return record_trace(sd.scene.geometry, *s.accel, requests, sd.path, sd.hash);
}

void Session::setScene(std::shared_ptr<const SceneData> scene) {
  scene_ = std::move(scene);
  structure_.reset();
  selectedNode_ = -1;
  picture_ = QImage();
  heat_.reset();
  trace_.reset();
  ray_ = step_ = 0;
  state_ = ReplayState{};
  Q_EMIT sceneChanged();
  Q_EMIT structureChanged();
  Q_EMIT pictureChanged();
  Q_EMIT heatChanged();
  Q_EMIT traceChanged();
  Q_EMIT stepChanged();
}

void Session::setStructure(std::shared_ptr<const StructureData> structure) {
  // A trace's cells and nodes are those of the structure it was recorded in: it goes with the old one.
  bool hadTrace = trace_ != nullptr;
  structure_ = std::move(structure);
  trace_.reset();
  ray_ = step_ = 0;
  state_ = ReplayState{};
  selectedNode_ = -1;
  Q_EMIT structureChanged();
  if (hadTrace) {
    Q_EMIT traceChanged();
    Q_EMIT stepChanged();
  }
}

void Session::setPicture(const QImage& image) {
  picture_ = image;
  Q_EMIT pictureChanged();
}

void Session::setHeat(std::shared_ptr<const HeatMap> heat) {
  heat_ = std::move(heat);
  Q_EMIT heatChanged();
}

void Session::setImageSize(int width, int height) {
  imageWidth_ = width;
  imageHeight_ = height;
}

void Session::setTrace(std::shared_ptr<const Trace> trace, const QString& source) {
  trace_ = std::move(trace);
  traceSource_ = source;
  ray_ = 0;
  step_ = 0;
  state_ = ray() ? replayAt(*ray(), 0) : ReplayState{};
  Q_EMIT traceChanged();
  Q_EMIT stepChanged();
}

const TracedRay* Session::ray() const {
  if (!trace_ || ray_ < 0 || ray_ >= int(trace_->rays.size())) return nullptr;
  return &trace_->rays[size_t(ray_)];
}

int Session::eventCount() const {
  const TracedRay* r = ray();
  return r ? int(r->events.size()) : 0;
}

void Session::setRay(int index) {
  if (!trace_ || index < 0 || index >= int(trace_->rays.size()) || index == ray_) return;
  ray_ = index;
  step_ = 0;
  state_ = replayAt(*ray(), 0);
  Q_EMIT traceChanged();
  Q_EMIT stepChanged();
}

void Session::setStep(int step) {
  const TracedRay* r = ray();
  if (!r || r->events.empty()) return;
  step = std::clamp(step, 0, int(r->events.size()) - 1);
  if (step == step_ && state_.step == step) return;
  step_ = step;
  state_ = replayAt(*r, step);
  Q_EMIT stepChanged();
}

bool Session::jumpTo(EventType type, bool forward) {
  const TracedRay* r = ray();
  if (!r) return false;
  int i = findEvent(*r, step_, type, forward);
  if (i < 0) return false;
  setStep(i);
  return true;
}

void Session::setSelectedNode(int node) {
  const KdTree* kd = structure_ ? structure_->kdTree() : nullptr;
  if (node < -1 || (node >= 0 && (!kd || size_t(node) >= kd->data().nodes.size()))) return;
  if (node == selectedNode_) return;
  selectedNode_ = node;
  Q_EMIT selectedNodeChanged();
}

}  // namespace raystep::viz
