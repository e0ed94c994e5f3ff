// An acceleration structure as cells with data, for ParaView: the grid's cells, the kd-tree's and the
// octree's node cells, the BVHs' node boxes, the BSP tree's convex cells (with its planes clipped to them),
// each with its depth, leaf flag, primitive count and the builder's cost where known. Also the nodes and
// cells a trace file carries, so that a recorded walk is shown without a rebuild.
//
// Adding a structure (as the octree and the BSP tree were) is one function in structure_cells.cpp that fills
// a CellSet from the built accelerator, and one row in that file's table: nothing else changes (the CLI, the
// writer and the walk export work from CellSets and traces only).
#pragma once

#include <cstddef>
#include <cstdint>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/accel/accelerator.h"
#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/cell_set.h"

namespace raystep::vtk_export {

// A BSP node's splitting plane, clipped to the node's cell: the convex polygon the lecture draws.
struct PlanePolygon {
  std::vector<glm::vec3> corners;  // in order around the polygon; empty if the plane misses the cell
  int32_t node = 0;
  int32_t depth = 0;
};

struct StructureCells {
  std::string kind;  // the accelerator's name ("grid", "kd", "bvh8", ...)
  CellSet cells;
  std::vector<PlanePolygon> planes;  // bsp: one per inner node written (the "planes" block)
  size_t total = 0;                  // cells (or nodes) the structure has; cells.size() is at most max_cells
  std::string note;                  // what was written when not everything was, for the user ("" when all)
};

// The default bound on the cells written for a structure: a two-million-triangle kd-tree has millions of
// nodes, more than ParaView shows usefully and hundreds of megabytes of hexahedra.
constexpr size_t kDefaultMaxCells = 200000;

// True for structures structure_cells can describe (those with a row in structure_cells.cpp's table).
bool exports_structure(const Accelerator& accel);
// The names of those structures, for messages.
std::string exported_structure_names();

// A built accelerator's cells. Trees: the nodes of depth 0..d for the largest d whose nodes number at most
// max_cells (the note says d); grid: every cell if they number at most max_cells, else the occupied cells,
// merged into blocks of 2x2x2, 4x4x4, ... cells while there are more than max_cells (the note says which).
// Throws InputError("", 0, ...) for a structure without a row in the table.
StructureCells structure_cells(const Accelerator& accel, size_t max_cells = kDefaultMaxCells);

// The cells and nodes a trace names (Trace::cells, Trace::nodes): the part of the structure its rays saw.
StructureCells trace_structure_cells(const Trace& trace);

}  // namespace raystep::vtk_export
