// kd-tree construction (lecture: "kd-tree build by the Surface Area Heuristic"): the SAH cost
// C = t_t + p_a N_a t_i + p_b N_b t_i with p = S_child / S_node (Crofton), candidate planes at the bounds of
// each primitive clipped to the node ("perfect splits"), planar primitives tried on either side. Three
// builders: the O(N log N) event sweep of Wald and Havran ("On building fast kd-trees for ray tracing, and on
// doing that in O(N log N)", 2006), a plain O(N^2)-per-node reference that must build the same tree, and a
// spatial-median builder for the lesson that shows why SAH wins.
#pragma once

#include <cstdint>
#include <string>

#include "raystep/accel/kdtree_node.h"
#include "raystep/scene/geometry.h"

namespace raystep {

enum class KdBuilder : uint8_t {
  sah,            // Wald-Havran event sweep, O(N log N)
  sah_reference,  // every candidate counted against every primitive: O(N^2) per node; tests only
  median,         // split the longest axis of the node at its middle; leaves by leaf_size, the depth limit, a
                  // plane that every primitive straddles (no_candidate) or the budget, never by cost. Same
                  // defaults as the SAH builders, so the lesson compares like with like (its node info and its
                  // one candidate per node carry the median plane's SAH cost)
};

struct KdOptions {
  KdBuilder builder = KdBuilder::sah;
  float t_i = 80.f;          // cost of one ray-primitive test (lecture: t_i = 80 t_t)
  float t_t = 1.f;           // cost of one traversal step
  float empty_bonus = 0.f;   // in [0, 1): a split with an empty child costs t_t + (1 - bonus) t_i (...)
  int max_depth = 0;  // 0: max(8, 1.2 log2 N); with an empty bonus 8 + 1.3 log2 N (pbrt); <= kKdMaxDepth
  int leaf_size = 1;         // a node with at most this many primitives is a leaf without a search
  // Bounded memory on pathological input: the leaves hold at most reference_budget * N primitive references
  // (never fewer than N). The root has this budget; a node splits only if its children's primitive counts fit
  // in its budget (else LeafReason::budget); the below child gets a share in proportion to its count, the
  // above child the rest, with what the below subtree left unused. >= 1.
  float reference_budget = 8.f;
};
constexpr int kKdMaxDepth = 64;

// The depth limit actually used for n primitives.
int kd_max_depth(const KdOptions& options, size_t prim_count);
// The reference budget actually used for n primitives: max(n, reference_budget * n).
size_t kd_reference_budget(const KdOptions& options, size_t prim_count);

// One candidate split plane of a node, as the SAH evaluated it. n_below and n_above count the planar
// primitives (those lying in the plane) on the side they were given; n_planar says how many there were.
struct SahCandidate {
  int axis = 0;
  float position = 0.f;
  uint32_t n_below = 0, n_above = 0, n_planar = 0;
  float area_below = 0.f, area_above = 0.f, area_node = 0.f;
  float cost = 0.f;
  bool planar_below = true;  // the side the planar primitives were put on (the cheaper one)
};

// Why a node became a leaf.
enum class LeafReason : uint8_t {
  few_primitives,  // N <= leaf_size
  max_depth,       // the depth limit
  no_cheaper_split,  // every candidate costs at least N * t_i
  no_candidate,      // no plane strictly inside the node (e.g. all primitives span it)
  budget,            // the reference budget is spent (bounded memory on pathological input)
};
const char* leaf_reason_name(LeafReason reason);

// What a builder tells about its work. The kernel takes the recorder as a template parameter: with
// NullBuildRecorder (`enabled` false) it costs nothing; BuildListenerRecorder forwards to a BuildListener
// (the SAH inspector, streamed build events, tests). Candidates are made only for nodes the recorder wants.
struct NullBuildRecorder {
  static constexpr bool enabled = false;
  bool wants_candidates(uint32_t /*node*/) const { return false; }
  void sah_candidate(uint32_t /*node*/, const SahCandidate&) {}
  void split(uint32_t /*node*/, const KdNodeInfo&, uint32_t /*n_prims*/, int /*axis*/, float /*position*/,
             float /*cost*/, float /*leaf_cost*/) {}
  void leaf_made(uint32_t /*node*/, const KdNodeInfo&, uint32_t /*n_prims*/, float /*leaf_cost*/,
                 LeafReason) {}
};

class BuildListener {
 public:
  virtual ~BuildListener() = default;
  virtual bool wants_candidates(uint32_t node) const = 0;
  virtual void sah_candidate(uint32_t node, const SahCandidate& c) = 0;
  virtual void split(uint32_t node, const KdNodeInfo& info, uint32_t n_prims, int axis, float position,
                     float cost, float leaf_cost) = 0;
  virtual void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n_prims, float leaf_cost,
                         LeafReason reason) = 0;
};

struct BuildListenerRecorder {
  static constexpr bool enabled = true;
  BuildListener* listener;
  bool wants_candidates(uint32_t node) const { return listener->wants_candidates(node); }
  void sah_candidate(uint32_t node, const SahCandidate& c) { listener->sah_candidate(node, c); }
  void split(uint32_t node, const KdNodeInfo& info, uint32_t n, int axis, float pos, float cost, float leaf) {
    listener->split(node, info, n, axis, pos, cost, leaf);
  }
  void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf_cost, LeafReason reason) {
    listener->leaf_made(node, info, n, leaf_cost, reason);
  }
};

// Build by options.builder. Throws InputError("", 0, "kd-tree: ...") for options out of range and for a
// primitive with non-finite bounds.
//
// Tie rule (both SAH builders, so that they build the same tree): the lowest cost wins; at equal cost the
// lower axis (x, y, z), then the lower position, then planar primitives below. A split is made only if its
// cost is strictly below the leaf cost N * t_i. Leaf rules, in the order tested: N <= leaf_size
// (few_primitives), depth = kd_max_depth (max_depth), no candidate plane strictly inside the node or a node
// box of zero surface area (no_candidate), best cost >= N * t_i (no_cheaper_split), n_below + n_above more
// than the node's share of the reference budget (budget). Empty geometry: one empty leaf whose box is empty.
//
// Classification (what the traversal may rely on): a primitive is in every child whose open interior its
// conservatively clipped bounds (geometry/triangle_clip.h; spheres by their box) reach. One that only touches
// the split plane from one side is in that side alone, and planar primitives lying in the plane are in the side
// the SAH chose. A ray crossing the plane visits both children anyway; a ray lying in the plane (t_split NaN)
// must visit both too, or it misses the planar primitives of the side it skips.
KdTreeData build_kdtree(const Geometry& geometry, const KdOptions& options);
KdTreeData build_kdtree(const Geometry& geometry, const KdOptions& options, BuildListener& listener);

// The shape of a built tree, and its SAH cost: the expected cost of a random ray through the root,
// sum over inner nodes of t_t * S(node) / S(root) plus over leaves of t_i * N_leaf * S(leaf) / S(root).
struct KdTreeStats {
  size_t nodes = 0, leaves = 0, empty_leaves = 0;
  int max_depth = 0;
  size_t references = 0;        // prim_index.size()
  size_t max_leaf_prims = 0;
  double sah_cost = 0.0;
};
KdTreeStats kd_tree_stats(const KdTreeData& tree, const KdOptions& options);

}  // namespace raystep
