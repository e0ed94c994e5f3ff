// A ray: origin o, direction d, and the open parametric interval (tmin, tmax) in which a hit counts.
// The direction need not be normalised; t is measured in units of |d|.
#pragma once

#include <glm/vec3.hpp>

#include "raystep/geometry/numerics.h"

namespace raystep {

enum class RayKind : uint8_t { primary, shadow, reflected, refracted };

struct Ray {
  glm::vec3 origin{0.f};
  glm::vec3 direction{0.f, 0.f, 1.f};
  float tmin = 0.f;
  float tmax = kInfinity;

  glm::vec3 at(float t) const { return origin + t * direction; }
};

// Hit condition shared by every primitive and accelerator: tmin < t < tmax.
inline bool in_range(const Ray& ray, float t) { return t > ray.tmin && t < ray.tmax; }

}  // namespace raystep
