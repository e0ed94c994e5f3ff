#include "raystep/trace/pixel_rays.h"

#include "raystep/render/camera.h"
#include "raystep/render/whitted.h"

namespace raystep {
namespace {

// A ray the tracer cast for pixel (px, py), as the trace file asks for it.
RayRequest pixel_request(const Ray& ray, RayKind kind, int depth, int px, int py) {
  RayRequest r;
  r.ray = ray;
  r.kind = kind;
  r.depth = depth;
  r.has_pixel = true;
  r.pixel[0] = px;
  r.pixel[1] = py;
  return r;
}

}  // namespace

std::vector<RayRequest> pixel_rays(const Scene& scene, const Accelerator& accel, int width, int height,
                                   int px, int py, bool secondary) {
  Ray primary = ProjectiveCamera(scene.camera, width, height).generate(float(px) + 0.5f, float(py) + 0.5f);
  std::vector<RayRequest> out;
  auto request = [&](const Ray& ray, RayKind kind, int depth) {
    out.push_back(pixel_request(ray, kind, depth, px, py));
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

PixelSampleRays pixel_sample_rays(const Scene& scene, const Accelerator& accel, int width, int height, int px,
                                  int py, const AntiAliasing& aa, uint64_t seed, bool secondary) {
  // The renderer's radiance (render_image): the camera's ray through (x, y), traced by the Whitted tracer;
  // the listener hears every ray in the order it is cast, each primary ray opening the next sample.
  const ProjectiveCamera camera(scene.camera, width, height);
  WhittedTracer tracer(scene, accel);
  PixelSampleRays out;
  int sample = -1;
  RayListener listener = [&](const Ray& ray, RayKind kind, int depth) {
    if (kind == RayKind::primary)
      ++sample;
    else if (!secondary)
      return;
    RayRequest r = pixel_request(ray, kind, depth, px, py);
    r.sample = sample;
    out.rays.push_back(r);
  };
  tracer.set_listener(&listener);
  RayCounts counts;
  const RadianceFn radiance = [&](float x, float y) {
    return tracer.trace_primary(camera.generate(x, y), &counts);
  };
  Pcg32 rng = pixel_rng(seed, px, py, width);
  out.sampling = sample_pixel(aa, px, py, rng, radiance);
  // The neighbours' samples the tent reaches are weighed in, but their rays are not the pixel's: unheard.
  tracer.set_listener(nullptr);
  apply_pixel_filter(out.sampling, seed, width, radiance);
  return out;
}

}  // namespace raystep
