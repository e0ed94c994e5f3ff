// The wide BVH (accel/wide_bvh.h): the same answers as brute force (primitive, t and barycentrics, bit for
// bit) with every kernel this CPU can run (scalar, SSE, AVX2) and both widths, on random, camera, edge-aimed
// and in-plane rays, +-0 directions, NaN and infinite rays, and pathological input; the same answers across
// kernels; the counted walk; the recorded walk against the kernel; describe()'s ids.
#include <gtest/gtest.h>

#include <algorithm>
#include <map>
#include <random>

#include "ray_battery.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/io/scene_loader.h"
#include "raystep/record/event_recorder.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "test_budget.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::make_soup;

// The levels this CPU runs; each test runs with each, and restores the best.
std::vector<WideSimd> levels() {
  std::vector<WideSimd> out;
  for (WideSimd s : {WideSimd::scalar, WideSimd::sse, WideSimd::avx2})
    if (int(s) <= int(WideBvh::best_simd())) out.push_back(s);
  return out;
}

struct RestoreSimd {
  ~RestoreSimd() { WideBvh::force_simd(WideBvh::best_simd()); }
};

bool same_hit(const Hit& a, const Hit& b) {
  return a.prim == b.prim && (!a.found() || (a.t == b.t && a.b1 == b.b1 && a.b2 == b.b2));
}

// An accelerator's answers on a ray set: the nearest hit and the occlusion.
struct Answers {
  std::vector<Hit> hits;
  std::vector<char> occluded;
};
Answers answers(const Accelerator& acc, const std::vector<Ray>& rays) {
  Answers out;
  out.hits.resize(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) {
    acc.intersect(rays[i], &out.hits[i]);
    out.occluded.push_back(acc.occluded(rays[i]));
  }
  return out;
}

// Rays on which the wide BVH differs from the reference answers: the hit (bit for bit) or the occlusion.
int disagreements(const WideBvh& wide, const Answers& reference, const std::vector<Ray>& rays) {
  int bad = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    Hit b;
    bool hb = wide.intersect(rays[i], &b);
    if (hb != reference.hits[i].found() || !same_hit(reference.hits[i], b) ||
        char(wide.occluded(rays[i])) != reference.occluded[i])
      ++bad;
  }
  return bad;
}
int disagreements(const WideBvh& wide, const BruteForce& brute, const std::vector<Ray>& rays) {
  return disagreements(wide, answers(brute, rays), rays);
}

// Axis-parallel rays with +0 and -0 components, rays in the planes of the boxes' faces, grazing rays.
std::vector<Ray> hard_rays(const Geometry& g, size_t count, uint64_t seed) {
  std::vector<Ray> rays;
  std::mt19937 rng{uint32_t(seed)};
  Bounds3 b = g.bounds();
  std::uniform_int_distribution<uint32_t> pick(0, uint32_t(g.size() - 1));
  std::uniform_real_distribution<float> u(0.f, 1.f);
  for (size_t i = 0; i < count; ++i) {
    uint32_t prim = pick(rng);
    Bounds3 pb = g.prim_bounds(prim);
    Ray r;
    glm::vec3 p = pb.lo + (pb.hi - pb.lo) * glm::vec3(u(rng), u(rng), u(rng));
    int axis = int(i % 3);
    // A point on one of the primitive box's faces (the node boxes are unions of these): in-plane rays.
    p[(axis + 1) % 3] = (i / 3) % 2 ? pb.lo[(axis + 1) % 3] : pb.hi[(axis + 1) % 3];
    r.origin = p;
    r.origin[axis] = (i / 6) % 2 ? b.lo[axis] - 1.f : b.hi[axis] + 1.f;
    glm::vec3 d(0.f);
    d[axis] = (i / 6) % 2 ? 1.f : -1.f;
    // +0 and -0 on the other axes.
    if ((i / 12) % 2) d[(axis + 1) % 3] = -0.f;
    if ((i / 24) % 2) d[(axis + 2) % 3] = -0.f;
    r.direction = d;
    rays.push_back(r);
  }
  return rays;
}

