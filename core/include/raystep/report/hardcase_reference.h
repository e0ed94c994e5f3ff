// The hard-case battery's judge: brute force in double precision, independent of the float kernel. Each
// edge decision uses a double determinant trusted beyond its rounding error bound and is settled exactly
// (geometry/exact.h) within it, so "cannot prove" is never turned into a miss; t is computed in double.
// Coincident and edge-sharing triangles give several primitives at one distance: all are kept as ties.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"

namespace raystep {

struct ReferenceHit {
  bool hit = false;
  double t = 0.0;             // the nearest distance
  std::vector<int32_t> tied;  // every primitive hit at the nearest distance within rounding, in id order
};

// Double-precision hit of one triangle with ray.tmin < t (tmax is not applied: the battery's rays have
// tmax = +inf; a finite tmax is compared in double). False for a ray with a NaN or infinite origin or
// direction, a zero direction, NaN bounds, or a triangle with no area seen from the ray (edge-on,
// degenerate).
bool reference_triangle_hit(const Ray& ray, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2,
                            double* t);

// The nearest hit over every triangle of g (spheres are not part of the battery: InputError if any).
// Ties: primitive j is tied with the nearest (t*) when |t_j - t*| is within 2^-16 (|t| + M / |d|), M the
// largest coordinate magnitude of the ray's origin and the triangle (a float kernel's t is that rounded), so
// the tolerance scales with the scene.
ReferenceHit reference_nearest(const Geometry& g, const Ray& ray);

// Does a structure's answer agree? Both miss, or both hit and the structure's primitive is one of the ties.
bool agrees_with_reference(const ReferenceHit& reference, const Hit& hit);

// The parity of the crossings of the ray with the triangles (every hit counted, not only the nearest):
// -1 when a crossing lies on an edge or vertex (exactly), where parity would be ambiguous.
int crossing_parity(const std::vector<glm::vec3>& positions, const std::vector<glm::uvec3>& triangles,
                    const Ray& ray);

}  // namespace raystep
