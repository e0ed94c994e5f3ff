// The binary bounding volume hierarchy as data (lecture: "bounding volume hierarchies: balanced trees with
// tight, possibly overlapping, bounds"): 32-byte nodes in depth-first order (the first child follows its
// parent, the second child's index is stored), each primitive id in exactly one leaf, and a cold side table
// per node for traces, statistics and the GUI. Built by bvh_build.h, walked by bvh.h, collapsed by
// wide_bvh.h.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/split_space.h"

namespace raystep {

// One node, 32 bytes: its tight box, and either its children or its primitives. Inner: `index` is the second
// child's node id (the first child is the next node) and the low 2 bits of `bits` the axis the builder split
// on. Leaf: `index` is where its primitive ids start in BvhData::prim_index, the low 2 bits of `bits` are 3
// and the high 30 bits the primitive count.
struct BvhNode {
  Bounds3 box;
  uint32_t index = 0;
  uint32_t bits = 3;

  static constexpr uint32_t kMaxCount = (1u << 30) - 1;

  static BvhNode make_leaf(const Bounds3& box, uint32_t first, uint32_t count) {
    BvhNode n;
    n.box = box;
    n.index = first;
    n.bits = 3u | (count << 2);
    return n;
  }
  static BvhNode make_inner(const Bounds3& box, int axis, uint32_t second_child) {
    BvhNode n;
    n.box = box;
    n.index = second_child;
    n.bits = uint32_t(axis);
    return n;
  }
  bool is_leaf() const { return (bits & 3u) == 3u; }
  int axis() const { return int(bits & 3u); }
  uint32_t second_child() const { return index; }
  uint32_t first_prim() const { return index; }
  uint32_t prim_count() const { return bits >> 2; }
};

// What a node was made of, kept beside the hot nodes (never read by the traversal).
struct BvhNodeInfo {
  int32_t parent = -1;  // -1 for the root (node 0)
  int32_t depth = 0;
  uint32_t prims = 0;  // primitives in the node's subtree (SBVH: the references the node was built over)
  float cost = 0.f;    // the builder's choice for this node: the split's SAH cost, or N * t_i for a leaf
};

// A built hierarchy. nodes[0] is the root (its box is the scene's bounds); node ids are positions in `nodes`
// (depth-first preorder), the ids that trace events and the SAH inspector use. prim_index lists each leaf's
// primitive ids, contiguous and in increasing id order within the leaf: a permutation of the primitive ids,
// except after spatial splits (BvhBuilder::sbvh), where a primitive may be referenced by several leaves (never
// twice by one), and `references` counts them.
struct BvhData {
  SplitSpace space;  // split on x, y, z, or on x and y in the plane (a flatland scene)
  std::vector<BvhNode> nodes;
  std::vector<BvhNodeInfo> info;  // one per node
  std::vector<uint32_t> prim_index;
};

}  // namespace raystep
