// The grid's resolution rule put to the test: max(nx, ny, nz) = d * cbrt(n) for d from 0.5 to 8, each grid
// built and traced, with cells and tests per ray, references per primitive, and build and trace times.
// `raystep grid-sweep` writes it; the debugger's sweep chart shows it with a slider that rebuilds the grid.
#pragma once

#include <array>
#include <atomic>
#include <functional>
#include <vector>

#include "raystep/geometry/ray.h"
#include "raystep/scene/scene.h"

namespace raystep {

struct GridSweepOptions {
  std::vector<float> densities;  // empty: 0.5, 0.75, 1, 1.5, 2, 3, 4, 6, 8
  int camera_width = 0, camera_height = 0;  // primary rays (0: the scene's size, capped at 256 x 256)
  uint64_t random_rays = 65536;             // random rays through the bounds (0: none)
  uint64_t seed = 1;
  int reps = 3;                             // timed passes; the median is reported
};

struct GridSweepRow {
  float density = 0.f;
  std::array<int, 3> resolution{1, 1, 1};
  uint64_t cells = 0;              // nx * ny * nz
  double references_per_prim = 0.0;
  double build_seconds = 0.0;
  double bytes = 0.0;              // the grid's memory
  double cells_per_ray = 0.0, tests_per_ray = 0.0, mailbox_per_ray = 0.0;  // over all rays
  double trace_seconds = 0.0;      // median pass over all rays
  double mrays_per_second = 0.0;
  bool coarsened = false;          // the reference budget lowered the resolution
};

struct GridSweep {
  uint64_t primitives = 0;
  uint64_t rays = 0;
  std::vector<GridSweepRow> rows;
};

// Single-threaded and without globals, so a GUI worker thread can run it. row_done (optional): after each
// density, from the calling thread, e.g. to fill a chart. cancel (optional): looked at every few thousand
// rays; once set, the row being measured is dropped and the rows finished so far are returned. Throws
// InputError("", 0, ...) for a density outside (0, 64] or NaN, reps outside 1..1000, more than 2^26 random
// rays, and InputError(scene.path, 0, ...) for a scene without primitives.
GridSweep run_grid_sweep(const Scene& scene, const GridSweepOptions& options,
                         const std::function<void(const GridSweepRow&)>& row_done = nullptr,
                         const std::atomic<bool>* cancel = nullptr);

}  // namespace raystep