std::unique_ptr<WideBvh> make_wide(const Geometry& g, int width) {
  auto w = std::make_unique<WideBvh>(width);
  w->build(g);
  return w;
}

TEST(WideBvh, NamesAndLevel) {
  EXPECT_EQ(WideBvh(4).name(), "bvh4");
  EXPECT_EQ(WideBvh(8).name(), "bvh8");
  EXPECT_THROW(WideBvh(5), InputError);
  std::string level = WideBvh::simd_level();
  EXPECT_TRUE(level == "avx2" || level == "sse" || level == "scalar");
#if defined(__x86_64__)
  EXPECT_NE(level, "scalar");
  EXPECT_EQ(level == "avx2", bool(__builtin_cpu_supports("avx2")));
#endif
}

TEST(WideBvh, AgreesWithBruteForceOnRandomAndHardRays) {
  RestoreSimd restore;
  for (int spheres : {0, 8}) {
    Geometry g = make_soup(5, 3000, spheres);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = random_rays(g.bounds(), 4000, 3);
    std::vector<Ray> hard = hard_rays(g, 3000, 4);
    rays.insert(rays.end(), hard.begin(), hard.end());
    for (int width : {4, 8}) {
      auto wide = make_wide(g, width);
      for (WideSimd level : levels()) {
        ASSERT_TRUE(WideBvh::force_simd(level));
        EXPECT_EQ(disagreements(*wide, brute, rays), 0)
            << "width " << width << " level " << WideBvh::simd_level() << " spheres " << spheres;
      }
    }
  }
}

TEST(WideBvh, WatertightOnEdgeAimedRays) {
  RestoreSimd restore;
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = edge_rays(g, test::budget(30000), 12);
  for (int width : {4, 8}) {
    auto wide = make_wide(g, width);
    for (WideSimd level : levels()) {
      ASSERT_TRUE(WideBvh::force_simd(level));
      EXPECT_EQ(disagreements(*wide, brute, rays), 0) << width << " " << WideBvh::simd_level();
      EXPECT_EQ(test::count_leaks(*wide, rays, test::budget(10000)), 0)
          << width << " " << WideBvh::simd_level();
    }
  }
}

TEST(WideBvh, AgreesOnCameraRaysOfTheScenes) {
  RestoreSimd restore;
  for (const char* name : {"cornell.json", "torus_knot.json", "spheres.json", "robustness.json"}) {
    Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name);
    BruteForce brute;
    brute.build(scene.geometry);
    std::vector<Ray> rays = camera_rays(scene.camera, 48, 36);
    for (int width : {4, 8}) {
      auto wide = make_wide(scene.geometry, width);
      for (WideSimd level : levels()) {
        ASSERT_TRUE(WideBvh::force_simd(level));
        EXPECT_EQ(disagreements(*wide, brute, rays), 0)
            << name << " " << width << " " << WideBvh::simd_level();
      }
    }
  }
}

TEST(WideBvh, NanAndInfiniteRaysMiss) {
  RestoreSimd restore;
  Geometry g = make_soup(2, 500, 0);
  float nan = std::nanf("");
  for (int width : {4, 8}) {
    auto wide = make_wide(g, width);
    for (WideSimd level : levels()) {
      ASSERT_TRUE(WideBvh::force_simd(level));
      EXPECT_EQ(test::count_non_finite_hits(*wide), 0) << width << " " << WideBvh::simd_level();
      Ray r;
      r.origin = glm::vec3(-5.f, 0.f, 0.f);
      r.direction = glm::vec3(1.f, 0.f, 0.f);
      r.tmax = nan;
      Hit h;
      EXPECT_FALSE(wide->intersect(r, &h));
    }
  }
}

