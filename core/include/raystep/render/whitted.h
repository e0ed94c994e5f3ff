// Whitted-style recursive ray tracing (Whitted, "An Improved Illumination Model for Shaded Display", 1980):
// at each hit, local Phong shading from the lights that a shadow ray reaches, plus a mirror ray weighted by
// `mirror` and a refracted ray (Snell's law, total internal reflection) weighted by `transparency`, recursively
// up to render.max_depth; a path whose weight falls below render.min_weight spawns no more rays (adaptive
// ray termination, Hall and Greenberg 1983). Only the rays a material calls for are spawned.
// Shadow rays treat every surface as opaque, transparent ones included (no caustics, no coloured shadows).
#pragma once

#include <cmath>
#include <cstdint>
#include <functional>

#include <glm/common.hpp>
#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/accel/accelerator.h"
#include "raystep/geometry/ray.h"
#include "raystep/scene/scene.h"

namespace raystep {

// Rays traced, by kind: the lecture estimates m^2 k^2 n 2^d rays for m^2 pixels, k^2 samples per pixel,
// n lights and depth d; these are the real numbers.
struct RayCounts {
  uint64_t primary = 0, shadow = 0, reflected = 0, refracted = 0;

  RayCounts& operator+=(const RayCounts& o) {
    primary += o.primary;
    shadow += o.shadow;
    reflected += o.reflected;
    refracted += o.refracted;
    return *this;
  }
  uint64_t total() const { return primary + shadow + reflected + refracted; }
};

// Mirror direction of d about the unit normal n.
inline glm::vec3 reflect(const glm::vec3& d, const glm::vec3& n) { return d - 2.f * glm::dot(d, n) * n; }

// Snell's law for the unit direction d arriving at a surface with unit normal n on the incoming side
// (dot(d, n) < 0), with eta = eta_incident / eta_transmitted: *t is the unit refracted direction.
// False on total internal reflection (sin^2 theta_t >= 1).
inline bool refract(const glm::vec3& d, const glm::vec3& n, float eta, glm::vec3* t) {
  float cos_i = -glm::dot(d, n);
  float sin2_i = glm::max(0.f, 1.f - cos_i * cos_i);
  float sin2_t = eta * eta * sin2_i;
  if (sin2_t >= 1.f) return false;
  float cos_t = std::sqrt(1.f - sin2_t);
  *t = eta * d + (eta * cos_i - cos_t) * n;
  return true;
}

// Told of every ray the tracer casts, with its kind and depth (primary 0, rays spawned at a depth-d hit d+1):
// `raystep trace --secondary` records a pixel's whole ray tree this way.
using RayListener = std::function<void(const Ray& ray, RayKind kind, int depth)>;

class WhittedTracer {
 public:
  // Both must outlive the tracer; the accelerator must be built over scene.geometry.
  WhittedTracer(const Scene& scene, const Accelerator& accel) : scene_(scene), accel_(accel) {}
  // Optional; must outlive the tracer. Null (the default) for rendering.
  void set_listener(const RayListener* listener) { listener_ = listener; }

  // Radiance arriving along a camera ray; counts the ray as primary and every ray it spawns by kind.
  glm::vec3 trace_primary(const Ray& ray, RayCounts* counts) const;

  // Radiance along a ray at recursion depth `depth` (primary rays: 0) whose path has weight `weight`
  // (primary rays: 1). The ray itself is not counted.
  glm::vec3 trace(const Ray& ray, int depth, float weight, RayCounts* counts) const;

 private:
  void notify(const Ray& ray, RayKind kind, int depth) const {
    if (listener_) (*listener_)(ray, kind, depth);
  }

  const Scene& scene_;
  const Accelerator& accel_;
  const RayListener* listener_ = nullptr;
};

}  // namespace raystep
