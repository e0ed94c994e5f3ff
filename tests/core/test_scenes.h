// Scenes for the core tests: small generated ones and the brute-force comparison shared by the structure
// tests (grid, kd-tree, traces), and anti-aliasing settings.
#pragma once

#include <cstdint>
#include <random>
#include <vector>

#include "raystep/accel/brute_force.h"
#include "raystep/scene/geometry.h"
#include "raystep/scene/scene.h"

namespace raystep::test {

// A soup of random small triangles and a few spheres in [-2, 2]^3.
inline Geometry make_soup(uint32_t seed, int triangles, int spheres) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.f, 2.f), s(-0.4f, 0.4f);
  g.begin_object("soup", 0);
  for (int i = 0; i < triangles; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    g.add_triangle(p, p + glm::vec3(s(rng), s(rng), s(rng)), p + glm::vec3(s(rng), s(rng), s(rng)));
  }
  for (int i = 0; i < spheres; ++i) g.add_sphere(Sphere{glm::vec3(u(rng), u(rng), u(rng)), 0.3f});
  return g;
}

// Rays on which a structure's answer differs from brute force's: another primitive, another t, or another
// occlusion. Ties (coincident faces, a shared edge) go to the lower primitive id everywhere, so they count
// too.
inline int count_disagreements(const Accelerator& acc, const BruteForce& brute,
                               const std::vector<Ray>& rays) {
  int bad = 0;
  for (const Ray& r : rays) {
    Hit a, b;
    bool ha = brute.intersect(r, &a), hb = acc.intersect(r, &b);
    if (ha != hb || a.prim != b.prim || a.t != b.t || brute.occluded(r) != acc.occluded(r)) ++bad;
  }
  return bad;
}

// An anti-aliasing setting, the fields the tests vary.
inline AntiAliasing make_aa(AntiAliasing::Mode mode, int k = 1, float threshold = 0.1f, int max_depth = 3) {
  AntiAliasing aa;
  aa.mode = mode;
  aa.k = k;
  aa.threshold = threshold;
  aa.max_depth = max_depth;
  return aa;
}

}  // namespace raystep::test
