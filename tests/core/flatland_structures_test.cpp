// The real structures restricted to the plane of a flatland scene (geometry/split_space.h): the kd-tree's,
// the BVH's and the BSP tree's SAH weigh a box by its perimeter and cut x and y only, the BSP tree by
// vertical planes, the grid has one layer of d sqrt(n) cells across, and the lines of Crofton's theorem lie
// in the plane. The slides' kd-tree figure walks as the slides draw it.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <set>
#include <string>
#include <vector>

#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_entry_probability.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/plane_outline.h"
#include "raystep/accel/random_lines.h"
#include "raystep/accel/structure_options.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/figure/flat_figure.h"
#include "raystep/io/scene_loader.h"
#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/replayer.h"
#include "raystep/replay/slide_stack.h"
#include "raystep/scene/flatland.h"
#include "raystep/trace/node_path.h"
#include "raystep/trace/record_trace.h"

namespace raystep {
namespace {

const std::string kFlatDir = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/flatland";

// Two circles: (1, 1) radius 1 and (5, 2) radius 1. The root's box is [0, 6] x [0, 3] in the plane (z in
// [-1, 1], which the plane ignores): perimeter 2 (6 + 3) = 18.
Scene two_circles() {
  return parse_scene(R"({"dimensions": 2, "objects": [
    {"type": "circle", "center": [1, 1], "radius": 1}, {"type": "circle", "center": [5, 2], "radius": 1}]})",
                     "two.json");
}

// The hand computation, candidate by candidate: C = t_t + t_i (P_b N_b + P_a N_a) / P.
struct Expected {
  int axis;
  float position;
  float p_below, p_above;
  uint32_t n_below, n_above;
};
const Expected kRootCandidates[] = {
    {0, 2.f, 2.f * (2 + 3), 2.f * (4 + 3), 1, 1},  // x = 2: [0, 2] x [0, 3] and [2, 6] x [0, 3]
    {0, 4.f, 2.f * (4 + 3), 2.f * (2 + 3), 1, 1},  // x = 4
    {1, 1.f, 2.f * (6 + 1), 2.f * (6 + 2), 1, 2},  // y = 1: the first circle reaches above it
    {1, 2.f, 2.f * (6 + 2), 2.f * (6 + 1), 2, 1},  // y = 2
};

float perimeter_cost(const Expected& e) {
  return 1.f + 80.f * (e.p_below / 18.f * float(e.n_below) + e.p_above / 18.f * float(e.n_above));
}

TEST(FlatlandStructures, KdSahWeighsPerimetersOnXAndYOnly) {
  Scene s = two_circles();
  ASSERT_TRUE(s.geometry.split_space().plane());
  SahCurve curve = record_sah_curve(s.geometry, KdOptions{}, 0);
  ASSERT_EQ(curve.candidates.size(), 4u);  // 2n = 4 per axis less the box's own faces; none on z
  for (size_t i = 0; i < 4; ++i) {
    const SahCandidate& c = curve.candidates[i];
    const Expected& e = kRootCandidates[i];
    EXPECT_EQ(c.axis, e.axis) << i;
    EXPECT_EQ(c.position, e.position) << i;
    EXPECT_EQ(c.n_below, e.n_below) << i;
    EXPECT_EQ(c.n_above, e.n_above) << i;
    EXPECT_FLOAT_EQ(c.area_node, 18.f);
    EXPECT_FLOAT_EQ(c.area_below, e.p_below) << i;
    EXPECT_FLOAT_EQ(c.area_above, e.p_above) << i;
    EXPECT_FLOAT_EQ(c.cost, perimeter_cost(e)) << i;
  }
  // x = 2 and x = 4 cost the same, 1 + 80 (10 + 14) / 18 = 107.67; the first is taken.
  EXPECT_NEAR(perimeter_cost(kRootCandidates[0]), 107.667f, 1e-3f);
  EXPECT_FALSE(curve.leaf);
  EXPECT_EQ(curve.axis, 0);
  EXPECT_EQ(curve.position, 2.f);
}

