// Crofton's theorem put to the test: the SAH assumes a ray through a node enters a child with probability
// S_child / S_node, so a random line through the root enters node n with probability S_n / S_root. Here that
// prediction meets measurement: the fraction of uniformly distributed random lines through the root's box that
// cross each node, and the fraction of the same lines, cast as rays, whose traversal (stopping at the first hit)
// entered it, which the SAH's assumption that rays pass through everything overestimates.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/kdtree.h"

namespace raystep {

struct KdNodeEntry {
  double predicted = 0.0;  // S_node / S_root (1 for the root; NaN below a root of zero area)
  double lines = 0.0;      // fraction of the lines that cross the node's box
  double rays = 0.0;       // fraction of the lines, cast as rays from outside the root, whose walk entered it
};

// One entry per node. Lines: directions uniform on the sphere, offsets uniform on the disc perpendicular to
// each that covers the root's bounding sphere, kept when they meet the root's box (the invariant measure of
// lines, for which Crofton's theorem holds). `lines` of them, reproducible by seed. The rays are cast until
// they have made max_ray_tests primitive tests in all (a bound on the time pathological scenes take, reached
// by none of the shared meshes at the default line count); *rays_cast says how many were.
constexpr uint64_t kMaxEntryRayTests = 200'000'000;
std::vector<KdNodeEntry> measure_entry_probability(const KdTree& tree, size_t lines, uint64_t seed,
                                                   size_t* rays_cast = nullptr,
                                                   uint64_t max_ray_tests = kMaxEntryRayTests);

}  // namespace raystep
