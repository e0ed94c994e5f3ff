// The octree: agreement with brute force (same primitive, same t) under every option on random,
// camera, edge-aimed and in-plane rays (lying in the cells' faces and centre planes, with +0 and -0
// components), non-finite rays (a miss, no crash), the pathological meshes (identical, coplanar, a teapot in
// a stadium, long slivers: bounded nodes and references, right hits), the recorded walk against the kernel
// (same hits and counters, cells front to back, Revelles' child order) and the trace's octree nodes read
// back.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <map>
#include <random>

#include "ray_battery.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/structure_options.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/record/event_recorder.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/octree_trace.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::camera_rays;
using test::count_disagreements;
using test::make_soup;

std::unique_ptr<Octree> make_octree(const Geometry& g, int leaf = 8, int depth = 0) {
  OctreeOptions o;
  o.leaf_size = leaf;
  o.max_depth = depth;
  auto tree = std::make_unique<Octree>(o);
  tree->build(g);
  return tree;
}

// Rays where the walk's decisions are ties: lying in a cell's face or centre plane (direction +0 or -0 on
// that axis), axis-parallel along a cell's edge, through a cell's centre (where eight children meet) and
// corner to corner, from outside and from inside the root.
std::vector<Ray> cell_rays(const OctreeData& d, uint32_t seed, size_t max_rays = 4000) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> nd;
  std::vector<Ray> rays;
  const Bounds3& root = d.bounds;
  glm::vec3 lo = root.lo - 0.25f * root.extent(), e = 1.5f * root.extent();
  for (size_t id = 0; id < d.nodes.size() && rays.size() < max_rays; ++id) {
    const Bounds3& box = d.info[id].box;
    glm::vec3 mid = 0.5f * (box.lo + box.hi);
    for (int k = 0; k < 6; ++k) {
      int axis = int(rng() % 3);
      float plane = k % 2 ? mid[axis] : (u(rng) < 0.5f ? box.lo[axis] : box.hi[axis]);
      Ray r;
      r.origin = lo + e * glm::vec3(u(rng), u(rng), u(rng));
      r.origin[axis] = plane;
      r.direction = glm::vec3(nd(rng), nd(rng), nd(rng));
      if (k < 2) r.direction[axis] = u(rng) < 0.5f ? 0.f : -0.f;  // lying in the plane
      if (k == 2) {                                               // axis-parallel along an edge
        r.direction = glm::vec3(u(rng) < 0.5f ? 0.f : -0.f);
        r.direction[(axis + 1) % 3] = u(rng) < 0.5f ? 1.f : -1.f;
        r.origin[(axis + 2) % 3] = u(rng) < 0.5f ? mid[(axis + 2) % 3] : box.lo[(axis + 2) % 3];
      }
      if (k == 3) {  // through the centre, where the eight children meet
        r.direction = mid - r.origin;
      }
      if (k == 4) {  // corner to corner, or along the centre lines
        r.origin = u(rng) < 0.5f ? box.lo : glm::vec3(mid.x, mid.y, box.lo.z);
        r.direction = u(rng) < 0.5f ? box.hi - box.lo : glm::vec3(-0.f, 0.f, 1.f);
      }
      if (k == 5) {  // from inside the cell, any direction
        r.origin = box.lo + (box.hi - box.lo) * glm::vec3(u(rng), u(rng), u(rng));
      }
      rays.push_back(r);
    }
  }
  return rays;
}

TEST(Octree, AgreesWithBruteForceOnRandomAndCameraRaysUnderEveryOption) {
  for (int spheres : {8, 0}) {
    Geometry g = make_soup(5, 400, spheres);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = random_rays(g.bounds(), 4000, 9);
    std::vector<Ray> cam = camera_rays(g.bounds(), 40);
    rays.insert(rays.end(), cam.begin(), cam.end());
    for (int leaf : {1, 3, 64})
      for (int depth : {0, 2, kOctreeMaxDepth}) {
        auto tree = make_octree(g, leaf, depth);
        OctreeStats st = octree_stats(tree->data());
        EXPECT_LE(st.max_depth, octree_max_depth(tree->options(), g.size()));
        EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << "K " << leaf << " depth " << depth;
      }
  }
}

