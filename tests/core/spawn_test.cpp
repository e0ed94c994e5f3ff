// spawn.h: secondary rays leave a surface without hitting it again, at every scale. Per decade of coordinate
// magnitude from 1e-4 to 1e6: hit a triangle (and a sphere) with many rays, spawn reflected and transmitted
// rays from the hit point (rays arriving from both sides, outgoing directions down to grazing), and test
// them against the SAME primitive with tmin = 0. No re-hits; the origin lands strictly on the side the ray
// leaves by; and the offset is tiny next to the coordinates.
#include <gtest/gtest.h>

#include <cmath>
#include <random>

#include "raystep/geometry/spawn.h"
#include "raystep/geometry/sphere.h"
#include "raystep/geometry/triangle.h"

namespace raystep {
namespace {

glm::vec3 reflect(const glm::vec3& w, const glm::vec3& n) {
  return w - 2.f * glm::dot(w, n) * n;
}

// An outgoing direction on the side `side` (+1: along n) of the surface, at cosine `c` to the normal.
glm::vec3 leaving(const glm::vec3& n, const glm::vec3& tangent, float c, float side) {
  return side * c * n + std::sqrt(1.f - c * c) * tangent;
}

const float kCosines[] = {1.f, 0.5f, 0.1f, 1e-2f, 1e-3f};  // down to grazing

// A spawned ray starts beyond the hit point's own rounding region: 2 |p_error|_1 along the ray, whatever its length.
TEST(Spawn, StartsBeyondTheHitPointsRoundingRegion) {
  const glm::vec3 p(3.f, 0.f, -2.f), err(1e-6f, 0.f, 2e-6f), n(0.f, 1.f, 0.f);
  Ray r = spawn_ray(p, err, n, glm::vec3(0.f, 2.f, 0.f));
  EXPECT_FLOAT_EQ(r.tmin * 2.f, 6e-6f);
  Ray s = spawn_ray_to(p, err, n, glm::vec3(3.f, 10.f, -2.f));
  EXPECT_NEAR(s.tmin * glm::length(s.direction), 6e-6f, 1e-12f);
  EXPECT_LT(s.tmin, s.tmax);
  EXPECT_EQ(spawn_ray(p, glm::vec3(0.f), n, glm::vec3(0.f, 1.f, 0.f)).tmin, 0.f);
}

TEST(Spawn, NoSelfIntersectionOnTrianglesAtEveryScale) {
  std::mt19937 rng(12);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  for (int decade = -4; decade <= 6; ++decade) {
    const float scale = std::pow(10.f, float(decade));
    int spawned = 0, rehits = 0, wrong_side = 0;
    float worst_offset = 0.f;
    for (int i = 0; i < 2000; ++i) {
      // Triangles of the scale's size, or 1000x smaller, with coordinates of the scale's magnitude.
      float size = (i % 2) ? scale : scale * 1e-3f;
      glm::vec3 c = scale * glm::vec3(1.f + w(rng), -1.f - w(rng), 1.f + w(rng));
      glm::vec3 p0 = c + size * glm::vec3(u(rng), u(rng), u(rng));
      glm::vec3 p1 = c + size * glm::vec3(u(rng), u(rng), u(rng));
      glm::vec3 p2 = c + size * glm::vec3(u(rng), u(rng), u(rng));
      glm::vec3 n = triangle_normal(p0, p1, p2);
      if (!(glm::length(n) > 0.f)) continue;
      glm::vec3 nn = glm::normalize(n);
      float b1 = w(rng), b2 = w(rng);
      if (b1 + b2 > 1.f) b1 = 1.f - b1, b2 = 1.f - b2;
      glm::vec3 target = (1.f - b1 - b2) * p0 + b1 * p1 + b2 * p2;
      float from_side = (i % 4 < 2) ? 1.f : -1.f;  // incoming from the front or the back
      glm::vec3 origin = target + from_side * size * (2.f * nn + glm::vec3(u(rng), u(rng), u(rng)));
      Ray in = Ray{origin, target - origin};
      TriangleHit h;
      if (!intersect_triangle(in, p0, p1, p2, &h)) continue;
      glm::vec3 err;
      glm::vec3 p = triangle_point(h, p0, p1, p2, &err);
      glm::vec3 tangent = glm::normalize(glm::cross(nn, glm::vec3(u(rng), u(rng), u(rng))));
      float in_side = glm::dot(in.direction, nn) < 0.f ? 1.f : -1.f;  // the side the ray came from
      std::vector<glm::vec3> outgoing = {reflect(glm::normalize(in.direction), nn), in.direction};
      for (float cosine : kCosines) {
        outgoing.push_back(leaving(nn, tangent, cosine, in_side));   // reflected, down to grazing
        outgoing.push_back(leaving(nn, tangent, cosine, -in_side));  // transmitted, down to grazing
      }
      float magnitude = std::fmax(std::fabs(c.x), std::fmax(std::fabs(c.y), std::fabs(c.z)));
      for (const glm::vec3& dir : outgoing) {
        Ray out = spawn_ray(p, err, n, dir);
        out.tmin = 0.f;  // the offset alone must keep the ray off its surface
        ++spawned;
        TriangleHit again;
        rehits += intersect_triangle(out, p0, p1, p2, &again);
        // The origin is strictly on the leaving side of the exact plane (double arithmetic).
        glm::dvec3 nd = glm::cross(glm::dvec3(p1) - glm::dvec3(p0), glm::dvec3(p2) - glm::dvec3(p0));
        double side = glm::dot(nd, glm::dvec3(out.origin) - glm::dvec3(p0));
        wrong_side += !(side * glm::dot(glm::dvec3(dir), nd) > 0.0);
        worst_offset = std::fmax(worst_offset, glm::length(out.origin - p) / magnitude);
      }
      // Shadow ray towards a light on the arriving side.
      Ray shadow = spawn_ray_to(p, err, n, origin + size * glm::vec3(u(rng), u(rng), u(rng)));
      shadow.tmin = 0.f;
      ++spawned;
      rehits += intersect_triangle(shadow, p0, p1, p2, &h);
    }
    EXPECT_GT(spawned, 20000) << "scale " << scale;
    EXPECT_EQ(rehits, 0) << "scale " << scale;
    EXPECT_EQ(wrong_side, 0) << "scale " << scale;
    EXPECT_LT(worst_offset, 1e-4f) << "scale " << scale;
  }
}

// Spheres: a reflected ray leaving the outside, or a transmitted ray leaving the inside, must not hit the
// sphere again; a ray going into the sphere must find the far side (at least half the chord 2 r cos away).
TEST(Spawn, NoSelfIntersectionOnSpheresAtEveryScale) {
  std::mt19937 rng(13);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.f, 1.f);
  for (int decade = -4; decade <= 6; ++decade) {
    const float scale = std::pow(10.f, float(decade));
    int spawned = 0, rehits = 0, short_chords = 0;
    float worst_offset = 0.f;
    for (int i = 0; i < 2000; ++i) {
      float radius = (i % 2) ? scale * (0.5f + w(rng)) : scale * 1e-3f;
      Sphere s{scale * glm::vec3(1.f + w(rng), -1.f - w(rng), 1.f + w(rng)), radius};
      // From outside (aimed at a point inside), or from the centre.
      bool from_inside = i % 3 == 0;
      glm::vec3 origin = from_inside
                             ? s.center
                             : s.center + 3.f * radius * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
      glm::vec3 aim = s.center + 0.9f * radius * glm::vec3(u(rng), u(rng), u(rng)) / std::sqrt(3.f);
      Ray in = Ray{origin, from_inside ? glm::vec3(u(rng), u(rng), u(rng)) : aim - origin};
      float t;
      if (!intersect_sphere(in, s, in.tmax, &t)) continue;
      glm::vec3 err;
      glm::vec3 p = sphere_point(in, s, t, &err);
      glm::vec3 n = p - s.center;
      glm::vec3 nn = glm::normalize(n);
      glm::vec3 tangent = glm::normalize(glm::cross(nn, glm::vec3(u(rng), u(rng), u(rng))));
      float magnitude =
          std::fmax(std::fabs(s.center.x), std::fmax(std::fabs(s.center.y), std::fabs(s.center.z)));
      for (float side : {1.f, -1.f}) {  // leaving outwards, or inwards
        for (float cosine : kCosines) {
          glm::vec3 dir = leaving(nn, tangent, cosine, side);
          Ray out = spawn_ray(p, err, n, dir);
          out.tmin = 0.f;  // the offset alone must keep the ray off its surface
          ++spawned;
          worst_offset = std::fmax(worst_offset, glm::length(out.origin - p) / magnitude);
          float t2;
          bool again = intersect_sphere(out, s, out.tmax, &t2);
          if (side > 0) {
            rehits += again;
          } else {
            // Inwards: the far side, not the spawn point. Chord from the exact surface point: 2 r cos.
            double chord = 2.0 * radius * cosine;
            if (!again || double(t2) * glm::length(glm::dvec3(dir)) < 0.5 * chord) ++short_chords;
          }
        }
      }
    }
    EXPECT_GT(spawned, 15000) << "scale " << scale;
    EXPECT_EQ(rehits, 0) << "scale " << scale;
    EXPECT_EQ(short_chords, 0) << "scale " << scale;
    EXPECT_LT(worst_offset, 1e-4f) << "scale " << scale;
  }
}

}  // namespace
}  // namespace raystep
