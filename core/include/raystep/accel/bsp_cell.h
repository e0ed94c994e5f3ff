// A BSP node's cell: a convex polytope, the root's box cut by the planes on the path to the node (lecture:
// "each BSP node is a convex region"). Its surface area weighs the node in the SAH (Crofton: a random line
// meets a convex child of a convex parent with probability S_child / S_parent), its faces are what the GUI
// draws. Double precision with a tolerant plane-side rule, so that a cut never leaves a cell with inverted or
// crossing faces. Nothing the traversal relies on comes from here: primitives are classified by exact
// predicates against the plane alone (bsp_build.h), so a cell that is off by rounding costs quality, never
// hits.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/accel/bsp_node.h"
#include "raystep/geometry/bounds.h"
#include "raystep/geometry/split_space.h"

namespace raystep {

class ConvexCell {
 public:
  ConvexCell() = default;
  // The closed box; empty for an empty box. A flat box (zero extent on an axis) is kept with its faces.
  static ConvexCell box(const Bounds3& b);

  bool empty() const { return face_start_.size() <= 1; }
  size_t face_count() const { return empty() ? 0 : face_start_.size() - 1; }
  // The vertices of face f in order, counter-clockwise seen from outside (outward area vector).
  const glm::dvec3* face(size_t f) const { return verts_.data() + face_start_[f]; }
  size_t face_size(size_t f) const { return face_start_[f + 1] - face_start_[f]; }

  double area() const;
  // The perimeter of its top face in the plane: a flatland tree's cell is a prism over a convex polygon
  // (every cut is vertical), and that polygon's perimeter weighs it in the SAH (Crofton in the plane).
  double perimeter() const;
  // area() in space, perimeter() in the plane.
  double measure(SplitSpace space) const { return space.plane() ? perimeter() : area(); }
  Bounds3 bounds() const;  // rounded outward to floats
  // The cell's extent along a direction: min and max of dot(n, vertex).
  void extent(const glm::dvec3& n, double* lo, double* hi) const;

  // The two parts of the cell on either side of dot(n, p) = d: `below` (dot <= d) and `above`. The side rule:
  // a vertex within tol = 2^-40 * (scale of the cell and d) of the plane counts as on it and belongs to both
  // parts; an edge is cut only between a vertex strictly below and one strictly above, so a cut point is
  // always well defined and lies on the edge. A part with no face left is empty.
  void split(const glm::dvec3& n, double d, ConvexCell* below, ConvexCell* above) const;
  // Their surface areas without building them (the SAH's inner loop): each face clipped as above, and the
  // cap by the closed surface's zero total area vector (the cap's is minus the sum of the others').
  void split_areas(const glm::dvec3& n, double d, double* below, double* above) const;
  // split_areas in space; in the plane the two parts' perimeters (of the parts split() makes).
  void split_measures(const glm::dvec3& n, double d, SplitSpace space, double* below, double* above) const;

 private:
  double tolerance(const glm::dvec3& n, double d) const;
  std::vector<glm::dvec3> verts_;
  std::vector<uint32_t> face_start_;  // face f is verts_[face_start_[f] .. face_start_[f + 1])
  double scale_ = 0.0;                // max |coordinate| of any vertex
};

}  // namespace raystep
