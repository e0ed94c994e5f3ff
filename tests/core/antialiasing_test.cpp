// Anti-aliasing against exact area coverage (the lecture's white polygon on black, pre-filtered by a box):
// each pattern's pixel estimates, their convergence rates (jittered N^-3/4, uniform random N^-1/2;
// Mitchell 1996), and adaptive supersampling against 16 jittered samples per pixel.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <numeric>

#include "raystep/accel/brute_force.h"
#include "raystep/render/antialiasing.h"
#include "raystep/render/camera.h"
#include "raystep/render/coverage.h"
#include "raystep/render/render.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using Mode = AntiAliasing::Mode;

using test::make_aa;

// ---- The patterns on analytic radiance functions ----

TEST(AntiAliasing, SampleCountsPerMode) {
  Pcg32 rng(1, 2);
  const RadianceFn grey = [](float, float) { return glm::vec3(0.5f); };
  EXPECT_EQ(estimate_pixel(make_aa(Mode::none), 3, 4, rng, grey).samples, 1u);
  EXPECT_EQ(estimate_pixel(make_aa(Mode::regular, 3), 3, 4, rng, grey).samples, 9u);
  EXPECT_EQ(estimate_pixel(make_aa(Mode::jitter, 4), 3, 4, rng, grey).samples, 16u);
  EXPECT_EQ(estimate_pixel(make_aa(Mode::random, 5), 3, 4, rng, grey).samples, 5u);  // k is N for random
  // Adaptive on a flat pixel: corners and centre only, grey or black (no division by max + min = 0).
  EXPECT_EQ(estimate_pixel(make_aa(Mode::adaptive), 3, 4, rng, grey).samples, 5u);
  const RadianceFn black = [](float, float) { return glm::vec3(0.f); };
  PixelEstimate e = estimate_pixel(make_aa(Mode::adaptive), 3, 4, rng, black);
  EXPECT_EQ(e.samples, 5u);
  EXPECT_EQ(e.value, glm::vec3(0.f));
  for (Mode m : {Mode::none, Mode::regular, Mode::jitter, Mode::random, Mode::adaptive})
    EXPECT_EQ(estimate_pixel(make_aa(m, 3), 0, 0, rng, grey).value, glm::vec3(0.5f));
}

TEST(AntiAliasing, SamplesStayInsideTheirPixel) {
  for (Mode m : {Mode::none, Mode::regular, Mode::jitter, Mode::random, Mode::adaptive}) {
    Pcg32 rng(9, 9);
    int outside = 0;
    // A noisy function so that adaptive subdivides all the way down.
    const RadianceFn probe = [&](float px, float py) {
      outside += !(px >= 7.f && px <= 8.f && py >= 2.f && py <= 3.f);
      return glm::vec3(std::fmod(px * 97.f + py * 31.f, 1.f));
    };
    estimate_pixel(make_aa(m, 4, 0.f, 2), 7, 2, rng, probe);
    EXPECT_EQ(outside, 0);
  }
}

TEST(AntiAliasing, RegularGridIsExactForLinearRadiance) {
  // The box filter of a linear function is its value at the centre; a symmetric grid finds it.
  const RadianceFn ramp = [](float px, float py) { return glm::vec3(px, py, px + 2.f * py); };
  Pcg32 rng(0, 0);
  PixelEstimate e = estimate_pixel(make_aa(Mode::regular, 4), 10, 20, rng, ramp);
  EXPECT_NEAR(e.value.x, 10.5f, 1e-5f);
  EXPECT_NEAR(e.value.y, 20.5f, 1e-5f);
  EXPECT_NEAR(e.value.z, 51.5f, 1e-4f);
}

