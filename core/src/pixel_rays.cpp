#include "raystep/trace/pixel_rays.h"

#include "raystep/render/camera.h"
#include "raystep/render/whitted.h"

namespace raystep {

std::vector<RayRequest> pixel_rays(const Scene& scene, const Accelerator& accel, int width, int height, int px,
                                   int py, bool secondary) {
  Ray primary = ProjectiveCamera(scene.camera, width, height).generate(float(px) + 0.5f, float(py) + 0.5f);
  std::vector<RayRequest> out;
  auto request = [&](const Ray& ray, RayKind kind, int depth) {
    RayRequest r;
    r.ray = ray;
    r.kind = kind;
    r.depth = depth;
    r.has_pixel = true;
    r.pixel[0] = px;
    r.pixel[1] = py;
    out.push_back(r);
  };
  if (!secondary) {
    request(primary, RayKind::primary, 0);
    return out;
  }
  RayListener listener = request;
  WhittedTracer tracer(scene, accel);
  tracer.set_listener(&listener);
  RayCounts counts;
  tracer.trace_primary(primary, &counts);
  return out;
}

}  // namespace raystep
