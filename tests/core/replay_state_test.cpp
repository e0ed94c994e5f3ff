// The debugger's replay model (core/replay/replay_state.h) on the mailbox trap of grid_test.cpp: a long
// triangle (0) found in cell 0 but lying in cell 2 (deferred), skipped by the mailbox in cell 1, where the
// small triangle (1) wins. Checks what the panels show at every step, and that the state depends on the step
// alone.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <set>

#include "raystep/accel/kdtree.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/explain.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/replay_state.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/grid_trace.h"
#include "raystep/trace/record_trace.h"
#include "test_scenes.h"

namespace raystep::replay {
namespace {

Trace trapTrace() {
  Geometry g;
  g.begin_object("trap", 0);
  g.add_triangle(glm::vec3(0.f, -1.f, 0.f), glm::vec3(0.f, 2.f, 0.f), glm::vec3(3.f, 0.5f, 0.6f));
  g.add_triangle(glm::vec3(1.5f, 0.f, 0.f), glm::vec3(1.5f, 1.f, 0.f), glm::vec3(1.5f, 0.f, 1.f));
  GridOptions o;
  o.resolution = std::array<int, 3>{3, 1, 1};
  UniformGrid grid(o);
  grid.build(g);
  RayRequest r;
  r.ray.origin = glm::vec3(-1.f, 0.5f, 0.5f);
  r.ray.direction = glm::vec3(1.f, 0.f, 0.f);
  return record_grid_trace(g, grid, {r}, "trap.json", "fnv1a64:0123456789abcdef");
}

TEST(Replay, MailboxTrapStepByStep) {
  Trace t = trapTrace();
  const TracedRay& ray = t.rays[0];
  ASSERT_EQ(ray.events.size(), 9u);  // begin, cell, test, deferred, cell, mailbox, test, accepted, end

  ReplayState s0 = replay_at(ray, 0);
  EXPECT_EQ(s0.cell_event, -1);
  EXPECT_FALSE(s0.has_interval);

  // In cell 0 the long triangle is being tested, then found (and deferred: t = 3.5 > t_exit = 2).
  ReplayState s2 = replay_at(ray, 2);
  EXPECT_EQ(s2.cell_event, 1);
  // The entry is the slab test's, widened outward by up to 2 gamma(3) (6 ulps) so that it never comes late.
  EXPECT_LE(s2.t_min, 1.f);
  EXPECT_GE(s2.t_min, 1.f - 2.f * gamma(3));
  EXPECT_FLOAT_EQ(s2.t_max, 2.f);
  ASSERT_EQ(s2.prims.size(), 1u);
  EXPECT_EQ(s2.prims[0].state, PrimState::testing);
  ReplayState s3 = replay_at(ray, 3);
  EXPECT_EQ(s3.prims[0].state, PrimState::hit);
  EXPECT_TRUE(s3.deferred);
  EXPECT_FALSE(s3.accepted);
  EXPECT_EQ(s3.nearest_prim, 0);
  EXPECT_FLOAT_EQ(s3.nearest_t, 3.5f);
  EXPECT_NE(explain_rule(ray, s3).find("t_exit(cell) = 2"), std::string::npos) << explain_rule(ray, s3);

  // Cell 1: the mailbox skips triangle 0; triangle 1 is not reached yet.
  ReplayState s4 = replay_at(ray, 4);
  EXPECT_EQ(s4.visited_cell_events, std::vector<int>{1});
  // Cell 0's Why steps on; cell 1 is the last: its Why names the DDA's axis but says the walk ends there.
  EXPECT_EQ(explain_rule(ray, replay_at(ray, 1)).rfind("tMax = (", 0), 0u)
      << explain_rule(ray, replay_at(ray, 1));
  ASSERT_GE(ray.events[4].next_axis, 0);  // the DDA had picked its axis when it entered the cell
  EXPECT_NE(explain_rule(ray, s4).find("the walk ends in this cell"), std::string::npos)
      << explain_rule(ray, s4);
  ASSERT_EQ(s4.prims.size(), 2u);
  EXPECT_EQ(s4.prims[0].state, PrimState::pending);
  EXPECT_EQ(s4.prims[1].state, PrimState::pending);
  ReplayState s5 = replay_at(ray, 5);
  EXPECT_EQ(s5.prims[0].state, PrimState::skipped);
  ASSERT_EQ(s5.mailbox.size(), 1u);
  EXPECT_EQ(s5.mailbox[0].prim, 0);
  EXPECT_EQ(s5.mailbox[0].cell[0], 0);
  EXPECT_EQ(s5.mailbox[0].skips, 1);
  EXPECT_EQ(s5.counters.mailbox_hits, 1u);

  // The small triangle wins inside cell 1: tmin(next cell) = 3 > tmax(ray) = 2.5.
  ReplayState s7 = replay_at(ray, 7);
  EXPECT_TRUE(s7.accepted);
  EXPECT_EQ(s7.nearest_prim, 1);
  EXPECT_FLOAT_EQ(s7.nearest_t, 2.5f);
  std::string rule = explain_rule(ray, s7);
  EXPECT_NE(rule.find("tmin(next cell) = t_exit = 3"), std::string::npos) << rule;
  EXPECT_NE(rule.find("t(hit) = 2.5"), std::string::npos) << rule;
  EXPECT_EQ(s7.counters.prim_tests, 2u);
  EXPECT_EQ(s7.counters.cells, 2u);
}

TEST(Replay, StateDependsOnTheStepAlone) {
  Trace t = trapTrace();
  const TracedRay& ray = t.rays[0];
  for (int k = 0; k < int(ray.events.size()); ++k) {
    ReplayState a = replay_at(ray, k), b = replay_at(ray, k);
    EXPECT_EQ(a.step, k);
    EXPECT_EQ(a.cell_event, b.cell_event);
    EXPECT_EQ(a.prims.size(), b.prims.size());
    EXPECT_EQ(describe_event(*a.event), describe_event(ray.events[size_t(k)]));
  }
  EXPECT_EQ(replay_at(ray, 100).step, int(ray.events.size()) - 1);  // clamped
}

TEST(Replay, FindsEventsByKind) {
  Trace t = trapTrace();
  const TracedRay& ray = t.rays[0];
  EXPECT_EQ(find_event(ray, 0, EventType::cell, true), 1);
  EXPECT_EQ(find_event(ray, 1, EventType::cell, true), 4);
  EXPECT_EQ(find_event(ray, 4, EventType::cell, false), 1);
  EXPECT_EQ(find_event(ray, 4, EventType::cell, true), -1);
  EXPECT_EQ(nth_event(ray, EventType::prim_test, 2), 6);
  EXPECT_EQ(nth_event(ray, EventType::prim_test, 3), -1);
}

// Trees: the stack is the pushes not yet popped.
TEST(Replay, TreeStackFromPushAndPop) {
  TracedRay ray;
  auto add = [&](EventType type, int node, float a, float b) {
    Event e;
    e.seq = uint32_t(ray.events.size());
    e.type = type;
    e.node = node;
    e.t_min_node = a;
    e.t_max_node = b;
    ray.events.push_back(e);
  };
  add(EventType::ray_begin, -1, 0, 0);
  add(EventType::node, 0, 1, 5);
  add(EventType::push, 2, 3, 5);
  add(EventType::leaf, 1, 1, 3);
  add(EventType::pop, 2, 3, 5);
  add(EventType::leaf, 2, 3, 5);
  add(EventType::ray_end, -1, 0, 0);
  EXPECT_EQ(replay_at(ray, 3).stack.size(), 1u);
  EXPECT_EQ(replay_at(ray, 3).stack[0].node, 2);
  EXPECT_FLOAT_EQ(replay_at(ray, 3).t_min, 1.f);
  EXPECT_TRUE(replay_at(ray, 4).stack.empty());
  EXPECT_FLOAT_EQ(replay_at(ray, 5).t_min, 3.f);
  EXPECT_EQ(replay_at(ray, 5).counters.pushes, 1u);
}

// The kd-tree panel's reading of a real walk: at every inner node, t* from the trace's split plane and the
// children crossed agree with what the kernel did next (push, or the one child visited), and at a push the
// inner node stays the current node while the stack grows by the far child.
TEST(Replay, KdCrossingsAgreeWithTheWalk) {
  Geometry g = test::make_soup(5, 200, 2);
  KdTree tree;
  tree.build(g);
  std::vector<RayRequest> rays;
  for (const Ray& r : random_rays(g.bounds(), 200, 9))
    rays.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
  Trace t = record_trace(g, tree, rays, "soup", "fnv1a64:0000000000000000");
  int kinds[4] = {0, 0, 0, 0};
  int stops = 0, walked = 0;
  for (const TracedRay& ray : t.rays) {
    if (!is_tree_ray(ray)) continue;  // it misses the root's box
    ++walked;
    for (int i = 0; i < int(ray.events.size()); ++i) {
      const Event& e = ray.events[size_t(i)];
      ReplayState s = replay_at(ray, i);
      // The nodes left behind, each once (a popped node, left for its own node event, is among them).
      std::set<int32_t> left(s.visited_nodes.begin(), s.visited_nodes.end());
      EXPECT_EQ(left.size(), s.visited_nodes.size());
      if (e.type == EventType::node && i > 0 && ray.events[size_t(i - 1)].type == EventType::node)
        EXPECT_EQ(left.count(ray.events[size_t(i - 1)].node), 1u);  // its parent, just left
      if (e.type == EventType::push) {
        ASSERT_GE(s.node_event, 0);
        EXPECT_EQ(ray.events[size_t(s.node_event)].type, EventType::node);
        EXPECT_EQ(s.node_event, i - 1);
        ASSERT_FALSE(s.stack.empty());
        EXPECT_EQ(s.stack.back().node, e.node);
        EXPECT_EQ(s.stack.back().push_event, i);
        EXPECT_EQ(s.t_min,
                  ray.events[size_t(i - 1)].t_min_node);  // the inner node's interval, not the far child's
      }
      if (e.type == EventType::hit_accepted && e.reason == AcceptReason::next_node_beyond) {
        ++stops;
        int pop = find_event(ray, i, EventType::pop, false);
        ASSERT_GE(pop, 0);
        EXPECT_LT(e.t, ray.events[size_t(pop)].t_min_node);
        std::string why = explain_rule(&t, ray, s);
        EXPECT_NE(why.find("tmin(next node) > tmax(ray)"), std::string::npos) << why;
      }
      if (e.type != EventType::node || ray.events[size_t(i + 1)].type == EventType::leaf) continue;
      NodeCrossing c = node_crossing(t, ray, s);
      ASSERT_TRUE(c.valid) << "node " << e.node;
      const TraceNode* n = find_node(t, e.node);
      ASSERT_NE(n, nullptr);
      EXPECT_EQ(c.axis, n->axis);
      const Event& next = ray.events[size_t(i + 1)];
      kinds[int(c.crossing)]++;
      switch (c.crossing) {
        // The near child is the side the ray starts in (the slides'): only it is visited when the plane lies
        // beyond the node's part of the ray or behind the origin; only the far one when the ray crossed the
        // plane before entering the node.
        case Crossing::near_only:
          EXPECT_TRUE(c.t_star > c.t_max || c.t_star < 0) << c.t_star;
          if (ray.ray.origin[c.axis] != c.split) EXPECT_EQ(c.near_is_below, ray.ray.origin[c.axis] < c.split);
          break;
        case Crossing::far_only:
          EXPECT_LT(c.t_star, c.t_min);
          EXPECT_GE(c.t_star, 0);
          break;
        case Crossing::both:
          // The far child's interval starts at t*, clamped to the node's: the kernel's own numbers.
          EXPECT_EQ(next.t_min_node, std::min(std::max(c.t_star, c.t_min), c.t_max));
          EXPECT_EQ(ray.events[size_t(i + 2)].t_max_node, next.t_min_node);
          EXPECT_EQ(c.near_child, ray.events[size_t(i + 2)].node);
          // Both visited: the near child is the first, the side the direction points into (the origin's side
          // but for an origin on the plane within rounding).
          EXPECT_EQ(c.near_child == e.node + 1, c.near_is_below);
          break;
        case Crossing::in_plane:
          EXPECT_TRUE(std::isnan(c.t_star));
          break;
      }
      std::string why = explain_rule(&t, ray, s);
      EXPECT_NE(why.find("t* ="), std::string::npos) << why;
    }
  }
  // The rays meet every kind of inner-node decision but the in-plane one, and the tree's stopping rule.
  EXPECT_GT(kinds[int(Crossing::near_only)], 0);
  EXPECT_GT(kinds[int(Crossing::far_only)], 0);
  EXPECT_GT(kinds[int(Crossing::both)], 0);
  EXPECT_GT(stops, 0);
  EXPECT_GT(walked, 50);
}

// Rays parallel to split planes (direction components +0 and -0): t* is infinite, the walk stays on the
// origin's side of each plane it runs along, and the explanation says the ray runs parallel.
TEST(Replay, KdRaysParallelToAPlaneStayOnTheirSide) {
  Geometry g = test::make_soup(7, 200, 0);
  KdTree tree;
  tree.build(g);
  Bounds3 b = g.bounds();
  std::vector<RayRequest> rays;
  for (int i = 0; i < 40; ++i) {
    float u = (i % 8 + 0.5f) / 8.f, v = (i / 8 + 0.5f) / 5.f;
    glm::vec3 o(b.lo.x + u * (b.hi.x - b.lo.x), b.lo.y + v * (b.hi.y - b.lo.y), b.hi.z + 1.f);
    Ray r;
    r.origin = o;
    r.direction = glm::vec3(i % 2 ? 0.f : -0.f, i % 3 ? -0.f : 0.f, -1.f);
    rays.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
  }
  Trace t = record_trace(g, tree, rays, "soup", "fnv1a64:0000000000000000");
  int parallel = 0;
  for (const TracedRay& ray : t.rays)
    for (int i = 0; i + 1 < int(ray.events.size()); ++i) {
      const Event& e = ray.events[size_t(i)];
      if (e.type != EventType::node || ray.events[size_t(i + 1)].type == EventType::leaf) continue;
      ReplayState s = replay_at(ray, i);
      NodeCrossing c = node_crossing(t, ray, s);
      ASSERT_TRUE(c.valid);
      if (!std::isinf(c.t_star)) continue;
      ++parallel;
      ASSERT_NE(c.crossing, Crossing::both);
      int32_t visited = c.near_child >= 0 ? c.near_child : c.far_child;
      bool originBelow = ray.ray.origin[c.axis] < c.split;
      if (ray.ray.origin[c.axis] != c.split)
        EXPECT_EQ(visited == e.node + 1, originBelow) << "node " << e.node;
      std::string why = explain_rule(&t, ray, s);
      EXPECT_NE(why.find("parallel"), std::string::npos) << why;
    }
  EXPECT_GT(parallel, 20);
}

// Ties: a primitive hit at the same t as the nearest so far, with a higher id, does not become the nearest.
TEST(Replay, ATieGoesToTheLowerPrimitiveId) {
  TracedRay ray;
  auto add = [&](EventType type, int prim, bool hit, float t) {
    Event& e = ray.events.emplace_back();
    e.seq = uint32_t(ray.events.size() - 1);
    e.type = type;
    e.prim = prim;
    e.hit = hit;
    e.t = t;
  };
  add(EventType::ray_begin, -1, false, 0.f);
  add(EventType::prim_test, 3, true, 2.f);
  add(EventType::prim_test, 5, true, 2.f);
  add(EventType::prim_test, 1, true, 2.f);
  add(EventType::ray_end, 1, true, 2.f);
  ReplayState s2 = replay_at(ray, 2);
  EXPECT_EQ(s2.nearest_prim, 3);
  EXPECT_NE(explain_rule(ray, s2).find("tie goes to the lower id"), std::string::npos)
      << explain_rule(ray, s2);
  EXPECT_EQ(replay_at(ray, 3).nearest_prim, 1);
  EXPECT_NE(explain_rule(ray, replay_at(ray, 3)).find("It becomes the nearest hit"), std::string::npos);
}

// The Why text of a triangle's test compares the watertight test with Möller–Trumbore on that ray and
// triangle. Lesson 14's leak (scenes/leak.json, pixel 33,19): the ray (33.5, 28.5, 40) along -z passes within
// rounding of the edge (28.70, 36.68, 6.29)-(38.93, 19.25, 12.73) shared by triangles 0 and 1.
// Möller–Trumbore rejects both: triangle 0 finds u + v = 1 + 8.9e-08 > 1, triangle 1 u = -2.1e-08 < 0. The
// watertight test finds the edge functions within their rounding error bound and settles them in the
// double-precision filter: 0 hit, 1 missed.
TEST(Replay, PrimTestComparesTheWatertightTestWithMollerTrumbore) {
  glm::vec3 v1(45.6170235f, 29.0892525f, -4.83244371f), v2(19.3059406f, 17.6921577f, 4.83244371f),
      v3(28.6986485f, 36.6775398f, 6.29141855f), v5(38.9325066f, 19.2474918f, 12.7304964f);
  Geometry g;
  g.begin_object("tilted octahedron", 0);
  g.add_triangle(v1, v3, v5);  // its faces 1 and 2 (octahedron.obj's order), sharing the edge v3-v5
  g.add_triangle(v3, v2, v5);
  GridOptions o;
  o.resolution = std::array<int, 3>{1, 1, 1};
  UniformGrid grid(o);
  grid.build(g);
  RayRequest r;
  r.ray.origin = glm::vec3(33.5f, 28.5f, 40.f);
  r.ray.direction = glm::vec3(0.f, 0.f, -1.f);
  Trace t = record_grid_trace(g, grid, {r}, "leak.json", "fnv1a64:0123456789abcdef");
  const TracedRay& ray = t.rays[0];
  int first = nth_event(ray, EventType::prim_test, 1), second = nth_event(ray, EventType::prim_test, 2);
  ASSERT_GE(second, 0);
  ASSERT_EQ(ray.events[size_t(first)].prim, 0);
  EXPECT_TRUE(ray.events[size_t(first)].hit);
  EXPECT_FALSE(ray.events[size_t(second)].hit);
  std::string why0 = explain_rule(&t, ray, replay_at(ray, first)),
              why1 = explain_rule(&t, ray, replay_at(ray, second));
  EXPECT_NE(
      why0.find("\nThis ray and triangle alone: watertight hit (settled by the double-precision filter); "
                "Möller–Trumbore miss (u + v = 1 + 8.9e-08 > 1)."),
      std::string::npos)
      << why0;
  EXPECT_NE(
      why1.find("\nThis ray and triangle alone: watertight miss (settled by the double-precision filter); "
                "Möller–Trumbore miss (u = -2.1e-08 < 0)."),
      std::string::npos)
      << why1;
  // Without the trace's vertices there is nothing to compare.
  EXPECT_EQ(explain_rule(ray, replay_at(ray, first)).find("Möller"), std::string::npos);

  // Away from edges both agree, in float alone: a hit inside, and a miss with u > 1 (u: p1's weight).
  TracePrimitive tri;
  tri.v[0] = glm::vec3(0.f, 0.f, 0.f), tri.v[1] = glm::vec3(1.f, 0.f, 0.f),
  tri.v[2] = glm::vec3(0.f, 1.f, 0.f);
  TracedRay inside;
  inside.ray.origin = glm::vec3(0.25f, 0.25f, 1.f);
  inside.ray.direction = glm::vec3(0.f, 0.f, -1.f);
  EXPECT_EQ(compare_triangle_tests(inside, tri),
            "This ray and triangle alone: watertight hit (float alone); Möller–Trumbore hit.");
  TracedRay outside = inside;
  outside.ray.origin.x = 2.f;
  EXPECT_EQ(compare_triangle_tests(outside, tri),
            "This ray and triangle alone: watertight miss (float alone); Möller–Trumbore miss (u = 2 > 1).");
  // A ray exactly through an edge of general coordinates: the edge function is exactly 0, which no error
  // bound can prove, so rational arithmetic settles it (and the edge counts as inside).
  TracePrimitive edge;
  edge.v[0] = glm::vec3(0.7f, 0.9f, 0.1f);
  edge.v[1] = glm::vec3(1.f - 0.7f, 1.f - 0.9f, -0.2f);  // exact: the edge's midpoint in x, y is (0.5, 0.5)
  edge.v[2] = glm::vec3(0.05f, 0.85f, 0.3f);
  TracedRay through = inside;
  through.ray.origin = glm::vec3(0.5f, 0.5f, 1.f);
  std::string line = compare_triangle_tests(through, edge);
  EXPECT_EQ(
      line.rfind("This ray and triangle alone: watertight hit (settled by exact rational arithmetic); ", 0),
      0u)
      << line;
  // Not a triangle: no line.
  TracePrimitive sphere;
  sphere.type = PrimType::sphere;
  sphere.radius = 1.f;
  EXPECT_EQ(compare_triangle_tests(inside, sphere), "");
}

// Without mailboxes a primitive in two cells is tested twice: the second hit is no nearer than the first.
TEST(Replay, ASecondTestOfTheNearestPrimitiveIsNotANewHit) {
  TracedRay ray;
  auto ev = [&](EventType type) {
    Event e;
    e.seq = uint32_t(ray.events.size());
    e.type = type;
    ray.events.push_back(e);
    return &ray.events.back();
  };
  ev(EventType::ray_begin);
  Event* c0 = ev(EventType::cell);
  c0->t_exit = 2.f;
  c0->next_axis = 0;
  Event* t0 = ev(EventType::prim_test);
  t0->prim = 4, t0->hit = true, t0->t = 3.f;
  ev(EventType::hit_deferred)->prim = 4;
  Event* c1 = ev(EventType::cell);
  c1->cell[0] = 1, c1->t_enter = 2.f, c1->t_exit = 4.f, c1->next_axis = 0;
  Event* t1 = ev(EventType::prim_test);
  t1->prim = 4, t1->hit = true, t1->t = 3.f;
  std::string first = explain_rule(ray, replay_at(ray, 2)), second = explain_rule(ray, replay_at(ray, 5));
  EXPECT_NE(first.find("nearer than any hit so far"), std::string::npos) << first;
  EXPECT_EQ(second.find("nearer than any hit so far"), std::string::npos) << second;
  EXPECT_NE(second.find("already the nearest hit"), std::string::npos) << second;
}

// A BVH walk as the trace contract (version 3) writes it: root 0 with two overlapping leaves, 1 (prim 0) and
// 2 (prim 1). Both boxes are hit; the nearer, 1, is entered and 2 pushed; prim 0 hits at t = 1.2, so popped 2
// (t_near = 1.5) is skipped and the hit is final.
TracedRay bvhRay() {
  TracedRay r;
  r.ray.origin = glm::vec3(0.f);
  r.ray.direction = glm::vec3(1.f, 0.f, 0.f);
  auto ev = [&](EventType type) -> Event& {
    Event e;
    e.seq = uint32_t(r.events.size());
    e.type = type;
    r.events.push_back(e);
    return r.events.back();
  };
  auto tree = [&](EventType type, int32_t node, int32_t depth, float a, float b) {
    Event& e = ev(type);
    e.node = node;
    e.depth = depth;
    e.t_min_node = a;
    e.t_max_node = b;
  };
  auto box = [&](int32_t child, bool hit, float a, float b) {
    Event& e = ev(EventType::box_test);
    e.parent = 0;
    e.node = child;
    e.depth = 1;
    e.hit = hit;
    e.t_min_node = a;
    e.t_max_node = b;
  };
  ev(EventType::ray_begin);                // 0
  tree(EventType::node, 0, 0, 1.f, 4.f);   // 1
  box(1, true, 1.f, 3.f);                  // 2
  box(2, true, 1.5f, 4.f);                 // 3: overlaps [1, 3]
  tree(EventType::push, 2, 1, 1.5f, 4.f);  // 4
  tree(EventType::node, 1, 1, 1.f, 3.f);   // 5
  tree(EventType::leaf, 1, 1, 1.f, 3.f);   // 6
  {
    Event& e = ev(EventType::prim_test);  // 7
    e.prim = 0;
    e.hit = true;
    e.t = 1.2f;
  }
  tree(EventType::pop, 2, 1, 1.5f, 4.f);   // 8
  tree(EventType::skip, 2, 1, 1.5f, 4.f);  // 9
  {
    Event& e = ev(EventType::hit_accepted);  // 10
    e.prim = 0;
    e.t = 1.2f;
    e.reason = AcceptReason::structure_done;
  }
  {
    Event& e = ev(EventType::ray_end);  // 11
    e.prim = 0;
    e.t = 1.2f;
  }
  return r;
}

TEST(Replay, BvhChildrenOrderPushAndSkip) {
  const TracedRay r = bvhRay();
  EXPECT_TRUE(is_tree_ray(r));
  EXPECT_TRUE(is_bvh_ray(nullptr, r));

  // At the root: the box tests are not reached yet, so the choice is not known.
  ReplayState s1 = replay_at(r, 1);
  BvhChoice c1 = bvh_choice(r, s1);
  ASSERT_TRUE(c1.valid);
  ASSERT_EQ(c1.tests.size(), 2u);
  EXPECT_FALSE(c1.tests[0].done);
  EXPECT_FALSE(c1.decided);
  EXPECT_NE(explain_rule(r, s1).find("may overlap"), std::string::npos) << explain_rule(r, s1);

  // After the second test: both hit, overlapping; nearer first (1), 2 pushed.
  ReplayState s3 = replay_at(r, 3);
  BvhChoice c3 = bvh_choice(r, s3);
  EXPECT_TRUE(c3.decided);
  EXPECT_EQ(c3.first, 1);
  EXPECT_EQ(c3.pushed, std::vector<int32_t>{2});
  EXPECT_FLOAT_EQ(c3.tests[1].t_near, 1.5f);
  EXPECT_EQ(s3.counters.box_tests, 2u);
  const std::string why3 = explain_rule(r, s3);
  EXPECT_NE(why3.find("bounding volumes can overlap"), std::string::npos) << why3;
  EXPECT_NE(why3.find("Nearer first: enter child 1"), std::string::npos) << why3;
  EXPECT_NE(why3.find("push child 2"), std::string::npos) << why3;

  // The leaf says why there is no mailbox.
  const std::string why6 = explain_rule(r, replay_at(r, 6));
  EXPECT_NE(why6.find("exactly one leaf"), std::string::npos) << why6;

  // The skip: its rule with the numbers, the node not counted as visited, the stack empty.
  ReplayState s9 = replay_at(r, 9);
  EXPECT_EQ(s9.skipped_nodes, std::vector<int32_t>{2});
  EXPECT_TRUE(s9.stack.empty());
  const std::string why9 = explain_rule(r, s9);
  EXPECT_NE(why9.find("skip: t_near = 1.5 > t of the nearest hit = 1.2"), std::string::npos) << why9;
  ReplayState s11 = replay_at(r, 11);
  EXPECT_EQ(std::count(s11.visited_nodes.begin(), s11.visited_nodes.end(), 2), 0);
  EXPECT_EQ(describe_event(r.events[3]), "3  box_test  child 2 of 0: hit [1.5, 4]");
}

}  // namespace
}  // namespace raystep::replay
