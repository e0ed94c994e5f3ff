// How good a built hierarchy is, in the numbers behind the lecture's "build balanced trees with tight
// bounding volumes", for every BVH builder and for the wide trees alike:
//   - the SAH cost: the expected cost of a random line through the root, each node weighted by the
//     probability S(node) / S(root) that the line meets its box (Crofton), t_t per inner node, t_i per
//     primitive of a leaf;
//   - EPO, the end-point overlap (Aila, Karras and Laine, "On quality metrics of bounding volume
//     hierarchies", HPG 2013): the surface of triangles that lies inside the boxes of nodes that do not
//     hold them, each node weighted by its cost (t_t inner, t_i N leaf), over the whole surface. A ray ends
//     on a surface point; every box around that point whose subtree lacks the triangle is work the SAH
//     does not see (it counts lines, which end nowhere). A tree whose boxes do not overlap other
//     subtrees' triangles has EPO 0 (spatial splits lower it; the kd-tree's cells hold every triangle that
//     crosses them, so it has none by construction);
//   - the leaves' primitive counts and depths as histograms;
//   - the measured cost on a ray set: nodes visited and primitives tested per ray, t_t nodes + t_i tests.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/geometry/ray.h"
#include "raystep/scene/geometry.h"

namespace raystep {

struct BvhQuality {
  size_t nodes = 0, inner = 0, leaves = 0;
  size_t references = 0;  // primitive ids in the leaves
  double sah_cost = 0.0;
  bool epo_measured = false;                 // false when the caller left EPO out (its cost on a big mesh)
  double epo = 0.0;                          // EPO, in the SAH's cost units (t_t, t_i)
  double epo_inner = 0.0, epo_leaves = 0.0;  // its two parts: inner nodes and leaves
  // leaf_prims[k]: leaves with k primitives (the last bin: that many or more); leaf_depth[d]: leaves at
  // depth d.
  std::vector<uint64_t> leaf_prims, leaf_depth;
};
constexpr int kLeafHistogramBins = 17;  // 0..15 primitives, 16 or more

// A binary BVH as the wide view's nodes (two children an inner node), so that one function measures both.
WideBvhView bvh_view(const BvhData& bvh);

// The quality of a tree (bvh_view or WideBvh::describe) over `geometry`'s primitives. EPO counts triangles
// only (a sphere's surface is left out of both sums) and costs O(N * nodes a triangle's box overlaps): 0.3 s
// on the bunny's 69k triangles; with_epo false leaves it out (the rest is O(nodes)).
BvhQuality tree_quality(const WideBvhView& tree, const Geometry& geometry, float t_i, float t_t,
                        bool with_epo = true);

// Work per ray of a structure on `rays`, nearest-hit queries with the counting recorder.
struct MeasuredCost {
  uint64_t rays = 0;
  double nodes_per_ray = 0.0;  // inner nodes visited (for the grid: cells)
  double leaves_per_ray = 0.0;
  double box_tests_per_ray = 0.0;
  double tests_per_ray = 0.0;  // ray-primitive tests
  double cost_per_ray = 0.0;   // t_t nodes + t_i tests: the SAH's units
};
MeasuredCost measure_cost(const Accelerator& accel, const std::vector<Ray>& rays, float t_i, float t_t);

}  // namespace raystep
