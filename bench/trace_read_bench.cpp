// Reading trace files (read_trace_json, the validating reader the debugger opens traces with): the aim is
// <= 0.4 s for a trace of 100,000 events. The traces are recorded here, through the core, and written to the
// temporary directory once:
//   grid_rays      ~100,000 events of camera rays through the bunny's grid (d = 3): cells, tests, mailboxes
//   grid_one_cell  the bunny in a 1x1x1 grid, pixel 160,120 with its shadow ray: 138,909 events and all
//                  69,451 triangles in the geometry; the same file as
//                  `raystep trace stanford-bunny.obj --grid-res 1,1,1 --pixel 160,120 --secondary -o t.json`
//   kd_rays        ~100,000 events of camera rays through the bunny's SAH kd-tree: nodes, pushes, pops, leaves
// Further trace files named on the command line (after the benchmark flags) are read too.
// The mesh is ../shared/meshes/stanford-bunny.obj; without it, a generated sphere of 80,000 triangles.
#include <benchmark/benchmark.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <memory>

#include "bench_util.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/render/camera.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"
#include "raystep/trace/trace_file.h"

namespace raystep {
namespace {

size_t event_count(const Trace& t) {
  size_t n = 0;
  for (const TracedRay& r : t.rays) n += r.events.size();
  return n;
}

// Camera rays of a 320x240 picture, as many as make about `target` events.
Trace camera_trace(const Scene& scene, const Accelerator& accel, size_t target) {
  std::vector<RayRequest> all;
  std::vector<Ray> rays = camera_rays(scene.camera, 320, 240);
  for (size_t i = 0; i < rays.size(); ++i) {
    RayRequest q;
    q.ray = rays[i];
    q.has_pixel = true;
    q.pixel[0] = int(i % 320);
    q.pixel[1] = int(i / 320);
    all.push_back(q);
  }
  // Only rays that hit make long walks: take the rows through the middle of the picture first.
  std::vector<RayRequest> chosen;
  size_t events = 0;
  for (size_t row = 0; row < 240 && events < target; ++row) {
    size_t y = (120 + (row % 2 ? -1 : 1) * int(row + 1) / 2) % 240;
    std::vector<RayRequest> line(all.begin() + y * 320, all.begin() + (y + 1) * 320);
    events += event_count(record_trace(scene.geometry, accel, line, "bench", "fnv1a64:0000000000000000"));
    chosen.insert(chosen.end(), line.begin(), line.end());
  }
  return record_trace(scene.geometry, accel, chosen, "bench", "fnv1a64:0000000000000000");
}

struct TraceFiles {
  std::vector<std::pair<std::string, std::string>> files;  // name, path
  TraceFiles() {
    Scene scene = bench::bench_scene();
    std::string dir = std::filesystem::temp_directory_path().string();
    auto write = [&](const std::string& name, const Trace& t) {
      std::string path = dir + "/raystep_bench_" + name + ".json";
      write_trace_json(path, t);
      std::fprintf(stderr, "%s: %zu events, %zu primitives, %zu cells, %zu nodes, %.1f MB (%s)\n", name.c_str(),
                   event_count(t), t.primitives.size(), t.cells.size(), t.nodes.size(),
                   double(std::filesystem::file_size(path)) / 1e6, path.c_str());
      files.emplace_back(name, path);
    };
    {
      UniformGrid grid;
      grid.build(scene.geometry);
      write("grid_rays", camera_trace(scene, grid, 100000));
    }
    {
      GridOptions o;
      o.resolution = std::array<int, 3>{1, 1, 1};
      UniformGrid grid(o);
      grid.build(scene.geometry);
      write("grid_one_cell", record_trace(scene.geometry, grid, pixel_rays(scene, grid, 320, 240, 160, 120, true),
                                          "bench", "fnv1a64:0000000000000000"));
    }
    {
      KdTree kd;
      kd.build(scene.geometry);
      write("kd_rays", camera_trace(scene, kd, 100000));
    }
  }
};

void BM_ReadTrace(benchmark::State& state, std::string path) {
  size_t events = 0;
  for (auto _ : state) {
    Trace t = read_trace_json(path);
    events = event_count(t);
    benchmark::DoNotOptimize(t.rays.data());
  }
  state.counters["events"] = double(events);
  state.counters["MB"] = double(std::filesystem::file_size(path)) / 1e6;
}

}  // namespace
}  // namespace raystep

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  std::vector<std::pair<std::string, std::string>> files = raystep::TraceFiles().files;
  for (int i = 1; i < argc; ++i) files.emplace_back(std::filesystem::path(argv[i]).filename().string(), argv[i]);
  for (const auto& [name, path] : files)
    benchmark::RegisterBenchmark(("BM_ReadTrace/" + name).c_str(), raystep::BM_ReadTrace, path)
        ->Unit(benchmark::kMillisecond)
        ->Iterations(1)
        ->Repetitions(5)
        ->ComputeStatistics("min", [](const std::vector<double>& v) { return *std::min_element(v.begin(), v.end()); });
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
}
