// raystep_bench_kernels: nanoseconds per test of the geometric kernels on randomised inputs prepared outside
// the timed loop: the watertight triangle test (hits and misses, with the per-ray set-up hoisted as in an
// accelerator, and including it), Möller–Trumbore on the same inputs, the slab test and the sphere test.
#include <benchmark/benchmark.h>

#include <cmath>
#include <random>
#include <vector>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/sphere.h"
#include "raystep/geometry/triangle.h"
#include "raystep/geometry/triangle_moller.h"

namespace raystep {
namespace {

constexpr size_t kCases = 4096;  // a power of two; small enough to stay in cache, large enough to vary
constexpr size_t kMask = kCases - 1;

struct TriangleCase {
  glm::vec3 p0, p1, p2;
  Ray ray;
};

// Random triangles of size ~1 in a box of 10; rays from 5 units away aimed inside (hit) or just outside
// (miss: barycentrics beyond an edge, the expensive kind of miss that passes the early tests).
std::vector<TriangleCase> triangle_cases(bool hit, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.05f, 0.9f);
  std::vector<TriangleCase> cases(kCases);
  for (TriangleCase& c : cases) {
    glm::vec3 centre = 5.f * glm::vec3(u(rng), u(rng), u(rng));
    c.p0 = centre + glm::vec3(u(rng), u(rng), u(rng));
    c.p1 = centre + glm::vec3(u(rng), u(rng), u(rng));
    c.p2 = centre + glm::vec3(u(rng), u(rng), u(rng));
    float b1 = w(rng), b2 = w(rng) * (1.f - b1);
    if (!hit) b1 = -b1;
    glm::vec3 target = (1.f - b1 - b2) * c.p0 + b1 * c.p1 + b2 * c.p2;
    c.ray.origin = target + 5.f * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    c.ray.direction = glm::normalize(target - c.ray.origin);
  }
  return cases;
}

void BM_TriangleWatertight(benchmark::State& state) {
  std::vector<TriangleCase> cases = triangle_cases(state.range(0), 1);
  std::vector<WatertightRay> prepared;
  for (const TriangleCase& c : cases) prepared.emplace_back(c.ray);
  size_t i = 0;
  for (auto _ : state) {
    const TriangleCase& c = cases[i];
    TriangleHit h;
    benchmark::DoNotOptimize(intersect_triangle(prepared[i], c.p0, c.p1, c.p2, c.ray.tmax, &h));
    benchmark::DoNotOptimize(h);
    i = (i + 1) & kMask;
  }
  state.SetLabel(state.range(0) ? "hit" : "miss");
}
BENCHMARK(BM_TriangleWatertight)->Arg(1)->Arg(0);

// Including the per-ray shear set-up (what a single isolated test costs).
void BM_TriangleWatertightWithRaySetup(benchmark::State& state) {
  std::vector<TriangleCase> cases = triangle_cases(state.range(0), 1);
  size_t i = 0;
  for (auto _ : state) {
    const TriangleCase& c = cases[i];
    TriangleHit h;
    benchmark::DoNotOptimize(intersect_triangle(c.ray, c.p0, c.p1, c.p2, &h));
    benchmark::DoNotOptimize(h);
    i = (i + 1) & kMask;
  }
  state.SetLabel(state.range(0) ? "hit" : "miss");
}
BENCHMARK(BM_TriangleWatertightWithRaySetup)->Arg(1)->Arg(0);

void BM_TriangleMollerTrumbore(benchmark::State& state) {
  std::vector<TriangleCase> cases = triangle_cases(state.range(0), 1);
  size_t i = 0;
  for (auto _ : state) {
    const TriangleCase& c = cases[i];
    TriangleHit h;
    benchmark::DoNotOptimize(intersect_triangle_moller(c.ray, c.p0, c.p1, c.p2, &h));
    benchmark::DoNotOptimize(h);
    i = (i + 1) & kMask;
  }
  state.SetLabel(state.range(0) ? "hit" : "miss");
}
BENCHMARK(BM_TriangleMollerTrumbore)->Arg(1)->Arg(0);

// Slab test: boxes of size 0.1..2 in a box of 10, rays from random points with random directions
// (about half hit), the reciprocal direction prepared once per ray as in a traversal.
void BM_Slab(benchmark::State& state) {
  std::mt19937 rng(2);
  std::uniform_real_distribution<float> u(-1.f, 1.f), s(0.05f, 1.f);
  std::vector<Bounds3> boxes;
  std::vector<SlabRay> rays;
  int hits = 0;
  for (size_t k = 0; k < kCases; ++k) {
    glm::vec3 c = 5.f * glm::vec3(u(rng), u(rng), u(rng));
    glm::vec3 half(s(rng), s(rng), s(rng));
    boxes.emplace_back(c - half, c + half);
    Ray r;
    r.origin = c + 4.f * glm::vec3(u(rng), u(rng), u(rng));
    r.direction = glm::normalize(c + 0.8f * glm::vec3(u(rng), u(rng), u(rng)) - r.origin);
    rays.emplace_back(r);
    hits += intersect_slabs(boxes.back(), rays.back(), nullptr, nullptr);
  }
  size_t i = 0;
  for (auto _ : state) {
    float t0, t1;
    benchmark::DoNotOptimize(intersect_slabs(boxes[i], rays[i], &t0, &t1));
    benchmark::DoNotOptimize(t0);
    benchmark::DoNotOptimize(t1);
    i = (i + 1) & kMask;
  }
  state.SetLabel(std::to_string(100 * hits / int(kCases)) + "% hits");
}
BENCHMARK(BM_Slab);

// Sphere test: spheres of radius 0.2..1, rays aimed at points up to ~2 radii from the centre (about half
// hit).
void BM_Sphere(benchmark::State& state) {
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> u(-1.f, 1.f), s(0.2f, 1.f);
  std::vector<Sphere> spheres;
  std::vector<Ray> rays;
  int hits = 0;
  for (size_t k = 0; k < kCases; ++k) {
    Sphere sp{5.f * glm::vec3(u(rng), u(rng), u(rng)), s(rng)};
    Ray r;
    r.origin = sp.center + 5.f * glm::normalize(glm::vec3(u(rng), u(rng), u(rng)));
    r.direction = glm::normalize(sp.center + 1.2f * sp.radius * glm::vec3(u(rng), u(rng), u(rng)) - r.origin);
    spheres.push_back(sp);
    rays.push_back(r);
    float t;
    hits += intersect_sphere(r, sp, r.tmax, &t);
  }
  size_t i = 0;
  for (auto _ : state) {
    float t;
    benchmark::DoNotOptimize(intersect_sphere(rays[i], spheres[i], rays[i].tmax, &t));
    benchmark::DoNotOptimize(t);
    i = (i + 1) & kMask;
  }
  state.SetLabel(std::to_string(100 * hits / int(kCases)) + "% hits");
}
BENCHMARK(BM_Sphere);

}  // namespace
}  // namespace raystep

BENCHMARK_MAIN();
