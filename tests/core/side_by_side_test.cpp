// The side-by-side view's model: which event every walk shows at the timeline's t, its counters and its cost
// there (against core's walk_cost / cost_at and the replay's own counting), the timeline's range, the cost
// staircase the chart draws, and the --compare list's checks. Plain C++, no display.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "raystep/accel/structure_options.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/util/error.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/side_by_side.h"
#include "test_scenes.h"

namespace raystep::replay {
namespace {

// The staircase's value at t: the last point at or before t (a riser's upper point wins at its own t).
double staircaseAt(const std::vector<std::pair<double, double>>& s, double t) {
  double y = s.front().second;
  for (const auto& [x, v] : s)
    if (x <= t) y = v;
  return y;
}

TEST(SideBySide, EveryWalkAtTIsCostAtAndTheReplaysCounters) {
  const Geometry g = test::make_soup(5, 200, 3);
  const std::vector<std::string> kinds = {"grid", "kd", "bvh", "octree", "bsp"};
  std::vector<std::unique_ptr<Accelerator>> accels;
  std::vector<const Accelerator*> built;
  for (const std::string& k : kinds) {
    accels.push_back(make_accelerator(k, StructureOptions{}));
    accels.back()->build(g);
    built.push_back(accels.back().get());
  }
  std::vector<RayRequest> requests;
  for (const Ray& r : random_rays(g.bounds(), 40, 17))
    requests.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
  const MultiTrace m = record_walks(g, built, requests, "soup", "fnv1a64:0000000000000000");
  const CostModel model;
  int checked = 0, beforeFirst = 0, midWalk = 0, done = 0;
  for (size_t r = 0; r < requests.size(); ++r) {
    std::vector<const TracedRay*> rays;
    for (const Trace& w : m.walks) rays.push_back(&w.rays[r]);
    const TimelineRange range = timeline_range(rays);
    ASSERT_TRUE(std::isfinite(range.start) && std::isfinite(range.end));
    ASSERT_LT(range.start, range.end);
    for (size_t i = 0; i < rays.size(); ++i) {
      const TracedRay& ray = *rays[i];
      const WalkCost cost = walk_cost(ray, model);
      const auto stairs = cost_staircase(cost, range.start, range.end);
      int lastStep = -1;
      // 61 positions of the slider, and every step's own entry t (where the walk moves on).
      std::vector<float> ts;
      for (int k = 0; k <= 60; ++k) ts.push_back(range.start + (range.end - range.start) * float(k) / 60.f);
      for (const CostPoint& p : cost.points)
        if (std::isfinite(p.t)) ts.push_back(p.t);
      std::sort(ts.begin(), ts.end());
      for (float t : ts) {
        const WalkAtT at = walk_at_t(ray, t, model);
        ASSERT_GE(at.step, 0);
        ASSERT_LT(at.step, int(ray.events.size()));
        EXPECT_GE(at.step, lastStep) << kinds[i] << " ray " << r << ": the walk goes back as t grows";
        lastStep = at.step;
        // The walk is at or before t and its next step beyond it.
        EXPECT_TRUE(!std::isfinite(at.entered) || at.entered <= t);
        EXPECT_GT(at.next, t);
        // Its cost is core's cost_at, and its counters are the replay's at the same event.
        EXPECT_DOUBLE_EQ(at.cost, cost_at(cost, t)) << kinds[i] << " ray " << r << " t " << t;
        const ReplayState s = replay_at(ray, at.step);
        EXPECT_EQ(at.steps, s.counters.cells + s.counters.nodes);
        EXPECT_EQ(at.prim_tests, s.counters.prim_tests);
        EXPECT_EQ(at.mailbox_hits, s.counters.mailbox_hits);
        EXPECT_EQ(at.box_tests, s.counters.box_tests);
        EXPECT_DOUBLE_EQ(staircaseAt(stairs, t), cost_at(cost, t));
        beforeFirst += at.steps == 0;
        midWalk += at.steps > 0 && at.step + 1 < int(ray.events.size());
        ++checked;
      }
      // At the end of the timeline every walk is done: its last event, its whole cost.
      const WalkAtT end = walk_at_t(ray, range.end, model);
      EXPECT_EQ(end.step, int(ray.events.size()) - 1);
      EXPECT_EQ(end.steps, cost.steps);
      EXPECT_EQ(end.prim_tests, cost.prim_tests);
      EXPECT_DOUBLE_EQ(end.cost, cost.total);
      done += end.steps > 0;
    }
  }
  std::printf("%d (walk, t) pairs checked: %d before the first step, %d in the middle of a walk; %d walks done\n",
              checked, beforeFirst, midWalk, done);
  EXPECT_GT(checked, 10000);
  EXPECT_GT(midWalk, 1000);  // the sweep stops in the middle of walks, not only at their ends
  EXPECT_GT(beforeFirst, 0);
  EXPECT_GT(done, 100);
}

TEST(SideBySide, BadListsAreRefusedInOneLine) {
  EXPECT_EQ(parse_side_by_side_list("grid,kd,bvh"), (std::vector<std::string>{"grid", "kd", "bvh"}));
  EXPECT_EQ(parse_side_by_side_list("octree,bsp,bvh8,kd-median").size(), 4u);
  const std::pair<const char*, const char*> bad[] = {{"grid", "give 2 to 4 structures"},
                                                     {"grid,kd,grid", "grid is listed twice"},
                                                     {"grid,quadtree", "unknown structure 'quadtree'"},
                                                     {"grid,,kd", "an empty name"},
                                                     {"grid,kd,bvh,octree,bsp", "at most 4"},
                                                     {"grid,brute", "brute records no events"},
                                                     {"kd,bvol-sphere", "bvol-sphere records no events"}};
  for (const auto& [list, says] : bad) {
    try {
      parse_side_by_side_list(list);
      ADD_FAILURE() << list << " accepted";
    } catch (const InputError& e) {
      const std::string what = e.what();
      EXPECT_NE(what.find(says), std::string::npos) << what;
      EXPECT_NE(what.find(std::string("--compare '") + list + "'"), std::string::npos) << what;
      EXPECT_EQ(what.find('\n'), std::string::npos) << what;
    }
  }
}

}  // namespace
}  // namespace raystep::replay
