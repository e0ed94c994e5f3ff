// The lecture's cost formula with real numbers: a ray tracer makes about m^2 k^2 n 2^d ray-primitive tests
// for m^2 pixels, k^2 samples per pixel, n primitives and ray trees of depth d. The report renders the scene
// with brute force (no adaptive ray termination, then with it) and with each structure, counting the tests,
// and says which technique cuts which factor: acceleration cuts n, adaptive ray termination cuts 2^d,
// adaptive sampling cuts k^2. `raystep cost` prints it.
#pragma once

#include <atomic>
#include <cstdint>
#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "raystep/accel/structure_options.h"
#include "raystep/render/whitted.h"
#include "raystep/scene/scene.h"

namespace raystep {

struct CostReportOptions {
  int width = 0, height = 0;            // 0: the scene's size
  std::optional<AntiAliasing> aa;       // default: the scene's anti-aliasing
  std::vector<std::string> structures;  // empty: every accelerator name but brute
  StructureOptions build;
  int threads = 0;  // 0: all cores
};

// One render, counted.
struct CostRow {
  std::string label;       // e.g. "brute force, no adaptive termination"
  std::string accel;       // structure name
  std::string aa;          // anti-aliasing spec
  float min_weight = 0.f;  // adaptive ray termination's threshold (0: off)
  RayCounts rays;
  double samples_per_pixel = 0.0;  // primary rays / m^2
  double rays_per_sample = 0.0;    // all rays / primary rays: the ray tree's real size, shadow rays included
  uint64_t tests = 0;              // ray-primitive tests, shadow rays' included
  double tests_per_ray = 0.0;
  double seconds = 0.0;  // the render's wall time (with counting)
};

// Which technique cuts which factor of the formula, and by how much (before / after).
struct CostFactor {
  std::string technique;  // "acceleration: grid", "adaptive ray termination", "adaptive sampling ..."
  std::string factor;     // "n", "2^d", "k^2"
  std::string measure;    // what before and after are, e.g. "tests per ray"
  double before = 0.0, after = 0.0;
  double cut() const { return after > 0 ? before / after : 0.0; }
};

struct CostReport {
  std::string scene_path;
  int width = 0, height = 0;
  uint64_t pixels = 0;           // m^2 = width * height
  double samples_per_pixel = 0;  // k^2: the anti-aliasing's largest samples per pixel
  std::string aa;
  uint64_t primitives = 0;  // n
  int depth = 0;            // d: the scene's max_depth
  int lights = 0;           // L
  double predicted = 0.0;   // the lecture's m^2 k^2 n 2^d
  // A strict bound on brute force's tests: every ray of a full binary ray tree of depth d, 2^(d+1) - 1 rays,
  // with L shadow rays at each hit, each testing all n primitives: m^2 k^2 n (2^(d+1) - 1)(1 + L). With d = 0
  // and no lights it equals the lecture's formula, and brute force meets it exactly.
  double bound = 0.0;
  std::vector<CostRow> rows;
  std::vector<CostFactor> factors;
};

struct CostReportHooks {
  std::function<void(const CostRow&)> row_done;  // after each render, from the calling thread
  std::function<void(double)> progress;          // fraction of the renders done, in [0, 1]
  const std::atomic<bool>* cancel = nullptr;     // once set: no further render starts; rows so far returned
};

// Throws InputError("", 0, ...) for an unknown structure, bad size or anti-aliasing (as render_image does).
CostReport run_cost_report(const Scene& scene, const CostReportOptions& options,
                           const CostReportHooks& hooks = {});

}  // namespace raystep
