#include "raystep/report/cost_report.h"

#include <gtest/gtest.h>

#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

Scene soup_scene() {
  Scene scene;
  scene.geometry = test::make_soup(5, 60, 2);
  scene.materials.emplace_back();
  scene.camera.eye = glm::vec3(0.f, 0.f, 8.f);
  scene.render.width = 12;
  scene.render.height = 10;
  return scene;
}

// No lights and depth 0: one ray per sample, each testing all n primitives: exactly m^2 k^2 n.
TEST(CostReport, BruteForceMeetsTheFormulaExactlyAtDepthZero) {
  Scene scene = soup_scene();
  scene.render.max_depth = 0;
  CostReportOptions o;
  o.aa = parse_antialiasing("regular:3");
  o.structures = {"grid"};
  CostReport r = run_cost_report(scene, o);
  EXPECT_EQ(r.pixels, 120u);
  EXPECT_EQ(r.samples_per_pixel, 9.0);
  EXPECT_EQ(r.primitives, 62u);
  EXPECT_EQ(r.predicted, 120.0 * 9 * 62);
  EXPECT_EQ(r.bound, r.predicted);
  ASSERT_GE(r.rows.size(), 3u);
  EXPECT_EQ(double(r.rows[0].tests), r.predicted);
  EXPECT_EQ(double(r.rows[1].tests), r.predicted);
  EXPECT_EQ(r.rows[0].rays.primary, 120u * 9u);
  EXPECT_LT(r.rows[2].tests, r.rows[0].tests);  // the grid tests fewer
}

TEST(CostReport, CountsStayWithinTheBoundAndTechniquesCutTheirFactor) {
  Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json");
  CostReportOptions o;
  o.width = 24;
  o.height = 24;
  o.aa = parse_antialiasing("jitter:2");
  CostReport r = run_cost_report(scene, o);
  EXPECT_EQ(r.depth, 5);
  EXPECT_EQ(r.lights, 1);
  // brute x2, every other structure (bvol, grid, kd, kd-median, bvh, bvh-sweep, bvh-median), adaptive sampling.
  const size_t structures = accelerator_names().size() - 1;
  ASSERT_EQ(r.rows.size(), structures + 3);
  for (const CostRow& row : r.rows) EXPECT_LE(double(row.tests), r.bound) << row.label;
  // Brute force tests every primitive on every nearest-hit query: n per camera ray at least.
  EXPECT_GE(double(r.rows[0].tests), double(r.pixels) * 4 * 23);
  // Adaptive termination spawns no more rays than the full tree.
  EXPECT_LE(r.rows[1].rays.total(), r.rows[0].rays.total());
  ASSERT_EQ(r.factors.size(), structures + 2);
  EXPECT_EQ(r.factors[0].factor, "2^d");
  for (size_t i = 1; i <= structures; ++i) {
    EXPECT_EQ(r.factors[i].factor, "n");
    EXPECT_GT(r.factors[i].cut(), 1.0) << r.factors[i].technique;
  }
  EXPECT_EQ(r.factors[structures + 1].factor, "k^2");
  EXPECT_EQ(r.factors[structures + 1].before, 4.0);
}

TEST(CostReport, BadInputThrows) {
  Scene scene = soup_scene();
  CostReportOptions o;
  o.structures = {"grid", "nope"};
  EXPECT_THROW(run_cost_report(scene, o), InputError);
  o.structures = {};
  o.width = 100000;
  o.height = 10;
  EXPECT_THROW(run_cost_report(scene, o), InputError);
}

}  // namespace
}  // namespace raystep
