// The quiz on the octree and the general BSP tree (question.h), and the lesson settings that name their nodes
// and open the report windows (lesson_state.h, lesson_runner.h, tree_nodes.h). The acceptance tests recompute
// each decision independently from the built tree and the ray at every event where a question applies, on 200
// random rays: the BSP tree's first child and push by bsp_crossing on the node's own plane, its next pop by
// its rule (entries beyond the hit dropped one by one); the octree's first child by Revelles' entry-plane
// rule on the cell's box, its next cell as the neighbour across the leaf's exit plane.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "question_test_util.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/structure_options.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/lesson/question.h"
#include "raystep/lesson/tree_nodes.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

const std::string kSource = RAYSTEP_SOURCE_DIR;

using test::nearest_before;
using test::soup_rays;

size_t end_of_block(const std::vector<Event>& ev, size_t i) {
  ++i;
  while (i < ev.size() && (ev[i].type == EventType::prim_test || ev[i].type == EventType::mailbox_hit ||
                           ev[i].type == EventType::hit_deferred))
    ++i;
  return i;
}

QuestionContext context_at(const Trace& trace, const Accelerator& accel, int ray, int step) {
  QuestionContext c;
  c.accel = &accel;
  c.trace = &trace;
  c.ray = ray;
  c.step = step;
  return c;
}

std::string octant_text(int octant) {
  std::string s;
  for (int a = 0; a < 3; ++a) s += std::string(1, "xyz"[a]) + ((octant >> a) & 1 ? "+" : "-");
  return s;
}

TEST(QuestionAcceptance, BspFirstChildAndNextPopAreTheKernels) {
  Geometry g = test::make_soup(5, 300, 6);
  StructureOptions options;
  auto accel = make_accelerator("bsp", options);
  accel->build(g);
  const BspTreeData& tree = dynamic_cast<const BspTree&>(*accel).data();
  Trace trace = record_trace(g, *accel, soup_rays(31), "soup", "");
  ASSERT_EQ(trace.structure.kind, "bsp");
  int first_child = 0, pushed = 0, slanted = 0, next_pop = 0, pops = 0, stops = 0, dropped = 0;
  for (int r = 0; r < int(trace.rays.size()); ++r) {
    const TracedRay& ray = trace.rays[size_t(r)];
    const std::vector<Event>& ev = ray.events;
    float root_min, root_max;
    if (!intersect_slabs(tree.bounds, ray.ray, &root_min, &root_max)) continue;
    const float margin = std::max(std::fabs(root_min), std::fabs(root_max)) / 4096.f;
    std::vector<const Event*> stack;
    for (int i = 0; i < int(ev.size()); ++i) {
      const Event& e = ev[size_t(i)];
      if (e.type == EventType::push) stack.push_back(&e);
      if (e.type == EventType::pop) stack.pop_back();
      if (e.type == EventType::node && !tree.nodes[size_t(e.node)].is_leaf()) {
        // The kernel's decision from the tree's own plane (not the trace's copy).
        const BspNode& n = tree.nodes[size_t(e.node)];
        const BspCrossing x = bsp_crossing(n.plane, ray.ray.origin, ray.ray.direction,
                                           std::max(std::fabs(e.t_min_node), std::fabs(e.t_max_node)));
        const int32_t below = e.node + 1, above = int32_t(n.above_child());
        const int32_t near_child = x.below_first ? below : above, far_child = x.below_first ? above : below;
        const bool near_only = x.kind == BspCrossing::stays || x.t_lo > e.t_max_node + margin;
        const bool far_only = !near_only && x.kind == BspCrossing::crosses && x.t_hi < e.t_min_node - margin;
        const int32_t first = far_only ? far_child : near_child;
        const bool push = !near_only && !far_only;

        const Answer a = answer_question(QuestionKind::first_child, context_at(trace, *accel, r, i));
        ++first_child;
        pushed += push;
        slanted += std::fabs(n.plane.normal.x) < 0.999f && std::fabs(n.plane.normal.y) < 0.999f &&
                   std::fabs(n.plane.normal.z) < 0.999f;
        ASSERT_EQ(a.first_child, first) << "ray " << r << " event " << i << ": " << a.why;
        ASSERT_EQ(a.first_is_below, first == below);
        ASSERT_EQ(a.far_pushed, push) << a.why;
        if (push) ASSERT_EQ(a.far_child, far_child);
        EXPECT_EQ(a.walk, "bsp");
        EXPECT_NE(a.why.find("n.o - d"), std::string::npos)
            << a.why;  // the signed distance, not "splits x at"
        EXPECT_EQ(a.why.find("splits"), std::string::npos) << a.why;
        EXPECT_TRUE(prediction_matches(
            a, std::string(first == below ? "below" : "above") + (push ? ",push" : ",no push")));
        EXPECT_FALSE(prediction_matches(a, first == below ? "above" : "below"));
      }
      if (e.type == EventType::leaf) {
        // The BSP rule: pop; an entry that starts beyond the nearest hit (and the margin) is dropped and the
        // next popped; the first kept is visited; none left: stop.
        int32_t hit;
        float t;
        nearest_before(ev, end_of_block(ev, size_t(i)), &hit, &t);
        std::vector<const Event*> rest = stack;
        int skipped = 0;
        while (!rest.empty() && hit >= 0 && t < rest.back()->t_min_node - margin) rest.pop_back(), ++skipped;
        const bool stop = rest.empty();
        for (int at : {i - 1, i, int(end_of_block(ev, size_t(i))) - 1}) {
          const Answer a = answer_question(QuestionKind::next_pop, context_at(trace, *accel, r, at));
          ++next_pop;
          ASSERT_EQ(a.stops, stop) << "ray " << r << " event " << at << ": " << a.why;
          if (!stop) ASSERT_EQ(a.node, rest.back()->node) << a.why;
          EXPECT_TRUE(prediction_matches(a, stop ? "stop" : std::to_string(rest.back()->node)));
        }
        dropped += skipped > 0;
        (stop ? stops : pops) += 1;
      }
    }
  }
  std::printf(
      "bsp: %d first-child answers agree (%d pushes, %d slanted planes), %d next-pop answers (%d pops, "
      "%d stops, %d leaves with entries dropped)\n",
      first_child, pushed, slanted, next_pop, pops, stops, dropped);
  EXPECT_GE(first_child, 1000);
  EXPECT_GE(pushed, 200);
  EXPECT_GE(slanted, 100);
  EXPECT_GE(pops, 200);
  EXPECT_GE(stops, 100);
}

