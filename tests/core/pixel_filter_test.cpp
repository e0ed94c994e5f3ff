// The tent filter, sampling and pre-filtering combined (render/pixel_filter.h): its weights share every
// sample out among four pixels; the exact tent pre-filter of a polygon (render/coverage.h) against
// quadrature; the renderer's tent pixels against the inspector's, bit for bit and whatever the threads;
// convergence to the exact tent picture; the references, the aa-report's rows and the trace's pixel section.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <random>
#include <string>

#include "loaded_scene.h"
#include "raystep/render/coverage.h"
#include "raystep/render/pixel_filter.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/render/reference.h"
#include "raystep/render/render.h"
#include "raystep/render/whitted.h"
#include "raystep/render/camera.h"
#include "raystep/report/aa_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/record_trace.h"
#include "raystep/trace/trace_file.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

using Filter = AntiAliasing::Filter;

bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}

TEST(PixelFilter, SpecReadsAndWritesTheTent) {
  for (const char* spec : {"none+tent", "regular:4+tent", "jitter:3+tent", "random:9+tent"}) {
    const AntiAliasing aa = parse_antialiasing(spec);
    EXPECT_EQ(aa.filter, Filter::tent) << spec;
    EXPECT_EQ(to_string(aa), spec);
  }
  EXPECT_EQ(parse_antialiasing("regular:4+box").filter, Filter::box);
  EXPECT_EQ(to_string(parse_antialiasing("regular:4+box")), "regular:4");
  EXPECT_EQ(parse_antialiasing("jitter:4").filter, Filter::box);
  for (const char* bad : {"regular:4+", "regular:4+gauss", "+tent", "regular:4+tent+tent", "adaptive:0.1+tent",
                          "adaptive:0.1:3+tent", "regular:+tent"})
    EXPECT_THROW(parse_antialiasing(bad), InputError) << bad;
  AntiAliasing adaptive = parse_antialiasing("adaptive:0.1:2");
  adaptive.filter = Filter::tent;
  EXPECT_THROW(validate(adaptive), InputError);
}

TEST(PixelFilter, TentWeightsShareEverySampleOutAmongFourPixels) {
  EXPECT_EQ(tent_weight(0.f, 0.f), 1.f);
  EXPECT_EQ(tent_weight(0.5f, 0.f), 0.5f);
  EXPECT_EQ(tent_weight(0.5f, -0.5f), 0.25f);
  EXPECT_EQ(tent_weight(1.f, 0.f), 0.f);
  EXPECT_EQ(tent_weight(0.f, -1.5f), 0.f);
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(0.f, 8.f);
  for (int i = 0; i < 1000; ++i) {
    const float px = u(rng), py = u(rng);
    double sum = 0;
    for (int y = -1; y < 10; ++y)
      for (int x = -1; x < 10; ++x) sum += tent_weight(px - (float(x) + 0.5f), py - (float(y) + 0.5f));
    EXPECT_NEAR(sum, 1.0, 1e-6) << px << "," << py;
  }
}

// The tent's integral over a polygon by the midpoint rule on an n x n grid over the tent's square.
double tent_quadrature(const std::vector<glm::dvec2>& polygon, int x, int y, int n) {
  auto inside = [&](const glm::dvec2& p) {  // even-odd rule
    bool in = false;
    for (size_t i = 0, m = polygon.size(), j = m - 1; i < m; j = i++) {
      const glm::dvec2 &a = polygon[i], &b = polygon[j];
      if ((a.y > p.y) != (b.y > p.y) && p.x < (b.x - a.x) * (p.y - a.y) / (b.y - a.y) + a.x) in = !in;
    }
    return in;
  };
  double sum = 0;
  const double h = 2.0 / n;
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i) {
      const double u = -1.0 + (i + 0.5) * h, v = -1.0 + (j + 0.5) * h;
      if (inside({x + 0.5 + u, y + 0.5 + v})) sum += (1.0 - std::fabs(u)) * (1.0 - std::fabs(v));
    }
  return sum * h * h;
}