TEST(Octree, SplitsUntilLeavesHoldAtMostKOrADepthLimit) {
  Geometry g = make_soup(2, 2000, 0);
  for (int leaf : {1, 4, 16}) {
    auto tree = make_octree(g, leaf);
    const OctreeData& d = tree->data();
    OctreeStats st = octree_stats(d);
    EXPECT_GT(st.nodes, 8u);
    EXPECT_EQ((st.nodes - 1) % 8, 0u) << "every inner node has eight children";
    for (size_t i = 0; i < d.nodes.size(); ++i) {
      const OctreeNode& n = d.nodes[i];
      if (!n.is_leaf()) {
        for (int c = 0; c < 8; ++c) {
          const OctreeNodeInfo& ci = d.info[n.child(c)];
          EXPECT_EQ(ci.parent, int32_t(i));
          EXPECT_EQ(ci.depth, d.info[i].depth + 1);
          // Child c is the octant of the parent's cell its bits name.
          for (int a = 0; a < 3; ++a) {
            float mid = 0.5f * (d.info[i].box.lo[a] + d.info[i].box.hi[a]);
            EXPECT_EQ((c >> a) & 1 ? ci.box.lo[a] : ci.box.hi[a], mid);
          }
        }
      } else if (n.prim_count() > uint32_t(leaf)) {
        EXPECT_NE(d.info[i].reason, OctreeLeafReason::few_primitives);
      }
    }
    // The root is a cube containing the scene.
    glm::vec3 e = d.bounds.extent();
    EXPECT_EQ(e.x, e.y);
    EXPECT_EQ(e.y, e.z);
    EXPECT_TRUE(d.bounds.contains(g.bounds().lo) && d.bounds.contains(g.bounds().hi));
  }
}

TEST(Octree, WatertightOnEdgeAimedAndCellPlaneRays) {
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = edge_rays(g, 6000, 12);
  for (int leaf : {1, 8}) {
    auto tree = make_octree(g, leaf);
    std::vector<Ray> all = rays, cells = cell_rays(tree->data(), 3);
    all.insert(all.end(), cells.begin(), cells.end());
    EXPECT_EQ(count_disagreements(*tree, brute, all), 0) << leaf;
    EXPECT_EQ(test::count_leaks(*tree, rays, rays.size()), 0) << leaf;
  }
}

TEST(Octree, SignedZeroDirectionsAgreeWithBruteForce) {
  // Axis-parallel rays with every sign pattern of zeros, from outside and inside, through a soup with
  // spheres.
  Geometry g = make_soup(11, 300, 6);
  BruteForce brute;
  brute.build(g);
  auto tree = make_octree(g, 2);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(-3.f, 3.f);
  std::vector<Ray> rays;
  for (int i = 0; i < 3000; ++i) {
    Ray r;
    r.origin = glm::vec3(u(rng), u(rng), u(rng));
    int axis = i % 3;
    for (int a = 0; a < 3; ++a) r.direction[a] = (i >> (a + 2)) & 1 ? -0.f : 0.f;
    r.direction[axis] = (i / 3) % 2 ? 1.f : -1.f;
    if (i % 7 == 0) r.direction[(axis + 1) % 3] = 0.5f;  // two moving axes, one zero
    rays.push_back(r);
  }
  EXPECT_EQ(count_disagreements(*tree, brute, rays), 0);
}

TEST(Octree, FarOriginsAimedAtCellEdgesAgreeWithBruteForce) {
  // From far away (10 to 10^4 scene sizes) t is large and rounds coarsely, so which child comes next is
  // decided by a near tie when the ray passes a cell's edge or corner: no cell the ray grazes may be lost.
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  g.begin_object("soup", 0);
  Geometry soup = make_soup(7, 300, 0);
  for (uint32_t i = 0; i < soup.size(); ++i)
    g.add_triangle(soup.vertex(i, 0), soup.vertex(i, 1), soup.vertex(i, 2));
  BruteForce brute;
  brute.build(g);
  auto tree = make_octree(g, 1);
  const OctreeData& d = tree->data();
  std::mt19937 rng(17);
  std::normal_distribution<float> nd;
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::vector<Ray> rays;
  for (size_t id = 0; id < d.nodes.size() && rays.size() < 4000; ++id) {
    const Bounds3& box = d.info[id].box;
    glm::vec3 mid = 0.5f * (box.lo + box.hi);
    for (int k = 0; k < 2; ++k) {
      glm::vec3 target = mid;  // the centre (a corner of all eight children), or a point on an edge
      if (k == 1) target[int(rng() % 3)] = box.lo.x + (box.hi.x - box.lo.x) * u(rng);
      glm::vec3 dir = glm::normalize(glm::vec3(nd(rng), nd(rng), nd(rng)));
      float distance = std::pow(10.f, 1.f + 3.f * u(rng)) * 4.f;
      Ray r;
      r.origin = target - distance * dir;
      r.direction = dir;
      rays.push_back(r);
    }
  }
  EXPECT_EQ(count_disagreements(*tree, brute, rays), 0);
}

