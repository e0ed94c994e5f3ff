// One pixel's samples recorded (render/pixel_samples.h) against the renderer's own sampling: the positions
// estimate_pixel queries, in its order, with its value bit for bit, for every pattern and several seeds; the
// adaptive tree re-derived square by square from its samples on whole renders; and each sample's rays
// (trace/pixel_rays.h) against the rays the renderer casts.
#include <gtest/gtest.h>

#include <cmath>
#include <cstring>
#include <string>
#include <vector>

#include "loaded_scene.h"
#include "raystep/accel/accelerator.h"
#include "raystep/render/antialiasing.h"
#include "raystep/render/camera.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/render/render.h"
#include "raystep/render/whitted.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using Mode = AntiAliasing::Mode;

using test::make_aa;

bool same_bits(float a, float b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_bits(const glm::vec3& a, const glm::vec3& b) {
  return std::memcmp(&a, &b, sizeof a) == 0;
}
bool same_bits(const Ray& a, const Ray& b) {
  return same_bits(a.origin, b.origin) && same_bits(a.direction, b.direction) && same_bits(a.tmin, b.tmin) &&
         same_bits(a.tmax, b.tmax);
}

// Radiance functions with edges inside the pixels, so that adaptive sampling has something to refine.
// A slanted half-plane, coloured differently per channel.
glm::vec3 half_plane(float px, float py) {
  const bool in = 0.37f * px - py + 0.21f > 0.f;
  return in ? glm::vec3(1.f, 0.5f, 0.f) : glm::vec3(0.f, 0.1f, 0.8f);
}
// A thin slanted stripe, a tenth of a pixel wide: narrower than most squares, so it is sometimes missed.
glm::vec3 stripe(float px, float py) {
  const float d = std::fabs(px + 0.6f * py - 7.3f);
  return d < 0.05f ? glm::vec3(1.f) : glm::vec3(0.05f);
}
// A checkerboard of period 0.3 pixel: contrast everywhere.
glm::vec3 checker(float px, float py) {
  const int c = int(std::floor(px / 0.3f)) + int(std::floor(py / 0.3f));
  return (c & 1) ? glm::vec3(0.9f, 0.2f, 0.4f) : glm::vec3(0.f, 0.f, 0.f);
}

std::vector<AntiAliasing> every_mode() {
  std::vector<AntiAliasing> modes{make_aa(Mode::none)};
  for (int k = 1; k <= 8; ++k) modes.push_back(make_aa(Mode::regular, k));
  for (int k = 2; k <= 8; ++k) modes.push_back(make_aa(Mode::jitter, k));
  for (int n = 1; n <= 64; ++n) modes.push_back(make_aa(Mode::random, n));
  for (float t : {0.f, 0.05f, 0.1f, 0.3f, 1.f})
    for (int d = 0; d <= 4; ++d) modes.push_back(make_aa(Mode::adaptive, 1, t, d));
  modes.push_back(make_aa(Mode::adaptive, 1, 0.1f, 6));
  return modes;
}

// The adaptive tree's structure and bookkeeping; the decisions are checked against the samples' colours.
void expect_consistent_tree(const PixelSampling& s) {
  const AntiAliasing& aa = s.aa;
  const int n = 2 << aa.max_depth;
  const float inv_n = 1.f / float(n);
  ASSERT_FALSE(s.squares.empty());
  EXPECT_EQ(s.squares[0].parent, -1);
  EXPECT_EQ(s.squares[0].size, n);
  int new_samples = 0;
  for (size_t q = 0; q < s.squares.size(); ++q) {
    SCOPED_TRACE("square " + std::to_string(q));
    const AdaptiveSquare& sq = s.squares[q];
    new_samples += sq.new_samples;
    // The five samples lie at the square's corners and centre, on the lattice.
    const int h = sq.size / 2;
    const int at[5][2] = {{sq.i0, sq.j0},
                          {sq.i0 + sq.size, sq.j0},
                          {sq.i0, sq.j0 + sq.size},
                          {sq.i0 + sq.size, sq.j0 + sq.size},
                          {sq.i0 + h, sq.j0 + h}};
    glm::vec3 v[5];
    for (int k = 0; k < 5; ++k) {
      ASSERT_GE(sq.samples[k], 0);
      ASSERT_LT(sq.samples[k], int(s.samples.size()));
      const PixelSample& p = s.samples[size_t(sq.samples[k])];
      EXPECT_EQ(p.lattice[0], at[k][0]);
      EXPECT_EQ(p.lattice[1], at[k][1]);
      EXPECT_TRUE(same_bits(p.px, float(s.x) + float(at[k][0]) * inv_n));
      EXPECT_TRUE(same_bits(p.py, float(s.y) + float(at[k][1]) * inv_n));
      v[k] = p.colour;
    }
    // The decision, re-derived: refine where the contrast exceeds the threshold, above the depth limit.
    const bool exceeds = contrast_exceeds(v, 5, aa.threshold);
    const AdaptiveSquare::Outcome expected = !exceeds                   ? AdaptiveSquare::Outcome::agree
                                             : sq.depth >= aa.max_depth ? AdaptiveSquare::Outcome::depth_limit
                                                                        : AdaptiveSquare::Outcome::subdivided;
    EXPECT_EQ(int(sq.outcome), int(expected));
    for (int c = 0; c < 3; ++c) {
      float lo = std::min({v[0][c], v[1][c], v[2][c], v[3][c], v[4][c]});
      float hi = std::max({v[0][c], v[1][c], v[2][c], v[3][c], v[4][c]});
      EXPECT_EQ(sq.contrast[c], hi + lo > 0.f ? (hi - lo) / (hi + lo) : 0.f);
    }
    if (sq.outcome == AdaptiveSquare::Outcome::subdivided) {
      const int corner[4][2] = {
          {sq.i0, sq.j0}, {sq.i0 + h, sq.j0}, {sq.i0, sq.j0 + h}, {sq.i0 + h, sq.j0 + h}};
      glm::vec3 sum(0.f);
      for (int c = 0; c < 4; ++c) {
        ASSERT_GT(sq.children[c], int(q));
        ASSERT_LT(sq.children[c], int(s.squares.size()));
        const AdaptiveSquare& child = s.squares[size_t(sq.children[c])];
        EXPECT_EQ(child.parent, int(q));
        EXPECT_EQ(child.depth, sq.depth + 1);
        EXPECT_EQ(child.size, h);
        EXPECT_EQ(child.i0, corner[c][0]);
        EXPECT_EQ(child.j0, corner[c][1]);
        sum = sum + child.value;
      }
      // Depth first: the first quadrant follows its parent directly.
      EXPECT_EQ(sq.children[0], int(q) + 1);
      EXPECT_TRUE(same_bits(sq.value, 0.25f * sum));
    } else {
      for (int c = 0; c < 4; ++c) EXPECT_EQ(sq.children[c], -1);
      EXPECT_TRUE(same_bits(sq.value, 0.2f * (v[0] + v[1] + v[2] + v[3] + v[4])));
    }
    if (sq.parent >= 0) {
      const AdaptiveSquare& parent = s.squares[size_t(sq.parent)];
      EXPECT_TRUE(parent.children[0] == int(q) || parent.children[1] == int(q) ||
                  parent.children[2] == int(q) || parent.children[3] == int(q));
    } else {
      EXPECT_EQ(q, 0u);
    }
  }
  EXPECT_EQ(new_samples, int(s.samples.size()));
  EXPECT_TRUE(same_bits(s.squares[0].value, s.value));
}

// ---- (a) The recorded samples are the sampler's, on analytic radiance ----

TEST(PixelSamples, PositionsOrderAndValueAreTheSamplersInEveryMode) {
  using Fn = glm::vec3 (*)(float, float);
  const Fn functions[] = {half_plane, stripe, checker};
  const int pixels[][2] = {{0, 0}, {7, 3}, {3, 2}, {1023, 767}};
  int adaptive_subdivided = 0;
  for (const AntiAliasing& aa : every_mode())
    for (Fn f : functions)
      for (uint64_t seed : {0ull, 1ull, 42ull})
        for (const auto& xy : pixels) {
          SCOPED_TRACE("mode " + std::to_string(int(aa.mode)) + " k " + std::to_string(aa.k) + " t " +
                       std::to_string(aa.threshold) + " d " + std::to_string(aa.max_depth) + " seed " +
                       std::to_string(seed) + " pixel " + std::to_string(xy[0]) + "," +
                       std::to_string(xy[1]));
          // What estimate_pixel asks the radiance function for, in order.
          std::vector<glm::vec2> asked;
          const RadianceFn logged = [&](float px, float py) {
            asked.emplace_back(px, py);
            return f(px, py);
          };
          Pcg32 rng = pixel_rng(seed, xy[0], xy[1], 1024);
          const PixelEstimate e = estimate_pixel(aa, xy[0], xy[1], rng, logged);

          Pcg32 rng2 = pixel_rng(seed, xy[0], xy[1], 1024);
          const RadianceFn plain = [&](float px, float py) { return f(px, py); };
          const PixelSampling s = sample_pixel(aa, xy[0], xy[1], rng2, plain);
          // Both streams are left in the same state: the recording drew no extra random numbers.
          EXPECT_EQ(rng.next_u32(), rng2.next_u32());

          ASSERT_EQ(s.samples.size(), asked.size());
          EXPECT_EQ(uint32_t(s.samples.size()), e.samples);
          for (size_t i = 0; i < asked.size(); ++i) {
            EXPECT_TRUE(same_bits(s.samples[i].px, asked[i].x)) << i;
            EXPECT_TRUE(same_bits(s.samples[i].py, asked[i].y)) << i;
            EXPECT_TRUE(same_bits(s.samples[i].colour, f(asked[i].x, asked[i].y))) << i;
          }
          EXPECT_TRUE(same_bits(s.value, e.value));
          EXPECT_EQ(s.x, xy[0]);
          EXPECT_EQ(s.y, xy[1]);

          // Stratum and lattice labels.
          for (size_t i = 0; i < s.samples.size(); ++i) {
            const PixelSample& p = s.samples[i];
            if (aa.mode == Mode::regular || aa.mode == Mode::jitter) {
              ASSERT_GE(p.stratum[0], 0);
              EXPECT_EQ(int(i), p.stratum[1] * aa.k + p.stratum[0]);  // row by row
              const float u = (p.px - float(xy[0])) * float(aa.k), v = (p.py - float(xy[1])) * float(aa.k);
              EXPECT_GE(u, float(p.stratum[0]) - 1e-3f);
              EXPECT_LE(u, float(p.stratum[0] + 1) + 1e-3f);
              EXPECT_GE(v, float(p.stratum[1]) - 1e-3f);
              EXPECT_LE(v, float(p.stratum[1] + 1) + 1e-3f);
            } else {
              EXPECT_EQ(p.stratum[0], -1);
              EXPECT_EQ(p.stratum[1], -1);
            }
            if (aa.mode != Mode::adaptive) EXPECT_EQ(p.lattice[0], -1);
          }
          if (aa.mode == Mode::adaptive) {
            expect_consistent_tree(s);
            if (s.squares.size() > 1) ++adaptive_subdivided;
          } else {
            EXPECT_TRUE(s.squares.empty());
          }
        }
  // The edges do make adaptive sampling subdivide (else the tree checks above would be vacuous).
  EXPECT_GT(adaptive_subdivided, 100);
}

TEST(PixelSamples, BadSettingsThrow) {
  Pcg32 rng(0, 0);
  const RadianceFn f = [](float, float) { return glm::vec3(1.f); };
  EXPECT_THROW(sample_pixel(make_aa(Mode::adaptive, 1, 0.1f, 7), 0, 0, rng, f), InputError);
  EXPECT_THROW(sample_pixel(make_aa(Mode::jitter, 0), 0, 0, rng, f), InputError);
}

TEST(PixelSamples, PixelRngIsTheRenderersStream) {
  // render_image seeds pixel (x, y) of a width-wide image with index y * width + x.
  Pcg32 a = pixel_rng(9, 5, 3, 40), b(9, 3 * 40 + 5);
  for (int i = 0; i < 8; ++i) EXPECT_EQ(a.next_u32(), b.next_u32());
}

// ---- (b) The adaptive tree is the sampler's on whole renders of real scenes ----

using test::LoadedScene;

void expect_render_recorded(const LoadedScene& s, const AntiAliasing& aa, int width, int height,
                            uint64_t seed) {
  RenderOptions o;
  o.aa = aa;
  o.width = width;
  o.height = height;
  o.seed = seed;
  o.threads = 2;
  const RenderResult r = render_image(s.scene, *s.accel, o);
  const ProjectiveCamera camera(s.scene.camera, width, height);
  const WhittedTracer tracer(s.scene, *s.accel);
  RayCounts counts;
  const RadianceFn radiance = [&](float px, float py) {
    return tracer.trace_primary(camera.generate(px, py), &counts);
  };
  int subdivided = 0, depth_limited = 0, mismatched = 0;
  for (int y = 0; y < height; ++y)
    for (int x = 0; x < width; ++x) {
      Pcg32 rng = pixel_rng(seed, x, y, width);
      const PixelSampling p = sample_pixel(aa, x, y, rng, radiance);
      const size_t pixel = size_t(y) * size_t(width) + size_t(x);
      if (p.samples.size() != r.samples[pixel] || !same_bits(p.value, r.image.pixels[pixel])) ++mismatched;
      if (aa.mode == Mode::adaptive) {
        SCOPED_TRACE("pixel " + std::to_string(x) + "," + std::to_string(y));
        expect_consistent_tree(p);
        for (const AdaptiveSquare& q : p.squares) {
          subdivided += q.outcome == AdaptiveSquare::Outcome::subdivided;
          depth_limited += q.outcome == AdaptiveSquare::Outcome::depth_limit;
        }
      }
    }
  EXPECT_EQ(mismatched, 0);
  if (aa.mode == Mode::adaptive) {
    EXPECT_GT(subdivided, 0);
    EXPECT_GT(depth_limited, 0);
  }
}

TEST(PixelSamples, AdaptiveTreesAreTheRenderersOnTheAliasingScene) {
  const LoadedScene s("aliasing.json");
  // 64 x 48 = 3072 pixels, the triangle's three slanted edges through many of them.
  expect_render_recorded(s, make_aa(Mode::adaptive, 1, 0.1f, 3), 64, 48, 0);
  expect_render_recorded(s, make_aa(Mode::adaptive, 1, 0.02f, 4), 40, 25, 0);
}

TEST(PixelSamples, EveryPatternIsTheRenderersOnAShadedScene) {
  const LoadedScene s("spheres.json");
  // 40 x 25 = 1000 pixels with reflections, refraction and shadows.
  expect_render_recorded(s, make_aa(Mode::adaptive, 1, 0.1f, 3), 40, 25, 3);
  expect_render_recorded(s, make_aa(Mode::jitter, 3), 40, 25, 3);
  expect_render_recorded(s, make_aa(Mode::random, 5), 40, 25, 11);
  expect_render_recorded(s, make_aa(Mode::regular, 2), 40, 25, 3);
}

// ---- (c) A sample's rays are the rays the renderer cast ----

// The renderer's loop for one pixel (render_image: its stream, the camera's ray at each position the sampler
// asks for, the Whitted tracer), with a listener that hears every ray it casts.
std::vector<RayRequest> renderer_rays(const Scene& scene, const Accelerator& accel, int width, int height,
                                      int x, int y, const AntiAliasing& aa, uint64_t seed, glm::vec3* value) {
  std::vector<RayRequest> rays;
  RayListener listener = [&](const Ray& ray, RayKind kind, int depth) {
    RayRequest r;
    r.ray = ray;
    r.kind = kind;
    r.depth = depth;
    rays.push_back(r);
  };
  const ProjectiveCamera camera(scene.camera, width, height);
  WhittedTracer tracer(scene, accel);
  tracer.set_listener(&listener);
  RayCounts counts;
  const RadianceFn radiance = [&](float px, float py) {
    return tracer.trace_primary(camera.generate(px, py), &counts);
  };
  Pcg32 rng = pixel_rng(seed, x, y, width);
  *value = estimate_pixel(aa, x, y, rng, radiance).value;
  return rays;
}

TEST(PixelSampleRays, EverySamplesRaysAreTheRenderersBitForBit) {
  const LoadedScene s("spheres.json");
  const int width = 40, height = 25;
  const uint64_t seed = 5;
  for (const AntiAliasing& aa : {make_aa(Mode::none), make_aa(Mode::jitter, 3), make_aa(Mode::random, 6),
                                 make_aa(Mode::regular, 2), make_aa(Mode::adaptive, 1, 0.1f, 2)}) {
    RenderOptions o;
    o.aa = aa;
    o.width = width;
    o.height = height;
    o.seed = seed;
    const RenderResult r = render_image(s.scene, *s.accel, o);
    int secondary_rays = 0;
    for (int y = 0; y < height; y += 3)
      for (int x = 0; x < width; x += 3) {
        SCOPED_TRACE("mode " + std::to_string(int(aa.mode)) + " pixel " + std::to_string(x) + "," +
                     std::to_string(y));
        glm::vec3 value;
        const std::vector<RayRequest> cast =
            renderer_rays(s.scene, *s.accel, width, height, x, y, aa, seed, &value);
        ASSERT_TRUE(
            same_bits(value, r.image.pixels[size_t(y) * width + x]));  // the loop above is the renderer's

        for (bool secondary : {false, true}) {
          const PixelSampleRays p =
              pixel_sample_rays(s.scene, *s.accel, width, height, x, y, aa, seed, secondary);
          EXPECT_TRUE(same_bits(p.sampling.value, value));
          size_t k = 0;
          int sample = -1;
          for (const RayRequest& want : cast) {
            if (want.kind == RayKind::primary)
              ++sample;
            else if (!secondary)
              continue;
            ASSERT_LT(k, p.rays.size());
            const RayRequest& got = p.rays[k++];
            EXPECT_TRUE(same_bits(got.ray, want.ray));
            EXPECT_EQ(int(got.kind), int(want.kind));
            EXPECT_EQ(got.depth, want.depth);
            EXPECT_EQ(got.sample, sample);
            EXPECT_TRUE(got.has_pixel);
            EXPECT_EQ(got.pixel[0], x);
            EXPECT_EQ(got.pixel[1], y);
            if (want.kind != RayKind::primary) ++secondary_rays;
          }
          EXPECT_EQ(k, p.rays.size());
          EXPECT_EQ(sample + 1, int(p.sampling.samples.size()));
          // Each primary ray is the camera's ray through its sample.
          const ProjectiveCamera camera(s.scene.camera, width, height);
          for (const RayRequest& got : p.rays)
            if (got.kind == RayKind::primary) {
              const PixelSample& ps = p.sampling.samples[size_t(got.sample)];
              EXPECT_TRUE(same_bits(got.ray, camera.generate(ps.px, ps.py)));
            }
        }
      }
    EXPECT_GT(secondary_rays, 0);  // the scene does spawn shadow, reflected and refracted rays
  }
}

}  // namespace
}  // namespace raystep
