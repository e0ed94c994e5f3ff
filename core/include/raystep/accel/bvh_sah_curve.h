// The SAH cost curve of one BVH node, for the lecture's question "why was this split chosen?": every
// candidate the builder evaluated (binned: each bin boundary on x, y and z; sweep: each boundary between
// sorted centroids; median: its one split) with N and the box area on each side and C = t_t + (S_l N_l + S_r
// N_r) t_i / S_node, and the decision (the chosen split, or a leaf at N t_i). Recorded by rebuilding with a
// listener that wants only that node.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/bvh_build.h"

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

// The curve as CSV (columns, a contract:
// axis,bin,position,n_left,n_right,area_left,area_right,area_node,cost, chosen) or JSON (the node, its
// decision and the same rows); written atomically.
void write_bvh_sah_csv(const std::string& path, const BvhSahCurve& curve);
void write_bvh_sah_json(const std::string& path, const BvhSahCurve& curve, const BvhOptions& options);

}  // namespace raystep
