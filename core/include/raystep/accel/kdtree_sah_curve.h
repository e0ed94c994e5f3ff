// The SAH cost curve of one kd-tree node, for the lecture's question "why was this split chosen?": every
// candidate plane the builder evaluated on x, y and z, with N_below, N_above, N_planar, the areas and the cost
// C = t_t + p_a N_a t_i + p_b N_b t_i, and the decision (the chosen split, or a leaf at N t_i). Recorded by
// rebuilding with a listener that wants only that node, so no whole-build log is needed.
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/kdtree_build.h"

namespace raystep {

struct SahCurve {
  uint32_t node = 0;
  KdNodeInfo info;
  uint32_t n_prims = 0;
  float leaf_cost = 0.f;  // N * t_i
  bool leaf = false;
  LeafReason leaf_reason = LeafReason::few_primitives;
  int chosen = -1;  // index in candidates of the chosen split; -1 for a leaf
  int axis = -1;    // the split (inner nodes)
  float position = 0.f, cost = 0.f;
  std::vector<SahCandidate> candidates;  // in the builder's order
};

// Node id from a path from the root: 'L' the child below the split plane, 'R' the child above ("" is the root).
// Throws InputError("", 0, ...) when the path leaves the tree or has another letter.
uint32_t kd_node_by_path(const KdTreeData& tree, const std::string& path);

// Builds the tree of `geometry` with `options`, recording node `node`'s curve. Throws InputError if the tree
// has no such node.
SahCurve record_sah_curve(const Geometry& geometry, const KdOptions& options, uint32_t node);

// The curve as CSV (columns, a contract: axis,position,n_below,n_above,n_planar,area_below,area_above,
// area_node,cost,chosen) or JSON (the node, its decision and the same rows); written atomically.
void write_sah_csv(const std::string& path, const SahCurve& curve);
void write_sah_json(const std::string& path, const SahCurve& curve, const KdOptions& options);

}  // namespace raystep
