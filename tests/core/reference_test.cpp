#include "raystep/render/reference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <stdexcept>

#include "raystep/accel/structure_options.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

Scene shipped(const std::string& name) {
  return load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name);
}

struct Built {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
};

Built build(const std::string& name) {
  Built b{shipped(name), make_accelerator("grid", StructureOptions{})};
  b.accel->build(b.scene.geometry);
  return b;
}

RenderResult render(const Built& b, const std::string& aa, uint64_t seed) {
  RenderOptions o = render_options(b.scene.render);
  o.aa = parse_antialiasing(aa);
  o.seed = seed;
  o.threads = 1;
  return render_image(b.scene, *b.accel, o);
}

TEST(Reference, ShippedFlatScenesAreExact) {
  for (const char* name : {"aliasing.json", "coverage.json", "grid_edges.json"}) {
    Scene s = shipped(name);
    EXPECT_EQ(exact_coverage_unavailable(s, s.render.width, s.render.height), "") << name;
  }
}

TEST(Reference, PerspectiveAndShadedScenesAreRefusedWithAReason) {
  for (const char* name : {"cornell.json", "spheres.json"}) {
    Scene s = shipped(name);
    const std::string why = exact_coverage_unavailable(s, s.render.width, s.render.height);
    EXPECT_NE(why, "") << name;
    EXPECT_EQ(why.find('\n'), std::string::npos);
    EXPECT_THROW(render_exact_coverage(s, 8, 8), InputError);
    EXPECT_FALSE(exact_pixel_value(s, 8, 8, 0, 0).has_value());
  }
}

// Each condition of the flat-colour rule on its own, starting from the exact aliasing scene.
TEST(Reference, EachConditionRefusesOnItsOwn) {
  Scene base = shipped("aliasing.json");
  auto why = [](const Scene& s) { return exact_coverage_unavailable(s, 64, 48); };
  {
    Scene s = base;
    s.camera.type = CameraType::pinhole;
    EXPECT_NE(why(s).find("orthographic"), std::string::npos);
  }
  {
    Scene s = base;
    s.lights.push_back(Light{});
    EXPECT_NE(why(s).find("lights"), std::string::npos);
    s.lights[0].intensity = 0.f;  // a light of no power shades nothing
    EXPECT_EQ(why(s), "");
  }
  {
    Scene s = base;
    s.materials[s.geometry.material(0)].mirror = 0.5f;
    s.render.max_depth = 1;
    EXPECT_NE(why(s).find("reflects"), std::string::npos);
    s.render.max_depth = 0;  // no secondary rays at all
    EXPECT_EQ(why(s), "");
  }
  {
    Scene s = base;
    s.geometry.add_sphere(Sphere{glm::vec3(10.f, 10.f, 0.f), 1.f});
    EXPECT_NE(why(s).find("spheres"), std::string::npos);
  }
  {
    Scene s = base;  // a second triangle over the first one's middle
    s.geometry.add_triangle(glm::vec3(20, 15, 1), glm::vec3(30, 15, 1), glm::vec3(25, 25, 1));
    EXPECT_NE(why(s).find("overlap"), std::string::npos);
  }
  {
    Scene s = base;  // two triangles overlapping only outside the image (x > 64): nothing on screen overlaps
    s.geometry.add_triangle(glm::vec3(62, 40, 0), glm::vec3(80, 40, 0), glm::vec3(80, 47, 0));
    s.geometry.add_triangle(glm::vec3(70, 38, 1), glm::vec3(90, 38, 1), glm::vec3(90, 47, 1));
    EXPECT_EQ(why(s), "");
    s.geometry.add_triangle(glm::vec3(61, 39, 2), glm::vec3(66, 39, 2), glm::vec3(66, 46, 2));  // on screen
    EXPECT_NE(why(s).find("overlap"), std::string::npos);
  }
  {
    Scene s = base;  // a triangle sharing an edge (58,14)-(20,43) with the first, outside it: no overlap
    s.geometry.add_triangle(glm::vec3(58, 14, 0), glm::vec3(60, 45, 0), glm::vec3(20, 43, 0));
    EXPECT_EQ(why(s), "");
  }
}