TEST(AntiAliasing, AdaptiveRefinesUntilMaxDepthWhereContrastIsHigh) {
  // Corners are shared between squares: full refinement to depth D costs the (2^D + 1)^2 corners of the
  // finest grid plus its 4^D centres.
  const RadianceFn noise = [](float px, float py) {
    return glm::vec3(0.5f + 0.5f * std::sin(px * 1000.f) * std::cos(py * 1700.f));
  };
  for (int depth : {0, 1, 2, 3}) {
    Pcg32 rng(3, 4);
    AntiAliasing aa = make_aa(Mode::adaptive, 1, 0.f, depth);
    const uint32_t side = (1u << depth) + 1u, full = side * side + (1u << (2 * depth));
    EXPECT_EQ(estimate_pixel(aa, 0, 0, rng, noise).samples, full) << depth;
    EXPECT_EQ(max_samples_per_pixel(aa), full);
  }
  // A vertical edge at x = 0.3 in pixel (0, 0): refined near the edge only, and the area-weighted leaves
  // give the coverage to within the finest squares' width (1/4 at depth 2) times half their value range.
  const RadianceFn edge = [](float px, float) { return glm::vec3(px < 0.3f ? 1.f : 0.f); };
  Pcg32 rng(5, 6);
  PixelEstimate e = estimate_pixel(make_aa(Mode::adaptive, 1, 0.1f, 2), 0, 0, rng, edge);
  EXPECT_NEAR(e.value.x, 0.3f, 0.125f);
  EXPECT_GT(e.samples, 5u);
  EXPECT_LT(e.samples, max_samples_per_pixel(make_aa(Mode::adaptive, 1, 0.1f, 2)));
}

TEST(AntiAliasing, ContrastTest) {
  const glm::vec3 black[2] = {glm::vec3(0.f), glm::vec3(0.f)};
  EXPECT_FALSE(contrast_exceeds(black, 2, 0.f));  // max + min = 0: no contrast, no division
  const glm::vec3 edge[2] = {glm::vec3(1.f), glm::vec3(0.f)};
  EXPECT_TRUE(contrast_exceeds(edge, 2, 0.99f));
  const glm::vec3 close[2] = {glm::vec3(1.f), glm::vec3(0.9f)};  // (1 - 0.9) / 1.9 = 0.0526
  EXPECT_FALSE(contrast_exceeds(close, 2, 0.1f));
  EXPECT_TRUE(contrast_exceeds(close, 2, 0.05f));
  const glm::vec3 one_channel[2] = {glm::vec3(0.5f, 0.5f, 0.2f), glm::vec3(0.5f, 0.5f, 0.f)};
  EXPECT_TRUE(contrast_exceeds(one_channel, 2, 0.5f));  // any channel counts
}

TEST(AntiAliasing, InvalidSettingsThrow) {
  EXPECT_THROW(validate(make_aa(Mode::jitter, 0)), InputError);
  EXPECT_THROW(validate(make_aa(Mode::regular, 1000)), InputError);  // a million samples per pixel
  EXPECT_THROW(validate(make_aa(Mode::random, 1 << 20)), InputError);
  EXPECT_THROW(validate(make_aa(Mode::adaptive, 1, 0.1f, 7)), InputError);
  EXPECT_THROW(validate(make_aa(Mode::adaptive, 1, 0.1f, -1)), InputError);
  EXPECT_THROW(validate(make_aa(Mode::adaptive, 1, std::nanf(""), 2)), InputError);
  EXPECT_NO_THROW(validate(make_aa(Mode::random, 256)));
  EXPECT_NO_THROW(validate(make_aa(Mode::adaptive, 1, 0.f, 6)));
}

// ---- The lecture's white polygon on black, rendered ----

// A slanted white triangle under an orthographic camera: ambient 1, diffuse 1, no lights, black background,
// so a sample is 1 inside the triangle and 0 outside, and a pixel's exact value is its area coverage.
struct PolygonScene {
  static constexpr int kSize = 32;
  Scene scene;
  BruteForce accel;
  std::vector<double> coverage;  // exact, per pixel
  std::vector<size_t> edge;      // pixels the boundary crosses (0 < coverage < 1)

