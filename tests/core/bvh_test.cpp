// The binary BVH's traversal: agreement with brute force (same primitive, same t) for every builder and both
// child orders on random, camera, edge-aimed and in-plane rays (lying in child boxes' faces, with +0 and -0
// components), non-finite rays (a miss, no crash), and the recorded walk against the kernel's own result.
#include <gtest/gtest.h>

#include <cmath>
#include <map>
#include <random>

#include "raystep/accel/brute_force.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/structure_options.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/render/render.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/scene_loader.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::count_disagreements;
using test::make_soup;

const BvhBuilder kBuilders[] = {BvhBuilder::binned, BvhBuilder::sweep, BvhBuilder::median};
const BvhOrder kOrders[] = {BvhOrder::entry_distance, BvhOrder::split_axis};

std::unique_ptr<Bvh> make_bvh(const Geometry& g, BvhBuilder builder,
                              BvhOrder order = BvhOrder::entry_distance, BvhOptions options = {}) {
  options.builder = builder;
  auto bvh = std::make_unique<Bvh>(options, order);
  bvh->build(g);
  return bvh;
}

// Pinhole rays from outside the scene's box through a grid over it.
std::vector<Ray> camera_rays(const Bounds3& b, int n) {
  std::vector<Ray> rays;
  glm::vec3 eye = b.center() + glm::vec3(0.3f, 0.4f, 2.5f) * glm::max(b.extent(), glm::vec3(1e-3f));
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      glm::vec3 target = b.lo + b.extent() * glm::vec3((i + 0.5f) / n, (j + 0.5f) / n, 0.5f);
      Ray r;
      r.origin = eye;
      r.direction = target - eye;
      rays.push_back(r);
    }
  return rays;
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
  std::vector<Ray> rays = edge_rays(g, 8000, 12);
  for (BvhBuilder builder : kBuilders)
    for (BvhOrder order : kOrders) {
      auto bvh = make_bvh(g, builder, order);
      std::vector<Ray> all = rays, faces = face_rays(bvh->data(), 3);
      all.insert(all.end(), faces.begin(), faces.end());
      EXPECT_EQ(count_disagreements(*bvh, brute, all), 0) << int(builder) << " " << int(order);
      int leaks = 0;
      for (size_t i = 0; i < rays.size(); ++i) {
        Ray r;
        r.origin = glm::vec3(0.f);
        r.direction = rays[i].origin + rays[i].direction;  // the edge target
        Hit h;
        leaks += !bvh->intersect(r, &h);
      }
      EXPECT_EQ(leaks, 0) << int(builder);
    }
}

TEST(Bvh, NonFiniteRaysMissAndTerminate) {
  Geometry g = make_soup(8, 50, 1);
  for (BvhBuilder builder : kBuilders) {
    auto bvh = make_bvh(g, builder);
    float nan = std::nanf(""), inf = kInfinity;
    for (glm::vec3 o : {glm::vec3(nan, 0, 0), glm::vec3(inf, 0, 0), glm::vec3(0.f)})
      for (glm::vec3 d : {glm::vec3(1, nan, 0), glm::vec3(inf, 1, 0), glm::vec3(0.f), glm::vec3(-0.f)}) {
        Ray r;
        r.origin = o;
        r.direction = d;
        Hit h;
        EXPECT_FALSE(bvh->intersect(r, &h));
        EXPECT_EQ(h.prim, -1);
        EXPECT_FALSE(bvh->occluded(r));
      }
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

}  // namespace
}  // namespace raystep
