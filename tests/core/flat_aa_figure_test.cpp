// The 2D anti-aliasing figure (figure/flat_aa_figure.h) on the slides' white polygon on black pixels: each
// pixel's sampled value is what the renderer's own samples give (one sample: 0 or 1), its exact value the area
// of the polygon inside it, the error their difference; more samples bring the error down; every sample drawn
// white lies inside the polygon and every one drawn black outside.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>

#include <glm/geometric.hpp>
#include <string>

#include "raystep/accel/structure_options.h"
#include "raystep/figure/flat_aa_figure.h"
#include "raystep/io/scene_loader.h"
#include "raystep/render/coverage.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

const std::string kPolygon = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/flatland/aliasing_polygon.json";

bool inside(const std::vector<glm::vec2>& poly, glm::vec2 p) {  // even-odd crossings
  bool in = false;
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++)
    if ((poly[i].y > p.y) != (poly[j].y > p.y) &&
        p.x < (poly[j].x - poly[i].x) * (p.y - poly[i].y) / (poly[j].y - poly[i].y) + poly[i].x)
      in = !in;
  return in;
}

// Whether p lies on an edge, where inside or out is the renderer's tie-break (a sample of a regular lattice
// can fall exactly on one).
bool on_edge(const std::vector<glm::vec2>& poly, glm::vec2 p) {
  for (size_t i = 0, j = poly.size() - 1; i < poly.size(); j = i++) {
    const glm::vec2 a = poly[j], b = poly[i], ab = b - a;
    const float t = std::clamp(glm::dot(p - a, ab) / glm::dot(ab, ab), 0.f, 1.f);
    if (glm::length(a + t * ab - p) < 1e-4f) return true;
  }
  return false;
}

const FigureLayer& layer(const Figure& f, const std::string& name) {
  for (const FigureLayer& l : f.layers)
    if (l.name == name) return l;
  static const FigureLayer none;
  ADD_FAILURE() << "no layer " << name;
  return none;
}

struct Built {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
};

FlatAa figure(Built& r, const std::string& spec, int w = 0, int h = 0) {
  FlatAaInput in;
  in.scene = &r.scene;
  in.accel = r.accel.get();
  in.aa = parse_antialiasing(spec);
  in.width = w;
  in.height = h;
  return flat_aa_figure(in);
}

TEST(FlatAaFigure, SampledExactAndErrorPerPixel) {
  Built r{load_scene(kPolygon), make_accelerator("kd", StructureOptions{})};
  r.accel->build(r.scene.geometry);
  const std::vector<glm::vec2>& poly = r.scene.flat->shapes[0].points;
  const FlatAa one = figure(r, "none");
  ASSERT_TRUE(one.exact) << one.why_not;
  EXPECT_EQ(one.pixels, 24 * 16);
  EXPECT_EQ(one.samples, size_t(one.pixels));
  // One sample a pixel: every sampled pixel is black or white, and the exact ones are the polygon's area.
  const FigureLayer& px = layer(one.figure, "pixels");
  int sampled = 0, exact = 0;
  double area = 0.0;
  for (const FigureItem& it : px.items) {
    if (it.css == "sampled") {
      ++sampled;
      EXPECT_TRUE(it.style.fill.r == 0.f || it.style.fill.r == 1.f);
    }
    if (it.css == "exact") {
      ++exact;
      area += double(it.style.fill.r);
    }
  }
  EXPECT_EQ(sampled, one.pixels);
  EXPECT_EQ(exact, one.pixels);
  std::vector<glm::dvec2> dpoly;
  for (const glm::vec2& p : poly) dpoly.push_back(p);
  // One unit a pixel: the exact values add up to the polygon's area.
  EXPECT_NEAR(area, std::fabs(signed_area(dpoly)), 1e-3);
  EXPECT_GT(one.mean_abs_error, 0.02);
  EXPECT_LE(one.max_abs_error, 1.0);

  // Sixteen samples a pixel: the error falls, regular and jittered alike; each dot's colour says whether its
  // position lies in the polygon.
  for (const std::string spec : {"regular:4", "jitter:4"}) {
    const FlatAa many = figure(r, spec);
    EXPECT_EQ(many.samples, size_t(16 * many.pixels)) << spec;
    EXPECT_LT(many.mean_abs_error, 0.5 * one.mean_abs_error) << spec;
    EXPECT_LT(many.max_abs_error, one.max_abs_error) << spec;
    int in = 0, out = 0;
    for (const FigureItem& d : layer(many.figure, "samples").items) {
      const bool white = d.css == "sample in";
      if (!on_edge(poly, d.points[0]))
        EXPECT_EQ(white, inside(poly, d.points[0])) << spec << " at " << d.points[0].x << "," << d.points[0].y;
      (white ? in : out)++;
    }
    EXPECT_GT(in, 100);
    EXPECT_GT(out, 100);
    EXPECT_EQ(layer(many.figure, "titles").items.size(), 3u);  // sampled, exact, error
  }
  // Adaptive sampling spends more where the edge is.
  const FlatAa adaptive = figure(r, "adaptive:0.1:2");
  EXPECT_GT(adaptive.samples, size_t(5 * adaptive.pixels));
  EXPECT_LT(adaptive.mean_abs_error, one.mean_abs_error);
}

TEST(FlatAaFigure, RefusesTooManyPixelsAndA3DScene) {
  Built r{load_scene(kPolygon), make_accelerator("kd", StructureOptions{})};
  r.accel->build(r.scene.geometry);
  EXPECT_THROW(figure(r, "none", 100, 100), InputError);
  Built cornell{load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json"),
              make_accelerator("kd", StructureOptions{})};
  cornell.accel->build(cornell.scene.geometry);
  EXPECT_THROW(figure(cornell, "none", 8, 8), InputError);
}

}  // namespace
}  // namespace raystep
