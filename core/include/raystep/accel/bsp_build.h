// General BSP tree construction (lecture: "BSP trees: splitting planes of any orientation", "BSP vs. k-d: a
// tradeoff between speed from simplicity and better adaptability"). Candidate planes come from a fixed set of
// directions (the 13 of a k-DOP: 3 axes, 6 face diagonals, 4 body diagonals) at the primitives' extents along
// each, and from the primitives' own planes (an autopartition); the SAH with the children's exact surface
// areas (the cells are convex polytopes, accel/bsp_cell.h) and the kd-tree's cost constants picks one.
#pragma once

#include <cstdint>
#include <string>

#include <glm/vec3.hpp>

#include "raystep/accel/bsp_node.h"
#include "raystep/scene/geometry.h"

namespace raystep {

enum class BspDirections : uint8_t {
  autopartition,  // the primitives' own planes only
  kdop,           // the 13 k-DOP directions only
  both,
};
const char* bsp_directions_name(BspDirections d);
// "autopartition", "kdop" or "both"; false for anything else.
bool parse_bsp_directions(const std::string& text, BspDirections* d);

struct BspOptions {
  BspDirections directions = BspDirections::both;
  // The cap on candidates per node that keeps the build O(N log N)-like: at most this many positions per
  // k-DOP direction (all of the 2N extents when 2N fits, else an even sample of them) and this many primitive
  // planes (an even sample of the node's triangles) with autopartition alone, a quarter as many (at least 1)
  // with both (measured better: bench/README.md). 1..4096.
  int candidates = 16;
  float t_i = 80.f;  // the kd-tree's cost constants (kdtree_build.h)
  float t_t = 1.f;
  int max_depth = 0;  // 0: max(8, 1.2 log2 N), as the kd-tree; <= kBspMaxDepth
  int leaf_size = 1;  // a node with at most this many primitives is a leaf without a search
  // Bounded memory on pathological input, as the kd-tree's: the leaves hold at most reference_budget * N
  // primitive references (never fewer than N), shared out down the tree. >= 1.
  float reference_budget = 8.f;
};
constexpr int kBspMaxDepth = 64;

int bsp_max_depth(const BspOptions& options, size_t prim_count);

// The 13 k-DOP directions in the builder's order (the tie order): 0..2 the axes, 3..8 the face diagonals,
// 9..12 the body diagonals; unit length in float, as the planes store them. Names like "x", "x+y", "-x+y+z".
constexpr int kBspKdopDirections = 13;
glm::vec3 bsp_kdop_direction(int direction);
const char* bsp_direction_name(int direction);

// One candidate plane as the builder weighed it (for the SAH inspector, accel/bsp_sah_curve.h): the plane,
// its counts and the exact polytope areas of both sides, C = t_t + t_i (S_b N_b + S_a N_a) / S.
struct BspCandidate {
  BspPlane plane;
  BspPlaneSource source = BspPlaneSource::axis;
  int direction = -1;          // 0..12: its k-DOP direction; -1: a primitive's own plane
  uint32_t prim = UINT32_MAX;  // a primitive's own plane: that triangle
  // The cell's extent along the normal: the offset lies strictly between (0..1 across the cell, for charts).
  double cell_min = 0.0, cell_max = 0.0;
  // As the builder counts them from the primitives' extents along the normal (planar ones below); the
  // chosen plane's children then get the exact classification (BspSahCurve::n_below, n_above).
  uint32_t n_below = 0, n_above = 0;
  double area_below = 0.0, area_above = 0.0, area_node = 0.0;
  double cost = 0.0;
  // The builder skipped this candidate's areas: t_t + t_i min(N_b, N_a), a lower bound of its cost, was
  // already no cheaper than the best so far. Its areas and cost are computed for the curve only.
  bool bounded = false;
  bool chosen = false;  // the plane the node was split by
};

// Why a BSP node became a leaf (bsp_build.h's leaf rules, in that order).
enum class BspLeafReason : uint8_t {
  few_primitives,     // N <= leaf_size
  max_depth,          // the depth limit
  no_area,            // the cell has no area (degenerate)
  no_cheaper_split,   // no candidate cuts the cell for less than N t_i (or none cuts it)
  separates_nothing,  // the cheapest plane would put all N primitives on both sides
  budget,             // the children would exceed the node's share of the reference budget
};
const char* bsp_leaf_reason_name(BspLeafReason reason);

// What the builder tells about its work, as the kd-tree's and the BVH's (a recorder template inside the
// builder: the plain build_bsp has no listener calls at all). Candidates are reported only for the nodes the
// listener wants, after the node's search, in the builder's order; then the node's decision.
class BspBuildListener {
 public:
  virtual ~BspBuildListener() = default;
  virtual bool wants_candidates(uint32_t node) const = 0;
  virtual void candidate(uint32_t node, const BspCandidate& c) = 0;
  // n_below, n_above: the children's primitive counts by the exact classification.
  virtual void split(uint32_t node, const BspNodeInfo& info, uint32_t n_prims, const BspCandidate& chosen,
                     uint32_t n_below, uint32_t n_above, float leaf_cost) = 0;
  virtual void leaf_made(uint32_t node, const BspNodeInfo& info, uint32_t n_prims, float leaf_cost,
                         BspLeafReason reason) = 0;
  // True once the listener has all it wants: the builder then makes every node still to come a leaf
  // without a search, so the tree returned is unfinished (recording only).
  virtual bool done() const { return false; }
};

// Build. Throws InputError("", 0, "bsp: ...") for options out of range and for non-finite primitives.
//
// Classification (what the traversal relies on): a primitive is in every child that holds a point of it,
// decided exactly: a triangle by the exact signs of its three vertices against the node's float plane, a
// sphere by the eight corners of its bounding box. One with a point strictly below is below, strictly above
// is above (both, if both); one lying wholly in the plane is below. So every point of a primitive lies in the
// closed cell of some leaf that lists it. The cells are only used for the SAH's areas and for display.
//
// Leaf rules, in the order tested: N <= leaf_size, depth = bsp_max_depth, a cell of zero area or no candidate
// plane cutting the cell (no_candidate), best cost >= N * t_i (no_cheaper_split), a split that separates
// nothing (both children would hold all N: no_cheaper_split), children over the node's budget (budget).
// Planar primitives go below, unlike the kd-tree which tries both sides. Ties: the first candidate in the
// order axes, face diagonals, body diagonals, primitive planes, increasing position.
BspTreeData build_bsp(const Geometry& geometry, const BspOptions& options);
// The same build, telling `listener` (the same decisions: the listener only watches).
BspTreeData build_bsp(const Geometry& geometry, const BspOptions& options, BspBuildListener& listener);

struct BspTreeStats {
  size_t nodes = 0, leaves = 0, empty_leaves = 0;
  int max_depth = 0;
  size_t references = 0, max_leaf_prims = 0;
  size_t inner_by_source[4] = {0, 0, 0, 0};  // inner nodes by BspPlaneSource
  double sah_cost = 0.0;  // over the cells' polytope areas: sum of t_t S(inner) + t_i N S(leaf), / S(root)
};
BspTreeStats bsp_tree_stats(const BspTreeData& tree, const BspOptions& options);

}  // namespace raystep
