// Structures side by side on the same rays: build time, memory, speed on camera and on random rays, the work
// per ray (cells or nodes walked, primitive tests), and the error column: rays on which a structure's nearest
// hit differs from brute force's. `raystep compare` writes it as CSV, Markdown and plots.
#pragma once

#include <atomic>
#include <cmath>
#include <cstdint>
#include <functional>
#include <string>
#include <vector>

#include "raystep/accel/structure_options.h"
#include "raystep/geometry/ray.h"
#include "raystep/scene/scene.h"

namespace raystep {

struct StructureCompareOptions {
  std::vector<std::string> structures;  // names as make_accelerator takes them; empty: accelerator_names()
  StructureOptions build;               // every structure's build options
  int camera_width = 0, camera_height = 0;  // primary rays (0: the scene's size, capped at 512 on a side)
  uint64_t random_rays = 65536;             // random rays through the bounds (0: none)
  uint64_t seed = 1;
  int reps = 3;  // timed passes; the median is reported
  // Brute force tests every primitive: it traces an evenly spread subset of each ray set, at most this many
  // primitive tests per set, and every structure is checked against it on that subset. A structure foreseen
  // (from the subset) to need more tests than this on all rays is also timed on the subset only (bounding
  // volumes around one big mesh), in one timed pass; StructureRaySet::rays says how many rays were timed.
  uint64_t test_budget = 100'000'000;
};

// How one structure's nearest hit compares with brute force's on one ray.
enum class HitAgreement {
  same,     // both miss, or the same primitive at the same t
  tie,      // another primitive at exactly the same t (a shared edge, coincident faces): not an error
  differs,  // one hits and the other misses, or another t
};
HitAgreement compare_hits(const Hit& brute, const Hit& other);

// One ray set (camera or random) traced by one structure.
struct StructureRaySet {
  uint64_t rays = 0;     // rays timed and counted (brute force: the checked subset)
  double seconds = 0.0;  // median pass, one thread
  double mrays_per_second = 0.0;
  double steps_per_ray = 0.0;  // grid cells, kd-tree nodes, bounding boxes entered (brute force: 0)
  double tests_per_ray = 0.0;  // ray-primitive tests
  uint64_t checked = 0;        // rays compared with brute force (the subset brute force traced)
  uint64_t disagreements = 0;  // HitAgreement::differs on the checked rays
  uint64_t ties = 0;           // HitAgreement::tie on the checked rays
};

struct StructureCompareRow {
  std::string name;
  std::string steps;           // steps_per_ray counts "cells", "nodes", "boxes", "volumes" (bvol kinds), "-"
  double build_seconds = 0.0;  // median of reps builds
  uint64_t memory_bytes = 0;   // Accelerator::memory_bytes()
  uint64_t tree_nodes = 0;  // the trees: nodes and the deepest node's depth (else 0 and -1)
  int tree_depth = -1;
  // The BVHs (binary and wide): the SAH cost and EPO of the tree (accel/bvh_quality.h); NaN for the others.
  // With steps and tests per ray they give the predicted against the measured cost.
  double sah_cost = std::nan("");
  double epo = std::nan("");
  StructureRaySet camera, random;
  uint64_t disagreements() const { return camera.disagreements + random.disagreements; }
  uint64_t ties() const { return camera.ties + random.ties; }
};

struct StructureComparison {
  std::string scene_path;
  uint64_t primitives = 0;
  int camera_width = 0, camera_height = 0;
  uint64_t camera_rays = 0, random_rays = 0;
  uint64_t camera_checked = 0, random_checked = 0;  // rays checked against brute force, per set
  std::vector<StructureCompareRow> rows;
};

struct StructureCompareHooks {
  std::function<void(const StructureCompareRow&)> row_done;  // after each structure, from the calling thread
  std::function<void(double)> progress;                      // fraction done in [0, 1]
  const std::atomic<bool>* cancel =
      nullptr;  // once set: the structure being measured is dropped, rows so far returned
};

// Single-threaded (timings are per thread) and without globals: a GUI worker thread may run it.
// Throws InputError("", 0, ...) for an unknown structure name (naming it), an empty list, reps
// outside 1..1000, more than 2^26 random rays; InputError(scene.path, 0, ...) for a scene without primitives.
StructureComparison compare_structures(const Scene& scene, const StructureCompareOptions& options,
                                       const StructureCompareHooks& hooks = {});

}  // namespace raystep