TEST(WideBvh, EmptyAndSingleTriangle) {
  Geometry empty;
  WideBvh wide(8);
  wide.build(empty);
  Ray r;
  Hit h;
  EXPECT_FALSE(wide.intersect(r, &h));
  EXPECT_FALSE(wide.occluded(r));
  EXPECT_TRUE(wide.describe().nodes.empty());

  Geometry one;
  one.begin_object("one", 0);
  one.add_triangle(glm::vec3(-1, -1, 1), glm::vec3(1, -1, 1), glm::vec3(0, 1, 1));
  wide.build(one);
  EXPECT_TRUE(wide.intersect(r, &h));
  EXPECT_EQ(h.prim, 0);
  EXPECT_EQ(h.t, 1.f);
}

// Pathological input: every centroid the same point, and thousands of triangles in one plane.
TEST(WideBvh, IdenticalAndCoplanarTriangles) {
  RestoreSimd restore;
  Geometry same;
  same.begin_object("identical", 0);
  for (int i = 0; i < test::budget(100000); ++i)
    same.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.2f), glm::vec3(0.f, 1.f, 0.4f));
  same.add_triangle(glm::vec3(-1.f, -1.f, 1.f), glm::vec3(2.f, -1.f, 1.f), glm::vec3(-1.f, 2.f, 1.f));

  Geometry plane;
  plane.begin_object("coplanar", 0);
  std::mt19937 rng(4);
  std::uniform_real_distribution<float> u(0.f, 10.f), s(0.05f, 0.5f);
  for (int i = 0; i < 10000; ++i) {
    glm::vec3 p(u(rng), u(rng), 0.5f);
    plane.add_triangle(p, p + glm::vec3(s(rng), 0.f, 0.f), p + glm::vec3(0.f, s(rng), 0.f));
  }
  for (const Geometry* g : {&same, &plane}) {
    BruteForce brute;
    brute.build(*g);
    std::vector<Ray> rays = random_rays(g->bounds(), 150, 9);
    std::vector<Ray> hard = hard_rays(*g, 150, 10);
    rays.insert(rays.end(), hard.begin(), hard.end());
    for (int width : {4, 8}) {
      auto wide = make_wide(*g, width);
      for (WideSimd level : levels()) {
        ASSERT_TRUE(WideBvh::force_simd(level));
        EXPECT_EQ(disagreements(*wide, brute, rays), 0)
            << g->size() << " " << width << " " << WideBvh::simd_level();
      }
    }
  }
  // The identical triangles: the lowest id wins the tie.
  auto wide = make_wide(same, 8);
  Ray r;
  r.origin = glm::vec3(0.2f, 0.2f, -1.f);
  r.direction = glm::vec3(0.f, 0.f, 1.f);
  Hit h;
  ASSERT_TRUE(wide->intersect(r, &h));
  EXPECT_EQ(h.prim, 0);
}

TEST(WideBvh, KernelsAgreeBitForBitAndCountTheirWork) {
  RestoreSimd restore;
  Geometry g;
  add_to_geometry(make_icosphere(4), g);
  std::vector<Ray> rays = random_rays(g.bounds(), 5000, 21);
  for (int width : {4, 8}) {
    auto wide = make_wide(g, width);
    std::vector<Hit> reference;
    CountingRecorder reference_counts;
    for (WideSimd level : levels()) {
      ASSERT_TRUE(WideBvh::force_simd(level));
      std::vector<Hit> hits(rays.size());
      CountingRecorder counts;
      for (size_t i = 0; i < rays.size(); ++i) {
        Hit counted;
        wide->intersect(rays[i], &hits[i]);
        wide->intersect_counted(rays[i], &counted, counts);
        EXPECT_TRUE(same_hit(hits[i], counted));
      }
      EXPECT_EQ(counts.rays, rays.size());
      EXPECT_GT(counts.nodes, 0u);
      EXPECT_GT(counts.box_tests, counts.nodes);
      EXPECT_GT(counts.prim_tests, 0u);
      if (reference.empty()) {
        reference = hits;
        reference_counts = counts;
        continue;
      }
      for (size_t i = 0; i < rays.size(); ++i) EXPECT_TRUE(same_hit(hits[i], reference[i])) << i;
      // The same walk: the kernels differ only in how many lanes an instruction handles.
      EXPECT_EQ(counts.nodes, reference_counts.nodes);
      EXPECT_EQ(counts.box_tests, reference_counts.box_tests);
      EXPECT_EQ(counts.prim_tests, reference_counts.prim_tests);
      EXPECT_EQ(counts.skips, reference_counts.skips);
    }
  }
}

