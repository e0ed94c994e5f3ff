// The ray batteries the structure tests share (lecture: "every accelerator agrees with brute force, on the
// rays that break naive code"): pinhole rays through a scene's box, the leak test on a closed mesh's
// edge-aimed rays, and the non-finite rays every structure must miss without a crash or a hang.
#pragma once

#include <cmath>
#include <cstddef>
#include <vector>

#include <glm/common.hpp>

#include "raystep/accel/accelerator.h"
#include "raystep/geometry/bounds.h"
#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"

namespace raystep::test {

// Pinhole rays from outside the scene's box through an n x n grid over it.
inline std::vector<Ray> camera_rays(const Bounds3& b, int n) {
  std::vector<Ray> rays;
  glm::vec3 eye = b.center() + glm::vec3(0.3f, 0.4f, 2.5f) * glm::max(b.extent(), glm::vec3(1e-3f));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      glm::vec3 target = b.lo + b.extent() * glm::vec3((i + 0.5f) / n, (j + 0.5f) / n, 0.5f);
      Ray r;
      r.origin = eye;
      r.direction = target - eye;
      rays.push_back(r);
    }
  return rays;
}

// Leaks of a closed mesh around the origin: of the first `count` edge-aimed rays (scene/ray_sets.h's
// edge_rays), those whose edge target, seen from the centre, the structure misses. Watertight: none.
inline int count_leaks(const Accelerator& acc, const std::vector<Ray>& edge_aimed, size_t count) {
  int leaks = 0;
  for (size_t i = 0; i < count; ++i) {
    Ray r;
    r.origin = glm::vec3(0.f);
    r.direction = edge_aimed[i].origin + edge_aimed[i].direction;  // the edge target
    Hit h;
    leaks += !acc.intersect(r, &h);
  }
  return leaks;
}

// A NaN or infinite origin (or the origin) with a NaN or infinite direction, or a zero one (+0 and -0).
inline std::vector<Ray> non_finite_rays() {
  const float nan = std::nanf(""), inf = kInfinity;
  std::vector<Ray> rays;
  for (glm::vec3 o : {glm::vec3(nan, 0, 0), glm::vec3(inf, 0, 0), glm::vec3(0.f)})
    for (glm::vec3 d : {glm::vec3(1, nan, 0), glm::vec3(inf, 1, 0), glm::vec3(0.f), glm::vec3(-0.f)}) {
      Ray r;
      r.origin = o;
      r.direction = d;
      rays.push_back(r);
    }
  return rays;
}

// The rays of non_finite_rays() on which the structure finds a hit, reports a primitive or an occlusion.
inline int count_non_finite_hits(const Accelerator& acc) {
  int bad = 0;
  for (const Ray& r : non_finite_rays()) {
    Hit h;
    bool found = acc.intersect(r, &h);
    bad += found || h.prim != -1 || acc.occluded(r);
  }
  return bad;
}

}  // namespace raystep::test
