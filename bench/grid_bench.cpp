// The grid's traversal kernel with each recorder: the null recorder must cost nothing (it times like the
// hook-free copy in grid_hookfree.h), and the counting recorder's overhead is measured (aim: <= 1.2x).
// Rays: primary rays of the mesh's camera; the mesh is ../shared/meshes/stanford-bunny.obj when present,
// otherwise a generated sphere of small triangles, so the benchmark always runs.
#include <benchmark/benchmark.h>

#include <memory>
#include <random>

#include "bench_util.h"
#include "grid_hookfree.h"
#include "raystep/accel/grid.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"

namespace raystep {
namespace {

struct Fixture {
  Scene scene;
  std::unique_ptr<UniformGrid> grid;
  std::vector<Ray> rays;

  Fixture() {
    scene = bench::bench_scene();
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
