// A set of cells with named per-cell numbers, in the export's own terms (no VTK type): a structure's cells or
// nodes (lecture: "spatial subdivision" and "bounding volume hierarchies" drawn as the boxes they are), or
// the cells a ray visited. Boxes become VTK hexahedra; a convex cell that is not a box (a BSP node's
// polytope) becomes a VTK polyhedron. The VTK side (cell_set_block.h) turns any CellSet into an unstructured
// grid.
#pragma once

#include <cstddef>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/geometry/bounds.h"

namespace raystep::vtk_export {

// A convex polytope by its faces, each a planar polygon whose vertices run counter-clockwise seen from
// outside.
struct ConvexCell {
  std::vector<std::vector<glm::vec3>> faces;
};

// One number per cell, named as ParaView shows it. Integer arrays are written as 32-bit ints (ids, depths,
// counts, codes), the others as 32-bit floats (t, costs, split positions); NaN marks "not known here".
struct CellArray {
  std::string name;
  bool integer = false;
  std::vector<double> values;
};

class CellSet {
 public:
  // Cells are either all boxes or all polytopes.
  void add_box(const Bounds3& box) { boxes_.push_back(box); }
  void add_polytope(ConvexCell cell) { polytopes_.push_back(std::move(cell)); }
  size_t size() const { return boxes_.size() + polytopes_.size(); }
  const std::vector<Bounds3>& boxes() const { return boxes_; }
  const std::vector<ConvexCell>& polytopes() const { return polytopes_; }

  // The array of this name, created (empty) on first use; the caller pushes one value per cell.
  CellArray& array(const std::string& name, bool integer);
  const std::vector<CellArray>& arrays() const { return arrays_; }
  // A pending cell's values: set(name, v) after add_box; arrays that get no value for a cell are padded
  // with NaN (float) or -1 (integer) by finish().
  void set(const std::string& name, double value, bool integer);
  void finish();

 private:
  std::vector<Bounds3> boxes_;
  std::vector<ConvexCell> polytopes_;
  std::vector<CellArray> arrays_;
};

}  // namespace raystep::vtk_export
