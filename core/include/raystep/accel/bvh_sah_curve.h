// The SAH cost curve of one BVH node, for the lecture's question "why was this split chosen?": every
// candidate the builder evaluated (binned: each bin boundary on x, y and z; sweep: each boundary between
// sorted centroids; median: its one split; SBVH: the binned object splits, then where they overlap the spatial
// splits at the bin boundaries of the node's box) with N and the box area on each side and C = t_t + (S_l N_l + S_r
// N_r) t_i / S_node, and the decision (the chosen split, or a leaf at N t_i). Recorded by rebuilding with a
// listener that wants only that node.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/bvh_build.h"
#include "raystep/accel/kdtree_sah_curve.h"

namespace raystep {

struct BvhSahCurve {
  uint32_t node = 0;
  BvhNode bvh_node;
  BvhNodeInfo info;
  float leaf_cost = 0.f;  // N * t_i
  bool leaf = false;
  BvhLeafReason leaf_reason = BvhLeafReason::few_primitives;
  int chosen = -1;                       // index in candidates of the chosen split; -1 for a leaf
  std::vector<BvhCandidate> candidates;  // in the builder's order; `chosen` set on the one taken
};

// Node id from a path from the root: 'L' the first (left) child, 'R' the second ("" is the root).
// Throws InputError("", 0, ...) when the path leaves the tree or has another letter.
uint32_t bvh_node_by_path(const BvhData& bvh, const std::string& path);

// Builds the BVH of `geometry` with `options`, recording node `node`'s curve. Throws InputError("", 0, ...)
// if the tree has no such node.
BvhSahCurve record_bvh_sah_curve(const Geometry& geometry, const BvhOptions& options, uint32_t node);
// The candidates alone (the SAH inspector's call).
std::vector<BvhCandidate> bvh_sah_curve(const Geometry& geometry, const BvhOptions& options, uint32_t node);

// The curve in the kd-tree's terms (kdtree_sah_curve.h: N below and above for left and right, the decision's
// axis, position and cost), as the SAH chart and the lessons' node facts read curves: the object candidates,
// and the spatial ones too when `spatial` (an SBVH's; the chosen index counts the candidates kept, -1 when
// the chosen one is left out).
SahCurve as_kd_curve(const BvhSahCurve& curve, bool spatial);

// The curve as CSV (columns, a contract:
// axis,bin,position,n_left,n_right,area_left,area_right,area_node,cost,chosen,kind with kind object or
// spatial) or JSON (the node, its
// decision and the same rows); written atomically.
void write_bvh_sah_csv(const std::string& path, const BvhSahCurve& curve);
void write_bvh_sah_json(const std::string& path, const BvhSahCurve& curve, const BvhOptions& options);

}  // namespace raystep
