#include "raystep/report/structure_compare.h"

#include <gtest/gtest.h>

#include "raystep/accel/grid.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

Scene soup_scene(int triangles) {
  Scene scene;
  scene.geometry = test::make_soup(3, triangles, 2);
  scene.materials.emplace_back();
  scene.camera.eye = glm::vec3(1.f, 0.5f, 8.f);
  scene.render.width = 40;
  scene.render.height = 30;
  return scene;
}

StructureCompareOptions small_options() {
  StructureCompareOptions o;
  o.random_rays = 3000;
  o.reps = 1;
  return o;
}

TEST(StructureCompare, HitAgreementClasses) {
  Hit miss, a, b, c;
  a.prim = 3, a.t = 2.f;
  b.prim = 5, b.t = 2.f;  // another primitive at the same t: a tie
  c.prim = 3, c.t = std::nextafter(2.f, 3.f);
  EXPECT_EQ(compare_hits(miss, miss), HitAgreement::same);
  EXPECT_EQ(compare_hits(a, a), HitAgreement::same);
  EXPECT_EQ(compare_hits(a, b), HitAgreement::tie);
  EXPECT_EQ(compare_hits(a, c), HitAgreement::differs);
  EXPECT_EQ(compare_hits(a, miss), HitAgreement::differs);
  EXPECT_EQ(compare_hits(miss, a), HitAgreement::differs);
  Hit d = b;
  d.t = 2.5f;
  EXPECT_EQ(compare_hits(a, d), HitAgreement::differs);
}

TEST(StructureCompare, EveryStructureAgreesWithBruteForce) {
  Scene scene = soup_scene(300);
  int rows_seen = 0;
  double last_progress = 0;
  StructureCompareHooks hooks;
  hooks.row_done = [&](const StructureCompareRow&) { ++rows_seen; };
  hooks.progress = [&](double p) {
    EXPECT_GE(p, last_progress);
    last_progress = p;
  };
  StructureComparison c = compare_structures(scene, small_options(), hooks);
  ASSERT_EQ(c.rows.size(), accelerator_names().size());
  EXPECT_EQ(rows_seen, int(c.rows.size()));
  EXPECT_DOUBLE_EQ(last_progress, 1.0);
  EXPECT_EQ(c.camera_rays, 1200u);
  EXPECT_EQ(c.random_rays, 3000u);
  EXPECT_EQ(c.camera_checked, 1200u);  // 302 primitives: brute force affords every ray
  for (const StructureCompareRow& r : c.rows) {
    EXPECT_EQ(r.disagreements(), 0u) << r.name;
    EXPECT_EQ(r.camera.checked, 1200u) << r.name;
    EXPECT_EQ(r.random.checked, 3000u) << r.name;
    EXPECT_GT(r.camera.tests_per_ray, 0.0) << r.name;
    if (r.name == "brute") {
      EXPECT_EQ(r.memory_bytes, 0u);
      EXPECT_EQ(r.steps, "-");
      EXPECT_DOUBLE_EQ(r.random.tests_per_ray, 302.0);  // every primitive, every ray
    } else {
      EXPECT_GT(r.memory_bytes, 0u) << r.name;
      EXPECT_GT(r.random.steps_per_ray, 0.0) << r.name;
      EXPECT_LT(r.random.tests_per_ray, 302.0) << r.name;
    }
  }
  EXPECT_EQ(c.rows[2].steps, "cells");
  EXPECT_EQ(c.rows[3].steps, "nodes");
}

TEST(StructureCompare, BruteForceSubsetKeepsToItsBudget) {
  Scene scene = soup_scene(300);
  StructureCompareOptions o = small_options();
  o.structures = {"brute", "grid", "bvol"};
  o.test_budget = 302 * 100;  // 100 rays per set
  StructureComparison c = compare_structures(scene, o);
  EXPECT_EQ(c.random_checked, 100u);
  EXPECT_EQ(c.camera_checked, 100u);
  EXPECT_EQ(c.rows[0].random.rays, 100u);   // brute force traces the subset
  EXPECT_EQ(c.rows[1].random.rays, 3000u);  // the grid traces all, checked on the subset
  EXPECT_EQ(c.rows[1].random.checked, 100u);
  EXPECT_EQ(c.rows[1].disagreements(), 0u);
  // One object, one box: bounding volumes test nearly every primitive, so they too are timed on the subset.
  EXPECT_EQ(c.rows[2].random.rays, 100u);
  EXPECT_EQ(c.rows[2].random.checked, 100u);
}

TEST(StructureCompare, MemoryIsTheGridsArrays) {
  Scene scene = soup_scene(100);
  UniformGrid grid;
  grid.build(scene.geometry);
  std::array<int, 3> n = grid.resolution();
  size_t cells = size_t(n[0]) * n[1] * n[2];
  // Offsets (cells + 1), references, and one bit per cell, at least.
  EXPECT_GE(grid.memory_bytes(), 4 * (cells + 1) + 4 * grid.reference_count() + cells / 8);
}

TEST(StructureCompare, BadInputThrows) {
  Scene scene = soup_scene(20);
  StructureCompareOptions o = small_options();
  o.structures = {"grid", "quadtree"};  // an unknown name (the octree is "octree")
  try {
    compare_structures(scene, o);
    FAIL();
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("quadtree"), std::string::npos);
  }
  o = small_options();
  o.reps = 0;
  EXPECT_THROW(compare_structures(scene, o), InputError);
}

TEST(StructureCompare, CancelReturnsFinishedRows) {
  Scene scene = soup_scene(100);
  std::atomic<bool> cancel{false};
  StructureCompareHooks hooks;
  hooks.cancel = &cancel;
  hooks.row_done = [&](const StructureCompareRow&) { cancel = true; };
  EXPECT_EQ(compare_structures(scene, small_options(), hooks).rows.size(), 1u);
}

}  // namespace
}  // namespace raystep