TEST(FlatlandStructures, BvhSahWeighsPerimeters) {
  Scene s = two_circles();
  BvhOptions o;
  o.builder = BvhBuilder::sweep;
  BvhSahCurve curve = record_bvh_sah_curve(s.geometry, o, 0);
  ASSERT_FALSE(curve.candidates.empty());
  for (const BvhCandidate& c : curve.candidates) {
    EXPECT_LT(c.axis, 2);
    EXPECT_FLOAT_EQ(c.area_node, 18.f);
  }
  // The split between the circles: boxes [0, 2] x [0, 2] and [4, 6] x [1, 3], perimeters 8 and 8.
  const BvhCandidate& chosen = curve.candidates[size_t(curve.chosen)];
  EXPECT_FLOAT_EQ(chosen.area_left, 8.f);
  EXPECT_FLOAT_EQ(chosen.area_right, 8.f);
  EXPECT_FLOAT_EQ(chosen.cost, 1.f + 80.f * (8.f + 8.f) / 18.f);
}

TEST(FlatlandStructures, BspCutsByVerticalPlanesWeighedByPerimeter) {
  Scene s = parse_scene(R"({"dimensions": 2, "objects": [
    {"type": "segment", "points": [[0, 0], [4, 1]]}, {"type": "segment", "points": [[1, 3], [3, 4]]},
    {"type": "polygon", "fill": true, "points": [[5, 0], [7, 0], [6, 2]]}]})",
                        "bsp.json");
  BspSahCurve curve = record_bsp_sah_curve(s.geometry, BspOptions{}, 0);
  ASSERT_FALSE(curve.candidates.empty());
  // The root's cell is the box [0, 7] x [0, 4]: perimeter 22.
  EXPECT_NEAR(curve.info.area, 22.f, 1e-5f);
  int own = 0;
  for (const BspCandidate& c : curve.candidates) {
    EXPECT_EQ(c.plane.normal.z, 0.f) << "direction " << c.direction;  // no cap's plane, no slanted k-DOP
    own += c.direction < 0;
    // The two parts' perimeters: the node's plus the cut's chord twice (the chord is at most the diagonal).
    const double chord = (c.area_below + c.area_above - 22.0) / 2.0;
    EXPECT_GT(chord, 0.0);
    EXPECT_LE(chord, std::hypot(7.0, 4.0) + 1e-9);
    EXPECT_NEAR(c.area_node, 22.0, 1e-5);
  }
  EXPECT_GT(own, 0);  // the walls' own planes are vertical: an autopartition of the segments
  // An axis plane x = p cuts the box's chord of length 4: parts 2 (p + 4) and 2 (7 - p + 4).
  for (const BspCandidate& c : curve.candidates)
    if (c.direction == 0) {
      EXPECT_NEAR(c.area_below, 2.0 * (double(c.plane.offset) + 4.0), 1e-4);
      EXPECT_NEAR(c.area_above, 2.0 * (7.0 - double(c.plane.offset) + 4.0), 1e-4);
    }
}

TEST(FlatlandStructures, TheGridIsOneLayerOfDSqrtNCellsAcross) {
  Scene s = load_scene(kFlatDir + "/grid_objects.json");
  UniformGrid grid;
  grid.build(s.geometry);
  const auto n = grid.resolution();
  EXPECT_EQ(n[2], 1);
  const float d = GridOptions{}.density;
  EXPECT_EQ(std::max(n[0], n[1]), int(std::round(d * std::sqrt(float(s.geometry.size())))));
  // In space the same bounds and count would take d cbrt(n) on the longest axis, z included.
  const auto space = UniformGrid::resolution_for(s.geometry.bounds(), s.geometry.size(), d);
  EXPECT_EQ(std::max({space[0], space[1], space[2]}),
            int(std::round(d * std::cbrt(float(s.geometry.size())))));
}

