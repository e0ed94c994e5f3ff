// The binary BVH's traversal: agreement with brute force (same primitive, same t) for every builder and both
// child orders on random, camera, edge-aimed and in-plane rays (lying in child boxes' faces, with +0 and -0
// components), non-finite rays (a miss, no crash), and the recorded walk against the kernel's own result.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <map>
#include <random>

#include "ray_battery.h"
#include "raystep/accel/brute_force.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/structure_options.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/io/scene_loader.h"
#include "raystep/render/render.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "test_budget.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::camera_rays;
using test::count_disagreements;
using test::make_soup;

const BvhBuilder kBuilders[] = {BvhBuilder::binned, BvhBuilder::sweep, BvhBuilder::median, BvhBuilder::sbvh};
const BvhOrder kOrders[] = {BvhOrder::entry_distance, BvhOrder::split_axis};

std::unique_ptr<Bvh> make_bvh(const Geometry& g, BvhBuilder builder,
                              BvhOrder order = BvhOrder::entry_distance, BvhOptions options = {}) {
  options.builder = builder;
  auto bvh = std::make_unique<Bvh>(options, order);
  bvh->build(g);
  return bvh;
}

// Rays lying in the faces of the children's boxes (the planes where a box test is decided by a tie), with +0
// and -0 components, axis-parallel ones along faces and edges, and corner-to-corner diagonals.
std::vector<Ray> face_rays(const BvhData& d, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  std::normal_distribution<float> nd;
  std::vector<Ray> rays;
  const Bounds3& root = d.nodes[0].box;
  glm::vec3 lo = root.lo - 0.25f * root.extent(), e = 1.5f * root.extent();
  for (size_t id = 1; id < d.nodes.size() && rays.size() < 4000; ++id) {
    const Bounds3& box = d.nodes[id].box;
    for (int k = 0; k < 5; ++k) {
      int axis = int(rng() % 3);
      float face = u(rng) < 0.5f ? box.lo[axis] : box.hi[axis];
      Ray r;
      r.origin = lo + e * glm::vec3(u(rng), u(rng), u(rng));
      r.origin[axis] = face;
      r.direction = glm::vec3(nd(rng), nd(rng), nd(rng));
      if (k < 2) r.direction[axis] = k == 0 ? 0.f : -0.f;  // lying in the face's plane
      if (k == 2) {                                        // axis-parallel along a face edge
        r.direction = glm::vec3(-0.f);
        r.direction[(axis + 1) % 3] = u(rng) < 0.5f ? 1.f : -1.f;
        r.origin[(axis + 2) % 3] = box.lo[(axis + 2) % 3];
      }
      if (k == 3) {  // axis-parallel through the face, with -0 on the other axes
        r.direction = glm::vec3(-0.f);
        r.direction[axis] = u(rng) < 0.5f ? 1.f : -1.f;
        r.origin[axis] = u(rng) < 0.5f ? root.lo[axis] - 1.f : root.hi[axis] + 1.f;
      }
      if (k == 4) {  // corner to corner
        r.origin = box.lo;
        r.direction = box.hi - box.lo;
      }
      rays.push_back(r);
    }
  }
  return rays;
}

TEST(Bvh, AgreesWithBruteForceOnRandomAndCameraRays) {
  for (int spheres : {8, 0}) {
    Geometry g = make_soup(5, 400, spheres);
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = random_rays(g.bounds(), 20000, 9);
    std::vector<Ray> cam = camera_rays(g.bounds(), 100);
    rays.insert(rays.end(), cam.begin(), cam.end());
    for (BvhBuilder builder : kBuilders)
      for (BvhOrder order : kOrders) {
        auto bvh = make_bvh(g, builder, order);
        EXPECT_GT(bvh->data().nodes.size(), 1u);
        EXPECT_EQ(count_disagreements(*bvh, brute, rays), 0)
            << "builder " << int(builder) << " order " << int(order) << " spheres " << spheres;
        for (size_t i = 0; i < rays.size(); i += 7) {
          Hit a, b;
          if (!brute.intersect(rays[i], &a)) continue;
          bvh->intersect(rays[i], &b);
          EXPECT_EQ(a.b1, b.b1);
          EXPECT_EQ(a.b2, b.b2);
        }
      }
  }
}

