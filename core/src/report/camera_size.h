// The camera image the structure reports (report_grid_sweep.cpp, report_structure_compare.cpp) cast one ray
// per pixel through: the size asked for, or else the scene's, scaled down so that the report stays quick.
// Internal to raystep_core.
#pragma once

#include <algorithm>
#include <cmath>

#include "raystep/scene/scene.h"

namespace raystep {

// *w x *h as given when both are positive; otherwise the scene's size, scaled down (aspect kept) so that
// neither side exceeds cap.
inline void report_camera_size(const Scene& scene, int cap, int* w, int* h) {
  if (*w > 0 && *h > 0) return;
  *w = scene.render.width;
  *h = scene.render.height;
  const double scale = std::min(1.0, double(cap) / double(std::max(*w, *h)));
  *w = std::max(1, int(std::lround(*w * scale)));
  *h = std::max(1, int(std::lround(*h * scale)));
}

}  // namespace raystep