TEST(PixelFilter, ExactTentCoverageIsTheTentsIntegralOverThePolygon) {
  // The whole tent: 1; a half-plane through the centre: 1/2 (both orientations).
  const std::vector<glm::dvec2> all = {{-10, -10}, {20, -10}, {20, 20}, {-10, 20}};
  EXPECT_NEAR(pixel_tent_coverage(all, 3, 4), 1.0, 1e-12);
  const std::vector<glm::dvec2> left = {{-10, -10}, {3.5, -10}, {3.5, 20}, {-10, 20}};
  EXPECT_NEAR(pixel_tent_coverage(left, 3, 4), 0.5, 1e-12);
  const std::vector<glm::dvec2> left_cw(left.rbegin(), left.rend());
  EXPECT_NEAR(pixel_tent_coverage(left_cw, 3, 4), 0.5, 1e-12);
  // The pixel's own square alone: 4 quadrants of the integral of (1 - u)(1 - v) over [0, 1/2]^2 = 9/64.
  const std::vector<glm::dvec2> own = {{3, 4}, {4, 4}, {4, 5}, {3, 5}};
  EXPECT_NEAR(pixel_tent_coverage(own, 3, 4), 4.0 * 9.0 / 64.0, 1e-12);
  // A slanted sliver and a triangle across the corner, against quadrature (error O(1/n) at the edges).
  const std::vector<std::vector<glm::dvec2>> shapes = {
      {{2.2, 3.1}, {5.7, 4.9}, {2.4, 3.6}}, {{3.9, 3.3}, {6.1, 5.2}, {2.7, 6.0}}, {{3.1, 4.2}, {3.8, 4.3}, {3.3, 4.9}}};
  for (const auto& t : shapes) {
    const double exact = pixel_tent_coverage(t, 3, 4);
    EXPECT_GT(exact, 0.0);
    EXPECT_NEAR(exact, tent_quadrature(t, 3, 4, 2000), 2e-5);
  }
  // Over all pixels the tents add up to 1, so a polygon's tent coverages add up to its area.
  const std::vector<glm::dvec2> tri = {{1.3, 1.7}, {7.9, 2.2}, {4.1, 6.8}};
  double sum = 0;
  for (int y = -1; y < 10; ++y)
    for (int x = -1; x < 10; ++x) sum += pixel_tent_coverage(tri, x, y);
  EXPECT_NEAR(sum, std::fabs(signed_area(tri)), 1e-12);
}

RenderResult render(const test::LoadedScene& s, const std::string& spec, int threads, uint64_t seed = 5) {
  RenderOptions o = render_options(s.scene.render);
  o.aa = parse_antialiasing(spec);
  o.threads = threads;
  o.seed = seed;
  return render_image(s.scene, *s.accel, o);
}

