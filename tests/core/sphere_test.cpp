// sphere.h: the stable ray-sphere quadratic (Haines et al., Ray Tracing Gems ch. 7). Analytic roots from
// outside, inside, tangent and behind; the open interval; grazing rays; a sphere 1e5 units from the ray
// origin (where the textbook float formula breaks down); and the reprojected hit point's error bound.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>

#include "exact_reference.h"
#include "raystep/geometry/sphere.h"

namespace raystep {
namespace {

Ray make_ray(glm::vec3 o, glm::vec3 d, float tmin = 0.f, float tmax = kInfinity) {
  Ray r;
  r.origin = o;
  r.direction = d;
  r.tmin = tmin;
  r.tmax = tmax;
  return r;
}

bool hit(const Ray& r, const Sphere& s, float* t) {
  return intersect_sphere(r, s, r.tmax, t);
}

const Sphere kUnit{glm::vec3(0.f), 1.f};

TEST(Sphere, AnalyticRoots) {
  float t = -1;
  ASSERT_TRUE(hit(make_ray({0.f, 0.f, -5.f}, {0.f, 0.f, 1.f}), kUnit, &t));  // outside: near root
  EXPECT_FLOAT_EQ(t, 4.f);
  ASSERT_TRUE(hit(make_ray({0.f, 0.f, -5.f}, {0.f, 0.f, 2.f}), kUnit, &t));  // unnormalised direction
  EXPECT_FLOAT_EQ(t, 2.f);
  ASSERT_TRUE(hit(make_ray({0.f, 0.f, 0.f}, {0.f, 0.6f, 0.8f}), kUnit, &t));  // inside: the exit
  EXPECT_FLOAT_EQ(t, 1.f);
  ASSERT_TRUE(hit(make_ray({0.f, 0.f, 0.5f}, {0.f, 0.f, -1.f}), kUnit, &t));
  EXPECT_FLOAT_EQ(t, 1.5f);
  EXPECT_FALSE(hit(make_ray({0.f, 0.f, 5.f}, {0.f, 0.f, 1.f}), kUnit, &t));   // sphere behind
  EXPECT_FALSE(hit(make_ray({0.f, 2.f, -5.f}, {0.f, 0.f, 1.f}), kUnit, &t));  // passes beside
  // Tangent: the double root counts as a hit.
  ASSERT_TRUE(hit(make_ray({1.f, 0.f, -5.f}, {0.f, 0.f, 1.f}), kUnit, &t));
  EXPECT_FLOAT_EQ(t, 5.f);
  // Off-centre sphere, off-axis ray: |(0.3, 0, z)| = 0.5 at z = -0.4, t = 3 - 0.4.
  Sphere s{glm::vec3(2.f, 3.f, 4.f), 0.5f};
  ASSERT_TRUE(hit(make_ray(s.center + glm::vec3(0.3f, 0.f, -3.f), {0.f, 0.f, 1.f}), s, &t));
  EXPECT_NEAR(t, 2.6f, 1e-6);
  // Origin on the sphere: leaving it, no hit (t = 0 is not in the open interval); entering, the far side.
  EXPECT_FALSE(hit(make_ray({1.f, 0.f, 0.f}, {1.f, 0.f, 0.f}), kUnit, &t));
  ASSERT_TRUE(hit(make_ray({1.f, 0.f, 0.f}, {-1.f, 0.f, 0.f}), kUnit, &t));
  EXPECT_FLOAT_EQ(t, 2.f);
}

TEST(Sphere, OpenInterval) {
  float t;
  const glm::vec3 o(0.f, 0.f, -5.f), d(0.f, 0.f, 1.f);  // roots 4 and 6
  EXPECT_FALSE(hit(make_ray(o, d, 0.f, 4.f), kUnit, &t));
  ASSERT_TRUE(hit(make_ray(o, d, 0.f, next_float_up(4.f)), kUnit, &t));
  EXPECT_EQ(t, 4.f);
  ASSERT_TRUE(hit(make_ray(o, d, 4.f, 10.f), kUnit, &t));  // the near root excluded: the far one
  EXPECT_EQ(t, 6.f);
  EXPECT_FALSE(hit(make_ray(o, d, 6.f, 10.f), kUnit, &t));
  EXPECT_FALSE(hit(make_ray(o, d, 4.5f, 6.f), kUnit, &t));
  EXPECT_FALSE(intersect_sphere(make_ray(o, d), kUnit, 3.f, &t));  // tmax passed apart from the ray
  const float nan = std::nanf("");
  EXPECT_FALSE(hit(make_ray({nan, 0.f, -5.f}, d), kUnit, &t));
  EXPECT_FALSE(hit(make_ray(o, {0.f, nan, 1.f}), kUnit, &t));
  EXPECT_FALSE(hit(make_ray(o, {0.f, 0.f, 0.f}), kUnit, &t));
  EXPECT_FALSE(hit(make_ray(o, d, nan, 10.f), kUnit, &t));
}

// Grazing rays: the line's distance to the centre (exact, in double) decides; within 1e-5 of the radius
// either answer is acceptable. Hits must be on the sphere.
TEST(Sphere, GrazingRays) {
  std::mt19937 rng(4);
  std::uniform_real_distribution<double> u(-1, 1);
  int hits = 0, misses = 0;
  for (int i = 0; i < 20000; ++i) {
    double scale = std::pow(10.0, int(rng() % 7) - 3);  // 1e-3 .. 1e3
    Sphere s{glm::vec3(scale * glm::dvec3(u(rng), u(rng), u(rng))), float(scale)};
    glm::vec3 o = s.center + float(5 * scale) * glm::vec3(glm::normalize(glm::dvec3(u(rng), u(rng), u(rng))));
    // Aim at a point beside the centre, perpendicular to the view, so that the line passes the centre at a
    // distance of 1 +- 1 % radii: a line through o and c + h side is at distance h L / sqrt(L^2 + h^2).
    glm::dvec3 view = glm::dvec3(s.center) - glm::dvec3(o);
    glm::dvec3 side = glm::normalize(glm::cross(view, glm::dvec3(u(rng), u(rng), u(rng))));
    double want = s.radius * (1 + 0.01 * u(rng)), L = glm::length(view);
    double h = want * L / std::sqrt(L * L - want * want);
    Ray r = make_ray(o, glm::vec3(glm::dvec3(s.center) + h * side - glm::dvec3(o)));
    glm::dvec3 d(r.direction), f = glm::dvec3(o) - glm::dvec3(s.center);
    double dist = glm::length(f - glm::dot(f, d) / glm::dot(d, d) * d);
    float t;
    bool got = hit(r, s, &t);
    if (dist < s.radius * (1 - 1e-5)) {
      ASSERT_TRUE(got) << i;
      ++hits;
      double on = glm::length(glm::dvec3(o) + double(t) * d - glm::dvec3(s.center));
      // Near tangency the root moves fast, but the point stays on the sphere: error in the normal direction
      // is at most |d| times t's rounding.
      ASSERT_NEAR(on, s.radius, 2 * gamma(1) * t * glm::length(d) + 1e-6 * s.radius) << i;
    } else if (dist > s.radius * (1 + 1e-5)) {
      ASSERT_FALSE(got) << i;
      ++misses;
    }
  }
  EXPECT_GT(hits, 5000);
  EXPECT_GT(misses, 5000);
}

// The textbook formula in float: a t^2 + b t + c with b = 2 oc.d, c = oc.oc - r^2, t = (-b -
// sqrt(b^2-4ac))/2a.
bool naive_float_sphere(const Ray& r, const Sphere& s, float* t) {
  glm::vec3 oc = r.origin - s.center;
  float a = glm::dot(r.direction, r.direction), b = 2.f * glm::dot(oc, r.direction);
  float c = glm::dot(oc, oc) - s.radius * s.radius;
  float disc = b * b - 4.f * a * c;
  if (disc < 0.f) return false;
  float t0 = (-b - std::sqrt(disc)) / (2.f * a);
  if (t0 <= r.tmin) t0 = (-b + std::sqrt(disc)) / (2.f * a);
  if (!(t0 > r.tmin && t0 < r.tmax)) return false;
  *t = t0;
  return true;
}

// A unit sphere 1e5 units from the ray origin, rays aimed at random points of its visible half: every ray
// hits, t is within one ulp of a long double reference, and the hit point lies on the sphere to within the
// rounding of t (relative to the distance travelled, a few 1e-8; absolute, about ulp(1e5) = 0.008, the
// resolution of float coordinates there). The textbook float formula loses c = |oc|^2 - r^2 entirely (r^2 is
// below half an ulp of 1e10) and is far off or misses; it is measured and printed, not asserted.
TEST(Sphere, FarSphereHitAccurately) {
  std::mt19937 rng(6);
  std::uniform_real_distribution<double> u(-1, 1);
  const Sphere s{glm::vec3(1e5f, 2e3f, -4e3f), 1.f};
  const glm::vec3 o(0.f);
  double worst = 0, naive_worst = 0;
  int naive_misses = 0;
  const int kRays = 20000;
  for (int i = 0; i < kRays; ++i) {
    glm::dvec3 n = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    if (glm::dot(n, glm::dvec3(o) - glm::dvec3(s.center)) < 0) n = -n;  // the visible half
    glm::dvec3 target = glm::dvec3(s.center) + 0.999 * n;               // just inside the surface
    Ray r = make_ray(o, glm::vec3(target - glm::dvec3(o)));
    float t;
    ASSERT_TRUE(hit(r, s, &t)) << i;
    glm::dvec3 d(r.direction);
    // Reference root in long double: along the line to the foot of the perpendicular, back by the half chord.
    long double dd = 0, fd = 0, ff = 0;
    for (int a = 0; a < 3; ++a) {
      long double fa = (long double)s.center[a] - o[a];
      dd += d[a] * (long double)d[a];
      fd += fa * d[a];
      ff += fa * fa;
    }
    long double foot = fd / dd, perp2 = ff - fd * fd / dd;
    double t_ref = double(foot - std::sqrt(((long double)s.radius * s.radius - perp2) / dd));
    ASSERT_LE(std::fabs(t - t_ref), std::nextafter(float(t_ref), kInfinity) - float(t_ref)) << i;  // 1 ulp
    double travelled = t * glm::length(d);
    double error = std::fabs(glm::length(glm::dvec3(o) + double(t) * d - glm::dvec3(s.center)) - s.radius);
    worst = std::fmax(worst, error / travelled);
    float tn;
    if (!naive_float_sphere(r, s, &tn)) {
      ++naive_misses;
    } else {
      double e = std::fabs(glm::length(glm::dvec3(o) + double(tn) * d - glm::dvec3(s.center)) - s.radius);
      naive_worst = std::fmax(naive_worst, e / travelled);
    }
  }
  EXPECT_LT(worst, 2 * gamma(1));  // t's own rounding, and nothing more
  std::printf(
      "[ info ] far sphere, relative error of the hit point: stable %.3g; naive float %.3g with %d of %d "
      "rays missed\n",
      worst, naive_worst, naive_misses, kRays);
}

// sphere_point reprojects onto the sphere; its error bound, projected on the normal (the offset spawn.h
// uses), covers the point's distance to the exact surface.
TEST(Sphere, ReprojectedPointWithinErrorBound) {
  std::mt19937 rng(7);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int hits = 0;
  for (int i = 0; i < 20000; ++i) {
    float scale = std::pow(10.f, float(int(rng() % 11) - 4));  // 1e-4 .. 1e6
    Sphere s{scale * glm::vec3(u(rng), u(rng), u(rng)) * 10.f, scale * (0.5f + std::fabs(u(rng)))};
    glm::vec3 o = s.center + 4.f * scale * glm::vec3(u(rng), u(rng), u(rng));
    Ray r = make_ray(o, s.center + 0.5f * s.radius * glm::vec3(u(rng), u(rng), u(rng)) - o);
    float t;
    if (!hit(r, s, &t)) continue;
    ++hits;
    glm::vec3 err;
    glm::vec3 p = sphere_point(r, s, t, &err);
    glm::dvec3 local = glm::dvec3(p) - glm::dvec3(s.center);
    glm::dvec3 n = glm::normalize(local);
    double off_surface = std::fabs(glm::length(local) - s.radius);
    ASSERT_LE(off_surface, glm::dot(glm::abs(n), glm::dvec3(err))) << i;
    ASSERT_LE(glm::length(glm::dvec3(err)), 1e-5 * (glm::length(glm::dvec3(p)) + s.radius));  // and small
  }
  EXPECT_GT(hits, 10000);
}

// Rays from inside a sphere always leave it: origins anywhere inside, down to a few float ulps below the surface
// (inside exactly, checked in rationals), spheres of radius 1e-3 .. 1e4 at the origin and 1e4 radii away (along a
// diagonal, and along one axis only), random directions. The exit is found, beyond tmin = 0, on the sphere.
TEST(Sphere, RaysFromInsideNeverMiss) {
  std::mt19937 rng(21);
  std::uniform_real_distribution<double> u(-1, 1);
  int near_surface = 0, rays = 0;
  for (int i = 0; i < 60000; ++i) {
    const float radius = std::pow(10.f, float(int(rng() % 8) - 3)) * float(0.5 + 0.5 * std::fabs(u(rng)));
    glm::vec3 center(0.f);
    if (i % 3 == 1) center = 1e4f * radius * glm::vec3(0.6f, -0.48f, 0.64f);
    if (i % 3 == 2) center[rng() % 3] = -1e4f * radius;
    const Sphere s{center, radius};
    glm::dvec3 n = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    // Depth below the surface: anything, or 2^-k of the radius for k up to 30 (a float ulp is 2^-24).
    double depth = (i % 2) ? std::fabs(u(rng)) : std::ldexp(1.0, -int(rng() % 31));
    glm::vec3 o(glm::dvec3(center) + (1 - depth) * double(radius) * n);
    test::QVec f = test::sub(test::to_q(o), test::to_q(center));
    if (!(test::dot(f, f) < test::Q(double(radius)) * test::Q(double(radius)))) continue;  // rounded outside
    near_surface += depth < 1e-6;
    ++rays;
    glm::vec3 d(glm::normalize(glm::dvec3(u(rng), u(rng), u(rng))) * std::pow(10.0, int(rng() % 5) - 2));
    float t;
    ASSERT_TRUE(hit(make_ray(o, d), s, &t)) << i << " radius " << radius << " depth " << depth;
    ASSERT_GT(t, 0.f);
    // On the sphere to within the rounding of t and of the coordinates (float ulps of the centre's position).
    double off = std::fabs(glm::length(glm::dvec3(o) + double(t) * glm::dvec3(d) - glm::dvec3(center)) - radius);
    ASSERT_LE(off, 4 * gamma(1) * (double(t) * glm::length(glm::dvec3(d)) + glm::length(glm::dvec3(center)) + radius))
        << i;
  }
  EXPECT_GT(rays, 45000);
  EXPECT_GT(near_surface, 5000);
}

// A root just above tmin that rounds to tmin as a float is a hit there, not a skip to the far root: from
// (0, 0, -5) along (0, 0, k) the unit sphere's roots are 4/k and 6/k; tmin is float(4/k) where that rounds down.
TEST(Sphere, RootRoundingToTminIsStillAHit) {
  int cases = 0;
  for (int k = 3; k < 200; ++k) {
    const double near_root = 4.0 / k;
    const float tmin = float(near_root);
    if (!(double(tmin) < near_root)) continue;
    ++cases;
    float t;
    ASSERT_TRUE(hit(make_ray({0.f, 0.f, -5.f}, {0.f, 0.f, float(k)}, tmin), kUnit, &t)) << k;
    EXPECT_EQ(t, next_float_up(tmin)) << k;  // the near root, at the first float beyond tmin
    // A tmax at that float excludes it (tmax is compared in float), and the far root too.
    EXPECT_FALSE(intersect_sphere(make_ray({0.f, 0.f, -5.f}, {0.f, 0.f, float(k)}, tmin), kUnit,
                                  next_float_up(tmin), &t));
  }
  EXPECT_GT(cases, 40);
}

// Tangent-ish rays from outside: where the exact discriminant (rationals: a r^2 - |f x d|^2 for the float inputs)
// is further from 0 than the double computation's rounding can move it, hit and miss agree with it. Spheres of
// radius 1e-3 .. 1e4, at the origin and 1e4 radii away; lines at relative distances 1 +- 1e-4 .. 1e-12 from the
// centre, most of them within the undecided band of float inputs, a few thousand decidable either way.
TEST(Sphere, TangentRaysAgreeWithTheExactDiscriminant) {
  std::mt19937 rng(22);
  std::uniform_real_distribution<double> u(-1, 1);
  int decided_hits = 0, decided_misses = 0;
  for (int i = 0; i < 60000; ++i) {
    const float radius = std::pow(10.f, float(int(rng() % 8) - 3));
    glm::vec3 center(0.f);
    if (i % 2) center = 1e4f * radius * glm::vec3(-0.36f, 0.48f, 0.8f);
    const Sphere s{center, radius};
    glm::dvec3 view = glm::normalize(glm::dvec3(u(rng), u(rng), u(rng)));
    glm::vec3 o(glm::dvec3(center) - 5.0 * radius * view);
    glm::dvec3 side = glm::normalize(glm::cross(view, glm::dvec3(u(rng), u(rng), u(rng))));
    double want = radius * (1 + std::ldexp(u(rng), -int(13 + rng() % 28)));
    glm::dvec3 to = glm::dvec3(center) - glm::dvec3(o);
    double L = glm::length(to);
    glm::vec3 d(to + want * L / std::sqrt(L * L - want * want) * side);
    test::QVec f = test::sub(test::to_q(o), test::to_q(center)), dq = test::to_q(d);
    test::QVec fxd = test::cross(f, dq);
    const test::Q rq = double(radius);
    test::Q disc = rq * rq * test::dot(dq, dq) - test::dot(fxd, fxd);
    // The double discriminant's rounding: relative gamma(16) of a (|f| + r)^2 is ample (l = f + (b/a) d and
    // |l|^2 each round a few times, relative to |f|).
    double band = gamma_double(16) * glm::dot(glm::dvec3(d), glm::dvec3(d)) *
                  std::pow(glm::length(glm::dvec3(o) - glm::dvec3(center)) + radius, 2);
    double exact = disc.get_d();
    if (std::fabs(exact) <= band) continue;
    float t;
    bool got = hit(make_ray(o, d), s, &t);
    ASSERT_EQ(got, exact > 0) << i << " radius " << radius;
    (exact > 0 ? decided_hits : decided_misses)++;
  }
  EXPECT_GT(decided_hits, 1000);
  EXPECT_GT(decided_misses, 1000);
}

}  // namespace
}  // namespace raystep