TEST(QuestionAcceptance, OctreeFirstChildAndNextCellFollowRevelles) {
  Geometry g = test::make_soup(6, 300, 6);
  StructureOptions options;
  options.octree.leaf_size = 2;
  auto accel = make_accelerator("octree", options);
  accel->build(g);
  const OctreeData& tree = dynamic_cast<const Octree&>(*accel).data();
  Trace trace = record_trace(g, *accel, soup_rays(32), "soup", "");
  ASSERT_EQ(trace.structure.kind, "octree");
  int first_child = 0, by_planes = 0, next_cell = 0, siblings = 0, upward = 0, stops = 0, grazed = 0;
  for (int r = 0; r < int(trace.rays.size()); ++r) {
    const TracedRay& ray = trace.rays[size_t(r)];
    const Ray& q = ray.ray;
    const std::vector<Event>& ev = ray.events;
    for (int i = 0; i < int(ev.size()); ++i) {
      const Event& e = ev[size_t(i)];
      if (e.type != EventType::node) continue;
      const OctreeNodeInfo& info = tree.info[size_t(e.node)];
      if (!tree.nodes[size_t(e.node)].is_leaf()) {
        // Revelles' first child, recomputed from the cell's box: the entry plane is the largest entry t; on
        // each other axis the far half (in the ray's direction) when that centre plane comes before it.
        float t0[3], mid[3];
        for (int a = 0; a < 3; ++a) {
          const bool neg = std::signbit(q.direction[a]);
          const float m = 0.5f * (info.box.lo[a] + info.box.hi[a]);
          t0[a] = ((neg ? info.box.hi[a] : info.box.lo[a]) - q.origin[a]) / q.direction[a];
          mid[a] = (m - q.origin[a]) / q.direction[a];
        }
        const int entry = t0[0] >= t0[1] && t0[0] >= t0[2] ? 0 : (t0[1] >= t0[2] ? 1 : 2);
        int octant = 0;
        for (int a = 0; a < 3; ++a) {
          const bool far = a != entry && mid[a] < t0[entry];
          const bool upper = far != std::signbit(q.direction[a]);
          octant |= int(upper) << a;
        }
        // Asked at the node event and at its push: the same answer, the walk's next cell.
        for (int at : {i, i + 1}) {
          const Answer a = answer_question(QuestionKind::first_child, context_at(trace, *accel, r, at));
          const Answer b = answer_question(QuestionKind::next_cell, context_at(trace, *accel, r, at));
          ++first_child;
          int next = i + 2;
          while (ev[size_t(next)].type != EventType::node) ++next;
          ASSERT_EQ(a.node, ev[size_t(next)].node) << a.why;
          ASSERT_EQ(b.node, a.node);
          ASSERT_EQ(int32_t(tree.nodes[size_t(e.node)].child(a.octant)), a.node) << a.why;
          EXPECT_EQ(a.walk, "octree");
          by_planes += a.octant == octant;
          EXPECT_TRUE(prediction_matches(a, std::to_string(a.node)));
          EXPECT_TRUE(prediction_matches(a, octant_text(a.octant)));
          EXPECT_FALSE(prediction_matches(a, octant_text(a.octant ^ 7)));
          EXPECT_NE(a.why.find("centre plane at t = "), std::string::npos) << a.why;
        }
        continue;
      }
      // A leaf: the next cell lies across its exit plane, begins where it ends, or the walk stops.
      float t1[3];
      for (int a = 0; a < 3; ++a)
        t1[a] =
            ((std::signbit(q.direction[a]) ? info.box.lo[a] : info.box.hi[a]) - q.origin[a]) / q.direction[a];
      const int exit = t1[0] <= t1[1] && t1[0] <= t1[2] ? 0 : (t1[1] <= t1[2] ? 1 : 2);
      const size_t end = end_of_block(ev, size_t(i) + 1);
      for (int at : {i, i + 1, int(end) - 1}) {
        const Answer a = answer_question(QuestionKind::next_cell, context_at(trace, *accel, r, at));
        ++next_cell;
        int next = -1;
        for (size_t k = end; k < ev.size() && next < 0; ++k)
          if (ev[k].type == EventType::node) next = int(k);
        ASSERT_EQ(a.stops, next < 0) << "ray " << r << " event " << at << ": " << a.why;
        if (a.stops) {
          // Stopped: by a hit (inside the cell, or one the next cell cannot beat) or at the root's far face.
          int32_t hit;
          float t;
          nearest_before(ev, end, &hit, &t);
          const bool root_face = std::signbit(q.direction[exit]) ? info.box.lo[exit] == tree.bounds.lo[exit]
                                                                 : info.box.hi[exit] == tree.bounds.hi[exit];
          EXPECT_TRUE(hit >= 0 || root_face) << a.why;
          EXPECT_TRUE(prediction_matches(a, "stop"));
          if (at == i) ++stops;
          continue;
        }
        ASSERT_EQ(a.node, ev[size_t(next)].node) << a.why;
        if (ev[size_t(next)].t_max_node <= ev[size_t(next)].t_min_node || e.t_max_node <= e.t_min_node) {
          // From or to a cell the ray only grazes (its interval a point), walked by the kernel's rounding
          // rule: said so.
          EXPECT_NE(a.why.find("grazes"), std::string::npos) << a.why;
          if (at == i) ++grazed;
          continue;
        }
        // The next cell touches the leaf on its exit face, and begins where the leaf ends.
        const Bounds3& nb = tree.info[size_t(a.node)].box;
        const float face = std::signbit(q.direction[exit]) ? info.box.lo[exit] : info.box.hi[exit];
        const float other = std::signbit(q.direction[exit]) ? nb.hi[exit] : nb.lo[exit];
        EXPECT_EQ(face, other) << "ray " << r << " event " << at << ": " << a.why;
        EXPECT_NEAR(ev[size_t(next)].t_min_node, e.t_max_node, 1e-4f * (1.f + std::fabs(e.t_max_node)));
        const bool sibling = tree.info[size_t(a.node)].parent == info.parent;
        EXPECT_EQ(a.why.find("sibling") != std::string::npos, sibling) << a.why;
        if (at == i) (sibling ? siblings : upward) += 1;
        EXPECT_TRUE(prediction_matches(a, std::to_string(a.node)));
        EXPECT_TRUE(prediction_matches(a, octant_text(a.octant)));
        EXPECT_FALSE(prediction_matches(a, "stop"));
      }
    }
  }
  std::printf(
      "octree: %d first-child answers (%d the planes' first child), %d next-cell answers at leaves (%d "
      "siblings, %d up the tree, %d from or to a grazed cell, %d stops)\n",
      first_child, by_planes, next_cell, siblings, upward, grazed, stops);
  EXPECT_GE(first_child, 400);
  EXPECT_GE(by_planes, first_child * 99 / 100);  // rays start outside the root: only a grazed child differs
  EXPECT_GE(siblings, 200);
  EXPECT_GE(upward, 100);
  EXPECT_GE(stops, 100);
}