// Crofton in the plane: lines uniform in direction and offset meet a box with probability L / (2 pi R), and a
// child's box given its parent's with the ratio of their perimeters.
TEST(FlatlandStructures, PlaneLinesMeetBoxesByPerimeter) {
  Bounds3 box;
  box.lo = glm::vec3(0.f, 0.f, -5.f);
  box.hi = glm::vec3(4.f, 1.f, 5.f);
  const LinesMeetingBox plane = lines_meeting_box(box, 200000, 3, SplitSpace{2});
  EXPECT_NEAR(plane.predicted, 10.0 / (2.0 * M_PI * 0.5 * std::hypot(4.0, 1.0)), 1e-6);  // R in float
  EXPECT_NEAR(plane.measured, plane.predicted, 0.01);
  Pcg32 rng(7, 0);
  for (int i = 0; i < 100; ++i) {
    const Ray r = random_plane_line(rng, glm::vec3(1.f, 2.f, 0.f), 3.f);
    EXPECT_EQ(r.origin.z, 0.f);
    EXPECT_EQ(r.direction.z, 0.f);
  }
  Scene s = load_scene(kFlatDir + "/kd_traversal.json");
  KdTree kd;
  kd.build(s.geometry);
  const std::vector<KdNodeEntry> entries = measure_entry_probability(kd, 100000, 5);
  const KdTreeData& t = kd.data();
  const float root = SplitSpace{2}.measure(t.bounds);
  ASSERT_GT(entries.size(), 4u);
  for (size_t i = 1; i < entries.size(); ++i) {
    EXPECT_NEAR(entries[i].predicted, SplitSpace{2}.measure(t.info[i].box) / root, 1e-6) << i;
    EXPECT_NEAR(entries[i].lines, entries[i].predicted, 0.01) << i;
  }
}

// The slides' figure: "Stack: LLR,R  Current: LLL", then R, then RR, where the ray hits G.
TEST(FlatlandStructures, TheKdFigureWalksAsTheSlidesDrawIt) {
  Scene s = load_scene(kFlatDir + "/kd_traversal.json");
  ASSERT_TRUE(s.flat && s.flat->has_ray);
  KdTree kd;
  kd.build(s.geometry);
  const Ray ray = flat_ray(s.flat->ray_origin, s.flat->ray_direction);
  Trace t = record_trace(s.geometry, kd, {RayRequest{ray, RayKind::primary, 0, false, {0, 0}}}, "kd.json",
                         "fnv1a64:0000000000000000");
  ASSERT_EQ(t.rays.size(), 1u);
  const TracedRay& r = t.rays[0];
  const replay::Replayer replayer(r);
  std::vector<std::string> visits, slides;
  for (int k = 0; k < replayer.size(); ++k) {
    const Event& e = r.events[size_t(k)];
    if (e.type != EventType::node) continue;
    visits.push_back(trace_node_path_text(t, e.node));
    slides.push_back(replay::slide_stack_text(t, r, replayer.at(k)));
  }
  const std::vector<std::string> expected_visits = {"root", "L", "LL", "LLL", "LLR", "R", "RR"};
  EXPECT_EQ(visits, expected_visits);
  ASSERT_EQ(slides.size(), expected_visits.size());
  EXPECT_EQ(slides[3], "Stack: LLR,R   Current: LLL");
  EXPECT_EQ(slides[4], "Stack: R   Current: LLR");
  EXPECT_EQ(slides[5], "Stack: (empty)   Current: R");
  EXPECT_EQ(slides[6], "Stack: (empty)   Current: RR");
  const replay::ReplayState end = replayer.at(replayer.size() - 1);
  ASSERT_GE(end.nearest_prim, 0);
  EXPECT_EQ(s.geometry.objects()[s.geometry.object_of(uint32_t(end.nearest_prim))].name, "G");

  // The figure ticks t* on the ray at the root, where the ray meets the root's split line x = 4.2.
  const PlaneOutline outline = plane_outline(kd);
  const Figure still = flat_figure_still(s, &outline, nullptr);
  const int root = replay::nth_event(r, EventType::node, 1);
  const FlatWalkLayers w = flat_figure_walk(FlatFigureInput{&s, &outline, &t, root}, still);
  const auto tick = std::find_if(w.marks.items.begin(), w.marks.items.end(),
                                 [](const FigureItem& it) { return it.css == "t-star"; });
  ASSERT_NE(tick, w.marks.items.end());
  EXPECT_NEAR(0.5f * (tick->points[0].x + tick->points[1].x), kd.data().nodes[0].split, 1e-4f);
}

