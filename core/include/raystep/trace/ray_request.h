// A ray to record into a trace, with what the tracer knows of it: its kind, its depth in the ray tree, and the
// pixel it belongs to. Made by hand (`raystep trace --ray`) or by pixel_rays() for a pixel and its secondaries.
#pragma once

#include "raystep/geometry/ray.h"

namespace raystep {

struct RayRequest {
  Ray ray;
  RayKind kind = RayKind::primary;
  int depth = 0;
  bool has_pixel = false;
  int pixel[2] = {0, 0};
  int sample = -1;  // the anti-aliasing sample it descends from (pixel_sample_rays), -1 for none
};

}  // namespace raystep