// The same hits as the binary BVH, bit for bit: collapsed from the binary BVH's own tree, and each built by
// default; every builder.
TEST(WideBvh, SameHitsAsTheBinaryBvh) {
  RestoreSimd restore;
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  Geometry soup = make_soup(11, 2000, 0);
  for (const Geometry* geometry : {&g, &soup}) {
    std::vector<Ray> rays = random_rays(geometry->bounds(), 3000, 31);
    std::vector<Ray> edges = edge_rays(*geometry, 3000, 32);
    std::vector<Ray> hard = hard_rays(*geometry, 2000, 33);
    rays.insert(rays.end(), edges.begin(), edges.end());
    rays.insert(rays.end(), hard.begin(), hard.end());
    for (BvhBuilder builder : {BvhBuilder::binned, BvhBuilder::sweep, BvhBuilder::median, BvhBuilder::sbvh}) {
      BvhOptions options;
      options.builder = builder;
      Bvh binary(options);
      binary.build(*geometry);
      Answers reference = answers(binary, rays);
      for (int width : {4, 8}) {
        WideBvh same_tree(width, options), own(width, options);
        same_tree.build(*geometry, binary.data());
        own.build(*geometry);
        for (WideSimd level : levels()) {
          ASSERT_TRUE(WideBvh::force_simd(level));
          EXPECT_EQ(disagreements(same_tree, reference, rays), 0) << int(builder) << " " << width;
          EXPECT_EQ(disagreements(own, reference, rays), 0) << int(builder) << " " << width;
        }
      }
    }
  }
}

// The recorded walk finds the kernel's hit, and tells it as the debugger expects: each node's box tests name
// it as their parent, the pushes are the other hit children farthest first, every push is popped or the walk
// ended on a hit, skipped entries start beyond the hit.
TEST(WideBvh, RecordedWalkMatchesTheKernel) {
  Geometry g = make_soup(3, 3000, 0);
  std::vector<Ray> rays = random_rays(g.bounds(), 400, 5);
  for (int width : {4, 8}) {
    WideBvh wide(width);
    wide.build(g);
    WideBvhView view = wide.describe();
    EventRecorder rec;
    for (const Ray& r : rays)
      for (bool any_hit : {false, true}) {
        rec.clear();
        Hit recorded, plain;
        bool found = wide.record(r, &recorded, any_hit, rec);
        bool plain_found = any_hit ? wide.occluded(r) : wide.intersect(r, &plain);
        ASSERT_EQ(found, plain_found);
        if (!any_hit) ASSERT_TRUE(same_hit(recorded, plain));
        const std::vector<Event>& ev = rec.events();
        ASSERT_GE(ev.size(), 2u);
        EXPECT_EQ(ev.front().type, EventType::ray_begin);
        EXPECT_EQ(ev.back().type, EventType::ray_end);
        int32_t current = -1;
        int pushes = 0, pops = 0, box_tests = 0, prim_tests = 0;
        std::vector<float> pushed_t;
        for (size_t i = 0; i < ev.size(); ++i) {
          const Event& e = ev[i];
          switch (e.type) {
            case EventType::node:
              current = e.node;
              ASSERT_FALSE(view.nodes[size_t(e.node)].leaf);
              pushed_t.clear();
              break;
            case EventType::box_test:
              ++box_tests;
              EXPECT_EQ(e.parent, current);
              EXPECT_EQ(view.nodes[size_t(e.node)].parent, current);
              EXPECT_EQ(e.depth, view.nodes[size_t(e.node)].depth);
              break;
            case EventType::push:
              ++pushes;
              EXPECT_EQ(view.nodes[size_t(e.node)].parent, current);
              // Farthest first (a shadow ray's are not sorted: any hit will do).
              if (!any_hit && !pushed_t.empty()) EXPECT_LE(e.t_min_node, pushed_t.back());
              pushed_t.push_back(e.t_min_node);
              break;
            case EventType::pop:
              ++pops;
              break;
            case EventType::skip:
              ASSERT_GT(i, 0u);
              EXPECT_EQ(ev[i - 1].type, EventType::pop);
              EXPECT_TRUE(recorded.found());
              EXPECT_GT(e.t_min_node, recorded.t);
              break;
            case EventType::leaf:
              EXPECT_TRUE(view.nodes[size_t(e.node)].leaf);
              break;
            case EventType::prim_test: {
              ++prim_tests;
              break;
            }
            default:
              break;
          }
        }
        EXPECT_TRUE(pops == pushes || (recorded.found() && pops <= pushes)) << pops << " " << pushes;
        EXPECT_EQ(int(rec.counters().box_tests), box_tests);
        EXPECT_EQ(int(rec.counters().prim_tests), prim_tests);
        if (!any_hit) {
          CountingRecorder counts;
          Hit h;
          wide.intersect_counted(r, &h, counts);
          EXPECT_EQ(counts.box_tests, uint64_t(box_tests));
          EXPECT_EQ(counts.prim_tests, uint64_t(prim_tests));
          EXPECT_EQ(counts.pushes, uint64_t(pushes));
        }
      }
  }
}