// The walk's marks in the plane: at a cell of the grid the 3D-DDA's tMax ticks lie on the ray where it
// crosses the cell's next boundary on that axis (a grid line), and at a mailbox hit the shape skipped is
// marked, with the mailbox's shapes dashed.
TEST(FlatlandStructures, TheGridWalksMarksShowTMaxAndTheMailbox) {
  Scene s = load_scene(kFlatDir + "/mailbox.json");
  ASSERT_TRUE(s.flat && s.flat->has_ray);
  auto grid = make_accelerator("grid", StructureOptions{});
  grid->build(s.geometry);
  const PlaneOutline outline = plane_outline(*grid);
  const Ray ray = flat_ray(s.flat->ray_origin, s.flat->ray_direction);
  const Trace t = record_trace(s.geometry, *grid, {RayRequest{ray, RayKind::primary, 0, false, {0, 0}}},
                               "mailbox.json", "fnv1a64:0000000000000000");
  const TracedRay& r = t.rays[0];
  const Figure still = flat_figure_still(s, &outline, nullptr);
  const auto* ug = dynamic_cast<const UniformGrid*>(grid.get());
  ASSERT_NE(ug, nullptr);
  int cells = 0, mailbox_hits = 0;
  std::set<std::string> skipped;
  for (int k = 0; k < int(r.events.size()); ++k) {
    const Event& e = r.events[size_t(k)];
    FlatFigureInput in{&s, &outline, &t, k};
    const FlatWalkLayers w = flat_figure_walk(in, still);
    auto count = [&](const std::string& css) {
      return std::count_if(w.marks.items.begin(), w.marks.items.end(),
                           [&](const FigureItem& it) { return it.css == css; });
    };
    if (e.type == EventType::cell) {
      ++cells;
      for (int a = 0; a < 2; ++a) {
        const std::string css = a == 0 ? "tmax-x" : "tmax-y";
        const auto tick = std::find_if(w.marks.items.begin(), w.marks.items.end(),
                                       [&](const FigureItem& it) { return it.css == css; });
        if (!std::isfinite(e.t_max[a])) continue;
        const glm::vec2 p = glm::vec2(ray.origin) + e.t_max[a] * glm::vec2(ray.direction);
        if (p.x > still.hi.x || p.y > still.hi.y) continue;  // beyond the picture: not drawn
        ASSERT_NE(tick, w.marks.items.end()) << "event " << k << " axis " << a;
        // The tick crosses the ray at the boundary: its points lie on either side of p, along the normal.
        const glm::vec2 a0 = tick->points[0], a1 = tick->points[1];
        const glm::vec2 u = glm::normalize(a1 - a0);
        EXPECT_NEAR(u.x * (p - a0).y - u.y * (p - a0).x, 0.f, 1e-4f);  // on the tick's line
        EXPECT_GT(glm::dot(p - a0, u), 0.f);                           // between its ends
        EXPECT_LT(glm::dot(p - a0, u), glm::length(a1 - a0));
        EXPECT_NEAR(glm::dot(u, glm::normalize(glm::vec2(ray.direction))), 0.f, 1e-4f);  // across the ray
        // p is on a grid line of axis a: the cell's boundary in the walk's direction.
        const float cell = (ug->bounds().hi[a] - ug->bounds().lo[a]) / float(ug->resolution()[a]);
        const float lines = (p[a] - ug->bounds().lo[a]) / cell;
        EXPECT_NEAR(lines, std::round(lines), 1e-3f) << "event " << k << " axis " << a;
      }
    }
    if (e.type == EventType::mailbox_hit) {
      ++mailbox_hits;
      EXPECT_EQ(count("mailbox-hit"), 1) << "event " << k;
      EXPECT_GE(count("mailboxed"), 1) << "event " << k;
      skipped.insert(s.flat->shapes[size_t(s.flat->shape_of(uint32_t(e.prim)))].name);
    }
    if (e.type == EventType::prim_test) EXPECT_EQ(count("testing"), 1) << "event " << k;
  }
  EXPECT_GT(cells, 3);
  EXPECT_GT(mailbox_hits, 0);
  EXPECT_TRUE(skipped.count("long wall"));  // the wall beside the ray, skipped in cell after cell
}

