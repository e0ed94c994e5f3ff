// Tests of the quiz (question.h) and of entering lesson steps (lesson_runner.h). The acceptance test of the
// issue: a question's computed answer equals the kernel's decision, recomputed here independently from the
// structure and the ray, at every event where the question applies, on 200 random rays per structure.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/accel/structure_options.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/lesson/question.h"
#include "raystep/render/camera.h"
#include "raystep/render/whitted.h"
#include "raystep/report/bvol_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "question_test_util.h"
#include "test_scenes.h"

namespace raystep {
namespace {

const std::string kSource = RAYSTEP_SOURCE_DIR;

using test::nearest_before;
using test::soup_rays;

size_t end_of_block(const std::vector<Event>& ev, size_t i) {
  ++i;
  while (i < ev.size() && (ev[i].type == EventType::prim_test || ev[i].type == EventType::mailbox_hit)) ++i;
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

TEST(QuestionAcceptance, GridAnswersEqualThe3dDda) {
  Geometry g = test::make_soup(7, 300, 6);
  StructureOptions options;
  auto accel = make_accelerator("grid", options);
  accel->build(g);
  const UniformGrid& grid = dynamic_cast<const UniformGrid&>(*accel);
  const std::array<int, 3> res = grid.resolution();
  Trace trace = record_trace(g, *accel, soup_rays(11), "soup", "");
  int next_cell = 0, dda_axis = 0, stops = 0, steps = 0;
  for (int r = 0; r < int(trace.rays.size()); ++r) {
    const TracedRay& ray = trace.rays[size_t(r)];
    const std::vector<Event>& ev = ray.events;
    float t0, t1;
    const bool enters = intersect_slabs(grid.bounds(), ray.ray, &t0, &t1);
    for (int i = 0; i < int(ev.size()); ++i) {
      if (ev[size_t(i)].type != EventType::cell) continue;
      ASSERT_TRUE(enters);
      const Event& e = ev[size_t(i)];
      // The kernel's decision, recomputed: the smallest tMax (ties to x, then y), the neighbour by the sign
      // of the direction, and the stopping rules (hit inside the cell, past the grid's exit, out of the
      // grid).
      const float* tm = &e.t_max.x;
      const int axis = (tm[0] <= tm[1] && tm[0] <= tm[2]) ? 0 : (tm[1] <= tm[2] ? 1 : 2);
      const int step = ray.ray.direction[axis] > 0.f ? 1 : -1;
      std::array<int, 3> next{e.cell[0], e.cell[1], e.cell[2]};
      next[size_t(axis)] += step;
      int32_t hit;
      float t;
      nearest_before(ev, end_of_block(ev, size_t(i)), &hit, &t);
      const float cell_exit = std::min(tm[axis], t1);
      const bool stop = (hit >= 0 && t * (1.f + 1.f / 4096.f) < cell_exit) || tm[axis] > t1 ||
                        next[size_t(axis)] < 0 || next[size_t(axis)] >= res[size_t(axis)];

      const Answer a = answer_question(QuestionKind::next_cell, context_at(trace, *accel, r, i));
      const Answer b = answer_question(QuestionKind::dda_axis, context_at(trace, *accel, r, i));
      ++next_cell, ++dda_axis;
      ASSERT_EQ(a.stops, stop) << "ray " << r << " event " << i << ": " << a.why;
      ASSERT_EQ(b.axis, stop ? -1 : axis) << "ray " << r << " event " << i << ": " << b.why;
      if (stop) {
        ++stops;
        continue;
      }
      ++steps;
      ASSERT_EQ(a.cell, next) << a.why;
      ASSERT_EQ(b.cell, next);
      EXPECT_TRUE(prediction_matches(
          a, std::to_string(next[0]) + "," + std::to_string(next[1]) + "," + std::to_string(next[2])));
      EXPECT_TRUE(prediction_matches(b, std::string(1, "xyz"[axis])));
      EXPECT_FALSE(prediction_matches(b, "none"));
    }
  }
  std::printf("grid: %d next-cell and %d dda-axis answers agree (%d steps, %d stops)\n", next_cell, dda_axis,
              steps, stops);
  EXPECT_GE(steps, 1000);
  EXPECT_GE(stops, 150);
}

// first-child and next-pop against the kd traversal's rules, recomputed from the tree and the ray.
void check_tree(const std::string& name) {
  Geometry g = test::make_soup(3, 300, 6);
  StructureOptions options;
  auto accel = make_accelerator(name, options);
  accel->build(g);
  const KdTree& kd = dynamic_cast<const KdTree&>(*accel);
  const KdTreeData& tree = kd.data();
  Trace trace = record_trace(g, *accel, soup_rays(name == "kd" ? 21 : 22), "soup", "");
  int first_child = 0, pushed = 0, next_pop = 0, pops = 0, stops = 0;
  for (int r = 0; r < int(trace.rays.size()); ++r) {
    const TracedRay& ray = trace.rays[size_t(r)];
    const std::vector<Event>& ev = ray.events;
    float root_min, root_max;
    if (!intersect_slabs(tree.bounds, ray.ray, &root_min, &root_max)) continue;
    const float margin = std::max(std::fabs(root_min), std::fabs(root_max)) / 4096.f;
    std::vector<const Event*> stack;  // reconstructed from the pushes and pops
    for (int i = 0; i < int(ev.size()); ++i) {
      const Event& e = ev[size_t(i)];
      if (e.type == EventType::push) stack.push_back(&e);
      if (e.type == EventType::pop) stack.pop_back();
      if (e.type == EventType::node && !tree.nodes[size_t(e.node)].is_leaf()) {
        const KdNode& n = tree.nodes[size_t(e.node)];
        const float o = ray.ray.origin[n.axis()], d = ray.ray.direction[n.axis()];
        const float t_split = (n.split - o) * (1.f / d);
        const bool below_first = !std::signbit(d);
        const int32_t below = e.node + 1, above = int32_t(n.above_child());
        const int32_t near_child = below_first ? below : above, far_child = below_first ? above : below;
        const bool push = !(t_split > e.t_max_node + margin) && !(t_split < e.t_min_node - margin);
        const int32_t first = (t_split < e.t_min_node - margin) ? far_child : near_child;

        const Answer a = answer_question(QuestionKind::first_child, context_at(trace, *accel, r, i));
        ++first_child;
        pushed += push;
        ASSERT_EQ(a.first_child, first) << "ray " << r << " event " << i << ": " << a.why;
        ASSERT_EQ(a.first_is_below, first == below);
        ASSERT_EQ(a.far_pushed, push) << a.why;
        if (push) ASSERT_EQ(a.far_child, far_child);
        EXPECT_TRUE(prediction_matches(
            a, std::string(first == below ? "below" : "above") + (push ? ",push" : ",no push")));
        EXPECT_FALSE(prediction_matches(a, std::string(first == below ? "above" : "below")));
        // The slides' path notation: the path the answer names leads from the root to the same node.
        ASSERT_FALSE(a.first_child_path.empty());
        ASSERT_EQ(kd_node_by_path(tree, a.first_child_path), uint32_t(first)) << a.first_child_path;
        EXPECT_TRUE(prediction_matches(a, a.first_child_path));
        std::string lower = a.first_child_path;
        for (char& ch : lower) ch = char(std::tolower(ch));
        EXPECT_TRUE(prediction_matches(a, lower + (push ? ",push" : ",no push")));
        EXPECT_FALSE(prediction_matches(a, a.first_child_path + (a.first_child_path.back() == 'L' ? "L" : "R")));
        if (push) ASSERT_EQ(kd_node_by_path(tree, a.far_child_path), uint32_t(far_child));
      }
      if (e.type == EventType::leaf) {
        // The stop rule: an empty stack, or the nearest hit before the top's t_min (beyond the margin).
        int32_t hit;
        float t;
        nearest_before(ev, end_of_block(ev, size_t(i)), &hit, &t);
        const bool stop = stack.empty() || (hit >= 0 && t < stack.back()->t_min_node - margin);
        // Asked at the leaf's node event, at the leaf event and at its tests: the same answer.
        for (int at : {i - 1, i, int(end_of_block(ev, size_t(i))) - 1}) {
          const Answer a = answer_question(QuestionKind::next_pop, context_at(trace, *accel, r, at));
          ++next_pop;
          ASSERT_EQ(a.stops, stop) << "ray " << r << " event " << at << ": " << a.why;
          if (!stop) ASSERT_EQ(a.node, stack.back()->node) << a.why;
          EXPECT_TRUE(prediction_matches(a, stop ? "stop" : std::to_string(stack.back()->node)));
          if (!stop) {
            ASSERT_EQ(kd_node_by_path(tree, a.node_path == "root" ? "" : a.node_path),
                      uint32_t(stack.back()->node));
            EXPECT_TRUE(prediction_matches(a, a.node_path));
          }
        }
        (stop ? stops : pops) += 1;
      }
    }
  }
  std::printf(
      "%s: %d first-child answers agree (%d pushes), %d next-pop answers agree (%d leaves: %d pops, %d "
      "stops)\n",
      name.c_str(), first_child, pushed, next_pop, pops + stops, pops, stops);
  EXPECT_GE(first_child, 1000);
  EXPECT_GE(pushed, 200);
  EXPECT_GE(pops, 200);
  EXPECT_GE(stops, 150);
}

// next-pop on a BVH against its rule, recomputed from the stack: pop the top; an entry whose box starts beyond
// the nearest hit (and the walk's margin) is skipped and the next one popped, since a BVH's stack is not ordered
// by distance; the first entry not skipped is visited; an empty stack ends the walk. first-child does not apply.
TEST(QuestionAcceptance, BvhNextPopSkipsEntriesBeyondTheHit) {
  Geometry g = test::make_soup(3, 300, 6);
  StructureOptions options;
  auto accel = make_accelerator("bvh", options);
  accel->build(g);
  const BvhData& bvh = dynamic_cast<const Bvh&>(*accel).data();
  Trace trace = record_trace(g, *accel, soup_rays(23), "soup", "");
  int answers = 0, pops = 0, stops = 0, after_skips = 0;
  bool first_child_refused = false;
  for (int r = 0; r < int(trace.rays.size()); ++r) {
    const std::vector<Event>& ev = trace.rays[size_t(r)].events;
    float root_min, root_max;
    if (!intersect_slabs(bvh.nodes[0].box, trace.rays[size_t(r)].ray, &root_min, &root_max)) continue;
    const float margin = std::max(std::fabs(root_min), std::fabs(root_max)) / 4096.f;
    std::vector<const Event*> stack;
    for (int i = 0; i < int(ev.size()); ++i) {
      const Event& e = ev[size_t(i)];
      if (e.type == EventType::push) stack.push_back(&e);
      if (e.type == EventType::pop) stack.pop_back();
      if (e.type == EventType::node && !first_child_refused && i + 1 < int(ev.size()) &&
          ev[size_t(i) + 1].type != EventType::leaf) {
        EXPECT_THROW(answer_question(QuestionKind::first_child, context_at(trace, *accel, r, i)), InputError);
        first_child_refused = true;
      }
      if (e.type != EventType::leaf) continue;
      int32_t hit;
      float t;
      nearest_before(ev, end_of_block(ev, size_t(i)), &hit, &t);
      std::vector<const Event*> rest = stack;
      int skipped = 0;
      while (!rest.empty() && hit >= 0 && rest.back()->t_min_node > t + margin) {
        rest.pop_back();
        ++skipped;
      }
      const bool stop = rest.empty();
      const Answer a = answer_question(QuestionKind::next_pop, context_at(trace, *accel, r, i));
      ++answers;
      ASSERT_EQ(a.stops, stop) << "ray " << r << " event " << i << ": " << a.why;
      if (!stop) {
        ASSERT_EQ(a.node, rest.back()->node) << a.why;
        after_skips += skipped > 0;
      }
      (stop ? stops : pops) += 1;
    }
  }
  std::printf("bvh: %d next-pop answers agree (%d pops, %d of them after skips, %d stops)\n", answers, pops,
              after_skips, stops);
  EXPECT_TRUE(first_child_refused);
  EXPECT_GE(pops, 100);
  EXPECT_GE(after_skips, 5);
  EXPECT_GE(stops, 50);
}

TEST(QuestionAcceptance, KdSahAnswersEqualTheTraversal) {
  check_tree("kd");
}
TEST(QuestionAcceptance, KdMedianAnswersEqualTheTraversal) {
  check_tree("kd-median");
}

// sah-plane: the cheapest candidate of the node's curve (the first at equal cost: the builder's tie rule) and
// the split the build stored, for every inner node of a small tree.
void check_sah(const std::string& name) {
  Geometry g = test::make_soup(5, 60, 2);
  auto accel = make_accelerator(name, StructureOptions{});
  accel->build(g);
  const KdTree& kd = dynamic_cast<const KdTree&>(*accel);
  int inner = 0;
  for (size_t id = 0; id < kd.data().nodes.size(); ++id) {
    const KdNode& n = kd.data().nodes[id];
    QuestionContext c;
    c.accel = accel.get();
    c.node = int(id);
    if (n.is_leaf()) {
      EXPECT_THROW(answer_question(QuestionKind::sah_plane, c), InputError);
      continue;
    }
    const Answer a = answer_question(QuestionKind::sah_plane, c);
    ++inner;
    EXPECT_EQ(a.axis, n.axis()) << "node " << id << ": " << a.why;
    EXPECT_EQ(a.position, n.split) << "node " << id;
    const SahCurve curve = record_sah_curve(g, kd.options(), uint32_t(id));
    ASSERT_FALSE(curve.candidates.empty());
    if (name == "kd") {
      size_t best = 0;
      for (size_t k = 1; k < curve.candidates.size(); ++k)
        if (curve.candidates[k].cost < curve.candidates[best].cost) best = k;
      EXPECT_EQ(a.axis, curve.candidates[best].axis) << "node " << id;
      EXPECT_EQ(a.position, curve.candidates[best].position) << "node " << id;
      EXPECT_LT(curve.candidates[best].cost, curve.leaf_cost);
    }
    EXPECT_TRUE(prediction_matches(a, std::string(1, "xyz"[a.axis]) + "," + std::to_string(a.position)));
    EXPECT_FALSE(prediction_matches(a, "leaf"));
  }
  std::printf("%s: %d sah-plane answers agree\n", name.c_str(), inner);
  EXPECT_GE(inner, 20);
}

TEST(QuestionAcceptance, SahPlaneIsTheBuildersChoice) {
  check_sah("kd");
}
TEST(QuestionAcceptance, SahPlaneOfTheMedianBuilder) {
  check_sah("kd-median");
}

// subdivide: the contrast rule recomputed from the five first samples, on every pixel of the aliasing scene.
TEST(QuestionAcceptance, SubdivideIsTheContrastRule) {
  Scene scene = load_scene(kSource + "/scenes/aliasing.json");
  auto accel = make_accelerator("grid", StructureOptions{});
  accel->build(scene.geometry);
  const int w = scene.render.width, h = scene.render.height;
  const ProjectiveCamera camera(scene.camera, w, h);
  const WhittedTracer tracer(scene, *accel);
  RayCounts counts;
  auto radiance = [&](float x, float y) { return tracer.trace_primary(camera.generate(x, y), &counts); };
  int yes = 0, no = 0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      QuestionContext c;
      c.scene = &scene;
      c.accel = accel.get();
      c.aa = "adaptive:0.1:3";
      c.width = w;
      c.height = h;
      c.pixel = {x, y};
      const Answer a = answer_question(QuestionKind::subdivide, c);
      const glm::vec3 v[5] = {radiance(x, y), radiance(x + 1.f, y), radiance(x, y + 1.f),
                              radiance(x + 1.f, y + 1.f), radiance(x + 0.5f, y + 0.5f)};
      bool split = false;
      for (int ch = 0; ch < 3; ++ch) {
        float lo = v[0][ch], hi = v[0][ch];
        for (const glm::vec3& s : v) lo = std::min(lo, s[ch]), hi = std::max(hi, s[ch]);
        split = split || (hi + lo > 0.f && (hi - lo) / (hi + lo) > 0.1f);
      }
      ASSERT_EQ(a.subdivided, split) << "pixel " << x << "," << y << ": " << a.why;
      ASSERT_EQ(a.samples > 5, split);
      EXPECT_TRUE(prediction_matches(a, split ? "yes" : "no"));
      (split ? yes : no) += 1;
    }
  std::printf("subdivide: %d answers agree (%d subdivided, %d not)\n", yes + no, yes, no);
  EXPECT_GE(yes, 50);
  EXPECT_GE(no, 500);
}

// bvol-kind: the kind with the fewest false positives per ray in the bounding-volume report of the same
// scene, every kind's numbers in the Why; the lecture's words accepted, a wrong kind answered with feedback.
TEST(QuestionAcceptance, BvolKindIsTheReportsFewestInVain) {
  for (const char* file : {"cornell.json", "moire.json"}) {
    Scene scene = load_scene(kSource + "/scenes/" + file);
    QuestionContext c;
    c.scene = &scene;
    const Answer a = answer_question(QuestionKind::bvol_kind, c);
    BvolReportOptions o;
    o.reps = 1;
    const std::vector<BvolReportRow> rows = run_bvol_report(scene, o);
    ASSERT_EQ(rows.size(), 4u);
    const BvolReportRow* best = &rows[0];
    for (const BvolReportRow& r : rows)
      if (r.false_positives_per_ray < best->false_positives_per_ray) best = &r;
    ASSERT_FALSE(a.volumes.empty()) << file;
    EXPECT_EQ(a.volumes.front(), best->kind) << file << ": " << a.why;
    for (const char* words : {"the box", "the sphere", "the 14-DOP", "the oriented box"})
      EXPECT_NE(a.why.find(words), std::string::npos) << a.why;
    const std::string typed = best->kind == "bvol"          ? "Box"
                              : best->kind == "bvol-sphere" ? "sphere"
                              : best->kind == "bvol-kdop"   ? "14-DOP"
                                                            : "oriented box";
    EXPECT_TRUE(prediction_matches(a, typed)) << file;
    EXPECT_EQ(prediction_feedback(a, typed), "");
    const std::string wrong = best->kind == "bvol-sphere" ? "box" : "sphere";
    EXPECT_FALSE(prediction_matches(a, wrong));
    EXPECT_NE(prediction_feedback(a, wrong), "");
    EXPECT_THROW(prediction_matches(a, "cone"), InputError);
  }
  // The lesson's two scenes: the 14-DOP on the Cornell box (the turned box's corners), the oriented box on
  // the slanted strips.
  Scene cornell = load_scene(kSource + "/scenes/cornell.json"), strips = load_scene(kSource + "/scenes/moire.json");
  QuestionContext c;
  c.scene = &cornell;
  EXPECT_EQ(answer_question(QuestionKind::bvol_kind, c).volumes, std::vector<std::string>{"bvol-kdop"});
  c.scene = &strips;
  EXPECT_EQ(answer_question(QuestionKind::bvol_kind, c).volumes, std::vector<std::string>{"bvol-obb"});
}

TEST(Question, NamesAndForms) {
  QuestionKind k;
  for (const char* name :
       {"next-cell", "dda-axis", "first-child", "next-pop", "sah-plane", "subdivide", "bvol-kind"}) {
    ASSERT_TRUE(parse_question_kind(name, &k));
    EXPECT_STREQ(question_kind_name(k), name);
    EXPECT_STRNE(question_prompt(k), "");
  }
  EXPECT_FALSE(parse_question_kind("guess", &k));
  Answer a;
  a.kind = QuestionKind::dda_axis;
  a.axis = 1;
  EXPECT_TRUE(prediction_matches(a, " Y "));
  EXPECT_THROW(prediction_matches(a, "w"), InputError);
  a.kind = QuestionKind::next_cell;
  a.cell = {3, 5, 2};
  EXPECT_TRUE(prediction_matches(a, "(3, 5, 2)"));
  EXPECT_FALSE(prediction_matches(a, "stop"));
  EXPECT_THROW(prediction_matches(a, "3,5"), InputError);
  a.kind = QuestionKind::sah_plane;
  a.axis = 0;
  a.position = 0.5f;
  a.extent = 2.f;
  EXPECT_TRUE(prediction_matches(a, "x, 0.50015"));
  EXPECT_FALSE(prediction_matches(a, "x, 0.501"));
  EXPECT_FALSE(prediction_matches(a, "y"));
  EXPECT_THROW(prediction_matches(a, "x,abc"), InputError);
  // The chart's own axis: across the node, 0% its minimum (here -1.5), 100% its maximum (0.5); within 2%.
  a.lo = -1.5f;
  EXPECT_TRUE(prediction_matches(a, "x, 100%"));
  EXPECT_TRUE(prediction_matches(a, "x,98.5%"));
  EXPECT_FALSE(prediction_matches(a, "x,97%"));
  EXPECT_FALSE(prediction_matches(a, "x,50%"));
  EXPECT_THROW(prediction_matches(a, "x,%"), InputError);
  a.kind = QuestionKind::first_child;
  a.first_child = 7;
  a.first_is_below = false;
  a.far_pushed = false;
  EXPECT_TRUE(prediction_matches(a, "7"));
  EXPECT_TRUE(prediction_matches(a, "Above, No push"));
  EXPECT_FALSE(prediction_matches(a, "above,push"));
  EXPECT_THROW(prediction_matches(a, "left"), InputError);
  // The slides' path notation, where the answer knows the node's path.
  EXPECT_THROW(prediction_matches(a, "LR"), InputError);  // no path known: not a form of this answer
  a.first_child_path = "LR";
  EXPECT_TRUE(prediction_matches(a, "lr, no push"));
  EXPECT_FALSE(prediction_matches(a, "LL"));
  a.kind = QuestionKind::next_pop;
  a.node = 4;
  a.node_path = "root";
  EXPECT_TRUE(prediction_matches(a, "Root"));
  EXPECT_FALSE(prediction_matches(a, "L"));
  EXPECT_TRUE(prediction_matches(a, "4"));
  a.kind = QuestionKind::subdivide;
  EXPECT_THROW(prediction_matches(a, "maybe"), InputError);
}

TEST(Question, DoesNotApplyGivesOneLine) {
  Geometry g = test::make_soup(7, 50, 0);
  auto grid = make_accelerator("grid", StructureOptions{});
  grid->build(g);
  Trace trace = record_trace(g, *grid, soup_rays(1), "soup", "");
  EXPECT_THROW(answer_question(QuestionKind::first_child, context_at(trace, *grid, 0, 0)), InputError);
  EXPECT_THROW(answer_question(QuestionKind::next_pop, context_at(trace, *grid, 0, 0)), InputError);
  EXPECT_THROW(answer_question(QuestionKind::dda_axis, context_at(trace, *grid, 0, 0)),
               InputError);  // ray_begin
  EXPECT_THROW(answer_question(QuestionKind::sah_plane, context_at(trace, *grid, 0, 0)), InputError);
  EXPECT_THROW(answer_question(QuestionKind::next_cell, context_at(trace, *grid, 0, 9999)), InputError);
  EXPECT_THROW(answer_question(QuestionKind::next_cell, QuestionContext{}), InputError);
  EXPECT_THROW(answer_question(QuestionKind::subdivide, QuestionContext{}), InputError);
}

// The example of docs/lesson-format.md, read from the page as if it were lessons/example.md, checks.
TEST(LessonRunner, TheFormatDocsExampleChecks) {
  std::ifstream in(kSource + "/docs/lesson-format.md");
  std::stringstream ss;
  ss << in.rdbuf();
  const std::string doc = ss.str();
  const size_t open = doc.find("````markdown\n");
  ASSERT_NE(open, std::string::npos);
  const size_t begin = open + 13, end = doc.find("\n````", begin);
  ASSERT_NE(end, std::string::npos);
  Lesson lesson = parse_lesson_text(doc.substr(begin, end - begin + 1), kSource + "/lessons/example.md");
  ASSERT_EQ(lesson.steps.size(), 3u);
  EXPECT_EQ(check_lesson(lesson), 1);
  LessonRunner runner;
  StepWorld w = runner.enter(lesson.steps[1].state, lesson.steps[1].ask);
  ASSERT_TRUE(w.answer);
  EXPECT_NE(w.answer->why.find("tMax = ("), std::string::npos);
  // The step after the question shows the cell the answer named.
  StepWorld next = runner.enter(lesson.steps[2].state);
  const Event& cell = next.trace->rays[0].events[size_t(next.step)];
  EXPECT_EQ(w.answer->cell, (std::array<int, 3>{cell.cell[0], cell.cell[1], cell.cell[2]}));
  EXPECT_EQ(next.trace, w.trace);  // the same state's trace is kept, not recorded again
}

std::string check_error(const std::string& text) {
  try {
    check_lesson(parse_lesson_text(text, kSource + "/lessons/t.md"));
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

TEST(LessonRunner, FailuresNameTheResponsibleLine) {
  const std::string f = kSource + "/lessons/t.md:";
  const std::string head = "# T\n## S\n```raystep\nscene: ../scenes/cornell.json\n";
  EXPECT_EQ(check_error(head + "pixel: 400,1\n```\n"),
            f + "5: step 'S': pixel 400,1: outside the 320x320 picture");
  EXPECT_EQ(check_error(head + "pixel: 160,200\nstep-to: cell:999\n```\n"),
            f + "6: step 'S': step-to cell:999: the ray has fewer such events");
  EXPECT_EQ(check_error(head + "pixel: 160,200\nstep: 100000\n```\n")
                .rfind(f + "6: step 'S': step 100000: the ray has ", 0),
            0u);
  EXPECT_EQ(check_error(head + "node: 3\n```\n"),
            f + "5: step 'S': node: no tree (accel: kd, kd-median, bvh, bvh-sweep, bvh-median, bvh-sbvh, bvh4, "
                "bvh8, bvh4-sbvh, bvh8-sbvh, octree or bsp)");
  EXPECT_EQ(check_error(head + "accel: kd\nnode-path: LLLLLLLLLLLLLLLLLLLLLLLLLL\n```\n")
                .rfind(f + "6: step 'S': node-path 'LLLLLLLLLLLLLLLLLLLLLLLLLL': ", 0),
            0u);
  EXPECT_EQ(
      check_error(head + "pixel: 160,200\nstep-to: cell:1\nask: first-child\n```\n"),
      f + "7: step 'S': first-child: event 1 is a cell event, not a node (step-to: node:K at an inner node)");
  EXPECT_EQ(check_error(head + "step-to: cell:2\n```\n"),
            f + "5: step 'S': step-to cell:2: no traced pixel (pixel: X,Y)");
  // A later step without the setting in it: the step's heading.
  EXPECT_EQ(
      check_error(head + "accel: kd\nnode: 1\n```\n## B\n```raystep\naccel: grid\n```\n"),
      f + "10: step 'B': node: no tree (accel: kd, kd-median, bvh, bvh-sweep, bvh-median, bvh-sbvh, bvh4, bvh8, "
          "bvh4-sbvh, bvh8-sbvh, octree or bsp)");
  EXPECT_EQ(check_error(head + "pixel: 160,200\n```\n## B\n\nask\n\n```raystep\nask: next-pop\n```\n"),
            f + "12: step 'B': next-pop: the ray walks a grid, not a tree (accel: kd, kd-median or a BVH)");
}

// An anti-aliased pixel is traced as the debugger traces it: every sample's rays, the pixel section with them
// (the same trace as `raystep trace --pixel --aa`); `sample: N` replays sample N's primary ray, `square: N`
// must name a square of an adaptive subdivision.
TEST(LessonRunner, AnAntiAliasedPixelIsTracedSampleBySample) {
  LessonRunner runner;
  Lesson l = parse_lesson_text(
      "# T\n## A\n```raystep\nscene: ../scenes/aliasing.json\naa: regular:4\npixel: 32,38\nsample: 6\n"
      "step-to: hit:1\n```\n## B\n```raystep\naa: adaptive:0.1\nsample: none\nsquare: 7\n```\n"
      "## C\n```raystep\naa: none\nsquare: none\n```\n",
      kSource + "/lessons/t.md");
  EXPECT_EQ(check_lesson(l), 0);
  StepWorld a = runner.enter(l.steps[0].state);
  ASSERT_TRUE(a.trace && a.trace->pixel);
  EXPECT_EQ(a.trace->pixel->sampling.samples.size(), 16u);
  EXPECT_EQ(a.trace->rays.size(), 16u);
  EXPECT_EQ(a.trace->rays[size_t(a.ray)].sample, 6);
  const PixelSample& six = a.trace->pixel->sampling.samples[6];
  const Ray expected = ProjectiveCamera(a.scene->camera, 64, 48).generate(six.px, six.py);
  EXPECT_EQ(a.trace->rays[size_t(a.ray)].ray.origin, expected.origin);
  EXPECT_EQ(a.trace->rays[size_t(a.ray)].ray.direction, expected.direction);
  EXPECT_EQ(a.trace->rays[size_t(a.ray)].events[size_t(a.step)].type, EventType::hit_accepted);

  StepWorld b = runner.enter(l.steps[1].state);
  ASSERT_TRUE(b.trace && b.trace->pixel);
  EXPECT_EQ(b.trace->pixel->sampling.aa.mode, AntiAliasing::Mode::adaptive);
  EXPECT_GT(b.trace->pixel->sampling.squares.size(), 7u);
  EXPECT_EQ(b.ray, 0);

  StepWorld c = runner.enter(l.steps[2].state);  // without anti-aliasing: the centre ray, no pixel section
  ASSERT_TRUE(c.trace);
  EXPECT_FALSE(c.trace->pixel.has_value());
  EXPECT_EQ(c.trace->rays.size(), 1u);

  const std::string f = kSource + "/lessons/t.md:";
  const std::string head = "# T\n## S\n```raystep\nscene: ../scenes/aliasing.json\npixel: 32,38\n";
  EXPECT_EQ(check_error(head + "aa: jitter:2\nsample: 4\n```\n"),
            f + "7: step 'S': sample 4: the pixel has 4 samples (0..3)");
  EXPECT_EQ(check_error(head + "aa: jitter:2\nsquare: 0\n```\n"),
            f + "7: step 'S': square 0: the pixel is not sampled adaptively (aa: adaptive:T[:D])");
  EXPECT_EQ(check_error(head + "aa: adaptive:0.1:1\nsquare: 99\n```\n"),
            f + "7: step 'S': square 99: the pixel's subdivision has 5 squares (0..4)");
}

// A lesson on the BVH: the runner records the pixel's walk through the BVH the state names (its builder,
// order and bins as the trace's parameters), steps to its box tests, selects a node by id, and says what does
// not apply (an L/R path, an id beyond the tree, bad options) with the responsible line.
TEST(LessonRunner, RecordsBvhTraces) {
  LessonRunner runner;
  Lesson l = parse_lesson_text(
      "# T\n## A\n```raystep\nscene: ../scenes/cornell.json\naccel: bvh\npixel: 160,200\n"
      "step-to: box_test:3\nnode: 2\n```\n## B\n```raystep\naccel: bvh-median\nbvh-order: axis\nbins: 8\n"
      "step-to: push:1\nheat: boxes\n```\n## C\n```raystep\naccel: bvh8\nstep-to: leaf:1\nnode: 5\n```\n",
      kSource + "/lessons/t.md");
  EXPECT_EQ(check_lesson(l), 0);
  StepWorld a = runner.enter(l.steps[0].state);
  ASSERT_TRUE(a.trace);
  EXPECT_EQ(a.trace->structure.kind, "bvh");
  EXPECT_EQ(a.trace->version, kTraceVersion);
  const Event& box = a.trace->rays[0].events[size_t(a.step)];
  EXPECT_EQ(box.type, EventType::box_test);
  EXPECT_EQ(a.node, 2);
  // The recorded walk ends where the structure's own kernel does.
  Hit hit;
  a.accel->intersect(a.trace->rays[0].ray, &hit);
  EXPECT_EQ(a.trace->rays[0].events.back().prim, hit.prim);
  EXPECT_TRUE(hit.found());

  StepWorld b = runner.enter(l.steps[1].state);
  ASSERT_TRUE(b.trace);
  EXPECT_EQ(b.trace->structure.kind, "bvh-median");
  std::map<std::string, std::string> text;
  std::map<std::string, double> number;
  for (const TraceParam& p : b.trace->structure.params)
    if (p.is_text)
      text[p.key] = p.text;
    else
      number[p.key] = p.number;
  EXPECT_EQ(text["order"], "split_axis");
  EXPECT_EQ(number["bins"], 8.0);
  EXPECT_EQ(b.trace->rays[0].events[size_t(b.step)].type, EventType::push);
  EXPECT_NE(a.accel, b.accel);  // another structure, built for the new options

  StepWorld c = runner.enter(l.steps[2].state);  // the wide BVH, its ids as describe() numbers them
  ASSERT_TRUE(c.trace);
  EXPECT_EQ(c.trace->structure.kind, "bvh8");
  EXPECT_EQ(c.trace->rays[0].events[size_t(c.step)].type, EventType::leaf);
  EXPECT_EQ(c.node, 5);
  c.accel->intersect(c.trace->rays[0].ray, &hit);
  EXPECT_EQ(c.trace->rays[0].events.back().prim, hit.prim);

  const std::string f = kSource + "/lessons/t.md:";
  const std::string head = "# T\n## S\n```raystep\nscene: ../scenes/cornell.json\naccel: bvh\n";
  EXPECT_EQ(check_error(head + "node: 99999\n```\n").rfind(f + "6: step 'S': node 99999: the BVH has ", 0),
            0u);
  // A binary BVH's node by its path (L the first child, R the second), as the debugger takes it.
  EXPECT_EQ(check_error(head + "node-path: LR\n```\n"), "no error");
  EXPECT_EQ(check_error(head + "node-path: LLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLL\n```\n")
                .rfind(f + "6: step 'S': node-path 'LLLLLLLLLLLLLLLLLLLLLLLLLLLLLLLL': node ", 0),
            0u);
  EXPECT_EQ(check_error(head + "bvh-leaf: 4\nbvh-max-leaf: 2\n```\n"),
            f + "7: step 'S': building the bvh: bvh: max_leaf_size must be at least leaf_size");
}

TEST(LessonRunner, AnswersEveryKindOnTheCornellBox) {
  LessonRunner runner;
  Lesson l = parse_lesson_text(
      "# T\n## A\n```raystep\nscene: ../scenes/cornell.json\naccel: kd\npixel: 160,200\nstep-to: node:1\n"
      "ask: first-child\n```\n## B\n```raystep\nstep-to: leaf:1\nask: next-pop\n```\n## C\n```raystep\n"
      "panel: sah\nask: sah-plane\n```\n## D\n```raystep\naa: adaptive:0.05:2\nask: subdivide\n```\n"
      "## E\n```raystep\naccel: grid\npanel: none\nstep-to: cell:2\nask: next-cell\n```\n",
      kSource + "/lessons/t.md");
  EXPECT_EQ(check_lesson(l), 5);
  for (const LessonStep& s : l.steps) {
    StepWorld w = runner.enter(s.state, s.ask);
    ASSERT_TRUE(w.answer);
    EXPECT_FALSE(w.answer->text.empty());
    EXPECT_FALSE(w.answer->why.empty());
    std::printf("%s: %s\n  %s\n", question_kind_name(*s.ask), w.answer->text.c_str(), w.answer->why.c_str());
  }
}

}  // namespace
}  // namespace raystep