  PolygonScene() {
    scene.camera.type = CameraType::orthographic;
    scene.camera.eye = glm::vec3(0.f, 0.f, 5.f);
    scene.camera.look_at = glm::vec3(0.f);
    scene.camera.ortho_height = 2.f;
    scene.render.ambient = glm::vec3(1.f);
    scene.render.background = glm::vec3(0.f);
    Material white;
    white.diffuse = glm::vec3(1.f);
    scene.materials.push_back(white);
    const glm::vec3 v[3] = {{-0.8f, -0.7f, 0.f}, {0.75f, -0.35f, 0.f}, {-0.15f, 0.8f, 0.f}};
    scene.geometry.begin_object("white triangle", 0);
    scene.geometry.add_triangle(v[0], v[1], v[2]);
    accel.build(scene.geometry);

    ProjectiveCamera camera(scene.camera, kSize, kSize);
    std::vector<glm::dvec2> raster(3);
    for (int i = 0; i < 3; ++i) camera.project(v[i], &raster[i]);
    for (int y = 0; y < kSize; ++y)
      for (int x = 0; x < kSize; ++x) {
        double c = pixel_coverage(raster, x, y);
        coverage.push_back(c);
        if (c > 1e-9 && c < 1.0 - 1e-9) edge.push_back(coverage.size() - 1);
      }
  }

  RenderResult render(const AntiAliasing& aa, uint64_t seed) const {
    RenderOptions o;
    o.aa = aa;
    o.width = o.height = kSize;
    o.seed = seed;
    o.threads = 1;
    return render_image(scene, accel, o);
  }

  // Mean squared error over the edge pixels.
  double edge_mse(const RenderResult& r) const {
    double sum = 0.0;
    for (size_t i : edge) {
      double e = double(r.image.pixels[i].x) - coverage[i];
      sum += e * e;
    }
    return sum / double(edge.size());
  }

  // RMS error over the edge pixels, the squared errors averaged over seeds 1..seeds.
  double edge_rms(const AntiAliasing& aa, int seeds, uint64_t* rays = nullptr) const {
    double mse = 0.0;
    if (rays) *rays = 0;
    for (int s = 1; s <= seeds; ++s) {
      RenderResult r = render(aa, uint64_t(s));
      mse += edge_mse(r);
      if (rays) *rays += r.rays.total();
    }
    return std::sqrt(mse / seeds);
  }
};

const PolygonScene& polygon_scene() {
  static const PolygonScene scene;
  return scene;
}

// Least-squares slope of log(err) against log(n).
double loglog_slope(const std::vector<double>& n, const std::vector<double>& err) {
  double mx = 0, my = 0;
  for (size_t i = 0; i < n.size(); ++i) {
    mx += std::log(n[i]) / n.size();
    my += std::log(err[i]) / n.size();
  }
  double sxy = 0, sxx = 0;
  for (size_t i = 0; i < n.size(); ++i) {
    sxy += (std::log(n[i]) - mx) * (std::log(err[i]) - my);
    sxx += (std::log(n[i]) - mx) * (std::log(n[i]) - mx);
  }
  return sxy / sxx;
}

TEST(AntiAliasing, WhitePolygonSamplesAreExactlyZeroOrOne) {
  const PolygonScene& p = polygon_scene();
  ASSERT_GT(p.edge.size(), 50u);
  RenderResult r = p.render(make_aa(Mode::none), 0);
  double total = 0.0, exact = 0.0;
  for (size_t i = 0; i < r.image.pixels.size(); ++i) {
    float v = r.image.pixels[i].x;
    EXPECT_TRUE(v == 0.f || v == 1.f) << i;
    EXPECT_EQ(r.image.pixels[i], glm::vec3(v));
    if (p.coverage[i] == 1.0) EXPECT_EQ(v, 1.f);  // inside pixels are white, outside black
    if (p.coverage[i] == 0.0) EXPECT_EQ(v, 0.f);
    total += v;
    exact += p.coverage[i];
  }
  EXPECT_NEAR(total, exact, 0.05 * exact);  // centre sampling gets the area roughly right
}

