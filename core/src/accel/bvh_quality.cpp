#include "raystep/accel/bvh_quality.h"

#include <algorithm>
#include <array>
#include <cmath>

#include <glm/geometric.hpp>
#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>

#include "raystep/record/recorder.h"

namespace raystep {

namespace {

// The area of the part of triangle v inside box b: the triangle clipped by the box's six planes
// (Sutherland-Hodgman, in double), then the polygon's area.
double clipped_area(const std::array<glm::dvec3, 3>& v, const Bounds3& b) {
  std::array<glm::dvec3, 12> poly, next;
  int n = 3;
  for (int k = 0; k < 3; ++k) poly[size_t(k)] = v[size_t(k)];
  for (int a = 0; a < 3 && n >= 3; ++a)
    for (int side = 0; side < 2 && n >= 3; ++side) {
      const double plane = side == 0 ? double(b.lo[a]) : double(b.hi[a]);
      auto inside = [&](const glm::dvec3& p) { return side == 0 ? p[a] >= plane : p[a] <= plane; };
      int m = 0;
      for (int i = 0; i < n; ++i) {
        const glm::dvec3& p = poly[size_t(i)];
        const glm::dvec3& q = poly[size_t((i + 1) % n)];
        const bool pin = inside(p), qin = inside(q);
        if (pin) next[size_t(m++)] = p;
        if (pin != qin) {
          const double t = (plane - p[a]) / (q[a] - p[a]);
          glm::dvec3 x = p + t * (q - p);
          x[a] = plane;
          next[size_t(m++)] = x;
        }
      }
      n = m;
      std::copy(next.begin(), next.begin() + n, poly.begin());
    }
  if (n < 3) return 0.0;
  glm::dvec3 sum(0.0);
  for (int i = 1; i + 1 < n; ++i) sum += glm::cross(poly[size_t(i)] - poly[0], poly[size_t(i + 1)] - poly[0]);
  return 0.5 * glm::length(sum);
}

}  // namespace

WideBvhView bvh_view(const BvhData& bvh) {
  WideBvhView view;
  view.nodes.resize(bvh.nodes.size());
  for (size_t i = 0; i < bvh.nodes.size(); ++i) {
    const BvhNode& n = bvh.nodes[i];
    WideBvhView::Node& v = view.nodes[i];
    v.box = n.box;
    v.parent = bvh.info[i].parent;
    v.depth = bvh.info[i].depth;
    v.leaf = n.is_leaf();
    if (v.leaf)
      v.prims.assign(bvh.prim_index.begin() + n.first_prim(),
                     bvh.prim_index.begin() + n.first_prim() + n.prim_count());
    else
      v.children = {int32_t(i + 1), int32_t(n.second_child())};
  }
  return view;
}

BvhQuality tree_quality(const WideBvhView& tree, const Geometry& geometry, float t_i, float t_t,
                        bool with_epo) {
  BvhQuality q;
  q.nodes = tree.nodes.size();
  q.leaf_prims.assign(kLeafHistogramBins, 0);
  if (tree.nodes.empty()) return q;
  const SplitSpace space = geometry.split_space();
  const double root = space.measure(tree.nodes[0].box);
  auto weight = [&](const Bounds3& b) { return root > 0.0 ? double(space.measure(b)) / root : 1.0; };

  // The SAH cost, the histograms, and each node's range of leaves in depth-first order (a subtree's leaves
  // are contiguous), for "does this node's subtree hold the primitive?".
  std::vector<uint32_t> first_leaf(tree.nodes.size(), 0), end_leaf(tree.nodes.size(), 0);
  std::vector<std::vector<uint32_t>> leaves_of(geometry.size());
  uint32_t leaf_order = 0;
  struct Visit {
    int32_t id;
    bool done;
  };
  std::vector<Visit> stack{{0, false}};
  while (!stack.empty()) {
    const Visit v = stack.back();
    stack.pop_back();
    const WideBvhView::Node& n = tree.nodes[size_t(v.id)];
    if (v.done) {
      end_leaf[size_t(v.id)] = leaf_order;
      continue;
    }
    first_leaf[size_t(v.id)] = leaf_order;
    const double p = weight(n.box);
    if (n.leaf) {
      ++q.leaves;
      q.references += n.prims.size();
      q.sah_cost += p * double(t_i) * double(n.prims.size());
      ++q.leaf_prims[std::min<size_t>(n.prims.size(), kLeafHistogramBins - 1)];
      if (q.leaf_depth.size() <= size_t(n.depth)) q.leaf_depth.resize(size_t(n.depth) + 1, 0);
      ++q.leaf_depth[size_t(n.depth)];
      for (uint32_t prim : n.prims)
        if (prim < geometry.size()) leaves_of[prim].push_back(leaf_order);
      ++leaf_order;
      end_leaf[size_t(v.id)] = leaf_order;
      continue;
    }
    ++q.inner;
    q.sah_cost += p * double(t_t);
    stack.push_back({v.id, true});
    for (size_t k = n.children.size(); k-- > 0;) stack.push_back({n.children[k], false});
  }

  // EPO: for each triangle, the boxes it reaches into whose subtree does not list it.
  if (!with_epo) return q;
  q.epo_measured = true;
  const size_t count = geometry.size();
  std::vector<double> area(count, 0.0), inner(count, 0.0), leaf(count, 0.0);
  tbb::parallel_for(tbb::blocked_range<size_t>(0, count, 256), [&](const tbb::blocked_range<size_t>& r) {
    std::vector<int32_t> todo;
    for (size_t id = r.begin(); id != r.end(); ++id) {
      if (geometry.type(uint32_t(id)) != PrimType::triangle) continue;
      std::array<glm::dvec3, 3> v;
      for (int k = 0; k < 3; ++k) v[size_t(k)] = glm::dvec3(geometry.vertex(uint32_t(id), k));
      area[id] = 0.5 * glm::length(glm::cross(v[1] - v[0], v[2] - v[0]));
      if (!(area[id] > 0.0)) continue;
      const Bounds3 bounds = geometry.prim_bounds(uint32_t(id));
      const std::vector<uint32_t>& mine = leaves_of[id];
      todo.assign(1, 0);
      while (!todo.empty()) {
        const int32_t at = todo.back();
        todo.pop_back();
        const WideBvhView::Node& n = tree.nodes[size_t(at)];
        if (n.box.empty() || !n.box.overlaps(bounds)) continue;
        const uint32_t lo = first_leaf[size_t(at)], hi = end_leaf[size_t(at)];
        const bool holds = std::any_of(mine.begin(), mine.end(), [&](uint32_t o) { return o >= lo && o < hi; });
        if (!holds) {
          const double a = clipped_area(v, n.box);
          if (n.leaf)
            leaf[id] += double(t_i) * double(n.prims.size()) * a;
          else
            inner[id] += double(t_t) * a;
        }
        for (int32_t c : n.children) todo.push_back(c);
      }
    }
  });
  double total = 0.0;
  for (size_t id = 0; id < count; ++id) {
    total += area[id];
    q.epo_inner += inner[id];
    q.epo_leaves += leaf[id];
  }
  if (total > 0.0) {
    q.epo_inner /= total;
    q.epo_leaves /= total;
  }
  q.epo = q.epo_inner + q.epo_leaves;
  return q;
}

MeasuredCost measure_cost(const Accelerator& accel, const std::vector<Ray>& rays, float t_i, float t_t) {
  MeasuredCost m;
  CountingRecorder c;
  for (const Ray& r : rays) {
    Hit hit;
    accel.intersect_counted(r, &hit, c);
  }
  m.rays = rays.size();
  if (rays.empty()) return m;
  const double n = double(rays.size());
  m.nodes_per_ray = double(c.nodes + c.cells) / n;
  m.leaves_per_ray = double(c.leaves) / n;
  m.box_tests_per_ray = double(c.box_tests) / n;
  m.tests_per_ray = double(c.prim_tests) / n;
  m.cost_per_ray = double(t_t) * m.nodes_per_ray + double(t_i) * m.tests_per_ray;
  return m;
}

}  // namespace raystep
