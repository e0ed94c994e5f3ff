// The Whitted tracer against analytic answers: Lambert and Phong terms, shadows, mirrors, Snell's law,
// total internal reflection, the depth limit, adaptive ray termination, and rays counted by kind.
#include <gtest/gtest.h>

#include <cmath>
#include <glm/geometric.hpp>

#include "raystep/accel/brute_force.h"
#include "raystep/render/whitted.h"

namespace raystep {
namespace {

// A scene with its accelerator; build() once the geometry is final.
struct World {
  Scene scene;
  BruteForce accel;

  World() {
    scene.render.ambient = glm::vec3(0.f);
    scene.render.background = glm::vec3(0.f);
    scene.render.min_weight = 0.f;
  }
  uint32_t material(const Material& m) {
    scene.materials.push_back(m);
    return uint32_t(scene.materials.size() - 1);
  }
  // Quad p0 p1 p2 p3 (counter-clockwise seen from its front) as two triangles.
  void quad(uint32_t mat, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2, const glm::vec3& p3) {
    scene.geometry.begin_object("quad", mat);
    scene.geometry.add_triangle(p0, p1, p2);
    scene.geometry.add_triangle(p0, p2, p3);
  }
  // The plane y = h, x and z in [c - s, c + s], facing +y.
  void floor(uint32_t mat, float h = 0.f, float s = 10.f, float cx = 0.f) {
    quad(mat, {cx - s, h, -s}, {cx - s, h, s}, {cx + s, h, s}, {cx + s, h, -s});
  }
  void sphere(uint32_t mat, const glm::vec3& c, float r) {
    scene.geometry.begin_object("sphere", mat);
    scene.geometry.add_sphere(Sphere{c, r});
  }
  void light(const glm::vec3& position, float intensity = 1.f) {
    Light l;
    l.type = LightType::point;
    l.position = position;
    l.intensity = intensity;
    scene.lights.push_back(l);
  }
  void sun(const glm::vec3& direction, float intensity = 1.f) {
    Light l;
    l.type = LightType::directional;
    l.direction = direction;
    l.intensity = intensity;
    scene.lights.push_back(l);
  }
  glm::vec3 trace(const glm::vec3& origin, const glm::vec3& direction, RayCounts* counts = nullptr) {
    accel.build(scene.geometry);
    WhittedTracer tracer(scene, accel);
    RayCounts local;
    Ray r;
    r.origin = origin;
    r.direction = glm::normalize(direction);
    glm::vec3 L = tracer.trace_primary(r, counts ? counts : &local);
    return L;
  }
};

Material diffuse(const glm::vec3& kd) {
  Material m;
  m.diffuse = kd;
  return m;
}

void expect_vec_near(const glm::vec3& a, const glm::vec3& b, float tol = 1e-5f) {
  EXPECT_NEAR(a.x, b.x, tol);
  EXPECT_NEAR(a.y, b.y, tol);
  EXPECT_NEAR(a.z, b.z, tol);
}

TEST(Whitted, LambertPlaneUnderPointAndDirectionalLights) {
  const glm::vec3 kd(0.5f, 0.6f, 0.7f), ambient(0.1f, 0.2f, 0.3f);
  World w;
  w.scene.render.ambient = ambient;
  w.floor(w.material(diffuse(kd)));
  w.light({3.f, 4.f, 0.f}, 2.f);  // over the origin: n.l = 4/5
  RayCounts counts;
  expect_vec_near(w.trace({0.f, 1.f, 0.f}, {0.f, -1.f, 0.f}, &counts), ambient * kd + kd * 0.8f * 2.f);
  EXPECT_EQ(counts.primary, 1u);
  EXPECT_EQ(counts.shadow, 1u);
  EXPECT_EQ(counts.reflected + counts.refracted, 0u);  // a matte scene spawns no secondary rays
  // Elsewhere on the plane: l = (1, 4, -1)/sqrt(18); point lights are not attenuated.
  expect_vec_near(w.trace({2.f, 3.f, 1.f}, {0.f, -1.f, 0.f}), ambient * kd + kd * (4.f / std::sqrt(18.f)) * 2.f);

  World d;
  d.floor(d.material(diffuse(kd)));
  d.sun({-1.f, -1.f, 0.f});  // travelling down at 45 degrees
  expect_vec_near(d.trace({0.f, 1.f, 0.f}, {0.1f, -1.f, 0.2f}), kd * std::sqrt(0.5f));
}

TEST(Whitted, PhongHighlight) {
  Material m = diffuse(glm::vec3(0.f));
  m.specular = glm::vec3(0.3f);
  m.shininess = 10.f;
  World w;
  w.floor(w.material(m));
  w.light({3.f, 4.f, 0.f}, 2.f);
  // Viewer straight above the origin: r = (-0.6, 0.8, 0), r.v = 0.8.
  expect_vec_near(w.trace({0.f, 1.f, 0.f}, {0.f, -1.f, 0.f}), glm::vec3(0.3f * std::pow(0.8f, 10.f) * 2.f));
  // Viewer in the mirror direction: r.v = 1.
  expect_vec_near(w.trace({-3.f, 4.f, 0.f}, {3.f, -4.f, 0.f}), glm::vec3(0.3f * 2.f));
}

TEST(Whitted, PointInShadowGetsAmbientOnly) {
  const glm::vec3 kd(0.5f), ambient(0.1f);
  World w;
  w.scene.render.ambient = ambient;
  w.floor(w.material(diffuse(kd)));
  w.sphere(w.material(diffuse(glm::vec3(1.f))), {1.5f, 2.f, 0.f}, 0.5f);  // halfway to the light
  w.light({3.f, 4.f, 0.f});
  RayCounts counts;
  expect_vec_near(w.trace({0.f, 1.f, 0.f}, {0.f, -1.f, 0.f}, &counts), ambient * kd);
  EXPECT_EQ(counts.shadow, 1u);
  // A light below the surface: ambient only, and no shadow ray is spent on it.
  World below;
  below.scene.render.ambient = ambient;
  below.floor(below.material(diffuse(kd)));
  below.light({3.f, -4.f, 0.f});
  RayCounts below_counts;
  expect_vec_near(below.trace({0.f, 1.f, 0.f}, {0.f, -1.f, 0.f}, &below_counts), ambient * kd);
  EXPECT_EQ(below_counts.shadow, 0u);
}

TEST(Whitted, InterpolatedVertexNormalsShade) {
  World w;
  uint32_t mat = w.material(diffuse(glm::vec3(1.f)));
  w.scene.geometry.begin_object("tilted normals", mat);
  uint32_t id = w.scene.geometry.add_triangle({-5.f, 0.f, -5.f}, {-5.f, 0.f, 5.f}, {5.f, 0.f, 0.f});
  const glm::vec3 n = glm::normalize(glm::vec3(1.f, 1.f, 0.f));
  w.scene.geometry.set_vertex_normals(id, n, n, n);
  w.sun({0.f, -1.f, 0.f});
  // Geometric normal (0, 1, 0) would give 1; the shading normal gives cos 45 degrees.
  expect_vec_near(w.trace({0.f, 1.f, 0.f}, {0.f, -1.f, 0.f}), glm::vec3(std::sqrt(0.5f)));
}

TEST(Whitted, NoSelfShadowingFarFromTheOrigin) {
  // Spawned rays are offset by the hit point's error bound, which grows with the coordinates: a plane at
  // x ~ 1e5 must not shadow itself (a fixed epsilon of 1e-4 would be below the rounding error there).
  const glm::vec3 kd(0.7f);
  World w;
  w.floor(w.material(diffuse(kd)), 1000.f, 10.f, 1e5f);
  w.sun({0.3f, -1.f, 0.1f});
  for (float dx : {0.123f, -3.7f, 6.1f}) {
    glm::vec3 L = w.trace({1e5f + dx, 1010.f, 0.77f}, {0.01f, -1.f, 0.02f});
    expect_vec_near(L, kd * (1.f / glm::length(glm::vec3(0.3f, -1.f, 0.1f))), 1e-4f);
  }
}

TEST(Whitted, NoShadowAcneOnAFarAwaySphere) {
  // The same for a sphere of radius 100 at x = 1e4: every visible point facing the light is fully lit,
  // with exactly Lambert's n.l (the shadow ray must not hit the sphere it leaves).
  World w;
  w.sphere(w.material(diffuse(glm::vec3(1.f))), {1e4f, 0.f, 0.f}, 100.f);
  const glm::vec3 to_light = glm::normalize(glm::vec3(-1.f, 0.6f, 0.3f));
  w.sun(-to_light);
  int lit = 0, checked = 0;
  for (int i = 0; i < 400; ++i) {
    const glm::vec3 target(1e4f - 100.f, -60.f + 0.3f * i, 37.f - 0.17f * i);  // over the near side
    const glm::vec3 origin(1e4f - 400.f, 0.f, 0.f);
    Ray r;
    r.origin = origin;
    r.direction = glm::normalize(target - origin);
    float t;
    ASSERT_TRUE(intersect_sphere(r, Sphere{{1e4f, 0.f, 0.f}, 100.f}, kInfinity, &t));
    const glm::vec3 n = glm::normalize(r.at(t) - glm::vec3(1e4f, 0.f, 0.f));
    const float n_dot_l = glm::dot(n, to_light);
    if (n_dot_l < 0.05f) continue;  // keep away from the terminator
    ++checked;
    const glm::vec3 L = w.trace(origin, r.direction);
    lit += std::fabs(L.x - n_dot_l) < 1e-3f;
  }
  EXPECT_GT(checked, 100);
  EXPECT_EQ(lit, checked);
}

TEST(Whitted, MirrorSeesTheObjectItReflects) {
  for (float mirror : {1.f, 0.5f}) {
    World w;
    w.scene.render.ambient = glm::vec3(1.f);
    Material m = diffuse(glm::vec3(0.f));  // a pure mirror: no local colour
    m.mirror = mirror;
    w.floor(w.material(m));
    w.sphere(w.material(diffuse({1.f, 0.f, 0.f})), {2.f, 2.f, 0.f}, 0.5f);
    RayCounts counts;
    // Hits the mirror at the origin, reflects along (1, 1, 0) into the red sphere.
    expect_vec_near(w.trace({-2.f, 2.f, 0.f}, {1.f, -1.f, 0.f}, &counts), glm::vec3(mirror, 0.f, 0.f));
    EXPECT_EQ(counts.reflected, 1u);
    EXPECT_EQ(counts.refracted, 0u);
    // Aimed elsewhere, the mirror shows the black background.
    expect_vec_near(w.trace({-2.f, 2.f, 0.f}, {1.f, -1.f, 0.5f}), glm::vec3(0.f));
  }
}

Material glass(float ior = 1.5f) {
  Material m = diffuse(glm::vec3(0.f));
  m.transparency = 1.f;
  m.ior = ior;
  return m;
}

TEST(Whitted, RayThroughTheSphereCentreIsUndeviated) {
  World w;
  w.scene.render.ambient = glm::vec3(1.f);
  w.sphere(w.material(glass()), {0.f, 0.f, 0.f}, 1.f);
  // A small green target straight behind the sphere.
  w.quad(w.material(diffuse({0.f, 1.f, 0.f})), {-0.05f, -0.05f, -5.f}, {0.05f, -0.05f, -5.f},
         {0.05f, 0.05f, -5.f}, {-0.05f, 0.05f, -5.f});
  RayCounts counts;
  expect_vec_near(w.trace({0.f, 0.f, 5.f}, {0.f, 0.f, -1.f}, &counts), glm::vec3(0.f, 1.f, 0.f));
  EXPECT_EQ(counts.refracted, 2u);  // in and out
  EXPECT_EQ(counts.reflected, 0u);  // transparent, not a mirror: no reflection ray
  // Off the centre the sphere is a lens: the ray is bent away from the target.
  expect_vec_near(w.trace({0.f, 0.5f, 5.f}, {0.f, 0.f, -1.f}), glm::vec3(0.f));
}

TEST(Whitted, SnellsLawThroughAGlassSlab) {
  // Slab between z = 0 and z = -1, each face facing outwards. A ray at 45 degrees enters at x = 5, crosses
  // at theta_t = asin(sin 45 / 1.5) and leaves parallel to itself: at z = -2 it lands at
  // x = 5 + tan(theta_t) + 1 = 6.5345 instead of 7.
  World w;
  w.scene.render.ambient = glm::vec3(1.f);
  uint32_t g = w.material(glass(1.5f));
  w.quad(g, {-50.f, -50.f, 0.f}, {50.f, -50.f, 0.f}, {50.f, 50.f, 0.f}, {-50.f, 50.f, 0.f});
  w.quad(g, {-50.f, -50.f, -1.f}, {-50.f, 50.f, -1.f}, {50.f, 50.f, -1.f}, {50.f, -50.f, -1.f});
  const float x_exit = 6.f + std::tan(std::asin(std::sqrt(0.5f) / 1.5f));
  ASSERT_NEAR(x_exit, 6.5345f, 1e-4f);
  auto strip = [&](float x0, float x1, const glm::vec3& colour) {
    w.quad(w.material(diffuse(colour)), {x0, -1.f, -2.f}, {x1, -1.f, -2.f}, {x1, 1.f, -2.f}, {x0, 1.f, -2.f});
  };
  strip(x_exit - 0.03f, x_exit + 0.03f, {0.f, 1.f, 0.f});  // where Snell's law lands
  strip(6.9f, 7.1f, {1.f, 0.f, 0.f});                      // where an undeviated ray would land
  RayCounts counts;
  expect_vec_near(w.trace({0.f, 0.f, 5.f}, {1.f, 0.f, -1.f}, &counts), glm::vec3(0.f, 1.f, 0.f));
  EXPECT_EQ(counts.refracted, 2u);
}

TEST(Whitted, RefractHelperFollowsSnell) {
  const glm::vec3 n(0.f, 0.f, 1.f);
  const glm::vec3 d = glm::normalize(glm::vec3(std::sin(0.6f), 0.f, -std::cos(0.6f)));
  glm::vec3 t;
  ASSERT_TRUE(refract(d, n, 1.f / 1.33f, &t));
  EXPECT_NEAR(glm::length(t), 1.f, 1e-6f);
  EXPECT_NEAR(t.x, std::sin(0.6f) / 1.33f, 1e-6f);  // sin theta_t = sin theta_i / n
  EXPECT_LT(t.z, 0.f);
  // From glass to air beyond the critical angle asin(1/1.5) = 41.8 degrees: total internal reflection.
  const glm::vec3 steep = glm::normalize(glm::vec3(std::sin(0.7f), 0.f, -std::cos(0.7f)));  // 40.1 deg
  const glm::vec3 shallow = glm::normalize(glm::vec3(std::sin(0.75f), 0.f, -std::cos(0.75f)));  // 43 deg
  EXPECT_TRUE(refract(steep, n, 1.5f, &t));
  EXPECT_FALSE(refract(shallow, n, 1.5f, &t));
  expect_vec_near(reflect(shallow, n), glm::vec3(shallow.x, 0.f, -shallow.z));
}

TEST(Whitted, TotalInternalReflectionInsideASphere) {
  // From (0, 0.9, 0) along +x inside a unit glass sphere: cos(theta_i) = sqrt(1 - 0.81) = 0.436, beyond
  // the critical angle, and every later bounce meets the surface at the same angle: only reflections,
  // up to the depth limit.
  World w;
  w.scene.render.max_depth = 5;
  w.sphere(w.material(glass(1.5f)), {0.f, 0.f, 0.f}, 1.f);
  RayCounts counts;
  w.trace({0.f, 0.9f, 0.f}, {1.f, 0.f, 0.f}, &counts);
  EXPECT_EQ(counts.refracted, 0u);
  EXPECT_EQ(counts.reflected, 5u);
  // Closer to the centre the angle is below critical: the ray leaves the sphere.
  RayCounts out;
  w.trace({0.f, 0.3f, 0.f}, {1.f, 0.f, 0.f}, &out);
  EXPECT_EQ(out.refracted, 1u);
  EXPECT_EQ(out.reflected, 0u);
}

// Two facing mirrors z = 0 and z = 2 with a ray bouncing between them along z.
World hall_of_mirrors(float mirror, int max_depth, float min_weight) {
  World w;
  w.scene.render.max_depth = max_depth;
  w.scene.render.min_weight = min_weight;
  Material m = diffuse(glm::vec3(0.f));
  m.mirror = mirror;
  uint32_t mat = w.material(m);
  w.quad(mat, {-5.f, -5.f, 0.f}, {5.f, -5.f, 0.f}, {5.f, 5.f, 0.f}, {-5.f, 5.f, 0.f});
  w.quad(mat, {-5.f, -5.f, 2.f}, {-5.f, 5.f, 2.f}, {5.f, 5.f, 2.f}, {5.f, -5.f, 2.f});
  return w;
}

TEST(Whitted, DepthLimitIsRespected) {
  for (int depth : {0, 1, 4, 9}) {
    World w = hall_of_mirrors(1.f, depth, 0.01f);
    RayCounts counts;
    w.trace({0.f, 0.f, 1.f}, {0.f, 0.f, -1.f}, &counts);
    EXPECT_EQ(counts.reflected, uint64_t(depth)) << depth;
    EXPECT_EQ(counts.primary, 1u);
  }
}

TEST(Whitted, AdaptiveTerminationStopsPaths) {
  // Weights 0.5^k: the k-th reflection is traced while 0.5^k >= min_weight.
  RayCounts low, high;
  World a = hall_of_mirrors(0.5f, 50, 0.01f);
  a.trace({0.f, 0.f, 1.f}, {0.f, 0.f, -1.f}, &low);
  EXPECT_EQ(low.reflected, 6u);  // 0.5^6 = 0.0156 >= 0.01 > 0.5^7
  World b = hall_of_mirrors(0.5f, 50, 0.1f);
  b.trace({0.f, 0.f, 1.f}, {0.f, 0.f, -1.f}, &high);
  EXPECT_EQ(high.reflected, 3u);  // 0.5^3 = 0.125 >= 0.1 > 0.5^4
  EXPECT_LT(high.total(), low.total());
}

TEST(Whitted, SceneWithoutGlassSpawnsNoRefractedRays) {
  World w;
  w.scene.render.ambient = glm::vec3(0.2f);
  w.floor(w.material(diffuse(glm::vec3(0.5f))));
  Material chrome = diffuse(glm::vec3(0.1f));
  chrome.mirror = 0.8f;
  w.sphere(w.material(chrome), {0.f, 1.f, 0.f}, 1.f);
  w.light({2.f, 5.f, 3.f});
  RayCounts counts;
  for (int i = 0; i < 100; ++i) {
    float a = 0.0628f * i;
    w.trace({4.f * std::cos(a), 2.f, 4.f * std::sin(a)}, {-std::cos(a), -0.3f, -std::sin(a)}, &counts);
  }
  EXPECT_EQ(counts.primary, 100u);
  EXPECT_GT(counts.reflected, 0u);
  EXPECT_GT(counts.shadow, 0u);
  EXPECT_EQ(counts.refracted, 0u);
  RayCounts sum = counts;
  sum += counts;
  EXPECT_EQ(sum.total(), 2 * (counts.primary + counts.shadow + counts.reflected));
}

}  // namespace
}  // namespace raystep
