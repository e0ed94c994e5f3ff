// BVH construction (lecture: "build similar to a kd-tree build", by the Surface Area Heuristic): a node's
// primitives are split in two by a plane through their centroids, chosen to minimise
// C = t_t + p_l N_l t_i + p_r N_r t_i with p = S(box of the side) / S(node box). Unlike the kd-tree, each
// primitive goes to exactly one side and each side's box is tight around its primitives, so the two boxes may
// overlap. Four builders write the same layout: binned SAH (Wald, "On fast construction of SAH-based
// bounding volume hierarchies", 2007; the default), a full sweep over every centroid (the reference the
// binned one is tested against), the object median (the contrast) and spatial splits (Stich, Friedrich and
// Dietrich, "Spatial splits in bounding volume hierarchies", 2009), which may also cut a primitive in two so
// that the children's boxes stop overlapping: a primitive is then referenced by more than one leaf.
#pragma once

#include <cstdint>
#include <string>

#include "raystep/accel/bvh_node.h"
#include "raystep/scene/geometry.h"

namespace raystep {

enum class BvhBuilder : uint8_t {
  binned,  // centroids binned into `bins` equal slots per axis; candidates between slots. O(N log N)
  sweep,   // every centroid boundary on every axis, by a sweep over the sorted centroids. O(N log^2 N)
  median,  // the longest axis of the centroids' box, split at the median centroid; leaves by size and depth
  sbvh,    // binned object splits, and spatial splits where the object split's children overlap (SBVH)
};

struct BvhOptions {
  BvhBuilder builder = BvhBuilder::binned;
  float t_i = 80.f;        // cost of one ray-primitive test (lecture: t_i = 80 t_t), the kd-tree's constants
  float t_t = 1.f;         // cost of one traversal step
  int bins = 16;           // binned builder: bins per axis, 2..256
  int leaf_size = 1;       // a node with at most this many primitives is a leaf without a search
  int max_leaf_size = 16;  // a node with more primitives is always split when a split exists (wide kernels)
  int max_depth = 64;      // <= kBvhMaxDepth
  int threads = 0;         // 0: TBB's default; the tree is the same for every thread count
  // SBVH: spatial splits are tried where the best object split's children overlap by more than
  // spatial_alpha of the root's measure (Stich et al.'s alpha), while the references made by splitting stay
  // within spatial_budget times the primitive count (the tree's references <= (1 + budget) N).
  float spatial_alpha = 1e-5f;
  float spatial_budget = 1.f;
};
constexpr int kBvhMaxDepth = 64;

// One candidate split of a node as the SAH evaluated it. An object split: primitives whose centroid's bin (or
// sorted position, for the sweep) is <= `bin` on `axis` go left; position is the plane between the two sides.
// A spatial split (SBVH): the plane at `position` cuts the node's box, bins 0..bin of the box lie left, and a
// primitive crossing the plane is referenced on both sides, each side's box holding only its part (so n_left
// + n_right may exceed the node's count).
struct BvhCandidate {
  int axis = 0;
  int bin = 0;
  float position = 0.f;
  uint32_t n_left = 0, n_right = 0;
  float area_left = 0.f, area_right = 0.f, area_node = 0.f;
  float cost = 0.f;
  bool chosen = false;   // the split the builder took (listener, SAH inspector)
  bool spatial = false;  // a spatial split (SBVH) rather than an object split
};

// Why a BVH node became a leaf.
enum class BvhLeafReason : uint8_t {
  few_primitives,    // N <= leaf_size
  max_depth,         // the depth limit
  no_cheaper_split,  // every candidate costs at least N * t_i (and N <= max_leaf_size)
  no_candidate,      // every centroid is the same point: no plane separates them
};
const char* bvh_leaf_reason_name(BvhLeafReason reason);

// What a builder tells about its work, as for the kd-tree (kdtree_build.h): a template parameter, with a null
// recorder that costs nothing and a listener for the SAH inspector and tests. Candidates are made only for
// nodes the listener wants.
class BvhBuildListener {
 public:
  virtual ~BvhBuildListener() = default;
  virtual bool wants_candidates(uint32_t node) const = 0;
  virtual void candidate(uint32_t node, const BvhCandidate& c) = 0;
  virtual void split(uint32_t node, const BvhNode& n, const BvhNodeInfo& info, const BvhCandidate& chosen,
                     float leaf_cost) = 0;
  virtual void leaf_made(uint32_t node, const BvhNode& n, const BvhNodeInfo& info, float leaf_cost,
                         BvhLeafReason reason) = 0;
};

// Throws InputError("", 0, "bvh: ...") for options out of range and for a primitive with non-finite bounds.
// Deterministic: the same tree for every thread count. Empty geometry: one empty leaf with an empty box.
// The listener hears about every node in id order, each with the decision the build took.
BvhData build_bvh(const Geometry& geometry, const BvhOptions& options);
BvhData build_bvh(const Geometry& geometry, const BvhOptions& options, BvhBuildListener& listener);

// The shape of a built hierarchy and its SAH cost: sum over inner nodes of t_t S(node) / S(root) plus over
// leaves of t_i N_leaf S(leaf) / S(root). Overlap: for each inner node the surface area of the intersection
// of its children's boxes over its own, summed over inner nodes weighted by S(node) / S(root) ("bounding
// volumes can overlap", measured).
struct BvhStats {
  size_t nodes = 0, leaves = 0;
  size_t references = 0;  // primitive ids in the leaves: the primitive count, more after spatial splits
  int max_depth = 0;
  size_t max_leaf_prims = 0;
  double mean_leaf_prims = 0.0;
  double sah_cost = 0.0;
  double overlap = 0.0;
};
BvhStats bvh_stats(const BvhData& bvh, const BvhOptions& options);

}  // namespace raystep