// Where a pixel lies wholly inside or outside every triangle, the exact value is what the centre ray sees.
TEST(Reference, ExactEqualsTheCentreRayAwayFromEdges) {
  for (const char* name : {"aliasing.json", "coverage.json"}) {
    Built b = build(name);
    const int w = b.scene.render.width, h = b.scene.render.height;
    const Image exact = render_exact_coverage(b.scene, w, h);
    const Image centre = render(b, "none", 0).image;
    const Image fine = render(b, "regular:8", 0).image;  // all 64 samples agree: the pixel is not on an edge
    int inside = 0, outside = 0, edge = 0;
    for (int y = 0; y < h; ++y)
      for (int x = 0; x < w; ++x) {
        const float v = exact.at(x, y).x;
        EXPECT_GE(v, -1e-6f);
        EXPECT_LE(v, 1.f + 1e-6f);
        if (v == 0.f || v == 1.f) {
          EXPECT_EQ(centre.at(x, y), exact.at(x, y)) << name << " " << x << "," << y;
          (v == 0.f ? outside : inside)++;
        } else {
          ++edge;
          EXPECT_NEAR(fine.at(x, y).x, v, 0.5f);
        }
        EXPECT_EQ(exact_pixel_value(b.scene, w, h, x, y).value(), exact.at(x, y));
      }
    EXPECT_GT(inside, 50) << name;
    EXPECT_GT(outside, 50) << name;
    EXPECT_GT(edge, 50) << name;
  }
}

// The aliasing triangle's area is the image's sum (one world unit per pixel, white on black).
TEST(Reference, AliasingTriangleAreaIsTheSumOfThePixels) {
  Scene s = shipped("aliasing.json");
  const Image exact = render_exact_coverage(s, 64, 48);
  double sum = 0.0;
  for (const glm::vec3& p : exact.pixels) sum += p.x;
  // (6,5) (58,14) (20,43): |(52*38 - 9*14)| / 2
  EXPECT_NEAR(sum, 0.5 * std::fabs(52.0 * 38.0 - 9.0 * 14.0), 1e-3);
}

TEST(Reference, JitterConvergesToTheExactPicture) {
  Built b = build("aliasing.json");
  const Image exact = render_exact_coverage(b.scene, 64, 48);
  const double e2 = rmse(render(b, "jitter:2", 1).image, exact);
  const double e8 = rmse(render(b, "jitter:8", 1).image, exact);
  const double e32 = rmse(render(b, "jitter:32", 1).image, exact);
  EXPECT_LT(e8, e2);
  EXPECT_LT(e32, e8);
  EXPECT_LT(e32, 0.005);
  EXPECT_GT(e32, 0.0);
}

TEST(Reference, MakeReferenceKinds) {
  Built b = build("aliasing.json");
  Reference exact = make_reference(b.scene, *b.accel, 64, 48, "auto", 1);
  EXPECT_EQ(exact.kind, "exact");
  EXPECT_EQ(exact.estimated_rmse, 0.0);
  double last = -1.0;
  Reference jitter = make_reference(b.scene, *b.accel, 64, 48, "jitter:8", 1, [&](double f) {
    EXPECT_GE(f, last);
    last = f;
  });
  EXPECT_EQ(last, 1.0);
  EXPECT_EQ(jitter.kind, "jitter:8");
  const double true_error = rmse(jitter.image, exact.image);
  // The two-seed estimate is a statistic, not the error itself: within a factor of two of it.
  EXPECT_GT(jitter.estimated_rmse, 0.5 * true_error);
  EXPECT_LT(jitter.estimated_rmse, 2.0 * true_error);

  Built cornell = build("cornell.json");
  EXPECT_EQ(make_reference(cornell.scene, *cornell.accel, 16, 12, "auto", 1).kind, "jitter:16");
  EXPECT_THROW(make_reference(cornell.scene, *cornell.accel, 16, 12, "exact", 1), InputError);
  for (const char* bad : {"", "jitter", "jitter:0", "regular:4", "exactly", "jitter:x"})
    EXPECT_THROW(make_reference(b.scene, *b.accel, 16, 12, bad, 1), InputError) << bad;
}

TEST(Reference, ErrorMeasures) {
  Image a(2, 1), b(2, 1);
  b.pixels[0] = glm::vec3(0.3f, 0.f, 0.f);
  b.pixels[1] = glm::vec3(0.f, -0.4f, 0.f);
  EXPECT_NEAR(rmse(a, b), std::sqrt((0.09 + 0.16) / 6.0), 1e-7);
  EXPECT_NEAR(max_abs_error(a, b), 0.4, 1e-7);
  const std::vector<float> e = pixel_errors(a, b);
  ASSERT_EQ(e.size(), 2u);
  EXPECT_FLOAT_EQ(e[0], 0.3f);
  EXPECT_FLOAT_EQ(e[1], 0.4f);
  EXPECT_EQ(rmse(a, a), 0.0);
  EXPECT_THROW(rmse(a, Image(1, 2)), std::invalid_argument);
  EXPECT_THROW(pixel_errors(a, Image(1, 1)), std::invalid_argument);
}

}  // namespace
}  // namespace raystep
