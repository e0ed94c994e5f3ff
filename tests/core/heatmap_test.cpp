// Heat maps: the traversal counts of one centre ray per pixel, and the samples map of a render (where
// adaptive sampling spent its rays), as the debugger's overlay and the lessons show them.
#include <gtest/gtest.h>

#include <numeric>

#include "raystep/accel/structure_options.h"
#include "raystep/render/camera.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/heatmap.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

TEST(Heatmap, QuantitiesByName) {
  EXPECT_EQ(parse_heat_quantity("cells"), HeatQuantity::cells);
  EXPECT_EQ(parse_heat_quantity("nodes"), HeatQuantity::cells);
  EXPECT_EQ(parse_heat_quantity("tests"), HeatQuantity::tests);
  EXPECT_EQ(parse_heat_quantity("mailbox"), HeatQuantity::mailbox);
  EXPECT_EQ(parse_heat_quantity("samples"), HeatQuantity::samples);
  EXPECT_EQ(parse_heat_quantity("boxes"), HeatQuantity::boxes);
  EXPECT_STREQ(heat_quantity_label(HeatQuantity::boxes), "bounding-box tests");
  EXPECT_THROW(parse_heat_quantity("rays"), InputError);
}

// A BVH's maps: boxes counts its box tests, cells its nodes visited, pixel by pixel as the counting recorder
// counts the centre ray; a structure without boxes (the grid) has none.
TEST(Heatmap, BoxesAndNodesOfABvh) {
  Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json");
  std::unique_ptr<Accelerator> bvh = make_accelerator("bvh", StructureOptions{});
  bvh->build(scene.geometry);
  const int w = 40, h = 30;
  const HeatMap boxes = compute_heatmap(scene.camera, *bvh, w, h, HeatQuantity::boxes, 2);
  const HeatMap nodes = compute_heatmap(scene.camera, *bvh, w, h, HeatQuantity::cells, 1);
  EXPECT_EQ(boxes.quantity, HeatQuantity::boxes);
  ProjectiveCamera cam(scene.camera, w, h);
  for (int y = 0; y < h; y += 7)
    for (int x = 0; x < w; x += 3) {
      CountingRecorder c;
      Hit hit;
      bvh->intersect_counted(cam.generate(float(x) + 0.5f, float(y) + 0.5f), &hit, c);
      EXPECT_EQ(boxes.values[size_t(y) * w + x], c.box_tests) << x << "," << y;
      EXPECT_EQ(nodes.values[size_t(y) * w + x], c.nodes) << x << "," << y;
    }
  // Every visited inner node tests two boxes, and the walk starts with the root's: more boxes than nodes.
  EXPECT_GT(boxes.mean_value, nodes.mean_value);
  EXPECT_GT(nodes.max_value, 2u);
  std::unique_ptr<Accelerator> grid = make_accelerator("grid", StructureOptions{});
  grid->build(scene.geometry);
  EXPECT_EQ(compute_heatmap(scene.camera, *grid, w, h, HeatQuantity::boxes, 1).max_value, 0u);
}

TEST(Heatmap, SamplesMapHoldsTheValuesAndTheirStatistics) {
  HeatMap h = samples_heatmap({5, 5, 9, 21, 5, 5}, 3, 2);
  EXPECT_EQ(h.quantity, HeatQuantity::samples);
  EXPECT_EQ(h.width, 3);
  EXPECT_EQ(h.height, 2);
  EXPECT_EQ(h.values[3], 21u);
  EXPECT_EQ(h.max_value, 21u);
  EXPECT_DOUBLE_EQ(h.mean_value, 50.0 / 6.0);
  EXPECT_THROW(samples_heatmap({1, 2, 3}, 2, 2), InputError);
  EXPECT_THROW(samples_heatmap({}, 0, 0), InputError);
}

// The lecture's aliasing triangle under adaptive sampling: flat pixels keep their 5 first samples, pixels on
// the edges take more, and the map adds up to the render's primary rays.
TEST(Heatmap, AdaptiveSamplesGatherOnTheEdges) {
  Scene scene = load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/aliasing.json");
  std::unique_ptr<Accelerator> accel = make_accelerator("grid", StructureOptions{});
  accel->build(scene.geometry);
  RenderOptions o = render_options(scene.render);
  o.aa = parse_antialiasing("adaptive:0.1:3");
  o.threads = 1;
  RenderResult r = render_image(scene, *accel, o);
  HeatMap h = samples_heatmap(r.samples, o.width, o.height);
  EXPECT_EQ(std::accumulate(h.values.begin(), h.values.end(), uint64_t(0)), r.rays.primary);
  EXPECT_EQ(h.values[0], 5u);  // the top-left corner lies outside the triangle: flat
  int refined = 0;
  for (uint32_t v : h.values) refined += v > 5;
  EXPECT_GT(refined, 50);                        // the triangle's three edges
  EXPECT_LT(refined, int(h.values.size()) / 4);  // and little else
  EXPECT_GT(h.max_value, 5u);
  EXPECT_THROW(compute_heatmap(scene.camera, *accel, 8, 8, HeatQuantity::samples, 1), InputError);
}

}  // namespace
}  // namespace raystep
