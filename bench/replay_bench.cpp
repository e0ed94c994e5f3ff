// Stepping through a ray of ten million events (core/replay/replayer.h): a step forward, a step back and a
// jump, each from the checkpoint before it; the aim is at most 20 ms a step. The ray is a real walk, recorded
// through the grid's kernel: a grid of 4096 x 2 x 1 cells over 2,441 slivers that lie along the ray without
// touching it, each in every cell of the ray's row. The first cell tests them all, every later cell finds
// each one in the mailbox: 1 + 4,096 cells x (1 + 2,441) + 1 = 10,002,434 events in one ray. (330,000 specks
// in the other row of cells, which the ray never enters, raise the grid's reference budget, 32 a primitive,
// above the slivers' ten million references.)
//   raystep_bench_replay [benchmark flags] [--write PATH]
// --write also writes the trace file, for the read's peak memory (bench/README.md, "Debugger responsiveness"):
//   /usr/bin/time -v build/cli/raystep replay PATH --step 5001217 --format json -o /tmp/state.json
#include <benchmark/benchmark.h>

#include <chrono>
#include <cstdio>
#include <cstring>
#include <random>
#include <string>

#include "raystep/accel/grid.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/replayer.h"
#include "raystep/replay/storyboard.h"
#include "raystep/trace/record_trace.h"
#include "raystep/trace/trace_file.h"

namespace raystep {
namespace {

constexpr int kSlivers = 2441, kCells = 4096, kSpecks = 330000;

// Slivers along x in the lower row of cells (y < 0.5), at heights spread over y and z, none on the ray's line
// (y = 0.3, z = 0.5); specks in the upper row.
Geometry long_walk_geometry() {
  Geometry g;
  g.begin_object("slivers", 0);
  for (int k = 0; k < kSlivers; ++k) {
    const float f = (k + 0.5f) / kSlivers, y = 0.1f + 0.35f * f, z = 0.2f + 0.6f * f;
    g.add_triangle(glm::vec3(0.f, y, z), glm::vec3(1.f, y, z), glm::vec3(1.f, y + 1e-4f, z));
  }
  g.begin_object("specks", 0);
  std::mt19937 rng(3);
  std::uniform_real_distribution<float> x(0.f, 1.f), y(0.6f, 0.9f), z(0.2f, 0.8f);
  for (int k = 0; k < kSpecks; ++k) {
    const glm::vec3 p(x(rng), y(rng), z(rng));
    g.add_triangle(p, p + glm::vec3(1e-5f, 0.f, 0.f), p + glm::vec3(0.f, 1e-5f, 0.f));
  }
  return g;
}

double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

}  // namespace
}  // namespace raystep

int main(int argc, char** argv) {
  using namespace raystep;
  std::string write;
  for (int i = 1; i < argc; ++i)
    if (std::strcmp(argv[i], "--write") == 0 && i + 1 < argc) {
      write = argv[i + 1];
      for (int j = i; j + 2 <= argc; ++j) argv[j] = argv[j + 2];
      argc -= 2;
      break;
    }
  benchmark::Initialize(&argc, argv);

  auto t0 = std::chrono::steady_clock::now();
  const Geometry g = long_walk_geometry();
  GridOptions o;
  o.resolution = std::array<int, 3>{kCells, 2, 1};
  UniformGrid grid(o);
  grid.build(g);
  RayRequest r;
  r.ray.origin = glm::vec3(-0.5f, 0.3f, 0.5f);
  r.ray.direction = glm::vec3(1.f, 0.f, 0.f);
  const Trace trace = record_trace(g, grid, {r}, "long-walk", "fnv1a64:0000000000000000");
  const TracedRay& ray = trace.rays[0];
  std::printf("recorded %zu events in %.1f s\n", ray.events.size(), seconds_since(t0));
  if (!write.empty()) {
    t0 = std::chrono::steady_clock::now();
    write_trace_json(write, trace);
    std::printf("wrote %s in %.1f s\n", write.c_str(), seconds_since(t0));
  }
  t0 = std::chrono::steady_clock::now();
  const replay::Replayer replayer(ray);
  std::printf("replayer (checkpoints every %d events) built in %.2f s\n", replay::Replayer::kCheckpointEvery,
              seconds_since(t0));
  const int n = replayer.size(), middle = n / 2;

  benchmark::RegisterBenchmark("BM_StepForward", [&](benchmark::State& st) {
    int k = middle;
    for (auto _ : st) benchmark::DoNotOptimize(replayer.at(++k));
  })->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_StepBack", [&](benchmark::State& st) {
    int k = middle;
    for (auto _ : st) benchmark::DoNotOptimize(replayer.at(--k));
  })->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_JumpAnywhere", [&](benchmark::State& st) {
    std::mt19937 rng(7);
    std::uniform_int_distribution<int> any(0, n - 1);
    for (auto _ : st) benchmark::DoNotOptimize(replayer.at(any(rng)));
  })->Unit(benchmark::kMillisecond);
  benchmark::RegisterBenchmark("BM_JumpToTheEnd", [&](benchmark::State& st) {
    for (auto _ : st) benchmark::DoNotOptimize(replayer.at(n - 1));
  })->Unit(benchmark::kMillisecond);
  // What a front end prints at a step: the state as the storyboard's JSON, the Why text included.
  benchmark::RegisterBenchmark("BM_StateJsonAtTheMiddle", [&](benchmark::State& st) {
    for (auto _ : st) benchmark::DoNotOptimize(replay::state_json(trace, ray, replayer.at(middle)));
  })->Unit(benchmark::kMillisecond);
  // Before checkpoints: every step replayed from event 0.
  benchmark::RegisterBenchmark("BM_FromEventZeroToTheMiddle", [&](benchmark::State& st) {
    for (auto _ : st) benchmark::DoNotOptimize(replay::replay_at(ray, middle));
  })->Unit(benchmark::kMillisecond)->Iterations(3);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
