// The wide BVH's data (private to wide_bvh*.cpp): 64-byte aligned nodes holding their children's boxes as
// structure of arrays, and the leaves' triangles copied in packets of four, in leaf order, for the SIMD
// filter in front of the watertight test.
#pragma once

#include <atomic>
#include <cstdint>
#include <vector>

#include "raystep/accel/wide_bvh.h"

namespace raystep {

constexpr uint32_t kWideLeaf = 0x80000000u;   // a child reference with this bit is a leaf
constexpr uint32_t kWideEmpty = 0xffffffffu;  // an unused child slot (its box is empty: never hit)
constexpr int kWidePacket = 4;                // triangles per packet

// One node of W children. box[2 * axis + 0][i] is child i's lower bound on `axis`, box[2 * axis + 1][i] its
// upper bound: the kernel picks, once per ray, which row is the near plane on each axis (by the sign of the
// direction), so no lane selects anything. An empty slot has lo = +inf, hi = -inf.
template <int W>
struct alignas(64) WideNode {
  float box[6][W];
  uint32_t child[W];  // inner: node index; leaf: kWideLeaf | position of its first primitive in `prims`
  uint32_t count[W];  // leaf: its primitive count
};
static_assert(sizeof(WideNode<8>) == 256 && sizeof(WideNode<4>) == 128, "nodes fill whole cache lines");

// Four triangles: v[3 * k + axis][lane] is vertex k of the lane's triangle, prim[lane] its id (the id
// beside the vertices: one cache miss less per leaf).
struct alignas(32) TriPacket {
  float v[9][kWidePacket];
  uint32_t prim[kWidePacket];
};

struct WideBvh::Impl {
  int width = 8;
  const Geometry* geometry = nullptr;
  bool empty = true;
  bool packets_ok = false;  // all primitives are triangles: leaves are tested through `packets`
  std::vector<WideNode<4>> nodes4;
  std::vector<WideNode<8>> nodes8;
  // Primitive ids in leaf order; each leaf starts at a multiple of kWidePacket (padding: kWideEmpty).
  std::vector<uint32_t> prims;
  std::vector<TriPacket> packets;  // prims.size() / kWidePacket, when packets_ok
  Bounds3 root_box;
  int max_depth = 0;
  // Cold, for traces: the id (describe()) of each wide node and of each child slot (node * width + lane).
  std::vector<int32_t> node_id, node_depth, slot_id;
  // And back: the child slot of each id (node * width + lane; the root, which is no slot: -1).
  std::vector<int32_t> id_slot;
  int32_t id_count = 0, leaf_count = 0;

  template <int W>
  const WideNode<W>* nodes() const {
    if constexpr (W == 4)
      return nodes4.data();
    else
      return nodes8.data();
  }
};

// The kernel level in use (WideBvh::force_simd). Inline: read once per ray, a call would cost more than
// the read.
extern std::atomic<int> g_wide_simd;
inline WideSimd wide_simd_in_use() {
  return WideSimd(g_wide_simd.load(std::memory_order_relaxed));
}

// The stack of a walk: up to width - 1 entries pushed per level.
constexpr int kWideStack = 7 * kBvhMaxDepth + 8;

}  // namespace raystep