TEST(AntiAliasing, JitteredConvergesAsNToTheMinusThreeQuarters) {
  const PolygonScene& p = polygon_scene();
  std::vector<double> n, err;
  for (int k : {2, 4, 8, 16}) {
    n.push_back(k * k);
    err.push_back(p.edge_rms(make_aa(Mode::jitter, k), 4));
  }
  double slope = loglog_slope(n, err);
  std::printf("jitter: RMS %.4f %.4f %.4f %.4f at N = 4 16 64 256, slope %.3f\n", err[0], err[1], err[2], err[3],
              slope);
  EXPECT_NEAR(slope, -0.75, 0.15);
}

TEST(AntiAliasing, UniformRandomConvergesAsNToTheMinusHalf) {
  const PolygonScene& p = polygon_scene();
  std::vector<double> n, err;
  for (int count : {4, 16, 64, 256}) {
    n.push_back(count);
    err.push_back(p.edge_rms(make_aa(Mode::random, count), 4));
  }
  double slope = loglog_slope(n, err);
  std::printf("random: RMS %.4f %.4f %.4f %.4f at N = 4 16 64 256, slope %.3f\n", err[0], err[1], err[2], err[3],
              slope);
  EXPECT_NEAR(slope, -0.5, 0.1);
}

TEST(AntiAliasing, RegularGridConverges) {
  const PolygonScene& p = polygon_scene();
  std::vector<double> n, err;
  for (int k : {1, 2, 4, 8, 16}) {
    n.push_back(k * k);
    err.push_back(p.edge_rms(make_aa(Mode::regular, k), 1));  // deterministic: one seed
  }
  double slope = loglog_slope(n, err);
  std::printf("regular: RMS %.4f %.4f %.4f %.4f %.4f at N = 1 4 16 64 256, slope %.3f\n", err[0], err[1], err[2],
              err[3], err[4], slope);
  for (size_t i = 1; i < err.size(); ++i) EXPECT_LT(err[i], err[i - 1]);
  EXPECT_LT(err.back(), 0.25 * err.front());
}

TEST(AntiAliasing, AdaptiveBeatsSixteenJitteredSamplesWithFewerRays) {
  const PolygonScene& p = polygon_scene();
  uint64_t jitter_rays = 0, adaptive_rays = 0;
  double jitter_rms = p.edge_rms(make_aa(Mode::jitter, 4), 4, &jitter_rays);
  double adaptive_rms = p.edge_rms(make_aa(Mode::adaptive, 1, 0.1f, 3), 4, &adaptive_rays);
  std::printf("jitter:4 RMS %.4f with %llu rays per image; adaptive (0.1, depth 3) RMS %.4f with %llu rays\n",
              jitter_rms, (unsigned long long)jitter_rays / 4, adaptive_rms, (unsigned long long)adaptive_rays / 4);
  EXPECT_LE(adaptive_rms, jitter_rms);
  EXPECT_LT(adaptive_rays, jitter_rays);
}

TEST(AntiAliasing, AdaptiveSpendsItsSamplesOnEdges) {
  const PolygonScene& p = polygon_scene();
  RenderResult r = p.render(make_aa(Mode::adaptive, 1, 0.1f, 3), 1);
  double on_edges = 0.0, flat = 0.0;
  size_t flat_count = 0;
  for (size_t i = 0; i < r.samples.size(); ++i) {
    if (p.coverage[i] == 0.0 || p.coverage[i] == 1.0) {
      flat += r.samples[i];
      ++flat_count;
      EXPECT_EQ(r.samples[i], 5u);  // a flat pixel never refines
    }
  }
  for (size_t i : p.edge) on_edges += r.samples[i];
  on_edges /= double(p.edge.size());
  flat /= double(flat_count);
  std::printf("adaptive: %.1f samples per edge pixel, %.1f per flat pixel\n", on_edges, flat);
  EXPECT_GT(on_edges, 3.0 * flat);
  // The map shows it: edge pixels brighter than flat ones.
  uint32_t max_count = 0;
  Image map = sample_count_image(r.samples, r.image.width, r.image.height, &max_count);
  EXPECT_GT(max_count, 5u);
  EXPECT_EQ(map.pixels[0], viridis(5.f / float(max_count)));  // a corner pixel is flat (black)
}

}  // namespace
}  // namespace raystep