TEST(PixelFilter, RenderedTentPixelsAreTheInspectorsBitForBitWhateverTheThreads) {
  const test::LoadedScene s("coverage.json");
  const int w = s.scene.render.width, h = s.scene.render.height;
  const ProjectiveCamera camera(s.scene.camera, w, h);
  const WhittedTracer tracer(s.scene, *s.accel);
  RayCounts counts;
  const RadianceFn radiance = [&](float x, float y) { return tracer.trace_primary(camera.generate(x, y), &counts); };
  for (const char* spec : {"jitter:3+tent", "random:5+tent", "regular:2+tent"}) {
    SCOPED_TRACE(spec);
    const RenderResult one = render(s, spec, 1), two = render(s, spec, 2);
    ASSERT_EQ(one.image.pixels.size(), two.image.pixels.size());
    for (size_t i = 0; i < one.image.pixels.size(); ++i) ASSERT_TRUE(same_bits(one.image.pixels[i], two.image.pixels[i]));
    // The image's pixels and the one-pixel frame around it each cast their samples once.
    const AntiAliasing aa = parse_antialiasing(spec);
    EXPECT_EQ(one.rays.primary, uint64_t(w + 2) * uint64_t(h + 2) * max_samples_per_pixel(aa));
    EXPECT_EQ(one.samples[0], max_samples_per_pixel(aa));
    // Corners, edges, the needle and the star: the inspector's value is the picture's.
    for (auto [x, y] : {std::pair{0, 0}, {w - 1, h - 1}, {0, h / 2}, {53, 17}, {w / 2, h / 2}, {20, 30}}) {
      Pcg32 rng = pixel_rng(5, x, y, w);
      PixelSampling p = sample_pixel(aa, x, y, rng, radiance);
      const glm::vec3 box = p.value;
      apply_pixel_filter(p, 5, w, radiance);
      EXPECT_TRUE(same_bits(p.value, one.image.pixels[size_t(y) * size_t(w) + size_t(x)])) << x << "," << y;
      EXPECT_TRUE(same_bits(p.box_value, box));
      // Every sample the tent reaches: the pixel's own and, of its neighbours', those less than a pixel away.
      EXPECT_GT(p.neighbours.size(), 0u);
      EXPECT_LT(p.neighbours.size(), 8u * max_samples_per_pixel(aa));
      for (const PixelSample& n : p.neighbours) {
        EXPECT_GT(n.weight, 0.f);
        EXPECT_FALSE(n.px >= float(x) && n.px < float(x + 1) && n.py >= float(y) && n.py < float(y + 1));
      }
    }
  }
  // The box filter is untouched by apply_pixel_filter.
  Pcg32 rng = pixel_rng(5, 9, 9, w);
  PixelSampling p = sample_pixel(parse_antialiasing("jitter:3"), 9, 9, rng, radiance);
  apply_pixel_filter(p, 5, w, radiance);
  EXPECT_TRUE(p.neighbours.empty());
  EXPECT_TRUE(same_bits(p.value, p.box_value));
}

TEST(PixelFilter, TentSupersamplingConvergesToTheExactTentPicture) {
  const test::LoadedScene s("coverage.json");
  const int w = s.scene.render.width, h = s.scene.render.height;
  const Image box = render_exact_coverage(s.scene, w, h);
  const Image tent = render_exact_coverage(s.scene, w, h, Filter::tent);
  const double e4 = rmse(render(s, "regular:4+tent", 2).image, tent);
  const double e32 = rmse(render(s, "regular:32+tent", 2).image, tent);
  EXPECT_LT(e32, e4 / 4.0);
  EXPECT_LT(e32, 0.002);
  // ... and not to the box's: the two pre-filters are different pictures.
  EXPECT_GT(rmse(box, tent), 10.0 * e32);
  EXPECT_GT(rmse(render(s, "regular:32+tent", 2).image, box), 5.0 * e32);
  // The inspector's exact value is the picture's.
  const std::optional<glm::vec3> v = exact_pixel_value(s.scene, w, h, 53, 17, Filter::tent);
  ASSERT_TRUE(v);
  EXPECT_TRUE(same_bits(*v, tent.pixels[size_t(17) * size_t(w) + 53]));
}

