// The replayer (replay/replayer.h): every state from a checkpoint equals the state replayed from the ray's
// start, on walks through every structure that records events, stepped forward, back and by jumps.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>

#include "raystep/accel/structure_options.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/replayer.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/record_trace.h"
#include "test_scenes.h"

namespace raystep::replay {
namespace {

void expectSame(const ReplayState& a, const ReplayState& b, const std::string& where) {
  SCOPED_TRACE(where);
  EXPECT_EQ(a.step, b.step);
  EXPECT_EQ(a.event, b.event);
  EXPECT_EQ(a.cell_event, b.cell_event);
  EXPECT_EQ(a.visited_cell_events, b.visited_cell_events);
  EXPECT_EQ(a.node_event, b.node_event);
  ASSERT_EQ(a.stack.size(), b.stack.size());
  for (size_t i = 0; i < a.stack.size(); ++i) {
    EXPECT_EQ(a.stack[i].node, b.stack[i].node);
    EXPECT_EQ(a.stack[i].push_event, b.stack[i].push_event);
    EXPECT_EQ(a.stack[i].t_min, b.stack[i].t_min);
    EXPECT_EQ(a.stack[i].t_max, b.stack[i].t_max);
  }
  EXPECT_EQ(a.visited_nodes, b.visited_nodes);
  EXPECT_EQ(a.skipped_nodes, b.skipped_nodes);
  EXPECT_EQ(a.block_event, b.block_event);
  ASSERT_EQ(a.prims.size(), b.prims.size());
  for (size_t i = 0; i < a.prims.size(); ++i) {
    EXPECT_EQ(a.prims[i].prim, b.prims[i].prim);
    EXPECT_EQ(a.prims[i].state, b.prims[i].state);
  }
  ASSERT_EQ(a.mailbox.size(), b.mailbox.size());
  for (size_t i = 0; i < a.mailbox.size(); ++i) {
    EXPECT_EQ(a.mailbox[i].prim, b.mailbox[i].prim);
    EXPECT_EQ(a.mailbox[i].tested_in_cell_event, b.mailbox[i].tested_in_cell_event);
    EXPECT_EQ(a.mailbox[i].leaf, b.mailbox[i].leaf);
    EXPECT_EQ(a.mailbox[i].hit, b.mailbox[i].hit);
    EXPECT_EQ(a.mailbox[i].skips, b.mailbox[i].skips);
  }
  EXPECT_EQ(a.counters.cells, b.counters.cells);
  EXPECT_EQ(a.counters.nodes, b.counters.nodes);
  EXPECT_EQ(a.counters.prim_tests, b.counters.prim_tests);
  EXPECT_EQ(a.counters.mailbox_hits, b.counters.mailbox_hits);
  EXPECT_EQ(a.counters.pushes, b.counters.pushes);
  EXPECT_EQ(a.counters.pops, b.counters.pops);
  EXPECT_EQ(a.counters.box_tests, b.counters.box_tests);
  EXPECT_EQ(a.nearest_prim, b.nearest_prim);
  EXPECT_EQ(a.nearest_prim_before, b.nearest_prim_before);
  EXPECT_EQ(a.nearest_t, b.nearest_t);
  EXPECT_EQ(a.deferred, b.deferred);
  EXPECT_EQ(a.accepted, b.accepted);
  EXPECT_EQ(a.ended, b.ended);
  EXPECT_EQ(a.has_interval, b.has_interval);
  EXPECT_EQ(a.t_min, b.t_min);
  EXPECT_EQ(a.t_max, b.t_max);
}

// The state replayed from the start, by the definition (one event after the other, every list rebuilt).
ReplayState fromStart(const TracedRay& ray, int step) {
  return Replayer(ray, 1 << 30).at(step);
}

TEST(Replayer, EveryStepFromACheckpointIsTheStepReplayedFromTheStart) {
  const Geometry g = test::make_soup(6, 250, 4);
  std::vector<RayRequest> requests;
  for (const Ray& r : random_rays(g.bounds(), 30, 23))
    requests.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
  std::mt19937 rng(5);
  int compared = 0, long_rays = 0;
  for (const std::string kind : {"grid", "kd", "bvh", "bvh8", "octree", "bsp"}) {
    for (bool mailbox : {true, false}) {
      StructureOptions o;
      o.kd_mailboxes = mailbox;
      o.grid.density = 6;  // many cells: walks longer than a checkpoint interval of 3 or 7
      std::unique_ptr<Accelerator> accel = make_accelerator(kind, o);
      accel->build(g);
      const Trace t = record_trace(g, *accel, requests, "soup", "fnv1a64:0000000000000000");
      for (const TracedRay& ray : t.rays) {
        const int n = int(ray.events.size());
        long_rays += n > 20;
        for (int every : {1, 3, 7}) {
          const Replayer r(ray, every);
          ASSERT_EQ(r.size(), n);
          // Forward, back, then jumps in a random order.
          std::vector<int> order;
          for (int k = 0; k < n; ++k) order.push_back(k);
          for (int k = n - 1; k >= 0; --k) order.push_back(k);
          std::vector<int> jumps(order.begin(), order.begin() + n);
          std::shuffle(jumps.begin(), jumps.end(), rng);
          order.insert(order.end(), jumps.begin(), jumps.end());
          for (int k : order) {
            expectSame(r.at(k), fromStart(ray, k),
                       kind + (mailbox ? "" : " no mailbox") + " every " + std::to_string(every) + " step " +
                           std::to_string(k));
            ++compared;
            if (::testing::Test::HasFailure()) return;
          }
        }
      }
    }
  }
  EXPECT_GT(long_rays, 50);
  EXPECT_GT(compared, 10000);
}

TEST(Replayer, StepsAreClampedAndAnEmptyRayHasNoState) {
  TracedRay empty;
  EXPECT_EQ(Replayer(empty).at(5).step, -1);
  EXPECT_EQ(Replayer(empty).at(5).event, nullptr);
  const Geometry g = test::make_soup(3, 40, 1);
  std::unique_ptr<Accelerator> accel = make_accelerator("grid", StructureOptions{});
  accel->build(g);
  const Trace t = record_trace(
      g, *accel, {RayRequest{random_rays(g.bounds(), 1, 2)[0], RayKind::primary, 0, false, {0, 0}}}, "soup",
      "fnv1a64:0000000000000000");
  const Replayer r(t.rays[0], 2);
  EXPECT_EQ(r.at(-4).step, 0);
  EXPECT_EQ(r.at(1 << 20).step, r.size() - 1);
  EXPECT_TRUE(r.at(1 << 20).ended);
}

}  // namespace
}  // namespace raystep::replay
