// The pieces the BVH builders share (bvh_build.cpp, bvh_build_split.cpp, bvh_sah_curve.cpp): a primitive
// reference with its bounds, and the one decision per node (leaf, or which split) that the build, the
// listener's replay and the SAH inspector all make with the same function, so they cannot disagree.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/bvh_build.h"

namespace raystep::bvh {

// A primitive while it is being built: its bounds and id. The centroid is the bounds' centre, computed where
// it is needed (the same float operations everywhere, so every pass puts a primitive on the same side).
struct PrimRef {
  Bounds3 box;
  uint32_t id;
  float centroid(int axis) const { return 0.5f * (box.lo[axis] + box.hi[axis]); }
};

// -0 and +0 compare equal; make them the same bits too (the same tree from mirrored input).
inline Bounds3 without_negative_zero(Bounds3 b) {
  b.lo += glm::vec3(0.f);
  b.hi += glm::vec3(0.f);
  return b;
}

// One reference per primitive, its bounds with -0 made +0 (the same tree from mirrored input). Throws
// InputError for a primitive whose bounds are not finite.
std::vector<PrimRef> make_refs(const Geometry& geometry);

// What to do with a node.
struct NodePlan {
  bool leaf = true;
  BvhLeafReason reason = BvhLeafReason::few_primitives;
  bool forced = false;  // all centroids equal: the id range is halved (N > max_leaf_size)
  BvhCandidate chosen;  // for a split
  float leaf_cost = 0.f;
};

// Decides a node of refs[0..n) (its box and its centroids' box given), cutting the axes of `space` and
// weighing boxes by its measure (geometry/split_space.h). Fills *candidates (when not null) with every
// candidate the builder evaluates, `chosen` set on the one taken. Does not reorder refs.
NodePlan plan_node(const PrimRef* refs, uint32_t n, const Bounds3& box, const Bounds3& centroids, int depth,
                   const BvhOptions& options, SplitSpace space, std::vector<BvhCandidate>* candidates);

// Reorders refs[0..n) so that the plan's left side comes first; returns the left count (plan.chosen.n_left).
uint32_t apply_split(PrimRef* refs, uint32_t n, const Bounds3& centroids, const NodePlan& plan,
                     const BvhOptions& options);

// The node's box and its centroids' box (in parallel over large ranges; min and max only: deterministic).
void range_bounds(const PrimRef* refs, uint32_t n, Bounds3* box, Bounds3* centroids);

// The SAH sweep over one axis's bins, the binned and the spatial search's: candidate b (the plane planes[b])
// puts bins 0..b on the left with n_left = enter[0] + .. + enter[b] and n_right = leave[b+1] + .. (the binned
// search counts a primitive in one bin, so enter = leave; a spatial one enters at its low end's bin and
// leaves at its high end's), each side's box the union of its bins'. Appends every candidate to *out (when not
// null); keeps in *best the cheapest with both sides non-empty, against *best already there when `found`.
// Returns whether *best holds one.
constexpr int kMaxSweepBins = 256;
bool sweep_bins(const Bounds3* box, const uint32_t* enter, const uint32_t* leave, const float* planes, int bins,
                int axis, bool spatial, float area_node, const BvhOptions& o, SplitSpace space,
                std::vector<BvhCandidate>* out, BvhCandidate* best, bool found);

// C = t_t + (S_l N_l + S_r N_r) t_i / S_node; a node box of zero area counts both sides fully.
float split_cost(const BvhOptions& o, float area_node, uint32_t n_l, float area_l, uint32_t n_r,
                 float area_r);

// The SBVH builder (bvh_build_sbvh.cpp): the whole build, telling the listener (when not null) about every
// node in id order after it. Options already validated.
BvhData build_sbvh(const Geometry& geometry, const BvhOptions& options, BvhBuildListener* listener);

// Ranges at least this long are binned, bounded and built in parallel.
constexpr uint32_t kParallelPrims = 4096;

}  // namespace raystep::bvh
