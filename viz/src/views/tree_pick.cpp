#include "views/tree_pick.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include <glm/geometric.hpp>

#include "app/session.h"

namespace raystep::viz {

namespace {

// The leaves a point location reaches, in the order it reaches them (the "below" side first).
template <class Visit>
void collect(uint32_t node, std::vector<uint32_t>* leaves, Visit&& children) {
  std::vector<uint32_t> stack{node};
  while (!stack.empty()) {
    uint32_t n = stack.back();
    stack.pop_back();
    std::vector<uint32_t> next;
    if (!children(n, &next)) {
      leaves->push_back(n);
      continue;
    }
    for (auto it = next.rbegin(); it != next.rend(); ++it) stack.push_back(*it);  // first child on top
  }
}

bool inside(const Bounds3& b, const glm::vec3& p, float tol) {
  for (int a = 0; a < 3; ++a)
    if (!(p[a] >= b.lo[a] - tol && p[a] <= b.hi[a] + tol)) return false;
  return true;
}

// The first leaf listing prim, else the first leaf; -1 for none.
template <class Lists>
int choose(const std::vector<uint32_t>& leaves, int prim, Lists&& lists) {
  if (leaves.empty()) return -1;
  if (prim >= 0)
    for (uint32_t n : leaves)
      if (lists(n, uint32_t(prim))) return int(n);
  return int(leaves.front());
}

bool listed(const std::vector<uint32_t>& index, uint32_t first, uint32_t count, uint32_t prim) {
  auto begin = index.begin() + first, end = begin + count;
  return std::find(begin, end, prim) != end;
}

}  // namespace

int leafAtPick(const StructureData& s, const glm::vec3& p, int prim) {
  std::vector<uint32_t> leaves;
  if (const KdTree* kd = s.kdTree(); kd && !kd->data().nodes.empty()) {
    const KdTreeData& t = kd->data();
    const float tol = 1e-5f * glm::length(t.bounds.hi - t.bounds.lo);
    if (!inside(t.bounds, p, tol)) return -1;
    collect(0, &leaves, [&](uint32_t n, std::vector<uint32_t>* next) {
      const KdNode& node = t.nodes[n];
      if (node.is_leaf()) return false;
      const float d = p[node.axis()] - node.split;
      if (d < tol) next->push_back(n + 1);
      if (d > -tol) next->push_back(node.above_child());
      return true;
    });
    return choose(leaves, prim, [&](uint32_t n, uint32_t q) {
      return listed(t.prim_index, t.nodes[n].first_prim, t.nodes[n].prim_count(), q);
    });
  }
  if (const Octree* o = s.octree(); o && !o->data().nodes.empty()) {
    const OctreeData& t = o->data();
    const float tol = 1e-5f * glm::length(t.bounds.hi - t.bounds.lo);
    if (!inside(t.bounds, p, tol)) return -1;
    collect(0, &leaves, [&](uint32_t n, std::vector<uint32_t>* next) {
      const OctreeNode& node = t.nodes[n];
      if (node.is_leaf()) return false;
      // Child i: bit a set for the upper half on axis a; near the centre plane, both halves.
      const Bounds3& b = t.info[n].box;
      for (int i = 0; i < 1 << t.axes; ++i) {  // eight, or a quadtree's four (z not cut)
        bool ok = true;
        for (int a = 0; a < t.axes && ok; ++a) {
          const float d = p[a] - 0.5f * (b.lo[a] + b.hi[a]);
          ok = (i >> a & 1) ? d > -tol : d < tol;
        }
        if (ok) next->push_back(node.child(i));
      }
      return true;
    });
    return choose(leaves, prim, [&](uint32_t n, uint32_t q) {
      return listed(t.prim_index, t.nodes[n].first, t.nodes[n].prim_count(), q);
    });
  }
  if (const BspTree* bsp = s.bsp(); bsp && !bsp->data().nodes.empty()) {
    const BspTreeData& t = bsp->data();
    const double tol = 1e-5 * double(glm::length(t.bounds.hi - t.bounds.lo));
    if (!inside(t.bounds, p, float(tol))) return -1;
    collect(0, &leaves, [&](uint32_t n, std::vector<uint32_t>* next) {
      const BspNode& node = t.nodes[n];
      if (node.is_leaf()) return false;
      const double d = glm::dot(glm::dvec3(node.plane.normal), glm::dvec3(p)) - double(node.plane.offset);
      if (d < tol) next->push_back(n + 1);
      if (d > -tol) next->push_back(node.above_child());
      return true;
    });
    return choose(leaves, prim, [&](uint32_t n, uint32_t q) {
      return listed(t.prim_index, t.nodes[n].first_prim(), t.nodes[n].prim_count(), q);
    });
  }
  if (const Bvh* bvh = s.bvh(); bvh && !bvh->data().nodes.empty()) {
    const BvhData& t = bvh->data();
    const Bounds3& root = t.nodes[0].box;
    const float tol = 1e-5f * glm::length(root.hi - root.lo);
    int best = -1, firstListed = -1;
    float bestSize = 0.f;
    for (uint32_t n = 0; n < t.nodes.size(); ++n) {
      const BvhNode& node = t.nodes[n];
      if (!node.is_leaf()) continue;
      // After spatial splits a primitive sits in several leaves: the one whose box holds the point.
      if (prim >= 0 && listed(t.prim_index, node.first_prim(), node.prim_count(), uint32_t(prim))) {
        if (inside(node.box, p, tol)) return int(n);
        if (firstListed < 0) firstListed = int(n);
        continue;
      }
      const float size = glm::length(node.box.hi - node.box.lo);
      if (prim < 0 && inside(node.box, p, tol) && (best < 0 || size < bestSize)) {
        best = int(n);
        bestSize = size;
      }
    }
    return prim >= 0 && firstListed >= 0 ? firstListed : best;
  }
  if (s.wideView && !s.wideView->nodes.empty()) {  // bvh4, bvh8: the same rule as the binary BVH
    const std::vector<WideBvhView::Node>& nodes = s.wideView->nodes;
    const Bounds3& root = nodes[0].box;
    const float tol = 1e-5f * glm::length(root.hi - root.lo);
    int best = -1;
    float bestSize = 0.f;
    for (uint32_t n = 0; n < nodes.size(); ++n) {
      if (!nodes[n].leaf) continue;
      const std::vector<uint32_t>& prims = nodes[n].prims;
      if (prim >= 0 && std::find(prims.begin(), prims.end(), uint32_t(prim)) != prims.end()) return int(n);
      const float size = glm::length(nodes[n].box.hi - nodes[n].box.lo);
      if (prim < 0 && inside(nodes[n].box, p, tol) && (best < 0 || size < bestSize)) {
        best = int(n);
        bestSize = size;
      }
    }
    return best;
  }
  return -1;
}

}  // namespace raystep::viz
