// The parallel render loop: the same bits whatever the thread count, sample counts that add up to the
// primary rays, the seed's effect, and option checking.
#include <gtest/gtest.h>

#include <cstring>
#include <numeric>

#include "raystep/accel/accelerator.h"
#include "raystep/render/camera.h"
#include "raystep/render/render.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

// A small scene with every kind of ray: matte floor, mirror and glass spheres, two lights.
struct TestScene {
  Scene scene;
  std::unique_ptr<Accelerator> accel = make_accelerator("bvol");

  TestScene() {
    scene.camera.eye = glm::vec3(0.f, 1.5f, 6.f);
    scene.camera.look_at = glm::vec3(0.f, 0.7f, 0.f);
    scene.camera.fov_deg = 45.f;
    scene.render.ambient = glm::vec3(0.1f);
    scene.render.background = glm::vec3(0.2f, 0.3f, 0.5f);
    Material floor;
    floor.diffuse = glm::vec3(0.7f, 0.7f, 0.6f);
    Material chrome;
    chrome.diffuse = glm::vec3(0.1f);
    chrome.specular = glm::vec3(0.5f);
    chrome.mirror = 0.7f;
    Material glass;
    glass.diffuse = glm::vec3(0.f);
    glass.transparency = 0.9f;
    glass.mirror = 0.1f;
    glass.ior = 1.5f;
    scene.materials = {floor, chrome, glass};
    Geometry& g = scene.geometry;
    g.begin_object("floor", 0);
    g.add_triangle({-5.f, 0.f, -5.f}, {-5.f, 0.f, 5.f}, {5.f, 0.f, 5.f});
    g.add_triangle({-5.f, 0.f, -5.f}, {5.f, 0.f, 5.f}, {5.f, 0.f, -5.f});
    g.begin_object("chrome", 1);
    g.add_sphere(Sphere{{-1.f, 1.f, 0.f}, 1.f});
    g.begin_object("glass", 2);
    g.add_sphere(Sphere{{1.2f, 0.8f, 1.f}, 0.8f});
    Light key;
    key.position = glm::vec3(3.f, 6.f, 4.f);
    Light sun;
    sun.type = LightType::directional;
    sun.direction = glm::vec3(-0.5f, -1.f, -0.3f);
    sun.intensity = 0.5f;
    scene.lights = {key, sun};
    accel->build(scene.geometry);
  }

  RenderResult render(AntiAliasing::Mode mode, int k, int threads, uint64_t seed = 7) const {
    RenderOptions o;
    o.aa.mode = mode;
    o.aa.k = k;
    o.aa.max_depth = 2;
    o.width = 48;
    o.height = 32;
    o.threads = threads;
    o.seed = seed;
    return render_image(scene, *accel, o);
  }
};

bool same_bits(const Image& a, const Image& b) {
  return a.width == b.width && a.height == b.height && a.pixels.size() == b.pixels.size() &&
         std::memcmp(a.pixels.data(), b.pixels.data(), a.pixels.size() * sizeof(glm::vec3)) == 0;
}

TEST(Render, BitIdenticalWhateverTheThreadCount) {
  TestScene t;
  for (AntiAliasing::Mode mode : {AntiAliasing::Mode::jitter, AntiAliasing::Mode::adaptive}) {
    RenderResult one = t.render(mode, 2, 1);
    for (int threads : {2, 4}) {
      RenderResult many = t.render(mode, 2, threads);
      EXPECT_TRUE(same_bits(one.image, many.image)) << threads << " threads";
      EXPECT_EQ(one.samples, many.samples);
      EXPECT_EQ(one.rays.total(), many.rays.total());
      EXPECT_EQ(one.rays.refracted, many.rays.refracted);
    }
  }
}

TEST(Render, SampleCountsAddUpToPrimaryRays) {
  TestScene t;
  for (auto [mode, k] : {std::pair{AntiAliasing::Mode::none, 1}, {AntiAliasing::Mode::regular, 3},
                         {AntiAliasing::Mode::jitter, 2}, {AntiAliasing::Mode::random, 5},
                         {AntiAliasing::Mode::adaptive, 1}}) {
    RenderResult r = t.render(mode, k, 0);
    ASSERT_EQ(r.samples.size(), size_t(48 * 32));
    uint64_t sum = std::accumulate(r.samples.begin(), r.samples.end(), uint64_t(0));
    EXPECT_EQ(sum, r.rays.primary);
    EXPECT_GT(r.rays.shadow, 0u);
    EXPECT_GT(r.rays.reflected, 0u);
    EXPECT_GT(r.rays.refracted, 0u);
    if (mode != AntiAliasing::Mode::adaptive) EXPECT_EQ(r.rays.primary, uint64_t(48 * 32) * r.samples[0]);
  }
}

