#include "raystep/accel/bvh.h"

#include "raystep/accel/bvh_names.h"

namespace raystep {

std::string Bvh::name() const {
  return bvh_name({2, options_.builder});
}

BvhPairs make_bvh_pairs(const BvhData& data) {
  BvhPairs out;
  const std::vector<BvhNode>& nodes = data.nodes;
  if (nodes.empty()) return out;
  // Pairs in the nodes' (depth-first) order: the pair of inner node i is the number of inner nodes before it.
  std::vector<uint32_t> pair_of(nodes.size(), 0);
  uint32_t inner = 0;
  for (size_t i = 0; i < nodes.size(); ++i)
    if (!nodes[i].is_leaf()) pair_of[i] = inner++;
  auto ref = [&](uint32_t id) {
    const BvhNode& n = nodes[id];
    return n.is_leaf() ? BvhRef{n.first_prim(), n.prim_count()} : BvhRef{pair_of[id], 0};
  };
  out.root = ref(0);
  for (int k = 0; k < 2; ++k)
    for (int a = 0; a < 3; ++a) {
      out.root_box.rows[a][k] = nodes[0].box.lo[a];
      out.root_box.rows[a][k + 2] = nodes[0].box.hi[a];
    }
  out.pairs.resize(inner);
  out.node_id.resize(inner);
  out.child_id.resize(2 * size_t(inner));
  out.axis.resize(inner);
  for (uint32_t i = 0; i < nodes.size(); ++i) {
    if (nodes[i].is_leaf()) continue;
    const uint32_t p = pair_of[i];
    const uint32_t children[2] = {i + 1, nodes[i].second_child()};
    BvhPair& pair = out.pairs[p];
    for (int k = 0; k < 2; ++k) {
      const Bounds3& b = nodes[children[k]].box;
      for (int a = 0; a < 3; ++a) {
        pair.rows[a][k] = b.lo[a];
        pair.rows[a][k + 2] = b.hi[a];
      }
      pair.child[k] = ref(children[k]);
      out.child_id[2 * p + k] = int32_t(children[k]);
    }
    out.node_id[p] = int32_t(i);
    out.axis[p] = uint8_t(nodes[i].axis());
  }
  return out;
}

void Bvh::build(const Geometry& geometry) {
  geometry_ = &geometry;
  bvh_ = build_bvh(geometry, options_);
  pairs_ = make_bvh_pairs(bvh_);
}

void Bvh::build(const Geometry& geometry, BvhBuildListener& listener) {
  geometry_ = &geometry;
  bvh_ = build_bvh(geometry, options_, listener);
  pairs_ = make_bvh_pairs(bvh_);
}

size_t Bvh::memory_bytes() const {
  return bvh_.nodes.capacity() * sizeof(BvhNode) + bvh_.info.capacity() * sizeof(BvhNodeInfo) +
         bvh_.prim_index.capacity() * sizeof(uint32_t) + pairs_.pairs.capacity() * sizeof(BvhPair) +
         (pairs_.node_id.capacity() + pairs_.child_id.capacity()) * sizeof(int32_t) + pairs_.axis.capacity();
}

}  // namespace raystep
