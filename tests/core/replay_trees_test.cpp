// The replay model on the octree and the general BSP tree: recorded walks of random rays through a soup,
// and at every inner node what the state panel would say. Octree: the child order by Revelles' planes (entry
// plane, then exit planes) is the order the kernel visits the children in; BSP: t* = (d - n.o) / (n.dir) is
// where the ray meets the node's plane, inside the kernel's rounding interval, and the near and far children
// and the intervals the walk gives them agree with it. Plain C++, no display.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "raystep/accel/bsp.h"
#include "raystep/accel/octree.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/record_trace.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/explain.h"
#include "test_scenes.h"

namespace raystep::replay {
namespace {

Trace traceOf(const Geometry& g, const Accelerator& accel, int rays, uint64_t seed) {
  std::vector<RayRequest> requests;
  for (const Ray& r : random_rays(g.bounds(), size_t(rays), seed))
    requests.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
  return record_trace(g, accel, requests, "soup", "fnv1a64:0000000000000000");
}

TEST(ReplayOctree, ChildOrderByEntryAndExitPlanesIsTheWalks) {
  Geometry g = test::make_soup(7, 300, 3);
  OctreeOptions o;
  o.leaf_size = 2;
  Octree tree(o);
  tree.build(g);
  Trace t = traceOf(g, tree, 300, 11);
  int inner = 0, fullPaths = 0, prefixes = 0, differ = 0, multi = 0, behind = 0;
  for (const TracedRay& ray : t.rays) {
    ASSERT_FALSE(is_bvh_ray(&t, ray));
    if (!is_tree_ray(ray)) continue;
    EXPECT_TRUE(is_octree_ray(&t, ray));
    EXPECT_TRUE(is_octree_ray(nullptr, ray));  // told by its events alone: it pushes the cell it is at
    for (int i = 0; i + 1 < int(ray.events.size()); ++i) {
      const Event& e = ray.events[size_t(i)];
      if (e.type != EventType::node || ray.events[size_t(i + 1)].type != EventType::push) continue;
      ReplayState s = replay_at(ray, i);
      OctreeChoice c = octree_choice(t, ray, s);
      ASSERT_TRUE(c.valid) << "node " << e.node;
      ++inner;
      EXPECT_EQ(c.t_enter, e.t_min_node);
      ASSERT_FALSE(c.path.empty());
      ASSERT_LE(c.path.size(), 4u);  // a line crosses at most 4 of 8 octants
      EXPECT_TRUE(c.path.back().leaves_parent);
      for (size_t k = 0; k + 1 < c.path.size(); ++k) {
        EXPECT_FALSE(c.path[k].leaves_parent);
        EXPECT_LE(c.path[k].t_exit, c.path[k + 1].t_exit);  // front to back
        // The next child is the neighbour across the exit plane: the octants differ in that axis alone.
        EXPECT_EQ(c.path[k].octant ^ c.path[k + 1].octant, 1 << c.path[k].exit_axis);
      }
      multi += c.path.size() > 1;
      // The walk visits the planes' order, or a part of it: it passes over the children behind the ray's
      // start (a ray starting inside the cell) and stops at a child beyond the ray's end or the nearest hit.
      // A grazed child (a near tie, walked for safety) would be extra: counted, not expected on random rays.
      std::vector<int32_t> planned;
      for (const OctreeChildStep& st : c.path) planned.push_back(st.node);
      size_t at = 0;
      for (int32_t v : c.visited) {
        while (at < planned.size() && planned[at] != v) ++at;
        if (at < planned.size())
          ++at;
        else
          ++differ;
      }
      fullPaths += c.visited == planned;
      prefixes += c.visited.size() <= planned.size() &&
                  std::equal(c.visited.begin(), c.visited.end(), planned.begin());
      // The children passed over at the start lie behind the ray's start: they end before t = tmin.
      if (!c.visited.empty() && c.visited[0] != planned[0]) {
        ++behind;
        EXPECT_LT(c.path[0].t_exit, ray.ray.tmin + 1e-3f * (1.f + std::fabs(c.t_exit))) << "node " << e.node;
      }
      // Each visited child's octant names the trace's child list, and the first is picked by the entry plane.
      if (!c.visited.empty()) EXPECT_GE(c.visited_octants[0], 0);
      const std::string why = explain_rule(&t, ray, s);
      EXPECT_NE(why.find("Cell " + std::to_string(e.node)), std::string::npos) << why;
      EXPECT_NE(why.find("First child: " + std::to_string(c.path[0].node)), std::string::npos) << why;
      EXPECT_EQ(why.find("far child"), std::string::npos) << why;  // not the kd-tree's words
      EXPECT_EQ(why.find("splits"), std::string::npos) << why;
    }
    // The stopping rule in the lecture's words.
    for (int i = 0; i < int(ray.events.size()); ++i)
      if (ray.events[size_t(i)].type == EventType::hit_accepted &&
          ray.events[size_t(i)].reason != AcceptReason::structure_done) {
        const std::string why = explain_rule(&t, ray, replay_at(ray, i));
        EXPECT_NE(why.find("tmin(cell) > tmax(ray)"), std::string::npos) << why;
      }
  }
  EXPECT_GT(inner, 300);
  EXPECT_GT(multi, inner / 4);  // most inner cells are crossed through several children
  EXPECT_GT(fullPaths, inner / 2);
  EXPECT_EQ(differ, 0) << prefixes << " prefixes of " << inner;
  EXPECT_GT(prefixes, inner / 2);
  std::printf("octree: %d inner cells, %d whole paths, %d prefixes, %d starting behind\n", inner, fullPaths,
              prefixes, behind);
}

TEST(ReplayBsp, TStarAndChildrenAgreeWithTheWalk) {
  Geometry g = test::make_soup(5, 300, 2);
  BspTree tree;
  tree.build(g);
  Trace t = traceOf(g, tree, 300, 9);
  int kinds[4] = {0, 0, 0, 0};
  int slanted = 0;
  for (const TracedRay& ray : t.rays) {
    if (!is_tree_ray(ray)) continue;
    EXPECT_FALSE(is_octree_ray(&t, ray));
    for (int i = 0; i + 1 < int(ray.events.size()); ++i) {
      const Event& e = ray.events[size_t(i)];
      if (e.type != EventType::node || ray.events[size_t(i + 1)].type == EventType::leaf) continue;
      ReplayState s = replay_at(ray, i);
      NodeCrossing c = node_crossing(t, ray, s);
      ASSERT_TRUE(c.valid) << "node " << e.node;
      const TraceNode* n = find_node(t, e.node);
      ASSERT_NE(n, nullptr);
      ASSERT_TRUE(n->has_plane);
      EXPECT_TRUE(c.general);
      EXPECT_EQ(c.normal, n->normal);
      EXPECT_EQ(c.offset, n->offset);
      slanted +=
          std::fabs(n->normal.x) != 1.f && std::fabs(n->normal.y) != 1.f && std::fabs(n->normal.z) != 1.f;
      kinds[int(c.crossing)]++;
      const float margin = std::max(std::fabs(c.t_min), std::fabs(c.t_max)) / 4096.f;
      const Event& next = ray.events[size_t(i + 1)];
      if (std::isfinite(c.t_star)) {
        // t* is where the ray meets the plane, within the kernel's rounding interval.
        EXPECT_LE(c.t_lo, c.t_star);
        EXPECT_GE(c.t_hi, c.t_star);
        const glm::vec3 p = ray.ray.at(c.t_star);
        const double scale = std::fabs(double(c.offset)) + glm::length(ray.ray.origin) +
                             std::fabs(c.t_star) * glm::length(ray.ray.direction);
        EXPECT_LE(std::fabs(glm::dot(glm::dvec3(n->normal), glm::dvec3(p)) - n->offset), 1e-5 * scale);
      }
      switch (c.crossing) {
        // The near child is the side the ray starts in (the slides'): alone when the plane lies beyond the
        // node's part of the ray or behind the origin; the far child alone when the ray crossed the plane
        // before entering the node.
        case Crossing::near_only:
          EXPECT_TRUE(!std::isfinite(c.t_star) || c.t_lo > c.t_max + margin || (c.t_hi < c.t_min - margin && c.t_star < 0))
              << c.t_star;
          EXPECT_EQ(c.near_child, next.node);
          if (c.origin_side != 0) EXPECT_EQ(c.near_is_below, c.origin_side < 0);
          break;
        case Crossing::far_only:
          EXPECT_LT(c.t_hi, c.t_min - margin);
          EXPECT_GE(c.t_star, 0);
          EXPECT_EQ(c.far_child, next.node);
          break;
        case Crossing::both:
          // Intersect(near, t_min, t*) now, (far, t*, t_max) pushed: the kernel's intervals, t* widened to
          // its rounding interval.
          EXPECT_EQ(next.type, EventType::push);
          EXPECT_EQ(c.far_child, next.node);
          EXPECT_EQ(next.t_min_node, std::min(std::max(c.t_lo, c.t_min), c.t_max));
          EXPECT_EQ(next.t_max_node, c.t_max);
          EXPECT_EQ(c.near_child, ray.events[size_t(i + 2)].node);
          EXPECT_EQ(c.near_child == e.node + 1, c.near_is_below);
          EXPECT_EQ(c.near_is_below, c.n_dot_dir > 0);
          break;
        case Crossing::in_plane:
          EXPECT_TRUE(std::isnan(c.t_star));
          break;
      }
      const std::string why = explain_rule(&t, ray, s);
      EXPECT_NE(why.find("plane n.p = d"), std::string::npos) << why;
      EXPECT_NE(why.find("signed distance n.o - d"), std::string::npos) << why;
      EXPECT_EQ(why.find("splits x at"), std::string::npos) << why;  // never the kd-tree's axis words
      if (c.crossing == Crossing::both) EXPECT_NE(why.find("Intersect(far = "), std::string::npos) << why;
    }
  }
  EXPECT_GT(kinds[int(Crossing::near_only)], 0);
  EXPECT_GT(kinds[int(Crossing::far_only)], 0);
  EXPECT_GT(kinds[int(Crossing::both)], 0);
  EXPECT_GT(slanted, 0);  // some planes are not the kd-tree's
}

}  // namespace
}  // namespace raystep::replay