// The octree of a 2D scene is a quadtree: each inner cell has four children that halve it on x and y and keep
// its z extent (the walls' height), the trace lists the four, the replay names them by quadrant, and rays off
// the plane (a pixel's, looking down at an angle) find what brute force finds, as rays in it do.
TEST(FlatlandStructures, TheOctreeOfA2DSceneIsAQuadtree) {
  Scene s = load_scene(kFlatDir + "/variations.json");
  Octree oc;
  oc.build(s.geometry);
  const OctreeData& d = oc.data();
  ASSERT_EQ(d.axes, 2);
  size_t inner = 0;
  for (size_t id = 0; id < d.nodes.size(); ++id) {
    if (d.nodes[id].is_leaf()) continue;
    ++inner;
    const Bounds3& b = d.info[id].box;
    for (int c = 0; c < 4; ++c) {
      const uint32_t k = d.nodes[id].child(c);
      ASSERT_LT(k, d.nodes.size());
      EXPECT_EQ(d.info[k].parent, int32_t(id));
      const Bounds3& cb = d.info[k].box;
      for (int a = 0; a < 2; ++a) {
        const float mid = 0.5f * (b.lo[a] + b.hi[a]);
        EXPECT_EQ(cb.lo[a], (c >> a) & 1 ? mid : b.lo[a]);
        EXPECT_EQ(cb.hi[a], (c >> a) & 1 ? b.hi[a] : mid);
      }
      EXPECT_EQ(cb.lo.z, b.lo.z);
      EXPECT_EQ(cb.hi.z, b.hi.z);
    }
  }
  ASSERT_GT(inner, 2u);
  EXPECT_EQ(d.nodes.size(), 1 + 4 * inner);  // four children to each inner cell, nothing else
  EXPECT_EQ(d.bounds.hi.x - d.bounds.lo.x, d.bounds.hi.y - d.bounds.lo.y);  // a square

  // The walk's trace: four children per inner cell, named by quadrant.
  ASSERT_TRUE(s.flat && s.flat->has_ray);
  const Ray ray = flat_ray(s.flat->ray_origin, s.flat->ray_direction);
  const Trace t = record_trace(s.geometry, oc, {RayRequest{ray, RayKind::primary, 0, false, {0, 0}}},
                               "variations.json", "fnv1a64:0000000000000000");
  int inner_nodes = 0;
  for (const TraceNode& n : t.nodes)
    if (!n.leaf) {
      EXPECT_EQ(n.children.size(), 4u);
      ++inner_nodes;
    }
  EXPECT_GT(inner_nodes, 0);
  const replay::Replayer replayer(t.rays[0]);
  int choices = 0;
  for (int k = 0; k < replayer.size(); ++k) {
    const replay::OctreeChoice c = replay::octree_choice(t, t.rays[0], replayer.at(k));
    if (!c.valid) continue;
    ++choices;
    EXPECT_EQ(c.axes, 2);
    for (const replay::OctreeChildStep& st : c.path) {
      EXPECT_LT(st.octant, 4);
      EXPECT_LT(st.exit_axis, 2);  // a ray in the plane leaves by x or y
    }
    // The order by the planes is the order the walk visits the children.
    for (size_t i = 0; i < c.visited.size() && i < c.path.size(); ++i)
      EXPECT_EQ(c.visited[i], c.path[i].node);
  }
  EXPECT_GT(choices, 0);
  EXPECT_EQ(replay::octant_name(2, 2), "x- y+");

  // Off the plane: rays from above at random angles, and straight down, as brute force.
  auto brute = make_accelerator("brute", StructureOptions{});
  brute->build(s.geometry);
  std::mt19937 rng(11);
  std::uniform_real_distribution<float> ux(s.flat->lo.x, s.flat->hi.x), uy(s.flat->lo.y, s.flat->hi.y),
      tilt(-1.f, 1.f);
  int hits = 0;
  for (int i = 0; i < 2000; ++i) {
    const glm::vec3 target(ux(rng), uy(rng), tilt(rng) * s.flat->half_height);
    const glm::vec3 dir = i % 5 == 0 ? glm::vec3(0.f, 0.f, -1.f) : glm::vec3(tilt(rng), tilt(rng), -1.f);
    Ray r;
    r.origin = target - 3.f * s.flat->half_height * dir;
    r.direction = dir;
    Hit a, b;
    const bool ha = oc.intersect(r, &a), hb = brute->intersect(r, &b);
    ASSERT_EQ(ha, hb) << "ray " << i;
    if (!ha) continue;
    ++hits;
    EXPECT_EQ(a.t, b.t) << "ray " << i;
  }
  EXPECT_GT(hits, 200);
}

