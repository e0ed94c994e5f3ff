#include "raystep/report/grid_sweep.h"

#include <gtest/gtest.h>

#include <cmath>

#include "raystep/accel/grid.h"
#include "raystep/render/camera.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

Scene soup_scene(int triangles) {
  Scene scene;
  scene.geometry = test::make_soup(7, triangles, 3);
  scene.materials.emplace_back();
  scene.camera.eye = glm::vec3(0.f, 0.f, 8.f);
  scene.render.width = 64;
  scene.render.height = 48;
  return scene;
}

GridSweepOptions small_options() {
  GridSweepOptions o;
  o.random_rays = 2000;
  o.reps = 1;
  return o;
}

TEST(GridSweep, DefaultDensitiesRowsAndCounts) {
  Scene scene = soup_scene(400);
  int called = 0;
  GridSweep sweep = run_grid_sweep(scene, small_options(), [&](const GridSweepRow&) { ++called; });
  ASSERT_EQ(sweep.rows.size(), 9u);
  EXPECT_EQ(called, 9);
  EXPECT_EQ(sweep.primitives, 403u);
  EXPECT_EQ(sweep.rays, 64u * 48u + 2000u);
  for (size_t i = 0; i < sweep.rows.size(); ++i) {
    const GridSweepRow& r = sweep.rows[i];
    // The row's resolution is the density rule's (no coarsening on 403 primitives).
    EXPECT_FALSE(r.coarsened);
    EXPECT_EQ(r.resolution, UniformGrid::resolution_for(scene.geometry.bounds(), 403, r.density));
    EXPECT_EQ(r.cells, uint64_t(r.resolution[0]) * r.resolution[1] * r.resolution[2]);
    EXPECT_GE(r.references_per_prim, 1.0);  // every primitive lies in at least one cell
    EXPECT_GT(r.bytes, 4.0 * double(r.cells));
    EXPECT_GT(r.cells_per_ray, 0.0);
    EXPECT_GT(r.tests_per_ray, 0.0);
    if (i > 0) {
      // Finer grids: more cells, more references per primitive, more cells walked per ray.
      const GridSweepRow& p = sweep.rows[i - 1];
      EXPECT_GT(r.cells, p.cells) << r.density;
      EXPECT_GE(r.references_per_prim, p.references_per_prim) << r.density;
      EXPECT_GT(r.cells_per_ray, p.cells_per_ray) << r.density;
    }
  }
  // Far fewer tests than brute force's 403 per ray, once the grid is at the rule's density.
  EXPECT_LT(sweep.rows[5].tests_per_ray, 403.0 / 4);
  EXPECT_LT(sweep.rows.back().tests_per_ray, sweep.rows.front().tests_per_ray);
}

TEST(GridSweep, CountsEqualTheGridsOwnCounters) {
  Scene scene = soup_scene(200);
  GridSweepOptions o = small_options();
  o.densities = {2.f};
  o.camera_width = 10;
  o.camera_height = 10;
  o.random_rays = 0;
  GridSweep sweep = run_grid_sweep(scene, o);
  ASSERT_EQ(sweep.rows.size(), 1u);
  GridOptions go;
  go.density = 2.f;
  UniformGrid grid(go);
  grid.build(scene.geometry);
  CountingRecorder c;
  ProjectiveCamera camera(scene.camera, 10, 10);
  for (int y = 0; y < 10; ++y)
    for (int x = 0; x < 10; ++x) {
      Hit h;
      grid.intersect_counted(camera.generate(x + 0.5f, y + 0.5f), &h, c);
    }
  EXPECT_DOUBLE_EQ(sweep.rows[0].cells_per_ray, double(c.cells) / 100.0);
  EXPECT_DOUBLE_EQ(sweep.rows[0].tests_per_ray, double(c.prim_tests) / 100.0);
  EXPECT_DOUBLE_EQ(sweep.rows[0].mailbox_per_ray, double(c.mailbox_hits) / 100.0);
  EXPECT_EQ(sweep.rows[0].bytes, double(grid.memory_bytes()));
}

TEST(GridSweep, CancelStopsAndKeepsFinishedRows) {
  Scene scene = soup_scene(100);
  std::atomic<bool> cancel{false};
  GridSweep sweep = run_grid_sweep(
      scene, small_options(), [&](const GridSweepRow&) { cancel = true; }, &cancel);
  EXPECT_EQ(sweep.rows.size(), 1u);
  cancel = true;
  EXPECT_TRUE(run_grid_sweep(scene, small_options(), nullptr, &cancel).rows.empty());
}

TEST(GridSweep, BadDensitiesThrow) {
  Scene scene = soup_scene(50);
  for (float d : {0.f, -1.f, 65.f, std::nanf("")}) {
    GridSweepOptions o = small_options();
    o.densities = {1.f, d};
    EXPECT_THROW(run_grid_sweep(scene, o), InputError) << d;
  }
  Scene empty;
  empty.materials.emplace_back();
  EXPECT_THROW(run_grid_sweep(empty, small_options()), InputError);
}

}  // namespace
}  // namespace raystep
