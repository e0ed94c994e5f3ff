// exact.h: the exact answers for decisions a float error bound cannot settle, checked against rational
// arithmetic (exact_reference.h) on random inputs and on exactly degenerate ones (an origin on the plane, a
// ray parallel to it, a ray through an edge or a vertex), where only the exact path can answer.
#include <gtest/gtest.h>

#include <random>

#include "exact_reference.h"
#include "raystep/geometry/exact.h"

namespace raystep {
namespace {

Ray make_ray(glm::vec3 o, glm::vec3 d, float tmin = 0.f) {
  Ray r;
  r.origin = o;
  r.direction = d;
  r.tmin = tmin;
  r.tmax = kInfinity;
  return r;
}

// The reference's answers to the two questions exact.h answers.
bool reference_beyond(const Ray& r, const glm::vec3& p0, const glm::vec3& p1, const glm::vec3& p2) {
  test::QVec o = test::to_q(r.origin), d = test::to_q(r.direction), v0 = test::to_q(p0);
  test::QVec n = test::cross(test::sub(test::to_q(p1), v0), test::sub(test::to_q(p2), v0));
  mpq_class den = test::dot(n, d);
  if (sgn(den) == 0) return false;
  return test::dot(n, test::sub(v0, o)) / den > mpq_class(double(r.tmin));
}

TEST(Exact, RandomAndDegenerateInputsAgreeWithRationals) {
  std::mt19937 rng(5);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  int filtered_cases = 0, exact_cases = 0, beyond = 0;
  for (int i = 0; i < 20000; ++i) {
    float s = std::pow(10.f, float(int(rng() % 8) - 3));
    glm::vec3 p0 = s * glm::vec3(u(rng), u(rng), u(rng)), p1 = s * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 p2 = s * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 o = s * glm::vec3(u(rng), u(rng), u(rng)), d(u(rng), u(rng), u(rng));
    switch (i % 5) {
      case 1:  // an axis-aligned triangle and an origin exactly on its plane
        p1.z = p2.z = o.z = p0.z;
        break;
      case 2:  // a direction exactly parallel to an axis-aligned triangle's plane
        p1.y = p2.y = p0.y;
        d.y = 0.f;
        break;
      case 3:  // a ray through a vertex exactly: d = p1 - o is exact for these small integers
        p0 = glm::vec3(float(rng() % 9), float(rng() % 9), 1.f), p1 = glm::vec3(2.f, 3.f, float(rng() % 5));
        p2 = glm::vec3(float(rng() % 9), 5.f, 7.f), o = glm::vec3(0.f, 1.f, -3.f), d = p1 - o;
        break;
      case 4:  // a ray through the midpoint of an edge exactly (integers: the halves are exact)
        p0 = glm::vec3(2.f * float(rng() % 5), 0.f, 4.f), p1 = glm::vec3(4.f, 2.f * float(rng() % 5), 0.f);
        p2 = glm::vec3(-3.f, 1.f, float(rng() % 7)), o = glm::vec3(1.f, -2.f, -5.f), d = 0.5f * (p0 + p1) - o;
        break;
      default:
        break;
    }
    float tmin = i % 3 == 0 ? 0.f : u(rng) * 2.f;
    Ray r = make_ray(o, d, tmin);
    exact_counters() = {};
    // orient3d: the side of the plane the origin is on, as the reference's det[p0 - o, p1 - o, p2 - o].
    EXPECT_EQ(orientation(p0, p1, p2, o), sgn(test::det(test::sub(test::to_q(p0), test::to_q(o)),
                                                        test::sub(test::to_q(p1), test::to_q(o)),
                                                        test::sub(test::to_q(p2), test::to_q(o)))))
        << "case " << i;
    bool b = plane_hit_beyond(p0, p1, p2, o, d, tmin);
    EXPECT_EQ(b, reference_beyond(r, p0, p1, p2)) << "case " << i;
    beyond += b;
    int signs[3];
    edge_signs(p0, p1, p2, o, d, signs);
    test::ExactHit ref = test::exact_ray_triangle(r, p0, p1, p2);
    for (int e = 0; e < 3; ++e) EXPECT_EQ(signs[e], ref.edge[e]) << "case " << i << " edge " << e;
    filtered_cases += exact_counters().exact == 0;
    exact_cases += exact_counters().exact > 0;
    // The whole test on the exact path: a hit exactly when the reference hits, inside (tmin, tmax).
    float t, b0, b1, b2;
    bool hit = exact_triangle_hit(p0, p1, p2, o, d, tmin, kInfinity, &t, &b0, &b1, &b2);
    EXPECT_EQ(hit, ref.hit) << "case " << i;
    if (hit && ref.hit) {
      EXPECT_GT(t, tmin);
      EXPECT_NEAR(t, ref.t.get_d(), 1e-5 * std::fabs(ref.t.get_d()) + 1e-30) << "case " << i;
      EXPECT_GE(std::min({b0, b1, b2}), 0.f);
      EXPECT_NEAR(b0 + b1 + b2, 1.f, 1e-6f);
    }
  }
  // The double filter settles the ordinary inputs; the degenerate ones need the rationals.
  EXPECT_GT(filtered_cases, 5000);
  EXPECT_GT(exact_cases, 5000);
  EXPECT_GT(beyond, 3000);
}

TEST(Exact, OriginOnThePlaneIsNotBeyondTminZero) {
  const glm::vec3 p0(0.f, 0.f, 0.f), p1(1.f, 0.f, 0.f), p2(0.f, 1.f, 0.f);
  // t* = 0 exactly: not beyond tmin = 0, beyond any negative tmin and -inf.
  EXPECT_FALSE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, 0.f}, {0.f, 0.f, -1.f}, 0.f));
  EXPECT_TRUE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, 0.f}, {0.f, 0.f, -1.f}, -1e-30f));
  EXPECT_TRUE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, 0.f}, {0.f, 0.f, -1.f}, -kInfinity));
  // The smallest step off the plane decides it: above the plane looking down is beyond 0, below it is not.
  EXPECT_TRUE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, 1e-45f}, {0.f, 0.f, -1.f}, 0.f));
  EXPECT_FALSE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, -1e-45f}, {0.f, 0.f, -1.f}, 0.f));
  // Parallel to the plane: never.
  EXPECT_FALSE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, 1.f}, {1.f, 0.f, 0.f}, -kInfinity));
  // Non-finite inputs answer false.
  EXPECT_FALSE(plane_hit_beyond(p0, p1, p2, {0.25f, 0.25f, 1.f}, {0.f, 0.f, -1.f}, std::nanf("")));
  EXPECT_FALSE(plane_hit_beyond(p0, p1, p2, {kInfinity, 0.25f, 1.f}, {0.f, 0.f, -1.f}, 0.f));
}

}  // namespace
}  // namespace raystep
