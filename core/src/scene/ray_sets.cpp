#include "raystep/scene/ray_sets.h"

#include <cmath>
#include <random>

#include <glm/common.hpp>

#include "raystep/util/error.h"

namespace raystep {
namespace {

// std::mt19937_64's output sequence is fixed by the standard; the conversions below are ours, so a seed
// gives the same rays with every standard library (distributions in <random> are implementation-defined).
struct Rng {
  std::mt19937_64 engine;
  explicit Rng(uint64_t seed) : engine(seed) {}
  float uniform() { return float(engine() >> 40) * 0x1p-24f; }  // [0, 1) with 24 random bits
  uint64_t below(uint64_t n) { return engine() % n; }
};

glm::vec3 uniform_in(Rng& rng, const Bounds3& b) {
  glm::vec3 p;
  for (int a = 0; a < 3; ++a) p[a] = b.lo[a] + rng.uniform() * (b.hi[a] - b.lo[a]);
  return glm::clamp(p, b.lo, b.hi);  // rounding must not step outside the box
}

// Archimedes: z uniform in [-1, 1] and an independent uniform angle give a uniform point on the sphere.
glm::vec3 uniform_direction(Rng& rng) {
  float z = 1.f - 2.f * rng.uniform();
  float r = std::sqrt(std::fmax(0.f, 1.f - z * z));
  float phi = 2.f * 3.14159265358979f * rng.uniform();
  return glm::vec3(r * std::cos(phi), r * std::sin(phi), z);
}

}  // namespace

Bounds3 ray_origin_bounds(const Bounds3& b) {
  glm::vec3 c = b.center(), half = 0.75f * b.extent();
  return Bounds3(c - half, c + half);
}

std::vector<Ray> random_rays(const Bounds3& b, size_t count, uint64_t seed) {
  if (b.empty()) throw InputError("", 0, "random rays need non-empty bounds");
  Bounds3 origins = ray_origin_bounds(b);
  Rng rng(seed);
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    r.origin = uniform_in(rng, origins);
    r.direction = uniform_direction(rng);
    r.tmin = 0.f;
    r.tmax = kInfinity;
  }
  return rays;
}

std::vector<glm::vec3> edge_targets(const Geometry& g, size_t count, uint64_t seed) {
  std::vector<uint32_t> triangles;
  for (uint32_t id = 0; id < g.size(); ++id)
    if (g.type(id) == PrimType::triangle) triangles.push_back(id);
  if (triangles.empty()) throw InputError("", 0, "edge rays need a mesh with triangles");
  Rng rng(seed);
  std::vector<glm::vec3> targets(count);
  for (size_t i = 0; i < count; ++i) {
    uint32_t id = triangles[rng.below(triangles.size())];
    int k = int(rng.below(3));
    if (i % 2 == 0) {
      targets[i] = g.vertex(id, k);  // a vertex: bit-identical in every triangle that shares it
    } else {
      // f = k/16 is exact in binary, so the point is off the edge line by a few roundings only, as near as
      // floats allow.
      float f = float(1 + rng.below(15)) / 16.f;
      const glm::vec3& p0 = g.vertex(id, k);
      const glm::vec3& p1 = g.vertex(id, k == 2 ? 0 : k + 1);
      targets[i] = p0 + f * (p1 - p0);
    }
  }
  return targets;
}

std::vector<Ray> edge_rays(const Geometry& g, size_t count, uint64_t seed) {
  std::vector<glm::vec3> targets = edge_targets(g, count, seed);
  Bounds3 origins = ray_origin_bounds(g.bounds());
  Rng rng(seed ^ 0x9e3779b97f4a7c15ull);  // a stream independent of the targets'
  std::vector<Ray> rays(count);
  for (size_t i = 0; i < count; ++i) {
    rays[i].origin = uniform_in(rng, origins);
    rays[i].direction = targets[i] - rays[i].origin;
    rays[i].tmin = 0.f;
    rays[i].tmax = kInfinity;
  }
  return rays;
}

}  // namespace raystep
