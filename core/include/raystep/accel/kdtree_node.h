// The kd-tree as data (lecture: "Non-uniform subdivision: kd-trees"): compact 8-byte nodes in depth-first
// order (the below child follows its parent, the above child's index is stored), the leaves' primitive
// lists in one array, and a cold side table per node (box, parent, depth) for traces, statistics and the GUI.
// Layout after pbrt-v3's KdAccelNode; the builders are in kdtree_build.h, the traversal in kdtree.h.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/split_space.h"

namespace raystep {

// One node, 8 bytes. Inner: the split plane's position and axis (0, 1, 2), and the index of the child above
// the plane (the child below is the next node). Leaf: axis bits 3, the number of primitives, and where
// their ids start in KdTreeData::prim_index.
struct KdNode {
  union {
    float split;          // inner
    uint32_t first_prim;  // leaf: offset into prim_index
  };
  uint32_t bits;  // low 2 bits: axis, or 3 for a leaf; high 30 bits: above child (inner) or primitive count

  static constexpr uint32_t kMaxIndex = (1u << 30) - 1;

  static KdNode make_leaf(uint32_t first, uint32_t count) {
    KdNode n;
    n.first_prim = first;
    n.bits = 3u | (count << 2);
    return n;
  }
  static KdNode make_inner(int axis, float split, uint32_t above_child) {
    KdNode n;
    n.split = split;
    n.bits = uint32_t(axis) | (above_child << 2);
    return n;
  }
  bool is_leaf() const { return (bits & 3u) == 3u; }
  int axis() const { return int(bits & 3u); }
  uint32_t above_child() const { return bits >> 2; }
  uint32_t prim_count() const { return bits >> 2; }
};
static_assert(sizeof(KdNode) == 8, "KdNode is 8 bytes");

// What a node was made of, kept beside the hot nodes (never read by the traversal).
struct KdNodeInfo {
  Bounds3 box;          // the node's cell
  int32_t parent = -1;  // -1 for the root (node 0)
  int32_t depth = 0;
  float cost = 0.f;  // the cost the builder chose for this node: the split's SAH cost, or N * t_i for a leaf
};

// A built tree. nodes[0] is the root; node ids are positions in `nodes` (depth-first preorder: a node, its
// whole below subtree, then its above subtree), the same ids that trace events and the SAH inspector use.
struct KdTreeData {
  Bounds3 bounds;    // the root's box: the scene's bounds
  SplitSpace space;  // split on x, y, z, or on x and y in the plane (a flatland scene)
  std::vector<KdNode> nodes;
  std::vector<KdNodeInfo> info;      // one per node
  std::vector<uint32_t> prim_index;  // leaves' primitive ids, in increasing id order within a leaf
};

}  // namespace raystep
