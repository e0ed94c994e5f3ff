// The octree as data (lecture: "Non-uniform subdivision: oct-tree"): a cube cut at its centre into eight
// equal cells, recursively, where the primitives are dense. Compact 8-byte nodes; the eight children of a
// node are consecutive (child index bit 0: upper half in x, bit 1: in y, bit 2: in z); a cold side table per
// node (cell, parent, depth) for traces, statistics and the debugger. Built by octree_build.h, walked by
// octree.h.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/geometry/bounds.h"

namespace raystep {

// The traversal's stack holds one frame per level: no tree is deeper.
constexpr int kOctreeMaxDepth = 20;

// One node, 8 bytes. Inner: the index of its first child (children first .. first + 7; a quadtree's
// first .. first + 3). Leaf: where its
// primitive ids start in OctreeData::prim_index, and how many there are.
struct OctreeNode {
  uint32_t first;  // inner: first child; leaf: offset into prim_index
  uint32_t bits;   // bit 0: leaf; leaf: primitive count in the high 31 bits

  static OctreeNode make_leaf(uint32_t first_prim, uint32_t count) { return {first_prim, (count << 1) | 1u}; }
  static OctreeNode make_inner(uint32_t first_child) { return {first_child, 0u}; }
  bool is_leaf() const { return bits & 1u; }
  uint32_t prim_count() const { return bits >> 1; }
  uint32_t child(int i) const { return first + uint32_t(i); }
};
static_assert(sizeof(OctreeNode) == 8, "OctreeNode is 8 bytes");

// Why a node holding more than K primitives was not split.
enum class OctreeLeafReason : uint8_t {
  few_primitives,  // at most K: the ordinary leaf
  max_depth,       // the depth limit (or cells too small for a float to halve)
  no_reduction,    // two or more children would each hold every primitive: nothing gained
  budget,          // the reference or node budget would be exceeded
};
const char* to_string(OctreeLeafReason r);

// What a node was made of, kept beside the hot nodes (read by the walk only for the root's cell).
struct OctreeNodeInfo {
  Bounds3 box;          // the node's cell
  int32_t parent = -1;  // -1 for the root (node 0)
  int32_t depth = 0;
  uint32_t prims = 0;  // primitives overlapping the cell (before the split, for an inner node)
  OctreeLeafReason reason = OctreeLeafReason::few_primitives;  // leaves only
};

// A built octree. nodes[0] is the root; node ids are positions in `nodes` (breadth first), the same ids that
// trace events use.
struct OctreeData {
  // 3: the octree; 2: a 2D scene's quadtree (geometry/split_space.h): cells cut on x and y only, four
  // children a node (child index bit 0: upper x, bit 1: upper y), every cell the root's z extent.
  int axes = 3;
  Bounds3 bounds;  // the root's cell: a cube around the scene's bounds (a quadtree's: a square in x, y)
  std::vector<OctreeNode> nodes;
  std::vector<OctreeNodeInfo> info;  // one per node
  std::vector<uint32_t> prim_index;  // leaves' primitive ids, in increasing id order within a leaf
};

}  // namespace raystep
