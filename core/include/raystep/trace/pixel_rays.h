// The rays of one pixel, for recording: its primary ray through the pixel's centre, and optionally every
// shadow, reflected and refracted ray the Whitted tracer spawns from it, in the order the tracer casts them.
#pragma once

#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/ray_request.h"

namespace raystep {

// (px, py): the pixel, 0,0 at the top left of a width x height image.
std::vector<RayRequest> pixel_rays(const Scene& scene, const Accelerator& accel, int width, int height, int px,
                                   int py, bool secondary);

}  // namespace raystep
