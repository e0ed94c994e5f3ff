// The reconstruction filter: how samples become a pixel's value. Sampling and pre-filtering combined, the
// lecture's third way to anti-alias: the samples estimate the scene pre-filtered by a kernel, and the kernel
// need not be the pixel's square.
//   box:  every sample of the pixel counts the same, nothing outside it counts;
//   tent: w(dx, dy) = (1 - |dx|)(1 - |dy|) over the pixel's centre's [-1, 1]^2 (Bartlett's window in two
//         dimensions; pbrt's "triangle" filter of radius 1): a sample counts the more the nearer it lies to
//         the centre, and the samples of the eight neighbouring pixels count too.
// The tent integrates to 1, and the tents of all pixels add up to 1 at every point, so each sample is shared
// out among the four pixels whose centres surround it, with weights that sum to 1. Its spectrum falls off as
// 1/f^2 where the box's falls as 1/f: less of the detail finer than the pixels folds back into them as alias,
// for a slightly softer picture. A pixel's value is the weighted mean sum(w_i L_i) / sum(w_i).
#pragma once

#include <cmath>

#include <glm/vec3.hpp>

#include "raystep/scene/scene.h"

namespace raystep {

// (dx, dy): a sample's offset from the pixel's centre, in pixels.
inline float tent_weight(float dx, float dy) {
  const float wx = 1.f - std::fabs(dx), wy = 1.f - std::fabs(dy);
  return wx > 0.f && wy > 0.f ? wx * wy : 0.f;
}

// How many pixels beyond its own, on each side, the filter reaches: box 0, tent 1.
inline int filter_reach(AntiAliasing::Filter filter) {
  return filter == AntiAliasing::Filter::tent ? 1 : 0;
}

// The weighted sum of the samples a pixel's filter reaches. The tent's is summed one row of source pixels at a
// time (the row above, the pixel's own, the row below: each in the order of its pixels and their samples),
// then the three rows in that order: render_image and apply_pixel_filter (render/pixel_samples.h) add in
// this order, so that the inspector's value is the picture's to the last bit.
struct FilterSum {
  glm::vec3 sum{0.f};
  float weight = 0.f;
  void add(float w, const glm::vec3& colour) {
    sum += w * colour;
    weight += w;
  }
  void add(const FilterSum& other) {
    sum += other.sum;
    weight += other.weight;
  }
  glm::vec3 value() const { return weight > 0.f ? sum / weight : glm::vec3(0.f); }
};

}  // namespace raystep
