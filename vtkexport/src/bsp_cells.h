// The BSP tree's convex cells for the export (lecture: "each BSP node is a convex region: the root's box cut
// by the planes of its ancestors"): core's ConvexCell (accel/bsp_cell.h, double) turned into the export's
// polytope, the splitting plane's polygon inside its cell, and the cells of the nodes a BSP trace names,
// rebuilt from the root box and the planes the trace carries (version 4).
#pragma once

#include <cstdint>
#include <unordered_map>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/accel/bsp_cell.h"
#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/cell_set.h"

namespace raystep::vtk_export {

// The polytope in floats, for VTK (faces counter-clockwise seen from outside, as core keeps them).
vtk_export::ConvexCell export_polytope(const raystep::ConvexCell& cell);

// The polygon where the plane dot(n, p) = d cuts the cell: the cap face of the part below it (empty when the
// plane misses the cell). `below` is that part, as cell.split made it.
std::vector<glm::vec3> plane_polygon(const raystep::ConvexCell& below, const glm::dvec3& n, double d);

// The cell of every node of a BSP trace, by node id: the structure's box cut by the planes of the node's
// ancestors (the child below a plane is its parent's id + 1, as in the tree's preorder). A node whose
// ancestors are not all in the trace gets its bounding box.
std::unordered_map<int32_t, raystep::ConvexCell> bsp_trace_cells(const Trace& trace);

}  // namespace raystep::vtk_export