TEST(WideBvh, DescribeGivesEverySlotAnId) {
  Geometry g = make_soup(7, 2000, 4);
  for (int width : {4, 8}) {
    WideBvh wide(width);
    wide.build(g);
    WideBvhView view = wide.describe();
    ASSERT_FALSE(view.nodes.empty());
    std::vector<int> seen(g.size(), 0);
    for (size_t id = 0; id < view.nodes.size(); ++id) {
      const WideBvhView::Node& n = view.nodes[id];
      if (id == 0) {
        EXPECT_EQ(n.parent, -1);
        EXPECT_EQ(n.depth, 0);
      } else {
        ASSERT_GE(n.parent, 0);
        EXPECT_LT(n.parent, int32_t(id));  // preorder
        EXPECT_EQ(n.depth, view.nodes[size_t(n.parent)].depth + 1);
        const auto& siblings = view.nodes[size_t(n.parent)].children;
        EXPECT_NE(std::find(siblings.begin(), siblings.end(), int32_t(id)), siblings.end());
      }
      if (n.leaf) {
        EXPECT_TRUE(n.children.empty());
        for (uint32_t p : n.prims) {
          ++seen[p];
          Bounds3 pb = g.prim_bounds(p);
          EXPECT_TRUE(n.box.contains(pb.lo) && n.box.contains(pb.hi));
        }
      } else {
        EXPECT_GE(n.children.size(), 1u);
        EXPECT_LE(n.children.size(), size_t(width));
        for (int32_t c : n.children) {
          const Bounds3& cb = view.nodes[size_t(c)].box;
          if (id > 0) EXPECT_TRUE(n.box.contains(cb.lo) && n.box.contains(cb.hi));
        }
      }
    }
    for (size_t p = 0; p < g.size(); ++p) EXPECT_EQ(seen[p], 1) << p;  // each primitive in exactly one leaf
    // The one-node lookup traces use: the same counts, and no node past them.
    EXPECT_EQ(wide.node_count(), view.nodes.size());
    EXPECT_EQ(wide.leaf_count(), size_t(std::count_if(view.nodes.begin(), view.nodes.end(),
                                                      [](const auto& n) { return n.leaf; })));
    EXPECT_THROW(wide.describe_node(-1), InputError);
    EXPECT_THROW(wide.describe_node(int32_t(view.nodes.size())), InputError);
  }
}

}  // namespace
}  // namespace raystep
