// The general BSP tree as data (lecture: "BSP tree: splitting planes of any orientation"): inner nodes hold a
// plane n . p = d of any direction, leaves a primitive list; a cold side table per node keeps its cell (a
// convex polytope, summarised by its bounding box and surface area), parent and depth for traces and the GUI.
// Laid out like the kd-tree (kdtree_node.h): depth-first preorder, the below child follows its parent.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"
#include "raystep/geometry/split_space.h"

namespace raystep {

// A splitting plane: the points p with dot(normal, p) = offset. "Below" is dot < offset, "above" dot >
// offset. The floats are the plane: the build classifies primitives against exactly these numbers and the
// traversal intersects rays with exactly these numbers, so the two never disagree about which plane is meant.
struct BspPlane {
  glm::vec3 normal{0.f, 0.f, 1.f};  // unit length up to float rounding
  float offset = 0.f;
};

// The exact sign (-1, 0, +1) of dot(plane.normal, p) - plane.offset for the float inputs: a double filter
// with an error bound, exact rational arithmetic (GMP) when the filter cannot decide.
int bsp_plane_side(const BspPlane& plane, const glm::vec3& p);

// Where a candidate plane's direction came from (the SAH inspector groups candidates by it).
enum class BspPlaneSource : uint8_t {
  axis,           // one of the 3 coordinate axes (the kd-tree's planes)
  face_diagonal,  // one of the 6 face diagonals of the 13 k-DOP directions
  body_diagonal,  // one of the 4 body diagonals
  primitive,      // a primitive's own plane (autopartition)
};
const char* bsp_plane_source_name(BspPlaneSource source);

// One node, 24 bytes. Inner: the plane and the index of the child above it (the child below is the next
// node). Leaf: prim_count primitives whose ids start at first_prim in BspTreeData::prim_index.
struct BspNode {
  static constexpr uint32_t kInner = 0xffffffffu;
  BspPlane plane;           // inner
  uint32_t child_or_first;  // inner: above child; leaf: offset into prim_index
  uint32_t count = kInner;  // leaf: primitive count; inner: kInner

  bool is_leaf() const { return count != kInner; }
  uint32_t above_child() const { return child_or_first; }
  uint32_t first_prim() const { return child_or_first; }
  uint32_t prim_count() const { return count; }
};
static_assert(sizeof(BspNode) == 24, "BspNode is 24 bytes");

// What a node was made of, kept beside the hot nodes (never read by the traversal).
struct BspNodeInfo {
  Bounds3 box;          // the bounding box of the node's cell (rounded outward to floats)
  float area = 0.f;     // the cell's surface area (of the polytope, not of its box)
  int32_t parent = -1;  // -1 for the root (node 0)
  int32_t depth = 0;
  float cost = 0.f;                              // the split's SAH cost, or N * t_i for a leaf
  BspPlaneSource source = BspPlaneSource::axis;  // inner: where its plane's direction came from
};

// A built tree. nodes[0] is the root (the scene's box); ids are positions in `nodes`.
struct BspTreeData {
  Bounds3 bounds;
  SplitSpace space;  // cut in space, or in the plane by vertical planes only (a flatland scene)
  std::vector<BspNode> nodes;
  std::vector<BspNodeInfo> info;
  std::vector<uint32_t> prim_index;  // leaves' primitive ids, increasing within a leaf
};

}  // namespace raystep
