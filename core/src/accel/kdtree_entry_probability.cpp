#include "raystep/accel/kdtree_entry_probability.h"

#include "entry_probability_common.h"

namespace raystep {

namespace {

// The kd-tree as entry_probability::measure sees it: the root's box is the tree's bounds, a node's box is in
// info (the nodes themselves hold only the split).
struct KdView {
  const KdTreeData& data;
  size_t size() const { return data.nodes.size(); }
  const Bounds3& root() const { return data.bounds; }
  SplitSpace space() const { return data.space; }
  const Bounds3& box(uint32_t id) const { return data.info[id].box; }
  bool is_leaf(uint32_t id) const { return data.nodes[id].is_leaf(); }
  uint32_t second_child(uint32_t id) const { return data.nodes[id].above_child(); }
};

}  // namespace

std::vector<KdNodeEntry> measure_entry_probability(const KdTree& tree, size_t lines, uint64_t seed,
                                                   size_t* rays_cast, uint64_t max_ray_tests) {
  return entry_probability::measure(KdView{tree.data()}, tree, lines, seed, rays_cast, max_ray_tests);
}

}  // namespace raystep
