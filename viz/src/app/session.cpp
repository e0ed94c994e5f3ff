#include "app/session.h"

#include <algorithm>

#include <chrono>

#include "views/kd_tree_model.h"
#include "views/scene_mesh.h"
#include "raystep/io/image_io.h"
#include "raystep/render/camera.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/render/reference.h"
#include "raystep/render/whitted.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/memory_limit.h"
#include "raystep/replay/replay_state.h"

namespace raystep::viz {
namespace {

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// EPO clips every triangle against the boxes it reaches into: seconds on a mesh of millions of triangles
// (`raystep bvh-stats` on the 2.2-million-triangle test mesh: 11 s in all, the bunny 0.5 s), which would hold
// the structure back from the window; bvh-stats measures it on any mesh.
bool withEpo(const Geometry& g) {
  return g.size() <= kEpoTriangles;
}

}  // namespace

std::shared_ptr<const SceneData> loadSceneData(const std::string& path) {
  auto data = std::make_shared<SceneData>();
  data->scene = load_scene(path);
  data->path = path;
  data->hash = file_content_hash(path);
  data->mesh = SceneMesh::fromScene(data->scene);
  return data;
}

std::shared_ptr<const StructureData> buildStructureData(std::shared_ptr<const SceneData> scene,
                                                        const std::string& kind,
                                                        const StructureOptions& options) {
  auto data = std::make_shared<StructureData>();
  data->scene = std::move(scene);
  data->kind = kind;
  data->accel = make_accelerator(kind, options);
  check_build_memory(data->scene->path, kind, data->scene->scene.geometry.size());
  auto t0 = std::chrono::steady_clock::now();
  data->accel->build(data->scene->scene.geometry);
  data->buildMs = msSince(t0);
  if (const WideBvh* wide = data->wideBvh()) {
    auto view = std::make_shared<WideBvhView>(wide->describe());
    // Ids are in preorder (children after their parent): summed from the last node up.
    data->wideViewPrims.assign(view->nodes.size(), 0);
    for (size_t i = view->nodes.size(); i-- > 0;) {
      const WideBvhView::Node& n = view->nodes[i];
      if (n.leaf) data->wideViewPrims[i] += uint32_t(n.prims.size());
      if (n.parent >= 0) data->wideViewPrims[size_t(n.parent)] += data->wideViewPrims[i];
    }
    data->wideView = std::move(view);
    data->quality = tree_quality(*data->wideView, data->scene->scene.geometry, wide->options().t_i,
                                 wide->options().t_t, withEpo(data->scene->scene.geometry));
  }
  if (const Bvh* bvh = data->bvh())
    data->quality = tree_quality(bvh_view(bvh->data()), data->scene->scene.geometry, bvh->options().t_i,
                                 bvh->options().t_t, withEpo(data->scene->scene.geometry));
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
  HeatMap h = scene_heatmap(s.scene->scene, *s.accel, antiAliasingOf(s.scene->scene, aaSpec), width, height, q, 0);
  if (ms) *ms = msSince(t0);
  return h;
}

AntiAliasing antiAliasingOf(const Scene& scene, const std::string& aaSpec) {
  return aaSpec.empty() || aaSpec == "scene" ? scene.render.aa : parse_antialiasing(aaSpec);
}

PixelSampling samplePixel(const StructureData& s, const AntiAliasing& aa, int width, int height, int px,
                          int py, bool positionsOnly) {
  const Scene& scene = s.scene->scene;
  Pcg32 rng = pixel_rng(scene.render.seed, px, py, width);
  if (positionsOnly && aa.mode != AntiAliasing::Mode::adaptive) {
    // Where the pixel's own samples fall (the overlay draws every pixel's: no neighbours needed).
    return sample_pixel(aa, px, py, rng, [](float, float) { return glm::vec3(0.f); });
  }
  const ProjectiveCamera camera(scene.camera, width, height);
  const WhittedTracer tracer(scene, *s.accel);
  RayCounts counts;
  const RadianceFn radiance = [&](float x, float y) {
    return tracer.trace_primary(camera.generate(x, y), &counts);
  };
  PixelSampling p = sample_pixel(aa, px, py, rng, radiance);
  apply_pixel_filter(p, scene.render.seed, width, radiance);
  return p;
}

QImage pixelBackdrop(const StructureData& s, int width, int height, int px, int py, int n, double reach) {
  const Scene& scene = s.scene->scene;
  const ProjectiveCamera camera(scene.camera, width, height);
  const WhittedTracer tracer(scene, *s.accel);
  RayCounts counts;
  QImage img(n, n, QImage::Format_RGB888);
  for (int j = 0; j < n; ++j) {
    uchar* row = img.scanLine(j);
    for (int i = 0; i < n; ++i) {
      const float span = float(1.0 + 2.0 * reach), x0 = float(px - reach), y0 = float(py - reach);
      const glm::vec3 c = tracer.trace_primary(
          camera.generate(x0 + span * (float(i) + 0.5f) / float(n), y0 + span * (float(j) + 0.5f) / float(n)),
          &counts);
      row[3 * i] = srgb_encode8(c.r);
      row[3 * i + 1] = srgb_encode8(c.g);
      row[3 * i + 2] = srgb_encode8(c.b);
    }
  }
  return img;
}

TracePixel centrePixel(const StructureData& s, int width, int height, int px, int py) {
  TracePixel p;
  p.sampling = samplePixel(s, AntiAliasing{}, width, height, px, py);
  p.width = width;
  p.height = height;
  p.seed = s.scene->scene.render.seed;
  p.exact = exact_pixel_value(s.scene->scene, width, height, px, py);
  return p;
}

Trace tracePixel(const StructureData& s, const AntiAliasing& aa, int width, int height, int px, int py,
                 bool secondary) {
  const SceneData& sd = *s.scene;
  if (aa.mode == AntiAliasing::Mode::none) {  // the centre ray, as the command line traces a pixel
    std::vector<RayRequest> requests = pixel_rays(sd.scene, *s.accel, width, height, px, py, secondary);
    return record_trace(sd.scene.geometry, *s.accel, requests, sd.path, sd.hash);
  }
  // The same trace as `raystep trace --pixel X,Y --aa SPEC` records, with the exact value where there is one.
  Trace trace = record_pixel_trace(sd.scene, *s.accel, width, height, px, py, aa, sd.scene.render.seed,
                                   secondary, sd.path, sd.hash);
  if (trace.pixel) trace.pixel->exact = exact_pixel_value(sd.scene, width, height, px, py, aa.filter);
  return trace;
}

void Session::setScene(std::shared_ptr<const SceneData> scene) {
  scene_ = std::move(scene);
  structure_.reset();
  pixel_.reset();
  square_ = -1;
  selectedNode_ = -1;
  picture_ = QImage();
  heat_.reset();
  trace_.reset();
  ray_ = step_ = 0;
  replayRay();
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
  replayRay();
  selectedNode_ = -1;
  pixel_.reset();
  square_ = -1;
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

void Session::setTrace(std::shared_ptr<const Trace> trace, const QString& source,
                       std::shared_ptr<const TracePixel> pixel, int step) {
  trace_ = std::move(trace);
  traceSource_ = source;
  // The trace's own pixel section shares the trace's lifetime.
  if (!pixel && trace_ && trace_->pixel) pixel = std::shared_ptr<const TracePixel>(trace_, &*trace_->pixel);
  pixel_ = std::move(pixel);
  square_ = squareCount() > 0 ? 0 : -1;
  ray_ = 0;
  step_ = 0;
  replayRay();
  if (step > 0 && replayer_) {
    step_ = std::clamp(step, 0, eventCount() - 1);
    state_ = replayer_->at(step_);
  }
  Q_EMIT traceChanged();
  Q_EMIT stepChanged();
}

void Session::replayRay() {
  const TracedRay* r = ray();
  replayer_ = r ? std::make_unique<replay::Replayer>(*r) : nullptr;
  state_ = replayer_ ? replayer_->at(0) : replay::ReplayState{};
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
  replayRay();
  Q_EMIT traceChanged();
  Q_EMIT stepChanged();
}

void Session::setStep(int step) {
  const TracedRay* r = ray();
  if (!r || r->events.empty()) return;
  step = std::clamp(step, 0, int(r->events.size()) - 1);
  if (step == step_ && state_.step == step) return;
  step_ = step;
  state_ = replayer_->at(step);
  Q_EMIT stepChanged();
}

bool Session::jumpTo(EventType type, bool forward) {
  const TracedRay* r = ray();
  if (!r) return false;
  int i = replay::find_event(*r, step_, type, forward);
  if (i < 0) return false;
  setStep(i);
  return true;
}

int Session::currentSample() const {
  const TracedRay* r = ray();
  if (!r || !pixel_) return -1;
  if (r->sample >= 0) return r->sample;
  // Without anti-aliasing the trace is the centre ray's: the one sample.
  return pixel_->sampling.samples.size() == 1 ? 0 : -1;
}

int Session::rayOfSample(int sample) const {
  if (!trace_ || !pixel_ || sample < 0 || sample >= int(pixel_->sampling.samples.size())) return -1;
  for (size_t i = 0; i < trace_->rays.size(); ++i)
    if (trace_->rays[i].sample == sample) return int(i);
  if (pixel_->sampling.samples.size() == 1 && !trace_->rays.empty()) return 0;
  return -1;
}

bool Session::selectSample(int sample) {
  const int r = rayOfSample(sample);
  if (r < 0) return false;
  if (r == ray_) {  // the same ray: back to its first event, as choosing it anew would
    setStep(0);
    return true;
  }
  setRay(r);
  return true;
}

void Session::setSquare(int index) {
  const int n = squareCount();
  if (n == 0) return;
  index = std::clamp(index, 0, n - 1);
  if (index == square_) return;
  square_ = index;
  Q_EMIT squareChanged();
}

void Session::setSelectedNode(int node) {
  // Any tree (kd-tree, binary or wide BVH, octree, BSP tree): ids as its tree view and traces name them.
  const std::unique_ptr<TreeShape> tree = structure_ ? treeShapeOf(*structure_) : nullptr;
  const size_t nodes = tree ? tree->size() : 0;
  if (node < -1 || (node >= 0 && size_t(node) >= nodes)) return;
  if (node == selectedNode_) return;
  selectedNode_ = node;
  Q_EMIT selectedNodeChanged();
}

}  // namespace raystep::viz
