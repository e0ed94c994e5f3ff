#include "raystep/accel/octree_build.h"

#include <algorithm>
#include <cmath>
#include <string>

#include "raystep/geometry/tri_box_overlap.h"
#include "raystep/util/error.h"

namespace raystep {

const char* to_string(OctreeLeafReason r) {
  switch (r) {
    case OctreeLeafReason::few_primitives:
      return "few primitives";
    case OctreeLeafReason::max_depth:
      return "depth limit";
    case OctreeLeafReason::no_reduction:
      return "no reduction";
    case OctreeLeafReason::budget:
      return "budget";
  }
  return "?";
}

int octree_max_depth(const OctreeOptions& options, size_t prim_count) {
  if (options.max_depth > 0) return options.max_depth;
  int d = int(std::ceil(0.5 * std::log2(double(std::max<size_t>(prim_count, 1))))) + 6;
  return std::clamp(d, 8, kOctreeMaxDepth);
}

size_t octree_reference_budget(size_t prim_count) {
  return std::min(size_t(1) << 28, std::max(size_t(1) << 22, 32 * prim_count));
}

size_t octree_node_budget(size_t prim_count) {
  return std::min(size_t(1) << 23, std::max(size_t(1) << 18, 16 * prim_count));
}

namespace {

// The root's cell: a cube centred on the scene's bounding box, its side the box's largest extent, a little
// enlarged. A cube keeps every cell a cube (the lecture's octree; a flat scene gets no flat cells) and the
// centre split meaningful on every axis.
// A 2D scene's quadtree (axes 2): a square in x and y, the scene's own z extent (never cut).
Bounds3 root_cube(const Bounds3& scene, int axes) {
  glm::vec3 c = scene.center(), e = scene.extent();
  float side = axes == 2 ? std::max(e.x, e.y) : std::max({e.x, e.y, e.z});
  float magnitude = std::max({std::fabs(c.x), std::fabs(c.y), std::fabs(c.z)});
  // 2^-10 of the side, and enough ulps of the position that the cube strictly contains the box after
  // rounding; a point scene (every primitive at one spot) gets a small cube of its own.
  float half = 0.5f * side * (1.f + 1.f / 1024.f) + magnitude * 1e-6f + 1e-30f;
  Bounds3 b;
  b.lo = c - glm::vec3(half);
  b.hi = c + glm::vec3(half);
  for (int a = 0; a < 3; ++a) {  // never narrower than the scene's box, whatever the rounding
    b.lo[a] = std::min(b.lo[a], scene.lo[a]);
    b.hi[a] = std::max(b.hi[a], scene.hi[a]);
  }
  if (axes == 2) {  // the walls' own height, a little enlarged
    const float h = 0.5f * e.z * (1.f + 1.f / 1024.f) + std::fabs(c.z) * 1e-6f + 1e-30f;
    b.lo.z = std::min(c.z - h, scene.lo.z);
    b.hi.z = std::max(c.z + h, scene.hi.z);
  }
  return b;
}

// Child i of a cell: the same halves the walk computes (mid = 0.5 (lo + hi), as a float), on the first
// `axes` axes; the others keep the cell's extent.
Bounds3 child_box(const Bounds3& box, int i, int axes) {
  Bounds3 b = box;
  for (int a = 0; a < axes; ++a) {
    float mid = 0.5f * (box.lo[a] + box.hi[a]);
    bool upper = (i >> a) & 1;
    b.lo[a] = upper ? mid : box.lo[a];
    b.hi[a] = upper ? box.hi[a] : mid;
  }
  return b;
}

bool overlaps(const Geometry& g, uint32_t id, const Bounds3& box) {
  if (g.type(id) == PrimType::triangle)
    return triangle_overlaps_box(g.vertex(id, 0), g.vertex(id, 1), g.vertex(id, 2), box);
  return sphere_overlaps_box(g.sphere(id).center, g.sphere(id).radius, box);
}

}  // namespace

OctreeData build_octree(const Geometry& geometry, const OctreeOptions& options) {
  if (options.leaf_size < 1 || options.leaf_size > (1 << 24))
    throw InputError("", 0, "octree: the leaf size K must be 1..16777216");
  if (options.max_depth < 0 || options.max_depth > kOctreeMaxDepth)
    throw InputError("", 0, "octree: the depth limit must be 0..20 (0: automatic)");
  OctreeData d;
  const size_t n = geometry.size();
  if (n == 0) return d;
  if (n > size_t(OctreeNode{0, ~0u}.prim_count())) throw InputError("", 0, "octree: too many primitives");
  const int max_depth = octree_max_depth(options, n);
  const size_t ref_budget = octree_reference_budget(n), node_budget = octree_node_budget(n);
  const size_t leaf_size = size_t(options.leaf_size);

  d.axes = geometry.split_space().axes == 2 ? 2 : 3;
  const int children_per_node = 1 << d.axes;
  d.bounds = root_cube(geometry.bounds(), d.axes);
  // Breadth first, so that the children of a node (eight, or a quadtree's four) are consecutive. Each node waiting to be split holds
  // its primitive list; the lists together never exceed the reference budget.
  std::vector<std::vector<uint32_t>> lists(1);
  lists[0].resize(n);
  for (uint32_t i = 0; i < n; ++i) lists[0][i] = i;
  d.nodes.push_back(OctreeNode::make_leaf(0, 0));
  d.info.push_back(OctreeNodeInfo{d.bounds, -1, 0, uint32_t(n), OctreeLeafReason::few_primitives});
  size_t references = n;  // held by the lists of nodes not yet split and the leaves made so far
  std::vector<uint32_t> children[8];
  for (size_t id = 0; id < d.nodes.size(); ++id) {
    std::vector<uint32_t> prims = std::move(lists[id]);
    lists[id] = {};
    OctreeNodeInfo& info = d.info[id];
    auto make_leaf = [&](OctreeLeafReason reason) {
      d.info[id].reason = reason;
      d.nodes[id] = OctreeNode::make_leaf(uint32_t(d.prim_index.size()), uint32_t(prims.size()));
      d.prim_index.insert(d.prim_index.end(), prims.begin(), prims.end());
    };
    if (prims.size() <= leaf_size) {
      make_leaf(OctreeLeafReason::few_primitives);
      continue;
    }
    // A cell a float cannot halve any more counts as the depth limit too.
    bool halvable = true;
    for (int a = 0; a < d.axes; ++a) {
      float mid = 0.5f * (info.box.lo[a] + info.box.hi[a]);
      halvable &= info.box.lo[a] < mid && mid < info.box.hi[a];
    }
    if (info.depth >= max_depth || !halvable) {
      make_leaf(OctreeLeafReason::max_depth);
      continue;
    }
    if (d.nodes.size() + size_t(children_per_node) > node_budget) {
      make_leaf(OctreeLeafReason::budget);
      continue;
    }
    size_t added = 0, unreduced = 0;
    const Bounds3 box = info.box;
    for (int c = 0; c < children_per_node; ++c) {
      children[c].clear();
      Bounds3 cb = child_box(box, c, d.axes);
      for (uint32_t p : prims)
        if (overlaps(geometry, p, cb)) children[c].push_back(p);
      added += children[c].size();
      unreduced += children[c].size() == prims.size();
    }
    added -=
        prims.size();  // each primitive is in at least one child (the conservative tests), so no underflow
    // Two or more children that each hold every primitive of the cell gain nothing (identical primitives, or
    // a stack of coplanar ones, across the centre): the split would copy all of them and test them again. One
    // such child is fine: the others hold only what reaches them (a floor under a dense object), or nothing
    // (a pure shrink of the cell, which copies nothing and stops at the depth limit).
    if (unreduced >= 2) {
      make_leaf(OctreeLeafReason::no_reduction);
      continue;
    }
    if (references + added > ref_budget) {
      make_leaf(OctreeLeafReason::budget);
      continue;
    }
    references += added;
    const uint32_t first = uint32_t(d.nodes.size());
    const int32_t depth = info.depth;  // `info` dangles once the tables grow
    d.nodes[id] = OctreeNode::make_inner(first);
    for (int c = 0; c < children_per_node; ++c) {
      d.nodes.push_back(OctreeNode::make_leaf(0, 0));
      d.info.push_back(OctreeNodeInfo{child_box(box, c, d.axes), int32_t(id), depth + 1, uint32_t(children[c].size()),
                                      OctreeLeafReason::few_primitives});
      lists.push_back(std::move(children[c]));
      children[c] = {};
    }
  }
  return d;
}

OctreeStats octree_stats(const OctreeData& data) {
  OctreeStats s;
  s.nodes = data.nodes.size();
  s.references = data.prim_index.size();
  for (size_t i = 0; i < data.nodes.size(); ++i) {
    const OctreeNode& node = data.nodes[i];
    s.max_depth = std::max(s.max_depth, data.info[i].depth);
    if (!node.is_leaf()) continue;
    ++s.leaves;
    if (node.prim_count() == 0) {
      ++s.empty_leaves;
      continue;
    }
    ++s.leaves_by_reason[int(data.info[i].reason)];
    s.max_leaf_prims = std::max<size_t>(s.max_leaf_prims, node.prim_count());
  }
  return s;
}

}  // namespace raystep
