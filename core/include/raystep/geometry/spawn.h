// Spawning secondary rays without self-intersection at any scale (pbrt-v4, section 6.8.6): move the origin
// along the surface normal by the hit point's own error bound, to the side the new ray leaves by, then
// round away from the surface. No fixed epsilon: the offset scales with the coordinates.
#pragma once

#include <glm/geometric.hpp>
#include <glm/vec3.hpp>

#include "raystep/geometry/numerics.h"
#include "raystep/geometry/ray.h"

namespace raystep {

// p: hit point; p_error: its absolute error bound per axis; n: surface normal (any length);
// w: direction of the new ray.
inline glm::vec3 offset_ray_origin(const glm::vec3& p, const glm::vec3& p_error, const glm::vec3& n,
                                   const glm::vec3& w) {
  glm::vec3 nn = glm::normalize(n);
  float d = glm::dot(glm::abs(nn), p_error);
  glm::vec3 offset = d * nn;
  if (glm::dot(w, nn) < 0) offset = -offset;
  glm::vec3 po = p + offset;
  for (int i = 0; i < 3; ++i) {
    if (offset[i] > 0) po[i] = next_float_up(po[i]);
    else if (offset[i] < 0) po[i] = next_float_down(po[i]);
  }
  return po;
}

// The part of a spawned ray that cannot be told from its surface point: within twice the point's error bound
// (|p_error|_1, the offset included) of the origin. Another surface met there passes through the hit point's
// own rounding region, as the neighbouring wall does at a corner, where the rounded hit point may lie a rounding
// error beyond it; the exact triangle test would report that crossing (at t near 1e-8), so the spawned ray
// starts after it. Scale-free: the bound grows with the coordinates.
inline float spawn_tmin(const glm::vec3& p_error, const glm::vec3& d) {
  float reach = 2.f * (p_error.x + p_error.y + p_error.z);
  float len = glm::length(d);
  return len > 0.f ? reach / len : 0.f;
}

// A ray leaving the surface at p in direction w.
inline Ray spawn_ray(const glm::vec3& p, const glm::vec3& p_error, const glm::vec3& n, const glm::vec3& w) {
  Ray r;
  r.origin = offset_ray_origin(p, p_error, n, w);
  r.direction = w;
  r.tmin = spawn_tmin(p_error, w);
  r.tmax = kInfinity;
  return r;
}

// A shadow ray from the surface towards point `to` (a point light): t in (0, 1 - shadow epsilon) along
// d = to - origin. The fraction keeps the ray from reaching the light's own position.
// A light that lies within the offset of the surface's tangent plane is on one side of p and on the other of
// the moved origin: d would cross back over the surface, and the ray met its own surface (a light 1.6 degrees
// below a sphere's tangent plane at 1e5, where the offset is 0.04). The ray then keeps the side it was moved
// to, parallel to to - p: it ends at the light moved by the offset, as near it as the origin is to p.
inline Ray spawn_ray_to(const glm::vec3& p, const glm::vec3& p_error, const glm::vec3& n, const glm::vec3& to) {
  Ray r;
  const glm::vec3 w = to - p, nn = glm::normalize(n);
  r.origin = offset_ray_origin(p, p_error, n, w);
  r.direction = to - r.origin;
  if ((glm::dot(r.direction, nn) < 0) != (glm::dot(w, nn) < 0)) r.direction = w;
  r.tmin = spawn_tmin(p_error, r.direction);
  r.tmax = 1.f - 1e-4f;
  return r;
}

}  // namespace raystep