TEST(PixelFilter, ReferencesAndTheAaReportMeasureEachFilterAgainstItsOwn) {
  const test::LoadedScene s("coverage.json");
  const int w = 32, h = 24;
  EXPECT_EQ(make_reference(s.scene, *s.accel, w, h, "auto", 1, nullptr, Filter::tent).kind, "exact+tent");
  const Reference j = make_reference(s.scene, *s.accel, w, h, "jitter:6", 1, nullptr, Filter::tent);
  EXPECT_EQ(j.kind, "jitter:6+tent");
  EXPECT_LT(rmse(j.image, render_exact_coverage(s.scene, w, h, Filter::tent)), 0.05);
  EXPECT_THROW(make_reference(s.scene, *s.accel, w, h, "jitter:6+tent", 1), InputError);

  AaReportOptions o;
  o.methods = {"regular:4", "regular:4+tent", "jitter:2+tent", "jitter:4+tent"};
  o.width = w;
  o.height = h;
  o.seeds = 2;
  const AaReport r = run_aa_report(s.scene, *s.accel, o);
  ASSERT_EQ(r.references.size(), 2u);
  EXPECT_EQ(r.references[0].kind, "exact");
  EXPECT_EQ(r.references[1].kind, "exact+tent");
  EXPECT_EQ(r.reference_kind, "exact");
  ASSERT_EQ(r.rows.size(), 4u);
  EXPECT_EQ(r.rows[0].reference, "exact");
  EXPECT_EQ(r.rows[1].reference, "exact+tent");
  EXPECT_EQ(r.rows[1].method, "regular+tent");
  EXPECT_EQ(r.rows[1].spec, "regular:4+tent");
  // Its error is against the tent's picture: recomputed here.
  const Image tent = render_exact_coverage(s.scene, w, h, Filter::tent);
  RenderOptions ro;
  ro.aa = parse_antialiasing("regular:4+tent");
  ro.width = w;
  ro.height = h;
  EXPECT_DOUBLE_EQ(r.rows[1].rmse, rmse(render_image(s.scene, *s.accel, ro).image, tent));
  // The frame's rays count: (w + 2)(h + 2) / (w h) times the pattern's samples per pixel.
  EXPECT_NEAR(r.rows[1].rays_per_pixel, 16.0 * (w + 2) * (h + 2) / (w * h), 1e-9);
  bool slope = false;
  for (const auto& [method, value] : r.slopes) slope |= method == "jitter+tent" && value < 0.0;
  EXPECT_TRUE(slope);
  // Only tent methods: one reference, the tent's.
  o.methods = {"jitter:2+tent"};
  const AaReport t = run_aa_report(s.scene, *s.accel, o);
  ASSERT_EQ(t.references.size(), 1u);
  EXPECT_EQ(t.reference_kind, "exact+tent");
}

TEST(PixelFilter, TracedTentPixelRoundTripsAndDamageIsRefused) {
  const test::LoadedScene s("coverage.json");
  const int w = s.scene.render.width, h = s.scene.render.height;
  const Trace t = record_pixel_trace(s.scene, *s.accel, w, h, 53, 17, parse_antialiasing("jitter:2+tent"), 4,
                                     false, "scene.json", "fnv1a64:0");
  ASSERT_TRUE(t.pixel);
  const PixelSampling& p = t.pixel->sampling;
  EXPECT_EQ(t.rays.size(), 4u);  // the pixel's own samples' rays only
  EXPECT_GT(p.neighbours.size(), 0u);
  const RenderResult r = render(s, "jitter:2+tent", 1, 4);
  EXPECT_TRUE(same_bits(p.value, r.image.pixels[size_t(17) * size_t(w) + 53]));
  const std::string once = trace_to_json(t);
  const Trace back = parse_trace_json(once, "mem.json");
  EXPECT_EQ(trace_to_json(back), once);
  ASSERT_TRUE(back.pixel);
  EXPECT_EQ(back.pixel->sampling.neighbours.size(), p.neighbours.size());
  EXPECT_TRUE(same_bits(back.pixel->sampling.box_value, p.box_value));
  EXPECT_EQ(back.pixel->sampling.samples[1].weight, p.samples[1].weight);

  auto refused = [&](const std::string& from, const std::string& to, const std::string& part) {
    std::string bad = once;
    const size_t at = bad.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    bad.replace(at, from.size(), to);
    try {
      parse_trace_json(bad, "bad.json");
      ADD_FAILURE() << "accepted " << to;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "bad.json");
      EXPECT_NE(std::string(e.what()).find(part), std::string::npos) << e.what();
    }
  };
  const size_t nb = once.find("\"neighbours\"");
  ASSERT_NE(nb, std::string::npos);
  const size_t weight = once.find("\"weight\":", nb);
  refused(once.substr(weight, once.find('}', weight) - weight), "\"weight\":0.9999", "not the tent's weight");
  const size_t px = once.find("\"px\":", nb);
  refused(once.substr(px, once.find(',', px) - px), "\"px\":60", "not a neighbour's sample");
}

}  // namespace
}  // namespace raystep