TEST(Bvh, AgreesWithBruteForceUnderEveryOption) {
  Geometry g = make_soup(6, 300, 4);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), 20000, 10);
  std::vector<BvhOptions> variants(6);
  variants[0].leaf_size = 8;
  variants[1].max_depth = 3;
  variants[2].t_i = 2.f;
  variants[2].t_t = 5.f;
  variants[3].t_i = 1000.f;
  variants[4].bins = 32;
  variants[5].bins = 2;
  variants[5].max_leaf_size = 1;
  for (size_t v = 0; v < variants.size(); ++v)
    for (BvhBuilder builder : kBuilders)
      EXPECT_EQ(
          count_disagreements(*make_bvh(g, builder, BvhOrder::entry_distance, variants[v]), brute, rays), 0)
          << "variant " << v << " builder " << int(builder);
}

TEST(Bvh, WatertightOnEdgeAimedAndFaceRays) {
  Geometry g;
  add_to_geometry(make_icosphere(3), g);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = edge_rays(g, test::budget(8000), 12);
  for (BvhBuilder builder : kBuilders)
    for (BvhOrder order : kOrders) {
      auto bvh = make_bvh(g, builder, order);
      std::vector<Ray> all = rays, faces = face_rays(bvh->data(), 3);
      all.insert(all.end(), faces.begin(), faces.end());
      EXPECT_EQ(count_disagreements(*bvh, brute, all), 0) << int(builder) << " " << int(order);
      EXPECT_EQ(test::count_leaks(*bvh, rays, rays.size()), 0) << int(builder);
    }
}

TEST(Bvh, NonFiniteRaysMissAndTerminate) {
  Geometry g = make_soup(8, 50, 1);
  for (BvhBuilder builder : kBuilders) {
    auto bvh = make_bvh(g, builder);
    EXPECT_EQ(test::count_non_finite_hits(*bvh), 0) << int(builder);
    float inf = kInfinity;
    // NaN interval ends miss too; an infinite tmax is the ordinary case.
    Ray r;
    r.origin = g.bounds().lo - glm::vec3(1.f);
    r.direction = g.bounds().center() - r.origin;
    Hit h;
    r.tmax = std::nanf("");
    EXPECT_FALSE(bvh->intersect(r, &h));
    r.tmax = inf;
    Hit a;
    BruteForce brute;
    brute.build(g);
    EXPECT_EQ(bvh->intersect(r, &h), brute.intersect(r, &a));
    EXPECT_EQ(h.prim, a.prim);
  }
}

// The walk tests an inner node's two children together (bvh_box_ray.h, SSE2 where there is SSE2): the same
// answer and the same interval bits as one box at a time, on boxes and rays made to be hard: thin and flat
// boxes, rays in their faces with +0 and -0 components, origins on planes (0 * inf), shrunk tmax, infinite
// tmax, negative tmin, boxes behind and around the origin, and huge and tiny coordinates.
TEST(Bvh, ChildPairTestEqualsOneBoxAtATimeBitForBit) {
  std::mt19937 rng(123);
  auto pick = [&](std::initializer_list<float> values) {
    return *(values.begin() + std::uniform_int_distribution<size_t>(0, values.size() - 1)(rng));
  };
  std::uniform_real_distribution<float> u(-2.f, 2.f);
  auto coordinate = [&] {
    return pick({0.f, -0.f, 1.f, -1.f, 0.5f, u(rng), u(rng), u(rng) * 1e6f, u(rng) * 1e-6f});
  };
  int disagreements = 0, hits = 0, misses = 0;
  for (int i = 0; i < 200000; ++i) {
    BvhPair p;
    for (int k = 0; k < 2; ++k)
      for (int a = 0; a < 3; ++a) {
        float lo = coordinate(), hi = pick({lo, lo + std::fabs(u(rng)), coordinate()});
        p.rows[a][k] = std::min(lo, hi);
        p.rows[a][k + 2] = std::max(lo, hi);
      }
    Ray r;
    for (int a = 0; a < 3; ++a) {
      r.origin[a] = pick({p.rows[a][0], p.rows[a][3], coordinate()});
      r.direction[a] = pick({0.f, -0.f, u(rng), u(rng), 1.f, -1e-30f, 1e30f});
    }
    r.tmin = pick({0.f, 0.f, -1.f, 1e-3f});
    r.tmax = pick({kInfinity, kInfinity, 1.f, 0.25f, 1e7f});
    BvhBoxRay slab{SlabRay(r)};
    if (!slab.valid) continue;
    if (i % 3 == 0) slab.set_tmax(slab.tmax * 0.5f);
    float simd_near[2], simd_far[2], scalar_near[2], scalar_far[2];
    int simd = slab.hit_children(p, simd_near, simd_far);
    int scalar = slab.hit_children_scalar(p, scalar_near, scalar_far);
    bool same = simd == scalar;
    for (int k = 0; k < 2; ++k)
      same = same && std::memcmp(&simd_near[k], &scalar_near[k], 4) == 0 &&
             std::memcmp(&simd_far[k], &scalar_far[k], 4) == 0;
    disagreements += !same;
    hits += (scalar & 1) + (scalar >> 1);
    misses += 2 - (scalar & 1) - (scalar >> 1);
  }
  EXPECT_EQ(disagreements, 0);
  EXPECT_GT(hits, 30000);  // both outcomes are well exercised
  EXPECT_GT(misses, 30000);
}

