// What the kd-tree's and the BVH's entry-probability measurements share (kdtree_entry_probability.cpp,
// bvh_entry_probability.cpp): the random lines through the root's box, the boxes each line crosses, and the
// nodes the same lines cast as rays enter. Both trees are binary with the first child next to its parent, so
// one walk serves; a tree is seen through a small view (root box, node box, leaf test, second child).
// Internal to raystep_core.
#pragma once

#include <cmath>
#include <cstdint>
#include <vector>

#include <glm/geometric.hpp>

#include "raystep/accel/kdtree_entry_probability.h"
#include "raystep/accel/random_lines.h"
#include "raystep/util/random.h"

namespace raystep::entry_probability {

// Counts the nodes a real traversal visits, and its primitive tests.
struct NodeVisitCounter : NullRecorder {
  std::vector<uint32_t>* counts;
  uint64_t prim_tests = 0;
  void node(const TreeStep& s) { ++(*counts)[size_t(s.node)]; }
  void prim_test(uint32_t, bool, float) { ++prim_tests; }
};

// Every node whose box the line crosses: the children of a crossed node whose boxes it meets (both may be).
template <class View>
void cross(const View& tree, const SlabRay& line, uint32_t id, std::vector<uint32_t>& counts) {
  for (;;) {
    ++counts[id];
    if (tree.is_leaf(id)) return;
    uint32_t first = id + 1, second = tree.second_child(id);
    bool hit_first = intersect_slabs(tree.box(first), line, nullptr, nullptr);
    bool hit_second = intersect_slabs(tree.box(second), line, nullptr, nullptr);
    if (hit_first && hit_second) cross(tree, line, second, counts);
    if (hit_first)
      id = first;
    else if (hit_second)
      id = second;
    else
      return;
  }
}

// The measurement of kdtree_entry_probability.h on any tree: View has size(), root() (the box the lines
// pass through), space() (in space or in the plane), box(id), is_leaf(id) and second_child(id); Accel has
// traverse(ray, hit, any, recorder).
template <class View, class Accel>
std::vector<KdNodeEntry> measure(const View& tree, const Accel& accel, size_t lines, uint64_t seed,
                                 size_t* rays_cast, uint64_t max_ray_tests) {
  std::vector<KdNodeEntry> out(tree.size());
  if (rays_cast) *rays_cast = 0;
  if (out.empty() || tree.root().empty()) return out;
  const Bounds3& root = tree.root();
  // Every line through the root enters the root; below a root of zero area (a point, a segment) the ratio is
  // 0/0 and says nothing.
  const SplitSpace space = tree.space();
  double s_root = space.measure(root);
  for (size_t i = 0; i < out.size(); ++i)
    out[i].predicted = i == 0       ? 1.0
                       : s_root > 0 ? double(space.measure(tree.box(uint32_t(i)))) / s_root
                                    : std::nan("");

  std::vector<uint32_t> crossed(out.size(), 0), entered(out.size(), 0);
  NodeVisitCounter counter;
  counter.counts = &entered;
  glm::vec3 centre = root.center();
  const float radius = line_radius(root, space);
  Pcg32 rng(seed, 0);
  size_t kept = 0, cast = 0;
  for (size_t attempts = 0; kept < lines && attempts < 64 * lines; ++attempts) {
    // Crofton's lines (random_lines.h) through the bounding sphere (the same lines for every tree for the
    // same seed and root box).
    const Ray ray = random_line(rng, centre, radius, space);
    SlabRay line(ray);
    if (!intersect_slabs(root, line, nullptr, nullptr)) continue;
    ++kept;
    cross(tree, line, 0, crossed);
    // The rays test primitives, lines do not: on a leaf of 100,000 identical triangles every ray tests them
    // all, so the rays stop after max_ray_tests tests in all and their fraction is over the rays cast.
    if (counter.prim_tests < max_ray_tests) {
      Hit hit;
      accel.traverse(ray, &hit, false, counter);
      ++cast;
    }
  }
  for (size_t i = 0; i < out.size() && kept; ++i) {
    out[i].lines = double(crossed[i]) / double(kept);
    out[i].rays = cast ? double(entered[i]) / double(cast) : 0.0;
  }
  if (rays_cast) *rays_cast = cast;
  return out;
}

}  // namespace raystep::entry_probability
