// The rays of one pixel, for recording: its primary ray through the pixel's centre, and optionally every
// shadow, reflected and refracted ray the Whitted tracer spawns from it, in the order the tracer casts them.
#pragma once

#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/ray_request.h"

namespace raystep {

// (px, py): the pixel, 0,0 at the top left of a width x height image.
std::vector<RayRequest> pixel_rays(const Scene& scene, const Accelerator& accel, int width, int height, int px,
                                   int py, bool secondary);

// An anti-aliased pixel: its sampling recorded (render/pixel_samples.h, the same samples and value as the
// renderer's with this seed and image width), and every sample's primary ray, with secondary its shadow,
// reflected and refracted rays too, in the order cast, each with RayRequest::sample set. With the tent filter
// the neighbours' samples are in the sampling, their rays not.
struct PixelSampleRays {
  PixelSampling sampling;
  std::vector<RayRequest> rays;
};
PixelSampleRays pixel_sample_rays(const Scene& scene, const Accelerator& accel, int width, int height, int px,
                                  int py, const AntiAliasing& aa, uint64_t seed, bool secondary);

}  // namespace raystep
