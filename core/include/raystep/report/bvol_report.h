// The kinds of bounding volumes measured on the same camera rays (`raystep bvol-report`): per kind, the
// volume tests and false positives (a volume entered, its object missed), the primitive tests and the time
// per ray, and the build time. The lecture's tradeoff in numbers: a tighter volume costs more per test and is
// entered in vain less often.
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/scene/scene.h"

namespace raystep {

struct BvolReportOptions {
  int camera_width = 0, camera_height = 0;  // one ray per pixel (0: the scene's size, at most 160 on a side)
  int reps = 3;                             // timed passes over the rays; the median is reported
};

struct BvolReportRow {
  std::string scene;  // the scene file's name
  std::string kind;   // accelerator name: bvol, bvol-sphere, bvol-kdop, bvol-obb
  uint64_t objects = 0, primitives = 0, rays = 0;
  double build_seconds = 0.0;            // median of reps builds
  double volume_tests_per_ray = 0.0;     // one per object per ray
  double volume_hits_per_ray = 0.0;      // volumes the ray meets
  double entered_per_ray = 0.0;          // volumes whose objects were tested (entry before the nearest hit)
  double false_positives_per_ray = 0.0;  // entered volumes whose objects gave no hit before the nearest
  double false_positive_rate = 0.0;      // false positives / entered
  double prim_tests_per_ray = 0.0;
  double ns_per_ray = 0.0;     // median pass, one thread, uninstrumented
  uint64_t disagreements = 0;  // rays whose nearest hit differs from brute force's (must be 0)
};

// Single-threaded. Throws InputError(scene.path, 0, ...) for a scene without primitives, InputError("", 0,
// ...) for reps outside 1..100 or an image above 4096 x 4096.
std::vector<BvolReportRow> run_bvol_report(const Scene& scene, const BvolReportOptions& options);

// The rows as CSV (a header line, then one line per row) and as a Markdown table.
std::string bvol_report_csv(const std::vector<BvolReportRow>& rows);
std::string bvol_report_markdown(const std::vector<BvolReportRow>& rows);

}  // namespace raystep