// The octree's and the BSP tree's words: prompts, the accepted forms, the questions that do not apply.
TEST(Question, OctreeAndBspFormsAndRefusals) {
  EXPECT_NE(std::string(question_prompt(QuestionKind::first_child, "octree")).find("octant"),
            std::string::npos);
  EXPECT_NE(std::string(question_prompt(QuestionKind::next_cell, "octree")).find("octant"),
            std::string::npos);
  EXPECT_NE(std::string(question_prompt(QuestionKind::first_child, "bsp")).find("slanted"),
            std::string::npos);
  EXPECT_STREQ(question_prompt(QuestionKind::next_pop, "kd"), question_prompt(QuestionKind::next_pop));

  Answer a;
  a.kind = QuestionKind::next_cell;
  a.walk = "octree";
  a.node = 12;
  a.octant = 5;  // x+ y- z+
  EXPECT_TRUE(prediction_matches(a, "x+ y- z+"));
  EXPECT_TRUE(prediction_matches(a, "X+Y-Z+"));
  EXPECT_TRUE(prediction_matches(a, "12"));
  EXPECT_FALSE(prediction_matches(a, "x+y+z+"));
  EXPECT_FALSE(prediction_matches(a, "stop"));
  EXPECT_THROW(prediction_matches(a, "x+y-"), InputError);
  EXPECT_THROW(prediction_matches(a, "below"), InputError);
  a.kind = QuestionKind::first_child;
  EXPECT_THROW(prediction_matches(a, "stop"), InputError);
  // A 2D scene's quadtree names its cells by quadrant: x and y only.
  a.axes = 2;
  a.octant = 1;  // x+ y-
  EXPECT_TRUE(prediction_matches(a, "x+ y-"));
  EXPECT_FALSE(prediction_matches(a, "x-y+"));
  EXPECT_THROW(prediction_matches(a, "x+y-z+"), InputError);
  a.axes = 3;

  // next-pop and dda-axis do not apply to an octree's walk; they say what to ask instead.
  Geometry g = test::make_soup(6, 100, 0);
  StructureOptions options;
  auto accel = make_accelerator("octree", options);
  accel->build(g);
  Trace trace = record_trace(g, *accel, soup_rays(33), "soup", "");
  int leaf = -1, ray = -1;
  for (int r = 0; r < int(trace.rays.size()) && leaf < 0; ++r)
    for (int i = 0; i < int(trace.rays[size_t(r)].events.size()) && leaf < 0; ++i)
      if (trace.rays[size_t(r)].events[size_t(i)].type == EventType::leaf) leaf = i, ray = r;
  ASSERT_GE(leaf, 0);
  for (QuestionKind k : {QuestionKind::next_pop, QuestionKind::dda_axis}) {
    try {
      answer_question(k, context_at(trace, *accel, ray, leaf));
      ADD_FAILURE() << question_kind_name(k) << " answered on an octree";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.detail()).find("next-cell"), std::string::npos) << e.detail();
    }
  }
  EXPECT_THROW(answer_question(QuestionKind::first_child, context_at(trace, *accel, ray, leaf)), InputError);
}