TEST(Octree, NonFiniteRaysMissAndTerminate) {
  Geometry g = make_soup(8, 50, 1);
  auto tree = make_octree(g, 1);
  EXPECT_EQ(test::count_non_finite_hits(*tree), 0);
  float nan = std::nanf(""), inf = kInfinity;
  Ray r;
  r.origin = g.bounds().lo - glm::vec3(1.f);
  r.direction = g.bounds().center() - r.origin;
  Hit h, a;
  r.tmax = nan;
  EXPECT_FALSE(tree->intersect(r, &h));
  r.tmax = inf;
  BruteForce brute;
  brute.build(g);
  EXPECT_EQ(tree->intersect(r, &h), brute.intersect(r, &a));
  EXPECT_EQ(h.prim, a.prim);
  // A direction so small that 1/d overflows on every axis: a miss or brute force's answer, never a crash.
  r.direction = glm::vec3(1e-40f, -1e-40f, 0.f);
  EXPECT_EQ(tree->intersect(r, &h), brute.intersect(r, &a));
}

TEST(Octree, EmptySceneBadOptionsAndFactory) {
  Geometry empty;
  auto tree = make_octree(empty);
  Ray r;
  Hit h;
  EXPECT_FALSE(tree->intersect(r, &h));
  EXPECT_FALSE(tree->occluded(r));
  Geometry g = make_soup(1, 10, 0);
  for (auto [leaf, depth] :
       {std::pair{0, 0}, {-1, 0}, {8, -1}, {8, kOctreeMaxDepth + 1}, {(1 << 24) + 1, 0}}) {
    OctreeOptions o;
    o.leaf_size = leaf;
    o.max_depth = depth;
    Octree bad(o);
    EXPECT_THROW(bad.build(g), InputError) << leaf << " " << depth;
  }
  std::vector<std::string> names = accelerator_names();
  EXPECT_NE(std::find(names.begin(), names.end(), "octree"), names.end());
  StructureOptions options;
  options.octree.leaf_size = 2;
  auto made = make_accelerator("octree", options);
  ASSERT_NE(dynamic_cast<Octree*>(made.get()), nullptr);
  EXPECT_EQ(made->name(), "octree");
  EXPECT_EQ(dynamic_cast<Octree*>(made.get())->options().leaf_size, 2);
}

// The pathological meshes: each built within the budgets (and far below them where a rule should act), with
// brute force's hits.
std::unique_ptr<Octree> check_pathological(const Geometry& g, size_t ray_count, const char* what) {
  auto tree = make_octree(g, 8);
  OctreeStats st = octree_stats(tree->data());
  EXPECT_LE(st.nodes, octree_node_budget(g.size())) << what;
  EXPECT_LE(st.references, octree_reference_budget(g.size())) << what;
  EXPECT_LE(st.max_depth, octree_max_depth(tree->options(), g.size())) << what;
  EXPECT_LT(tree->memory_bytes(), size_t(64) << 20) << what;
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), ray_count, 21);
  std::vector<Ray> cam = camera_rays(g.bounds(), 12);
  rays.insert(rays.end(), cam.begin(), cam.end());
  EXPECT_EQ(count_disagreements(*tree, brute, rays), 0) << what;
  return tree;
}

