#include "raystep/report/grid_sweep.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <string>

#include "raystep/accel/grid.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/util/error.h"
#include "camera_size.h"
#include "timing.h"

namespace raystep {

namespace {

using report_timing::cancelled;
using report_timing::Clock;
using report_timing::median;
using report_timing::seconds_since;

// The sweep's rays: one through each pixel centre of the (capped) camera image, then the random rays.
std::vector<Ray> sweep_rays(const Scene& scene, const GridSweepOptions& options) {
  int w = options.camera_width, h = options.camera_height;
  report_camera_size(scene, 256, &w, &h);
  std::vector<Ray> rays = camera_rays(scene.camera, w, h);
  if (options.random_rays > 0) {
    std::vector<Ray> random = random_rays(scene.geometry.bounds(), options.random_rays, options.seed);
    rays.insert(rays.end(), random.begin(), random.end());
  }
  return rays;
}

}  // namespace

GridSweep run_grid_sweep(const Scene& scene, const GridSweepOptions& options,
                         const std::function<void(const GridSweepRow&)>& row_done,
                         const std::atomic<bool>* cancel) {
  std::vector<float> densities = options.densities;
  if (densities.empty()) densities = {0.5f, 0.75f, 1.f, 1.5f, 2.f, 3.f, 4.f, 6.f, 8.f};
  for (float d : densities)
    if (!(d > 0.f && d <= 64.f))
      throw InputError("", 0, "grid density " + std::to_string(d) + " is outside (0, 64]");
  if (options.reps < 1 || options.reps > 1000) throw InputError("", 0, "grid sweep: reps must be 1..1000");
  if (options.random_rays > (uint64_t(1) << 26))
    throw InputError("", 0, "grid sweep: at most 67108864 random rays");
  if (scene.geometry.size() == 0)
    throw InputError(scene.path, 0, "the scene has no primitives to sweep a grid over");

  GridSweep sweep;
  sweep.primitives = scene.geometry.size();
  const std::vector<Ray> rays = sweep_rays(scene, options);
  sweep.rays = rays.size();
  const double ray_count = double(std::max<size_t>(rays.size(), 1));
  // Cancel is looked at every this many rays, so that a GUI's Stop takes effect within milliseconds.
  constexpr size_t kCancelStride = 4096;

  for (float d : densities) {
    if (cancelled(cancel)) break;
    GridSweepRow row;
    row.density = d;

    // Build at density d with the grid's normal options (exact insertion, the reference budget).
    GridOptions grid_options;
    grid_options.density = d;
    UniformGrid grid(grid_options);
    auto t0 = Clock::now();
    grid.build(scene.geometry);
    row.build_seconds = seconds_since(t0);
    row.resolution = grid.resolution();
    row.cells = uint64_t(row.resolution[0]) * uint64_t(row.resolution[1]) * uint64_t(row.resolution[2]);
    row.references_per_prim = double(grid.reference_count()) / double(sweep.primitives);
    row.bytes = double(grid.memory_bytes());
    row.coarsened = grid.coarsened();

    // The work per ray, counted once (the counts do not depend on the pass).
    CountingRecorder counts;
    bool stop = false;
    for (size_t i = 0; i < rays.size() && !stop; ++i) {
      Hit hit;
      grid.intersect_counted(rays[i], &hit, counts);
      stop = i % kCancelStride == 0 && cancelled(cancel);
    }
    if (stop) break;
    row.cells_per_ray = double(counts.cells) / ray_count;
    row.tests_per_ray = double(counts.prim_tests) / ray_count;
    row.mailbox_per_ray = double(counts.mailbox_hits) / ray_count;

    // The time of a pass with the uninstrumented kernel: the median of reps passes.
    std::vector<double> passes;
    for (int r = 0; r < options.reps && !stop; ++r) {
      auto t1 = Clock::now();
      for (size_t i = 0; i < rays.size(); ++i) {
        Hit hit;
        grid.intersect(rays[i], &hit);
        if (i % kCancelStride == 0 && cancelled(cancel)) {
          stop = true;
          break;
        }
      }
      passes.push_back(seconds_since(t1));
    }
    if (stop) break;
    row.trace_seconds = median(passes);
    row.mrays_per_second = row.trace_seconds > 0 ? double(rays.size()) / row.trace_seconds * 1e-6 : 0.0;

    sweep.rows.push_back(row);
    if (row_done) row_done(sweep.rows.back());
  }
  return sweep;
}

}  // namespace raystep