// The walk's copy holds every inner node once, with its children's boxes and references as BvhData has them.
TEST(Bvh, ChildPairsMirrorTheNodes) {
  Geometry g = make_soup(5, 300, 3);
  auto bvh = make_bvh(g, BvhBuilder::binned);
  const BvhData& d = bvh->data();
  const BvhPairs& pairs = bvh->pairs();
  size_t inner = 0;
  for (const BvhNode& n : d.nodes) inner += !n.is_leaf();
  ASSERT_EQ(pairs.pairs.size(), inner);
  ASSERT_GT(inner, 100u);
  EXPECT_FALSE(pairs.root.is_leaf());
  EXPECT_EQ(pairs.root.index, 0u);
  for (size_t p = 0; p < pairs.pairs.size(); ++p) {
    const BvhNode& node = d.nodes[pairs.node_id[p]];
    ASSERT_FALSE(node.is_leaf());
    EXPECT_EQ(pairs.axis[p], node.axis());
    const uint32_t children[2] = {uint32_t(pairs.node_id[p]) + 1, node.second_child()};
    for (int k = 0; k < 2; ++k) {
      const BvhNode& c = d.nodes[children[k]];
      EXPECT_EQ(pairs.child_id[2 * p + k], int32_t(children[k]));
      for (int a = 0; a < 3; ++a) {
        EXPECT_EQ(pairs.pairs[p].rows[a][k], c.box.lo[a]);
        EXPECT_EQ(pairs.pairs[p].rows[a][k + 2], c.box.hi[a]);
      }
      const BvhRef ref = pairs.pairs[p].child[k];
      ASSERT_EQ(ref.is_leaf(), c.is_leaf());
      if (c.is_leaf()) {
        EXPECT_EQ(ref.index, c.first_prim());
        EXPECT_EQ(ref.count, c.prim_count());
      } else {
        EXPECT_EQ(pairs.node_id[ref.index], int32_t(children[k]));
      }
    }
  }
  // A one-primitive scene is a root leaf, with no pairs.
  Geometry one;
  one.begin_object("t", 0);
  one.add_triangle({0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  auto tiny = make_bvh(one, BvhBuilder::binned);
  EXPECT_TRUE(tiny->pairs().root.is_leaf());
  EXPECT_TRUE(tiny->pairs().pairs.empty());
  Ray r;
  r.origin = {0.2f, 0.2f, 1.f};
  r.direction = {0.f, 0.f, -1.f};
  Hit h;
  EXPECT_TRUE(tiny->intersect(r, &h));
  EXPECT_EQ(h.prim, 0);
}

TEST(Bvh, EmptySceneAndFactory) {
  Geometry empty;
  for (BvhBuilder builder : kBuilders) {
    auto bvh = make_bvh(empty, builder);
    Ray r;
    Hit h;
    EXPECT_FALSE(bvh->intersect(r, &h));
    EXPECT_FALSE(bvh->occluded(r));
  }
  EXPECT_EQ(make_accelerator("bvh")->name(), "bvh");
  EXPECT_EQ(make_accelerator("bvh-sweep")->name(), "bvh-sweep");
  EXPECT_EQ(make_accelerator("bvh-median")->name(), "bvh-median");
  StructureOptions bad;
  bad.bvh.bins = 1;
  Geometry g = make_soup(1, 10, 0);
  EXPECT_THROW(make_accelerator("bvh", bad)->build(g), InputError);
  StructureOptions so;
  so.bvh_order = BvhOrder::split_axis;
  so.bvh.bins = 32;
  auto acc = make_accelerator("bvh-median", so);
  auto* bvh = dynamic_cast<Bvh*>(acc.get());
  ASSERT_NE(bvh, nullptr);
  EXPECT_EQ(bvh->order(), BvhOrder::split_axis);
  EXPECT_EQ(bvh->options().builder, BvhBuilder::median);
  EXPECT_EQ(bvh->options().bins, 32);
}

// Collects a walk's events, as the trace recorder would.
struct WalkLog {
  static constexpr bool enabled = true;
  enum class Kind { node, box, push, pop, skip, leaf, test, accepted, end };
  struct Entry {
    Kind kind;
    TreeStep step{};
    BoxTest box{};
    uint32_t prim = 0;
    bool hit = false;
    float t = 0.f;
  };
  std::vector<Entry> log;
  void ray_begin(const Ray&) { log.clear(); }
  void cell(const GridCellStep&) {}
  void box_entered(uint32_t, float) {}
  void node(const TreeStep& s) { log.push_back({Kind::node, s}); }
  void push(const TreeStep& s) { log.push_back({Kind::push, s}); }
  void pop(const TreeStep& s) { log.push_back({Kind::pop, s}); }
  void leaf(const TreeStep& s) { log.push_back({Kind::leaf, s}); }
  void box_test(const BoxTest& b) { log.push_back({Kind::box, {}, b}); }
  void skip(const TreeStep& s) { log.push_back({Kind::skip, s}); }
  void prim_test(uint32_t p, bool h, float t) { log.push_back({Kind::test, {}, {}, p, h, t}); }
  void mailbox_hit(uint32_t) {}
  void hit_deferred(uint32_t, float, float) {}
  void hit_accepted(uint32_t p, float t, AcceptReason) {
    log.push_back({Kind::accepted, {}, {}, p, true, t});
  }
  void ray_end(const Hit& h) { log.push_back({Kind::end, {}, {}, uint32_t(h.prim), h.found(), h.t}); }
};

// The recorded walk of hundreds of random rays against the kernel's own answer and the rules of the walk:
// pushes and pops balance (a nearest-hit walk empties its stack), a pop is the last push, a skip follows the
// pop of an entry whose t_near lies beyond the final hit, a visited child had a box hit, each primitive is
// tested once (no mailboxes needed), and the accepted hit is the nearest of the tests.
TEST(Bvh, RecordedWalkAgreesWithTheKernel) {
  Geometry g = make_soup(9, 300, 4);
  for (BvhBuilder builder : kBuilders)
    for (BvhOrder order : kOrders) {
      auto bvh = make_bvh(g, builder, order);
      const BvhData& d = bvh->data();
      std::vector<Ray> rays = random_rays(g.bounds(), 600, 15);
      WalkLog rec;
      int pushes = 0, skips = 0;
      for (const Ray& r : rays) {
        Hit plain, recorded;
        bvh->intersect(r, &plain);
        bool found = bvh->traverse(r, &recorded, false, rec);
        ASSERT_EQ(plain.prim, recorded.prim);
        ASSERT_EQ(plain.t, recorded.t);
        std::vector<WalkLog::Entry> stack;
        std::map<uint32_t, int> tested;
        std::map<int32_t, bool> box_hit;  // child -> its box was hit, since its parent's visit
        float best = kInfinity;
        int32_t best_prim = -1;
        const WalkLog::Entry* last_pop = nullptr;
        for (const WalkLog::Entry& e : rec.log) {
          switch (e.kind) {
            case WalkLog::Kind::box:
              box_hit[e.box.child] = e.box.hit;
              if (e.box.parent >= 0) {
                EXPECT_EQ(d.info[size_t(e.box.child)].parent, e.box.parent);
                EXPECT_EQ(e.box.depth, d.info[size_t(e.box.child)].depth);
              }
              if (e.box.hit) EXPECT_LE(e.box.t_near, e.box.t_far);
              break;
            case WalkLog::Kind::node:
              EXPECT_TRUE(box_hit[e.step.node]) << "node " << e.step.node << " visited without a box hit";
              EXPECT_EQ(e.step.depth, d.info[size_t(e.step.node)].depth);
              break;
            case WalkLog::Kind::push:
              EXPECT_TRUE(box_hit[e.step.node]);
              stack.push_back(e);
              ++pushes;
              break;
            case WalkLog::Kind::pop:
              ASSERT_FALSE(stack.empty());
              EXPECT_EQ(stack.back().step.node, e.step.node);
              EXPECT_EQ(stack.back().step.t_min, e.step.t_min);
              stack.pop_back();
              last_pop = &e;
              break;
            case WalkLog::Kind::skip:
              ASSERT_NE(last_pop, nullptr);
              EXPECT_EQ(last_pop->step.node, e.step.node);
              EXPECT_TRUE(found);
              EXPECT_GT(e.step.t_min, recorded.t) << "a skip only beyond the nearest hit";
              ++skips;
              break;
            case WalkLog::Kind::leaf:
              EXPECT_TRUE(d.nodes[size_t(e.step.node)].is_leaf());
              break;
            case WalkLog::Kind::test:
              // Each primitive is in one leaf, except after spatial splits: then at most once per leaf
              // that lists it.
              ++tested[e.prim];
              if (builder != BvhBuilder::sbvh) EXPECT_EQ(tested[e.prim], 1) << "primitive " << e.prim << " tested twice";
              if (e.hit && (e.t < best || (e.t == best && int32_t(e.prim) < best_prim))) {
                best = e.t;
                best_prim = int32_t(e.prim);
              }
              break;
            case WalkLog::Kind::accepted:
              EXPECT_EQ(int32_t(e.prim), recorded.prim);
              break;
            case WalkLog::Kind::end:
              break;
          }
        }
        EXPECT_TRUE(stack.empty()) << "a nearest-hit walk pops every push";
        EXPECT_EQ(best_prim, recorded.prim);
        ASSERT_EQ(rec.log.back().kind, WalkLog::Kind::end);
      }
      EXPECT_GT(pushes, 100);
      EXPECT_GT(skips, 10) << "front-to-back walks skip boxes beyond the hit";
    }
}

TEST(Bvh, CountedQueriesGiveTheSameHitsAndShadowRaysStopEarly) {
  Geometry g = make_soup(10, 300, 2);
  auto bvh = make_bvh(g, BvhBuilder::binned);
  std::vector<Ray> rays = random_rays(g.bounds(), 2000, 16);
  CountingRecorder nearest, any;
  for (const Ray& r : rays) {
    Hit a, b;
    bvh->intersect(r, &a);
    bvh->intersect_counted(r, &b, nearest);
    EXPECT_EQ(a.prim, b.prim);
    EXPECT_EQ(a.t, b.t);
    EXPECT_EQ(bvh->occluded_counted(r, any), a.found());
  }
  EXPECT_EQ(nearest.rays, rays.size());
  EXPECT_EQ(nearest.pushes, nearest.pops);
  EXPECT_EQ(nearest.box_tests, 2 * (nearest.nodes - nearest.leaves) + nearest.rays);
  EXPECT_LT(any.prim_tests, nearest.prim_tests);
  EXPECT_GT(bvh->memory_bytes(), bvh->data().nodes.size() * sizeof(BvhNode));
}

// The whole tracer (shadow, mirror and glass rays) gives the same picture, bit for bit, as with brute force.
TEST(Bvh, RendersTheSamePictureAsBruteForce) {
  for (const char* name : {"spheres.json", "cornell.json"}) {
    Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name);
    RenderOptions opt = render_options(scene.render);
    opt.width = 48;
    opt.height = 36;
    BruteForce brute;
    brute.build(scene.geometry);
    Image reference = render_image(scene, brute, opt).image;
    for (BvhBuilder builder : kBuilders) {
      auto bvh = make_bvh(scene.geometry, builder);
      EXPECT_TRUE(render_image(scene, *bvh, opt).image.pixels == reference.pixels)
          << name << " " << int(builder);
    }
  }
}

}  // namespace
}  // namespace raystep
