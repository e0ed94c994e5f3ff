// What the structure reports share when they time their passes (report_grid_sweep.cpp,
// report_structure_compare.cpp): wall-clock seconds since a start, the median of repeated passes, and the
// cancel flag polled between steps. Internal to raystep_core.
#pragma once

#include <algorithm>
#include <atomic>
#include <chrono>
#include <vector>

namespace raystep::report_timing {

using Clock = std::chrono::steady_clock;

inline double seconds_since(Clock::time_point t0) {
  return std::chrono::duration<double>(Clock::now() - t0).count();
}

// The upper middle of the passes: one measured pass, never an average of two (v must not be empty).
inline double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  return v[v.size() / 2];
}

inline bool cancelled(const std::atomic<bool>* cancel) {
  return cancel && cancel->load(std::memory_order_relaxed);
}

}  // namespace raystep::report_timing