std::string check_error(const std::string& text) {
  try {
    check_lesson(parse_lesson_text(text, kSource + "/lessons/t.md"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "";
}

// node, node-path and panel name an octree's and a BSP tree's nodes (tree_nodes.h), as the debugger does.
TEST(LessonRunner, NodeSettingsForTheOctreeAndTheBspTree) {
  const std::string lesson = kSource + "/lessons/t.md";
  LessonRunner runner;
  Lesson l = parse_lesson_text(
      "# T\n## A\n```raystep\nscene: ../scenes/cornell.json\naccel: octree\noctree-leaf: 2\nnode-path: "
      "01\n```\n"
      "## B\n```raystep\nnode: 3\n```\n## C\n```raystep\npanel: kd\nnode: none\n```\n"
      "## D\n```raystep\naccel: bsp\npanel: none\nnode-path: LR\n```\n",
      lesson);
  StepWorld a = runner.enter(l.steps[0].state);
  const OctreeData& oct = dynamic_cast<const Octree&>(*a.accel).data();
  ASSERT_FALSE(oct.nodes[0].is_leaf());
  const uint32_t c0 = oct.nodes[0].child(0);
  ASSERT_FALSE(oct.nodes[c0].is_leaf());
  EXPECT_EQ(a.node, int(oct.nodes[c0].child(1)));
  EXPECT_EQ(oct.info[size_t(a.node)].parent, int(c0));
  EXPECT_EQ(runner.enter(l.steps[1].state).node, 3);
  EXPECT_EQ(runner.enter(l.steps[2].state).node, -1);  // the tree dock, no node selected
  StepWorld d = runner.enter(l.steps[3].state);
  const BspTreeData& bsp = dynamic_cast<const BspTree&>(*d.accel).data();
  ASSERT_FALSE(bsp.nodes[0].is_leaf());
  ASSERT_FALSE(bsp.nodes[1].is_leaf());
  EXPECT_EQ(d.node, int(bsp.nodes[1].above_child()));  // L: the node below the root's plane, R: above it
  EXPECT_EQ(lesson_tree(*d.accel).name, std::string("BSP tree"));
  EXPECT_EQ(lesson_node_by_path(*d.accel, ""), 0u);

  const std::string f = lesson + ":";
  const std::string head = "# T\n## S\n```raystep\nscene: ../scenes/cornell.json\n";
  EXPECT_EQ(
      check_error(head + "accel: octree\nnode-path: LR\n```\n"),
      f + "6: step 'S': node-path 'LR': use one digit 0..7 per level for an octree (the child's octant: 1 "
          "upper x, 2 upper y, 4 upper z)");
  EXPECT_EQ(check_error(head + "accel: bsp\nnode-path: 01\n```\n"),
            f + "6: step 'S': node-path '01': use L (below the plane) and R (above) for a BSP tree");
  EXPECT_EQ(check_error(head + "accel: octree\nnode-path: 00000000000000000000\n```\n")
                .rfind(f + "6: step 'S': node-path '00000000000000000000': cell ", 0),
            0u);
  EXPECT_EQ(check_error(head + "accel: bvh8\nnode-path: LR\n```\n"),
            f + "6: step 'S': node-path: a wide BVH's node is named by id (node: ID)");
  EXPECT_EQ(check_error(head + "accel: octree\nnode: 99999\n```\n")
                .rfind(f + "6: step 'S': node 99999: the octree has ", 0),
            0u);
  EXPECT_EQ(
      check_error(head + "node: 3\n```\n"),
      f + "5: step 'S': node: no tree (accel: kd, kd-median, bvh, bvh-sweep, bvh-median, bvh-sbvh, bvh4, bvh8, "
          "bvh4-sbvh, bvh8-sbvh, octree or bsp)");
  EXPECT_NE(check_error(head + "node-path: L0\n```\n").find("node-path 'L0': expected"), std::string::npos);
}

// report: opens report windows for one step (not carried over); the bounding-volume report is run by check.
TEST(LessonRunner, ReportSettingOpensReportsForOneStep) {
  const std::string lesson = kSource + "/lessons/t.md";
  Lesson l = parse_lesson_text(
      "# T\n## A\n```raystep\nscene: ../scenes/cornell.json\nreport: bvol,grid-sweep\nshow: report\n```\n"
      "## B\nNothing.\n## C\n```raystep\nreport: aa\n```\n## D\n```raystep\nreport: none\n```\n",
      lesson);
  ASSERT_EQ(l.steps.size(), 4u);
  EXPECT_EQ(l.steps[0].state.report, "bvol,grid-sweep");
  EXPECT_EQ(l.steps[0].state.show, "report");
  EXPECT_EQ(l.steps[1].state.report, "");  // not carried over
  EXPECT_EQ(l.steps[1].state.show, "report");
  EXPECT_EQ(l.steps[2].state.report, "aa");
  EXPECT_EQ(l.steps[3].state.report, "");
  const std::vector<std::string> args = l.steps[0].state.scripted_args();
  ASSERT_GE(args.size(), 2u);
  EXPECT_EQ(args[args.size() - 2], "--report");
  EXPECT_EQ(args.back(), "bvol,grid-sweep");
  EXPECT_EQ(check_lesson(l), 0);

  for (const char* bad : {"report: bvh\n", "report: bvol,bvol\n", "report: aa,\n", "report: \n"})
    EXPECT_NE(
        check_error(std::string("# T\n## S\n```raystep\nscene: ../scenes/cornell.json\n") + bad + "```\n")
            .find(":5: report"),
        std::string::npos)
        << bad;
}

}  // namespace
}  // namespace raystep
