// Reproducible ray sets for tests and benchmarks, each determined by its seed: random rays through a scene's
// bounds, and the watertightness stress set of rays aimed exactly at the shared edges and vertices of a
// mesh (the case Woop et al. 2013 designed the watertight test for). Camera rays belong here too.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"

namespace raystep {

// The box ray origins are drawn from: b enlarged 1.5x about its centre.
Bounds3 ray_origin_bounds(const Bounds3& b);

// Origins uniform in ray_origin_bounds(b), directions uniform on the unit sphere, tmin 0, tmax +inf.
// Throws InputError if b is empty.
std::vector<Ray> random_rays(const Bounds3& b, size_t count, uint64_t seed);

// Points exactly on the mesh's shared features, alternating a triangle vertex (even indices) and a point
// p0 + f (p1 - p0) on a triangle edge with f = k/16, k = 1..15 (odd indices); triangles chosen uniformly.
// Throws InputError if g has no triangles.
std::vector<glm::vec3> edge_targets(const Geometry& g, size_t count, uint64_t seed);

// The watertightness stress set: origins uniform in ray_origin_bounds(g.bounds()), each ray aimed at
// edge_targets(g, count, seed)[i] with direction = target - origin (so the target is at t = 1), tmin 0,
// tmax +inf. A watertight test must let no such ray through a closed mesh unless it only grazes the mesh.
std::vector<Ray> edge_rays(const Geometry& g, size_t count, uint64_t seed);

}  // namespace raystep
