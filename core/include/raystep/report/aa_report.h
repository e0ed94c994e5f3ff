// Speed against error for anti-aliasing: every method at several sample counts rendered, timed, counted ray
// by kind and measured against a reference (render/reference.h), over several seeds for the random methods.
// `raystep aa-report` writes it as CSV, Markdown and plots; the debugger's report chart fills in from the
// same rows as they are measured.
#pragma once

#include <atomic>
#include <functional>
#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/render/reference.h"
#include "raystep/render/whitted.h"
#include "raystep/scene/scene.h"

namespace raystep {

struct AaReportOptions {
  std::vector<std::string> methods;  // anti-aliasing specs (scene/antialiasing_spec.h); empty: the defaults
  std::string reference = "auto";    // "exact" | "jitter:K" | "auto"
  int width = 0, height = 0;         // 0: the scene's size
  int seeds = 5;                     // runs of each random method (jitter, random), seeds 1..seeds
  int threads = 0;
};

// The default methods: none, regular:2..8, jitter:2..8, random:4..64 (powers of two), adaptive at several
// thresholds (depth 3) and, at threshold 0.1, depths 1 and 2 (on a black-and-white scene every threshold
// below 1 refines the same pixels: only the depth changes anything there), and with the tent filter
// regular:4, jitter:2, jitter:4 and jitter:8.
std::vector<std::string> default_aa_methods();

// Throws InputError("", 0, "bad method list: ...") naming the first bad entry, or for an empty list.
std::vector<AntiAliasing> parse_aa_methods(const std::vector<std::string>& specs);

// One method over its seeds (one seed for the deterministic methods).
struct AaReportRow {
  std::string method;      // "none", "regular", "jitter", "random", "adaptive"
  std::string spec;        // e.g. "jitter:4", "adaptive:0.1:3"
  int seeds = 1;
  double rays_per_pixel = 0.0;  // primary rays per pixel (mean over seeds)
  RayCounts rays;               // rays by kind, mean over seeds (rounded)
  double seconds = 0.0;         // median wall time of one render (deterministic methods: of min(3, seeds)
                                // identical renders, so that their time is a median too)
  double rmse = 0.0;            // mean over seeds
  double rmse_min = 0.0, rmse_max = 0.0, rmse_stddev = 0.0;  // spread over seeds (equal for one seed)
  double max_error = 0.0;       // the largest pixel error (mean over seeds)
  std::vector<double> seed_rmse;  // one per seed, in seed order
  std::vector<std::string> images;  // when written: the PFM of each seed, file names inside hooks.image_dir
                                    // (e.g. "jitter-4-seed1.pfm", "regular-3.pfm")
  std::string reference;   // the kind of reference its error is measured against: its filter's (AaReport)
};

struct AaReference {
  std::string kind;        // "exact" or "jitter:K", with "+tent" for the tent filter's
  double rmse = 0.0;       // its own estimated error (0 for exact)
  double seconds = 0.0;
};

struct AaReport {
  std::string scene_path;
  int width = 0, height = 0;
  // Each method is measured against the scene pre-filtered by its own filter: one reference per filter the
  // methods use, the box's first. The three fields below are references[0]'s.
  std::vector<AaReference> references;
  std::string reference_kind;       // "exact" or "jitter:K" (the box filter's, if any method uses it)
  double reference_rmse = 0.0;      // the reference's own estimated error (0 for exact)
  double reference_seconds = 0.0;
  std::vector<AaReportRow> rows;
  // Least-squares slopes of log(rmse) against log(rays per pixel), per method with at least two counts
  // (adaptive excluded: its rays are an outcome, not a setting); the theory at edges: regular between -1/2
  // (edges along the grid) and -1 (slanted edges), jitter about -3/4, random -1/2.
  std::vector<std::pair<std::string, double>> slopes;
};

struct AaReportHooks {
  // Called after each row is measured (from the calling thread), e.g. to fill a chart as the report runs.
  std::function<void(const AaReport& so_far, const AaReportRow& row)> row_done;
  // Overall fraction done in [0, 1].
  std::function<void(double)> progress;
  // When set and true, the report stops after the current render and returns the rows it completed (a
  // method cut short is left out: its seeds would not compare with the others').
  const std::atomic<bool>* cancel = nullptr;
  // When not empty: each render's image is written here as PFM (the references as reference.pfm and, for the
  // tent filter, reference-tent.pfm).
  std::string image_dir;
};

// Throws InputError("", 0, ...) for bad options (methods, reference, size).
AaReport run_aa_report(const Scene& scene, const Accelerator& accel, const AaReportOptions& options,
                       const AaReportHooks& hooks = {});

// Least-squares slope of log(y) against log(x) (points with x, y > 0); NaN with fewer than two points.
double loglog_slope(const std::vector<double>& x, const std::vector<double>& y);

}  // namespace raystep
