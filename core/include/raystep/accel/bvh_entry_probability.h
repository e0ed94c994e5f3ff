// Crofton's theorem put to the test on the BVH: the SAH assumes a random line through a node's box enters a
// child's box with probability S_child / S_node, so a line through the root crosses node n's box with
// probability S_n / S_root. Measured on uniformly distributed random lines through the root's box (the
// fraction that crosses each node's box), and on the same lines cast as rays, whose traversal stops at the
// first hit and skips boxes beyond it, which the SAH's assumption that rays pass through everything
// overestimates.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/bvh.h"
#include "raystep/accel/kdtree_entry_probability.h"

namespace raystep {

// One entry per node: predicted = S_node / S_root (1 for the root; NaN below a root of zero area), lines and
// rays as for the kd-tree (KdNodeEntry, kdtree_entry_probability.h: the same lines for the same seed).
using BvhNodeEntry = KdNodeEntry;

std::vector<BvhNodeEntry> measure_bvh_entry_probability(const Bvh& bvh, size_t lines, uint64_t seed,
                                                        size_t* rays_cast = nullptr,
                                                        uint64_t max_ray_tests = kMaxEntryRayTests);

}  // namespace raystep
