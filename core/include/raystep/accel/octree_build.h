// Building the octree (lecture: "oct-tree: split a cell at its centre into eight while it holds too many
// primitives"): over a cube around the scene's bounds, a cell holding more than K primitives and above the
// depth limit is cut into eight; each primitive goes into every child it really overlaps (the grid's exact
// triangle-box and sphere-box tests). Bounded memory on any input: the depth limit, no split in which two or
// more children would each hold every primitive of the cell, and a reference and node budget.
#pragma once

#include <cstddef>
#include <cstdint>

#include "raystep/accel/octree_node.h"
#include "raystep/scene/geometry.h"

namespace raystep {

struct OctreeOptions {
  int leaf_size = 8;  // K: a cell with at most K primitives is a leaf (1 ..)
  int max_depth = 0;  // 0: automatic (octree_max_depth); else 1..kOctreeMaxDepth
};

// The depth limit a build uses: the explicit one, or clamp(ceil(log2(N) / 2) + 6, 8, 20) (a surface of N
// primitives meets about 4^d cells at depth d, so N / K leaves of an even surface need about log4(N / K)
// levels; six more let a small dense part of a large scene adapt, a teapot in a stadium; where K cannot be
// reached the budgets and the no-reduction rule stop the splitting).
int octree_max_depth(const OctreeOptions& options, size_t prim_count);

// The references (primitive ids in leaves) a build may store: min(2^28, max(2^22, 32 N)), as the grid's.
size_t octree_reference_budget(size_t prim_count);
// The nodes a build may make: min(2^23, max(2^18, 16 N)).
size_t octree_node_budget(size_t prim_count);

// Throws InputError("", 0, ...) for options out of range.
OctreeData build_octree(const Geometry& geometry, const OctreeOptions& options);

struct OctreeStats {
  size_t nodes = 0, leaves = 0, empty_leaves = 0, references = 0;
  int max_depth = 0;
  size_t leaves_by_reason[4] = {0, 0, 0, 0};  // non-empty leaves, by OctreeLeafReason
  size_t max_leaf_prims = 0;
};
OctreeStats octree_stats(const OctreeData& data);

}  // namespace raystep
