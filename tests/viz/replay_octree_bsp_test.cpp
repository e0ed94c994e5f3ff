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
#include "replay.h"
#include "test_scenes.h"

namespace raystep::viz {
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
    ASSERT_FALSE(isBvhRay(&t, ray));
    if (!isTreeRay(ray)) continue;
    EXPECT_TRUE(isOctreeRay(&t, ray));
    EXPECT_TRUE(isOctreeRay(nullptr, ray));  // told by its events alone: it pushes the cell it is at
    for (int i = 0; i + 1 < int(ray.events.size()); ++i) {
      const Event& e = ray.events[size_t(i)];
      if (e.type != EventType::node || ray.events[size_t(i + 1)].type != EventType::push) continue;
      ReplayState s = replayAt(ray, i);
      OctreeChoice c = octreeChoice(t, ray, s);
      ASSERT_TRUE(c.valid) << "node " << e.node;
      ++inner;
      EXPECT_EQ(c.tEnter, e.t_min_node);
      ASSERT_FALSE(c.path.empty());
      ASSERT_LE(c.path.size(), 4u);  // a line crosses at most 4 of 8 octants
      EXPECT_TRUE(c.path.back().leavesParent);
      for (size_t k = 0; k + 1 < c.path.size(); ++k) {
        EXPECT_FALSE(c.path[k].leavesParent);
        EXPECT_LE(c.path[k].tExit, c.path[k + 1].tExit);  // front to back
        // The next child is the neighbour across the exit plane: the octants differ in that axis alone.
        EXPECT_EQ(c.path[k].octant ^ c.path[k + 1].octant, 1 << c.path[k].exitAxis);
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
        EXPECT_LT(c.path[0].tExit, ray.ray.tmin + 1e-3f * (1.f + std::fabs(c.tExit))) << "node " << e.node;
      }
      // Each visited child's octant names the trace's child list, and the first is picked by the entry plane.
      if (!c.visited.empty()) EXPECT_GE(c.visitedOctants[0], 0);
      const std::string why = explainRule(&t, ray, s);
      EXPECT_NE(why.find("Cell " + std::to_string(e.node)), std::string::npos) << why;
      EXPECT_NE(why.find("First child: " + std::to_string(c.path[0].node)), std::string::npos) << why;
      EXPECT_EQ(why.find("far child"), std::string::npos) << why;  // not the kd-tree's words
      EXPECT_EQ(why.find("splits"), std::string::npos) << why;
    }
    // The stopping rule in the lecture's words.
    for (int i = 0; i < int(ray.events.size()); ++i)
      if (ray.events[size_t(i)].type == EventType::hit_accepted &&
          ray.events[size_t(i)].reason != AcceptReason::structure_done) {
        const std::string why = explainRule(&t, ray, replayAt(ray, i));
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
    if (!isTreeRay(ray)) continue;
    EXPECT_FALSE(isOctreeRay(&t, ray));
    for (int i = 0; i + 1 < int(ray.events.size()); ++i) {
      const Event& e = ray.events[size_t(i)];
      if (e.type != EventType::node || ray.events[size_t(i + 1)].type == EventType::leaf) continue;
      ReplayState s = replayAt(ray, i);
      NodeCrossing c = nodeCrossing(t, ray, s);
      ASSERT_TRUE(c.valid) << "node " << e.node;
      const TraceNode* n = findNode(t, e.node);
      ASSERT_NE(n, nullptr);
      ASSERT_TRUE(n->has_plane);
      EXPECT_TRUE(c.general);
      EXPECT_EQ(c.normal, n->normal);
      EXPECT_EQ(c.offset, n->offset);
      slanted +=
          std::fabs(n->normal.x) != 1.f && std::fabs(n->normal.y) != 1.f && std::fabs(n->normal.z) != 1.f;
      kinds[int(c.crossing)]++;
      const float margin = std::max(std::fabs(c.tMin), std::fabs(c.tMax)) / 4096.f;
      const Event& next = ray.events[size_t(i + 1)];
      if (std::isfinite(c.tStar)) {
        // t* is where the ray meets the plane, within the kernel's rounding interval.
        EXPECT_LE(c.tLo, c.tStar);
        EXPECT_GE(c.tHi, c.tStar);
        const glm::vec3 p = ray.ray.at(c.tStar);
        const double scale = std::fabs(double(c.offset)) + glm::length(ray.ray.origin) +
                             std::fabs(c.tStar) * glm::length(ray.ray.direction);
        EXPECT_LE(std::fabs(glm::dot(glm::dvec3(n->normal), glm::dvec3(p)) - n->offset), 1e-5 * scale);
      }
      switch (c.crossing) {
        // The near child is the side the ray starts in (the slides'): alone when the plane lies beyond the
        // node's part of the ray or behind the origin; the far child alone when the ray crossed the plane
        // before entering the node.
        case Crossing::nearOnly:
          EXPECT_TRUE(!std::isfinite(c.tStar) || c.tLo > c.tMax + margin || (c.tHi < c.tMin - margin && c.tStar < 0))
              << c.tStar;
          EXPECT_EQ(c.nearChild, next.node);
          if (c.originSide != 0) EXPECT_EQ(c.nearIsBelow, c.originSide < 0);
          break;
        case Crossing::farOnly:
          EXPECT_LT(c.tHi, c.tMin - margin);
          EXPECT_GE(c.tStar, 0);
          EXPECT_EQ(c.farChild, next.node);
          break;
        case Crossing::both:
          // Intersect(near, t_min, t*) now, (far, t*, t_max) pushed: the kernel's intervals, t* widened to
          // its rounding interval.
          EXPECT_EQ(next.type, EventType::push);
          EXPECT_EQ(c.farChild, next.node);
          EXPECT_EQ(next.t_min_node, std::min(std::max(c.tLo, c.tMin), c.tMax));
          EXPECT_EQ(next.t_max_node, c.tMax);
          EXPECT_EQ(c.nearChild, ray.events[size_t(i + 2)].node);
          EXPECT_EQ(c.nearChild == e.node + 1, c.nearIsBelow);
          EXPECT_EQ(c.nearIsBelow, c.nDotDir > 0);
          break;
        case Crossing::inPlane:
          EXPECT_TRUE(std::isnan(c.tStar));
          break;
      }
      const std::string why = explainRule(&t, ray, s);
      EXPECT_NE(why.find("plane n.p = d"), std::string::npos) << why;
      EXPECT_NE(why.find("signed distance n.o - d"), std::string::npos) << why;
      EXPECT_EQ(why.find("splits x at"), std::string::npos) << why;  // never the kd-tree's axis words
      if (c.crossing == Crossing::both) EXPECT_NE(why.find("Intersect(far = "), std::string::npos) << why;
    }
  }
  EXPECT_GT(kinds[int(Crossing::nearOnly)], 0);
  EXPECT_GT(kinds[int(Crossing::farOnly)], 0);
  EXPECT_GT(kinds[int(Crossing::both)], 0);
  EXPECT_GT(slanted, 0);  // some planes are not the kd-tree's
}

}  // namespace
}  // namespace raystep::viz
