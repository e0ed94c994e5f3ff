// The grid's traversal kernel with each recorder: the null recorder must cost nothing (it times like the
// hook-free copy in grid_hookfree.h), and the counting recorder's overhead is measured (aim: <= 1.2x).
// Rays: primary rays of the mesh's camera; the mesh is ../shared/meshes/stanford-bunny.obj when present,
// otherwise a generated sphere of small triangles, so the benchmark always runs.
#include <benchmark/benchmark.h>

#include <filesystem>
#include <memory>
#include <random>

#include "grid_hookfree.h"
#include "raystep/accel/grid.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/scene_loader.h"

namespace raystep {
namespace {

struct Fixture {
  Scene scene;
  std::unique_ptr<UniformGrid> grid;
  std::vector<Ray> rays;

  Fixture() {
    std::string mesh = std::string(RAYSTEP_SOURCE_DIR) + "/../shared/meshes/stanford-bunny.obj";
    if (std::filesystem::exists(mesh)) {
      scene = load_scene(mesh);
    } else {
      // A sphere of 80,000 small triangles: a stand-in with a mesh's structure.
      scene.geometry.begin_object("sphere", 0);
      const int rings = 200, segments = 200;
      auto p = [&](int i, int j) {
        float th = 3.14159265f * i / rings, ph = 6.2831853f * j / segments;
        return glm::vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
      };
      for (int i = 0; i < rings; ++i)
        for (int j = 0; j < segments; ++j) {
          scene.geometry.add_triangle(p(i, j), p(i + 1, j), p(i + 1, j + 1));
          scene.geometry.add_triangle(p(i, j), p(i + 1, j + 1), p(i, j + 1));
        }
      scene.camera.eye = glm::vec3(0.f, 0.5f, 3.5f);
    }
    grid = std::make_unique<UniformGrid>();
    grid->build(scene.geometry);
    rays = camera_rays(scene.camera, 256, 256);
  }
};

Fixture& fixture() {
  static Fixture f;
  return f;
}

void BM_GridHookFree(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state)
    for (const Ray& r : f.rays) {
      Hit h;
      benchmark::DoNotOptimize(bench::grid_intersect_hookfree(*f.grid, r, &h));
    }
  state.SetItemsProcessed(state.iterations() * int64_t(f.rays.size()));
}

void BM_GridNullRecorder(benchmark::State& state) {
  Fixture& f = fixture();
  for (auto _ : state)
    for (const Ray& r : f.rays) {
      Hit h;
      NullRecorder rec;
      benchmark::DoNotOptimize(f.grid->traverse(r, &h, false, rec));
    }
  state.SetItemsProcessed(state.iterations() * int64_t(f.rays.size()));
}

void BM_GridCountingRecorder(benchmark::State& state) {
  Fixture& f = fixture();
  CountingRecorder rec;
  for (auto _ : state)
    for (const Ray& r : f.rays) {
      Hit h;
      benchmark::DoNotOptimize(f.grid->traverse(r, &h, false, rec));
    }
  benchmark::DoNotOptimize(rec.cells);
  state.SetItemsProcessed(state.iterations() * int64_t(f.rays.size()));
}

BENCHMARK(BM_GridHookFree)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_GridNullRecorder)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);
BENCHMARK(BM_GridCountingRecorder)->Unit(benchmark::kMillisecond)->Repetitions(5)->ReportAggregatesOnly(true);

}  // namespace
}  // namespace raystep

BENCHMARK_MAIN();