TEST(Octree, PathologicalMeshesStayBoundedAndRight) {
  {  // 100,000 identical triangles: no split reduces the count, so the root stays a leaf with one copy each.
    Geometry g;
    g.begin_object("identical", 0);
    for (int i = 0; i < 100000; ++i) g.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0.5f});
    auto tree = check_pathological(g, 40, "identical");
    OctreeStats st = octree_stats(tree->data());
    EXPECT_EQ(st.references, g.size());
    EXPECT_EQ(st.leaves_by_reason[int(OctreeLeafReason::no_reduction)], 1u);
    EXPECT_LE(st.nodes, 9u);
  }
  {  // 10,000 coplanar triangles: a tessellated floor in the plane z = 0.5, the root's centre plane (every
     // triangle lies in both halves' closed cells).
    Geometry g;
    g.begin_object("floor", 0);
    for (int j = 0; j < 50; ++j)
      for (int i = 0; i < 100; ++i) {
        glm::vec3 p(i * 0.01f, j * 0.02f, 0.5f), dx(0.01f, 0.f, 0.f), dy(0.f, 0.02f, 0.f);
        g.add_triangle(p, p + dx, p + dx + dy);
        g.add_triangle(p, p + dx + dy, p + dy);
      }
    g.add_triangle({0, 0, 0}, {1, 0, 1}, {0, 1, 1});  // one slanted triangle, so that the box is not flat
    auto tree = check_pathological(g, 400, "coplanar floor");
    EXPECT_LT(octree_stats(tree->data()).references, 16 * g.size());
  }
  {  // 2,000 large coplanar triangles overlapping each other: every cell holds most of them, so splitting
     // copies references until the budget stops it.
    Geometry g;
    g.begin_object("coplanar", 0);
    std::mt19937 rng(3);
    std::uniform_real_distribution<float> u(0.f, 1.f);
    for (int i = 0; i < 2000; ++i)
      g.add_triangle({u(rng), u(rng), 0.5f}, {u(rng), u(rng), 0.5f}, {u(rng), u(rng), 0.5f});
    auto tree = check_pathological(g, 300, "coplanar overlapping");
    EXPECT_GT(octree_stats(tree->data()).leaves_by_reason[int(OctreeLeafReason::budget)], 0u);
  }
  {  // A teapot in a stadium: a dense small sphere mesh far from two huge floor triangles.
    Geometry g;
    g.begin_object("stadium", 0);
    g.add_triangle({-1000, 0, -1000}, {1000, 0, -1000}, {1000, 0, 1000});
    g.add_triangle({-1000, 0, -1000}, {1000, 0, 1000}, {-1000, 0, 1000});
    add_to_geometry(make_icosphere(4, glm::vec3(700.f, 1.f, 300.f), 0.01f), g, "teapot");
    auto tree = check_pathological(g, 2000, "stadium");
    EXPECT_EQ(octree_stats(tree->data()).max_depth, octree_max_depth(tree->options(), g.size()))
        << "the tree adapts down to the teapot, to the depth limit";
    // Rays aimed at the teapot itself.
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = edge_rays(g, 2000, 5);
    EXPECT_EQ(count_disagreements(*tree, brute, rays), 0);
  }
  {  // Long slivers: 2,000 needle triangles spanning the scene, a thousandth wide, crossing each other.
    Geometry g;
    g.begin_object("slivers", 0);
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 2000; ++i) {
      glm::vec3 a(u(rng), u(rng), u(rng)), b(-a.x, u(rng), -a.z);
      g.add_triangle(a, b, b + glm::vec3(0.f, 1e-3f, 1e-3f));
    }
    auto tree = check_pathological(g, 1000, "slivers");
    EXPECT_GT(octree_stats(tree->data()).leaves_by_reason[int(OctreeLeafReason::max_depth)], 0u);
  }
}

