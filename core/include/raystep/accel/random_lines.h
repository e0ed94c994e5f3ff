// Random lines with the invariant measure of integral geometry, the one Crofton's theorem is about: an
// isotropic direction, and an offset uniform on the disc perpendicular to it that covers a sphere. A convex
// body inside the sphere is met by the fraction A / (pi R^2) of them, where A is its shadow's area averaged
// over directions; by Cauchy's formula A = S / 4 for every convex body (a sphere: pi r^2 = 4 pi r^2 / 4). So
// a random line that meets a convex parent meets a convex child with probability S_child / S_parent: the
// SAH's p.
#pragma once

#include <cstddef>
#include <cstdint>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/ray.h"
#include "raystep/util/random.h"

namespace raystep {

// One random line through the sphere (centre, radius), as a ray that starts outside it (2 radii back along
// its direction from the offset point) and runs through it.
Ray random_line(Pcg32& rng, const glm::vec3& centre, float radius);

// The box against its bounding sphere: of `lines` random lines through the sphere (reproducible by seed),
// the fraction that meet the box, and Cauchy-Crofton's prediction (S_box / 4) / (pi R^2).
struct LinesMeetingBox {
  double measured = 0.0;
  double predicted = 0.0;
};
LinesMeetingBox lines_meeting_box(const Bounds3& box, size_t lines, uint64_t seed);

}  // namespace raystep