// A partition's outline: its leaves' regions tile the root's (their areas add up to it), regions are by node
// id with the slides' paths, and every split line lies in its node's region. A BVH's boxes instead overlap.
TEST(FlatlandStructures, TheOutlinesLeavesTileTheRoot) {
  Scene s = load_scene(kFlatDir + "/variations.json");
  auto area = [](const std::vector<glm::vec2>& p) {
    double a = 0.0;
    for (size_t i = 0; i < p.size(); ++i) {
      const glm::vec2 &u = p[i], &v = p[(i + 1) % p.size()];
      a += double(u.x) * double(v.y) - double(v.x) * double(u.y);
    }
    return a / 2.0;
  };
  // (Not the octree yet: it still halves z too, so its children come in pairs over the same square.)
  for (const char* name : {"kd", "kd-median", "bsp"}) {
    auto accel = make_accelerator(name, StructureOptions{});
    accel->build(s.geometry);
    const PlaneOutline o = plane_outline(*accel);
    ASSERT_EQ(o.regions.size(), o.total_nodes) << name;
    double leaves = 0.0;
    int splits = 0;
    for (size_t i = 0; i < o.regions.size(); ++i) {
      const OutlineRegion& r = o.regions[i];
      EXPECT_EQ(r.node, int32_t(i)) << name;
      EXPECT_EQ(r.path.size(), size_t(r.depth)) << name;
      // Counter-clockwise (a BSP tree may cut a sliver of no width off a wall: area 0, perimeter twice its
      // length).
      EXPECT_GE(area(r.polygon), -1e-9) << name << " node " << i;
      if (r.leaf) leaves += area(r.polygon);
      splits += !r.leaf;
    }
    const double root = double(o.hi.x - o.lo.x) * double(o.hi.y - o.lo.y);
    EXPECT_NEAR(leaves, root, 1e-4 * root) << name;
    EXPECT_EQ(o.lines.size(), size_t(splits)) << name;
    for (const OutlineLine& l : o.lines) {
      const std::vector<glm::vec2>& p = o.regions[size_t(l.node)].polygon;
      for (const glm::vec2& e : {l.a, l.b}) {
        glm::vec2 lo(1e30f), hi(-1e30f);
        for (const glm::vec2& q : p) lo = glm::min(lo, q), hi = glm::max(hi, q);
        EXPECT_TRUE(e.x >= lo.x - 1e-4f && e.x <= hi.x + 1e-4f && e.y >= lo.y - 1e-4f && e.y <= hi.y + 1e-4f)
            << name << " node " << l.node;
      }
    }
  }
  auto bvh = make_accelerator("bvh", StructureOptions{});
  bvh->build(s.geometry);
  const PlaneOutline b = plane_outline(*bvh);
  EXPECT_TRUE(b.boxes);
  EXPECT_TRUE(b.lines.empty());
  auto brute = make_accelerator("brute", StructureOptions{});
  brute->build(s.geometry);
  EXPECT_FALSE(has_plane_outline(*brute));
}

