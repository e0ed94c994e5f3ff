// The SAH costs of one general BSP node's candidate planes, by orientation, for the lecture's question "why
// this plane?" (BSP vs. k-d: more orientations to choose from): each of the 13 k-DOP directions' positions
// and the primitives' own planes, with N and the exact polytope area on each side and C = t_t + t_i (S_b N_b
// + S_a N_a) / S, and the decision. Recorded by the builder itself (build_bsp with a listener for that node).
#pragma once

#include <string>
#include <vector>

#include "raystep/accel/bsp_build.h"

namespace raystep {

struct BspSahCurve {
  uint32_t node = 0;
  BspNodeInfo info;  // the cell's box, its polytope area, parent, depth; the cost of the decision
  uint32_t n_prims = 0;
  float leaf_cost = 0.f;  // N * t_i
  bool leaf = false;
  BspLeafReason leaf_reason = BspLeafReason::few_primitives;
  int chosen = -1;                    // index in candidates of the plane the node was split by; -1 for a leaf
  BspCandidate split;                 // inner nodes: the chosen plane (also candidates[chosen])
  uint32_t n_below = 0, n_above = 0;  // inner nodes: the children's counts by the exact classification
  std::vector<BspCandidate> candidates;  // in the builder's order: directions 0..12, then own planes
};

// Node id from a path from the root: 'L' the child below the plane, 'R' the child above ("" is the root).
// Throws InputError("", 0, ...) when the path leaves the tree or has another letter.
uint32_t bsp_node_by_path(const BspTreeData& tree, const std::string& path);

// Builds the BSP tree of `geometry` with `options` up to node `node`, recording its candidates and decision
// (the build stops once the node is decided). Throws InputError("", 0, "--node ...") if the tree has no such
// node.
BspSahCurve record_bsp_sah_curve(const Geometry& geometry, const BspOptions& options, uint32_t node);

// The curve as CSV (columns, a contract: direction,name,source,prim,normal_x,normal_y,normal_z,offset,
// cell_min,cell_max,n_below,n_above,area_below,area_above,area_node,cost,bounded,chosen; direction -1 and
// name "own plane" for a primitive's plane, prim -1 for the k-DOP's) or JSON (the node, its decision and the
// same rows); written atomically.
void write_bsp_sah_csv(const std::string& path, const BspSahCurve& curve);
void write_bsp_sah_json(const std::string& path, const BspSahCurve& curve, const BspOptions& options);

}  // namespace raystep
