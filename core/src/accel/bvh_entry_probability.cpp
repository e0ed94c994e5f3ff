#include "raystep/accel/bvh_entry_probability.h"

#include "entry_probability_common.h"

namespace raystep {

namespace {

// The BVH as entry_probability::measure sees it: every node holds its own box, the root's included.
struct BvhView {
  const BvhData& data;
  size_t size() const { return data.nodes.size(); }
  const Bounds3& root() const { return data.nodes[0].box; }
  SplitSpace space() const { return data.space; }
  const Bounds3& box(uint32_t id) const { return data.nodes[id].box; }
  bool is_leaf(uint32_t id) const { return data.nodes[id].is_leaf(); }
  uint32_t second_child(uint32_t id) const { return data.nodes[id].second_child(); }
};

}  // namespace

std::vector<BvhNodeEntry> measure_bvh_entry_probability(const Bvh& bvh, size_t lines, uint64_t seed,
                                                        size_t* rays_cast, uint64_t max_ray_tests) {
  return entry_probability::measure(BvhView{bvh.data()}, bvh, lines, seed, rays_cast, max_ray_tests);
}

}  // namespace raystep
