// Random lines with the invariant measure of integral geometry, the one Crofton's theorem is about: an
// isotropic direction, and an offset uniform on the disc perpendicular to it that covers a sphere. A convex
// body inside the sphere is met by the fraction A / (pi R^2) of them, where A is its shadow's area averaged
// over directions; by Cauchy's formula A = S / 4 for every convex body (a sphere: pi r^2 = 4 pi r^2 / 4). So
// a random line that meets a convex parent meets a convex child with probability S_child / S_parent: the
// SAH's p. In the plane (a flatland scene) the invariant measure is a uniform direction and an offset uniform
// across a disc: a convex set inside the disc is met by the fraction L / (2 pi R) of them, L its perimeter
// (Cauchy's formula in the plane: its width averaged over directions is L / pi), so p = L_child / L_parent.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/ray.h"
#include "raystep/geometry/split_space.h"
#include "raystep/util/random.h"

namespace raystep {

// One random line through the sphere (centre, radius), as a ray that starts outside it (2 radii back along
// its direction from the offset point) and runs through it.
Ray random_line(Pcg32& rng, const glm::vec3& centre, float radius);
// The radius of the sphere around a box that the lines are drawn through (in the plane: the circle around its
// rectangle in x and y).
float line_radius(const Bounds3& box, SplitSpace space);
// The same in the plane z = centre.z through the disc (centre, radius).
Ray random_plane_line(Pcg32& rng, const glm::vec3& centre, float radius);
// random_line in space, random_plane_line in the plane.
inline Ray random_line(Pcg32& rng, const glm::vec3& centre, float radius, SplitSpace space) {
  return space.plane() ? random_plane_line(rng, centre, radius) : random_line(rng, centre, radius);
}

// The box against its bounding sphere: of `lines` random lines through the sphere (reproducible by seed),
// the fraction that meet the box, and Cauchy-Crofton's prediction (S_box / 4) / (pi R^2). In the plane: the
// lines through the box's bounding circle in the plane, and the prediction L_box / (2 pi R).
struct LinesMeetingBox {
  double measured = 0.0;
  double predicted = 0.0;
};
LinesMeetingBox lines_meeting_box(const Bounds3& box, size_t lines, uint64_t seed, SplitSpace space = {});

// Crofton's theorem at a node: random lines through the node's bounding sphere (circle), the ones that meet
// the node kept, and of those the share that meets each child, against the ratio of measures the SAH uses
// (S_child / S, in the plane L_child / L). `kept` of the lines meeting the node are returned as their part
// inside it (from where they enter to where they leave), for a picture.
struct LinesMeetingChildren {
  size_t thrown = 0, meeting_node = 0;
  std::vector<size_t> meeting_child;  // per child
  std::vector<double> share;          // meeting_child / meeting_node
  std::vector<double> ratio;          // measure(child) / measure(node)
  std::vector<std::pair<glm::vec3, glm::vec3>> kept;
};
LinesMeetingChildren lines_meeting_children(const Bounds3& node, const std::vector<Bounds3>& children,
                                            size_t lines, uint64_t seed, SplitSpace space, size_t kept = 0);

}  // namespace raystep