TEST(Octree, RecordedWalkEqualsTheKernelAndGoesFrontToBack) {
  Geometry g = make_soup(9, 300, 4);
  for (int leaf : {1, 8}) {
    auto tree = make_octree(g, leaf);
    const OctreeData& d = tree->data();
    std::vector<Ray> rays = random_rays(g.bounds(), 600, 15);
    std::vector<Ray> cam = camera_rays(g.bounds(), 10);
    rays.insert(rays.end(), cam.begin(), cam.end());
    EventRecorder rec;
    int deferred = 0, beyond = 0, inside = 0;
    for (size_t ri = 0; ri < rays.size(); ++ri) {
      const Ray& r = rays[ri];
      bool shadow = ri % 5 == 4;
      rec.clear();
      Hit plain, recorded, counted;
      CountingRecorder counters;
      bool found_plain = shadow ? tree->occluded(r) : tree->intersect(r, &plain);
      bool found = tree->traverse(r, &recorded, shadow, rec);
      bool found_counted = tree->traverse(r, &counted, shadow, counters);
      ASSERT_EQ(found_plain, found);
      ASSERT_EQ(found, found_counted);
      if (!shadow) {
        ASSERT_EQ(plain.prim, recorded.prim);
        ASSERT_EQ(plain.t, recorded.t);
      }
      ASSERT_EQ(counted.prim, recorded.prim);
      const RayCounters& c = rec.counters();
      EXPECT_EQ(counters.nodes, c.nodes);
      EXPECT_EQ(counters.prim_tests, c.prim_tests);
      EXPECT_EQ(counters.mailbox_hits, c.mailbox_hits);
      EXPECT_EQ(counters.pushes, c.pushes);
      EXPECT_EQ(counters.pops, c.pops);

      // Replay: the stack of pushed nodes, each node a child of the top one; leaves front to back; each
      // primitive tested once; the nearest tested hit is the result.
      std::vector<int32_t> stack;
      std::map<uint32_t, int> tested;
      float last_leaf_enter = -kInfinity, best = kInfinity;
      int32_t best_prim = -1, accepted = -1;
      const float slack = 1e-4f * std::max(1.f, std::fabs(recorded.t));
      for (const Event& e : rec.events()) {
        switch (e.type) {
          case EventType::node:
            EXPECT_EQ(e.depth, d.info[size_t(e.node)].depth);
            if (stack.empty())
              EXPECT_EQ(e.node, 0);
            else
              EXPECT_EQ(d.info[size_t(e.node)].parent, stack.back())
                  << "a node is a child of the node on top";
            EXPECT_LE(e.t_min_node, e.t_max_node);
            break;
          case EventType::push:
            EXPECT_FALSE(d.nodes[size_t(e.node)].is_leaf());
            stack.push_back(e.node);
            break;
          case EventType::pop:
            ASSERT_FALSE(stack.empty());
            EXPECT_EQ(stack.back(), e.node);
            stack.pop_back();
            break;
          case EventType::leaf:
            EXPECT_TRUE(d.nodes[size_t(e.node)].is_leaf());
            EXPECT_GE(e.t_min_node, last_leaf_enter - slack) << "leaves front to back (Revelles' order)";
            last_leaf_enter = std::max(last_leaf_enter, e.t_min_node);
            break;
          case EventType::prim_test:
            EXPECT_EQ(++tested[uint32_t(e.prim)], 1) << "primitive " << e.prim << " tested twice";
            if (e.hit && (e.t < best || (e.t == best && e.prim < best_prim))) {
              best = e.t;
              best_prim = e.prim;
            }
            break;
          case EventType::hit_deferred:
            ++deferred;
            break;
          case EventType::hit_accepted:
            accepted = e.prim;
            beyond += e.reason == AcceptReason::next_node_beyond;
            inside += e.reason == AcceptReason::inside_cell;
            break;
          default:
            break;
        }
      }
      if (!shadow) EXPECT_EQ(best_prim, recorded.prim);
      EXPECT_EQ(accepted, recorded.prim);
    }
    EXPECT_GT(inside, 50) << "most hits lie inside their cell";
    EXPECT_GT(deferred + beyond, 0) << "some hits lie beyond their cell's exit";
  }
}

TEST(Octree, TraceListsTheCellsAndReadsBack) {
  Geometry g = make_soup(4, 200, 2);
  auto tree = make_octree(g, 4);
  std::vector<RayRequest> reqs;
  for (const Ray& r : random_rays(g.bounds(), 30, 2)) {
    RayRequest q;
    q.ray = r;
    reqs.push_back(q);
  }
  Trace t = record_octree_trace(g, *tree, reqs, "soup.json", "fnv1a64:0000000000000000");
  EXPECT_EQ(t.structure.kind, "octree");
  ASSERT_FALSE(t.nodes.empty());
  size_t inner = 0;
  for (const TraceNode& n : t.nodes) {
    EXPECT_EQ(n.axis, -1);
    EXPECT_EQ(n.box.lo, tree->data().info[size_t(n.id)].box.lo);
    if (!n.leaf) {
      ++inner;
      EXPECT_EQ(n.children.size(), 8u);
    }
  }
  EXPECT_GT(inner, 0u);
  Trace back = parse_trace_json(trace_to_json(t), "t.json");
  ASSERT_EQ(back.nodes.size(), t.nodes.size());
  for (size_t i = 0; i < t.nodes.size(); ++i) EXPECT_EQ(back.nodes[i].children, t.nodes[i].children);
  ASSERT_EQ(back.rays.size(), t.rays.size());
  EXPECT_EQ(back.rays[0].events.size(), t.rays[0].events.size());

  // An inner octree node with another number of children than eight is refused, naming the place.
  std::string json = trace_to_json(t);
  size_t at = json.find("\"children\":[");
  ASSERT_NE(at, std::string::npos);
  size_t comma = json.find(',', at);
  std::string broken = json.substr(0, at + 12) + json.substr(comma + 1);
  try {
    parse_trace_json(broken, "t.json");
    ADD_FAILURE() << "7 children accepted";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("children"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace raystep
