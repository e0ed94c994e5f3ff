// The binary BVH as its walk reads it (lecture: "at an inner node, test both children's boxes"): each inner
// node's two children side by side in one 64-byte line, their boxes stored as rows (left lo, right lo, left
// hi, right hi) per axis, so that one 4-wide SIMD slab test (SSE2: every x86-64) tests both children with the
// same float operations, in the same order, as BvhBoxRay::hit (bvh_box_ray.h) tests one box: the same
// answers, bit for bit. A copy made from BvhData by the Bvh; the ids of traces stay BvhData's.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/bvh_node.h"

namespace raystep {

// A child of an inner node: another inner node (count 0: `index` is its pair) or a leaf (count > 0 primitives
// from BvhData::prim_index[index]). A BVH leaf always holds at least one primitive.
// No default member values: the walk's stack of them is not cleared for every ray.
struct BvhRef {
  uint32_t index;
  uint32_t count;
  bool is_leaf() const { return count > 0; }
};

// The two children of one inner node. rows[axis][lane]: lanes 0 and 1 are the left and right child's lower
// bounds on the axis, lanes 2 and 3 their upper bounds.
struct alignas(64) BvhPair {
  float rows[3][4];
  BvhRef child[2];
};
static_assert(sizeof(BvhPair) == 64, "a pair fills one cache line");

// Every inner node as a pair (pairs[0]: the root's children), and on the side, for traces only, the BvhData
// ids of each pair's node, its children and the builder's split axis.
struct BvhPairs {
  std::vector<BvhPair> pairs;
  std::vector<int32_t> node_id;   // per pair
  std::vector<int32_t> child_id;  // two per pair
  std::vector<uint8_t> axis;      // per pair
  BvhRef root{0, 0};              // the root: pair 0, or a leaf when the whole tree is one
  BvhPair root_box{};  // the root's box in both lanes: the walk's first test, as SIMD as the others
};

BvhPairs make_bvh_pairs(const BvhData& data);

}  // namespace raystep