// A wide BVH in the plane: its regions are the boxes of every child slot, numbered as its traces number them
// (WideBvh::describe), each inside its parent's, and a recorded walk lights the very box of each node it
// visits, with the boxes it pushed dashed on the stack.
TEST(FlatlandStructures, TheWideBvhsOutlineIsTheBoxesItsWalkVisits) {
  Scene s = load_scene(kFlatDir + "/sah_build.json");
  ASSERT_TRUE(s.flat && s.flat->has_ray);
  for (const char* name : {"bvh4", "bvh8"}) {
    auto accel = make_accelerator(name, StructureOptions{});
    accel->build(s.geometry);
    const WideBvhView view = dynamic_cast<const WideBvh&>(*accel).describe();
    ASSERT_TRUE(has_plane_outline(*accel)) << name;
    const PlaneOutline o = plane_outline(*accel);
    EXPECT_TRUE(o.boxes) << name;
    EXPECT_TRUE(o.lines.empty()) << name;
    ASSERT_EQ(o.regions.size(), view.nodes.size()) << name;
    ASSERT_GT(view.nodes.size(), 1u) << name;
    auto box_of = [](const OutlineRegion& r) {
      glm::vec2 lo(1e30f), hi(-1e30f);
      for (const glm::vec2& p : r.polygon) lo = glm::min(lo, p), hi = glm::max(hi, p);
      return std::pair<glm::vec2, glm::vec2>(lo, hi);
    };
    for (size_t id = 0; id < view.nodes.size(); ++id) {
      const OutlineRegion& r = o.regions[id];
      EXPECT_EQ(r.node, int32_t(id)) << name;
      EXPECT_EQ(r.leaf, view.nodes[id].leaf) << name << " node " << id;
      EXPECT_EQ(r.depth, view.nodes[id].depth) << name << " node " << id;
      const auto [lo, hi] = box_of(r);
      EXPECT_EQ(lo, glm::vec2(view.nodes[id].box.lo)) << name << " node " << id;
      EXPECT_EQ(hi, glm::vec2(view.nodes[id].box.hi)) << name << " node " << id;
      if (view.nodes[id].parent < 0) continue;
      const auto [plo, phi] = box_of(o.regions[size_t(view.nodes[id].parent)]);
      EXPECT_TRUE(lo.x >= plo.x && lo.y >= plo.y && hi.x <= phi.x && hi.y <= phi.y) << name << " node " << id;
    }

    const Ray ray = flat_ray(s.flat->ray_origin, s.flat->ray_direction);
    const Trace t = record_trace(s.geometry, *accel, {RayRequest{ray, RayKind::primary, 0, false, {0, 0}}},
                                 "sah_build.json", "fnv1a64:0000000000000000");
    ASSERT_EQ(t.rays.size(), 1u);
    const TracedRay& r = t.rays[0];
    const replay::Replayer replayer(r);
    const Figure still = flat_figure_still(s, &o, nullptr);
    int walked = 0, stacked = 0;
    for (int k = 0; k < replayer.size(); ++k) {
      const replay::ReplayState at = replayer.at(k);
      if (at.node_event < 0 || at.ended) continue;
      const int32_t node = r.events[size_t(at.node_event)].node;
      ASSERT_GE(node, 0);
      ASSERT_LT(size_t(node), o.regions.size()) << name;
      ++walked;
      const FlatWalkLayers w = flat_figure_walk(FlatFigureInput{&s, &o, &t, k}, still);
      const auto current = std::find_if(w.walk.items.begin(), w.walk.items.end(),
                                        [](const FigureItem& it) { return it.css == "current"; });
      ASSERT_NE(current, w.walk.items.end()) << name << " step " << k;
      EXPECT_EQ(current->points, o.regions[size_t(node)].polygon) << name << " step " << k;
      stacked += int(at.stack.size());
      // The caption writes the stack as the slides do, by the ids the tree view gives the nodes.
      std::string stack;
      for (size_t i = at.stack.size(); i-- > 0;)
        stack += (stack.empty() ? "" : ",") + std::to_string(at.stack[i].node);
      const std::string slides = "Stack: " + (stack.empty() ? std::string("(empty)") : stack) +
                                 "   Current: " + (node == 0 ? std::string("root") : std::to_string(node));
      EXPECT_NE(std::find(w.caption.begin(), w.caption.end(), slides), w.caption.end())
          << name << " step " << k << ": " << slides;
      EXPECT_EQ(size_t(std::count_if(w.walk.items.begin(), w.walk.items.end(),
                                     [](const FigureItem& it) { return it.css == "stacked"; })),
                at.stack.size())
          << name << " step " << k;
    }
    EXPECT_GT(walked, 1) << name;
    // At each inner node the choice names the child entered first, a hit one, also when it is a leaf (a wide
    // BVH enters a leaf child with its leaf event): "no child hit" only when none was.
    int entered_leaf = 0;
    for (int k = 0; k < replayer.size(); ++k) {
      if (r.events[size_t(k)].type != EventType::node) continue;
      const replay::BvhChoice c = replay::bvh_choice(r, replayer.at(replayer.size() - 1 > k ? k + 1 : k));
      if (!c.valid) continue;
      std::vector<int32_t> hit;
      for (const replay::BoxTestMark& m : c.tests)
        if (m.hit) hit.push_back(m.child);
      if (hit.empty()) {
        EXPECT_EQ(c.first, -1) << name << " step " << k;
      } else {
        EXPECT_NE(std::find(hit.begin(), hit.end(), c.first), hit.end()) << name << " step " << k;
        entered_leaf += c.first >= 0 && o.regions[size_t(c.first)].leaf;
      }
    }
    EXPECT_GT(entered_leaf, 0) << name;
    EXPECT_GT(stacked, 0) << name;  // the walk keeps the farther boxes for later
  }
}

}  // namespace
}  // namespace raystep
