#include "raystep/report/structure_compare.h"

#include <algorithm>
#include <chrono>
#include <cmath>

#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_quality.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/util/error.h"
#include "camera_size.h"
#include "timing.h"

namespace raystep {

HitAgreement compare_hits(const Hit& brute, const Hit& other) {
  if (brute.found() != other.found()) return HitAgreement::differs;
  if (!brute.found()) return HitAgreement::same;
  if (brute.t != other.t) return HitAgreement::differs;
  return brute.prim == other.prim ? HitAgreement::same : HitAgreement::tie;
}

namespace {

using report_timing::cancelled;
using report_timing::Clock;
using report_timing::median;
using report_timing::seconds_since;

// Thrown inside to leave a half-measured structure; never escapes compare_structures.
struct Cancelled {};

constexpr size_t kCancelStride = 4096;

const char* step_name(const Accelerator& accel) {
  if (dynamic_cast<const UniformGrid*>(&accel)) return "cells";
  if (dynamic_cast<const KdTree*>(&accel) || dynamic_cast<const BspTree*>(&accel)) return "nodes";
  if (auto* bvol = dynamic_cast<const BoundingVolumes*>(&accel))
    return bvol->kind() == BvolKind::box ? "boxes" : "volumes";
  if (dynamic_cast<const Octree*>(&accel)) return "nodes";
  return "-";
}

// A binary space partition's shape (kd-trees, the BSP tree: the lecture's "tradeoff" in nodes and depth).
// The tree's size and depth; a BVH's SAH cost and EPO (bvh_quality.h) too.
void tree_shape(const Accelerator& accel, const Geometry* geometry, StructureCompareRow* row) {
  auto deepest = [](const auto& info) {
    int d = 0;
    for (const auto& i : info) d = std::max(d, int(i.depth));
    return d;
  };
  if (auto* kd = dynamic_cast<const KdTree*>(&accel)) {
    row->tree_nodes = kd->data().nodes.size();
    row->tree_depth = deepest(kd->data().info);
  } else if (auto* bsp = dynamic_cast<const BspTree*>(&accel)) {
    row->tree_nodes = bsp->data().nodes.size();
    row->tree_depth = deepest(bsp->data().info);
  } else if (auto* bvh = dynamic_cast<const Bvh*>(&accel)) {
    row->tree_nodes = bvh->data().nodes.size();
    row->tree_depth = deepest(bvh->data().info);
    const BvhQuality q = tree_quality(bvh_view(bvh->data()), bvh->geometry(), bvh->options().t_i,
                                      bvh->options().t_t);
    row->sah_cost = q.sah_cost;
    row->epo = q.epo;
  } else if (auto* wide = dynamic_cast<const WideBvh*>(&accel)) {
    const WideBvhView view = wide->describe();
    row->tree_nodes = view.nodes.size();
    row->tree_depth = deepest(view.nodes);
    const BvhQuality q = tree_quality(view, *geometry, wide->options().t_i, wide->options().t_t);
    row->sah_cost = q.sah_cost;
    row->epo = q.epo;
  }
}

// One ray set, and the evenly spread subset brute force traces (every stride-th ray).
struct RaySet {
  std::vector<Ray> rays;
  std::vector<Ray> subset;
  std::vector<Hit> reference;  // brute force's hits on the subset
  size_t stride = 1;
};

void choose_subset(RaySet* set, uint64_t prims, uint64_t budget) {
  uint64_t most = std::max<uint64_t>(1, budget / std::max<uint64_t>(prims, 1));
  set->stride = set->rays.empty() ? 1 : size_t((set->rays.size() + most - 1) / most);
  set->stride = std::max<size_t>(set->stride, 1);
  set->subset.clear();
  for (size_t i = 0; i < set->rays.size(); i += set->stride) set->subset.push_back(set->rays[i]);
}

// Counts the work on rays (hits into *hits), then times reps uninstrumented passes.
StructureRaySet measure(const Accelerator& accel, const std::vector<Ray>& rays, int reps,
                        std::vector<Hit>* hits, const std::atomic<bool>* cancel) {
  StructureRaySet out;
  out.rays = rays.size();
  hits->assign(rays.size(), Hit{});
  CountingRecorder counts;
  for (size_t i = 0; i < rays.size(); ++i) {
    accel.intersect_counted(rays[i], &(*hits)[i], counts);
    if (i % kCancelStride == 0 && cancelled(cancel)) throw Cancelled{};
  }
  const double n = double(std::max<size_t>(rays.size(), 1));
  out.steps_per_ray = double(counts.cells + counts.nodes) / n;
  out.tests_per_ray = double(counts.prim_tests) / n;
  std::vector<double> passes;
  for (int r = 0; r < reps; ++r) {
    auto t0 = Clock::now();
    for (size_t i = 0; i < rays.size(); ++i) {
      Hit hit;
      accel.intersect(rays[i], &hit);
      if (i % kCancelStride == 0 && cancelled(cancel)) throw Cancelled{};
    }
    passes.push_back(seconds_since(t0));
  }
  out.seconds = median(passes);
  out.mrays_per_second = out.seconds > 0 ? double(rays.size()) / out.seconds * 1e-6 : 0.0;
  return out;
}

}  // namespace

StructureComparison compare_structures(const Scene& scene, const StructureCompareOptions& options,
                                       const StructureCompareHooks& hooks) {
  std::vector<std::string> names = options.structures.empty() ? accelerator_names() : options.structures;
  // Every name is checked before any work, so a typo at the end of a list fails at once.
  for (const std::string& name : names) make_accelerator(name, options.build);
  if (options.reps < 1 || options.reps > 1000) throw InputError("", 0, "compare: reps must be 1..1000");
  if (options.random_rays > (uint64_t(1) << 26))
    throw InputError("", 0, "compare: at most 67108864 random rays");
  if (scene.geometry.size() == 0)
    throw InputError(scene.path, 0, "the scene has no primitives to compare structures on");

  StructureComparison result;
  result.scene_path = scene.path;
  result.primitives = scene.geometry.size();
  int w = options.camera_width, h = options.camera_height;
  report_camera_size(scene, 512, &w, &h);
  result.camera_width = w;
  result.camera_height = h;
  RaySet sets[2];
  sets[0].rays = camera_rays(scene.camera, w, h);
  if (options.random_rays > 0)
    sets[1].rays = random_rays(scene.geometry.bounds(), options.random_rays, options.seed);
  for (RaySet& s : sets) choose_subset(&s, result.primitives, options.test_budget);
  result.camera_rays = sets[0].rays.size();
  result.random_rays = sets[1].rays.size();
  result.camera_checked = sets[0].subset.size();
  result.random_checked = sets[1].subset.size();

  // Stages: the reference, then each structure; progress moves by stage.
  const double stages = double(names.size() + 1);
  auto progress = [&](double done) {
    if (hooks.progress) hooks.progress(std::min(1.0, done / stages));
  };
  try {
    // The reference: brute force's hits on each subset.
    std::unique_ptr<Accelerator> brute = make_accelerator("brute");
    brute->build(scene.geometry);
    for (RaySet& s : sets) {
      s.reference.resize(s.subset.size());
      for (size_t i = 0; i < s.subset.size(); ++i) {
        brute->intersect(s.subset[i], &s.reference[i]);
        if (i % kCancelStride == 0 && cancelled(hooks.cancel)) throw Cancelled{};
      }
    }
    progress(1);

    for (size_t a = 0; a < names.size(); ++a) {
      if (cancelled(hooks.cancel)) break;
      std::unique_ptr<Accelerator> accel = make_accelerator(names[a], options.build);
      StructureCompareRow row;
      row.name = names[a];
      row.steps = step_name(*accel);
      std::vector<double> builds;
      for (int r = 0; r < options.reps; ++r) {
        auto t0 = Clock::now();
        accel->build(scene.geometry);
        builds.push_back(seconds_since(t0));
        if (cancelled(hooks.cancel)) throw Cancelled{};
      }
      row.build_seconds = median(builds);
      row.memory_bytes = accel->memory_bytes();
      tree_shape(*accel, &scene.geometry, &row);
      for (int k = 0; k < 2; ++k) {
        RaySet& s = sets[k];
        StructureRaySet& out = k == 0 ? row.camera : row.random;
        // First the checked subset: the hits to compare with brute force's, and the work per ray, from which
        // the cost of all rays is foreseen.
        std::vector<Hit> hits(s.subset.size());
        CountingRecorder counts;
        for (size_t i = 0; i < s.subset.size(); ++i) {
          accel->intersect_counted(s.subset[i], &hits[i], counts);
          if (i % kCancelStride == 0 && cancelled(hooks.cancel)) throw Cancelled{};
        }
        uint64_t disagreements = 0, ties = 0;
        for (size_t i = 0; i < s.subset.size(); ++i) {
          HitAgreement agreement = compare_hits(s.reference[i], hits[i]);
          disagreements += agreement == HitAgreement::differs;
          ties += agreement == HitAgreement::tie;
        }
        // Then all rays, timed and counted, unless that would take more tests than the budget (brute force,
        // or bounding volumes around one big object): such a structure is measured on the subset.
        const double foreseen =
            double(counts.prim_tests) / double(std::max<size_t>(s.subset.size(), 1)) * double(s.rays.size());
        const bool all = s.subset.size() == s.rays.size() || foreseen <= double(options.test_budget);
        // A structure measured on the subset is slow: one timed pass of it lasts long enough to be steady.
        out = measure(*accel, all ? s.rays : s.subset, all ? options.reps : 1, &hits, hooks.cancel);
        out.checked = s.subset.size();
        out.disagreements = disagreements;
        out.ties = ties;
        progress(double(a + 1) + 0.5 * (k + 1));
      }
      result.rows.push_back(row);
      if (hooks.row_done) hooks.row_done(result.rows.back());
    }
  } catch (const Cancelled&) {
  }
  return result;
}

}  // namespace raystep