TEST(Render, SeedChangesRandomPatternsOnly) {
  TestScene t;
  EXPECT_FALSE(same_bits(t.render(AntiAliasing::Mode::jitter, 2, 2, 1).image,
                         t.render(AntiAliasing::Mode::jitter, 2, 2, 2).image));
  EXPECT_TRUE(same_bits(t.render(AntiAliasing::Mode::regular, 2, 2, 1).image,
                        t.render(AntiAliasing::Mode::regular, 2, 2, 2).image));
}

TEST(Render, PixelCentreImageMatchesTheTracer) {
  // Mode none: pixel (x, y) is the radiance through its centre.
  TestScene t;
  RenderResult r = t.render(AntiAliasing::Mode::none, 1, 2);
  ProjectiveCamera camera(t.scene.camera, 48, 32);
  WhittedTracer tracer(t.scene, *t.accel);
  RayCounts counts;
  for (int y : {0, 13, 31})
    for (int x : {0, 20, 47})
      EXPECT_EQ(r.image.at(x, y), tracer.trace_primary(camera.generate(x + 0.5f, y + 0.5f), &counts));
  EXPECT_EQ(r.image.at(0, 0), t.scene.render.background);  // the sky in the top-left corner
}

TEST(Render, PixelsDrawIndependentSamples) {
  // A white half-plane whose edge halves pixel column 16 (orthographic, 2 world units over 32 pixels):
  // with one random sample per pixel, the column's pixels are independent coin flips, so both
  // colours occur (a shared stream would make the whole column one colour).
  Scene scene;
  scene.camera.type = CameraType::orthographic;
  scene.camera.eye = glm::vec3(0.f, 0.f, 5.f);
  scene.camera.look_at = glm::vec3(0.f);
  scene.camera.ortho_height = 2.f;
  scene.render.ambient = glm::vec3(1.f);
  Material white;
  white.diffuse = glm::vec3(1.f);
  scene.materials = {white};
  const float edge = -1.f + 16.5f / 16.f;
  scene.geometry.add_triangle({-9.f, -9.f, 0.f}, {edge, -9.f, 0.f}, {edge, 9.f, 0.f});
  scene.geometry.add_triangle({-9.f, -9.f, 0.f}, {edge, 9.f, 0.f}, {-9.f, 9.f, 0.f});
  auto accel = make_accelerator("brute");
  accel->build(scene.geometry);
  RenderOptions o;
  o.aa.mode = AntiAliasing::Mode::random;
  o.aa.k = 1;
  o.width = o.height = 32;
  RenderResult r = render_image(scene, *accel, o);
  int white_pixels = 0;
  for (int y = 0; y < 32; ++y) {
    EXPECT_EQ(r.image.at(15, y), glm::vec3(1.f));
    EXPECT_EQ(r.image.at(17, y), glm::vec3(0.f));
    white_pixels += r.image.at(16, y).x == 1.f;
  }
  EXPECT_GT(white_pixels, 4);
  EXPECT_LT(white_pixels, 28);
}

TEST(Render, OptionsFromTheSceneAndBadOptions) {
  TestScene t;
  RenderSettings s;
  s.width = 17;
  s.height = 9;
  s.seed = 99;
  s.aa.mode = AntiAliasing::Mode::random;
  s.aa.k = 3;
  RenderOptions o = render_options(s);
  EXPECT_EQ(o.width, 17);
  EXPECT_EQ(o.height, 9);
  EXPECT_EQ(o.seed, 99u);
  EXPECT_EQ(o.aa.k, 3);
  RenderResult r = render_image(t.scene, *t.accel, o);
  EXPECT_EQ(r.image.width, 17);
  EXPECT_EQ(r.rays.primary, 17u * 9u * 3u);
  EXPECT_GE(r.seconds, 0.0);

  RenderOptions bad = o;
  bad.width = 0;
  EXPECT_THROW(render_image(t.scene, *t.accel, bad), InputError);
  bad = o;
  bad.height = 1 << 20;
  EXPECT_THROW(render_image(t.scene, *t.accel, bad), InputError);
  bad = o;
  bad.threads = -2;
  EXPECT_THROW(render_image(t.scene, *t.accel, bad), InputError);
  bad = o;
  bad.aa.mode = AntiAliasing::Mode::jitter;
  bad.aa.k = 0;
  EXPECT_THROW(render_image(t.scene, *t.accel, bad), InputError);
}

}  // namespace
}  // namespace raystep
