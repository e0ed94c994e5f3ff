// The ParaView export (docs/vtk-export.md): the scene's geometry, a structure's cells and each
// recorded ray's walk written with VTK's XML writers as one multiblock dataset, DIR/raystep.vtm, whose
// blocks are named "geometry", "structure" and "ray 0", "ray 1", ... (each ray a multiblock of "path",
// "visited" and "tests"). This library links VTK privately: no header of it names a VTK type (the F3D split).
#pragma once

#include <string>
#include <vector>

#include "raystep/scene/geometry.h"
#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/structure_cells.h"

namespace raystep::vtk_export {

// The multiblock file's name inside the output folder; its pieces go in the folder "raystep" beside it.
constexpr const char* kMultiBlockFile = "raystep.vtm";

struct ExportInput {
  const Geometry* geometry = nullptr;         // the scene's primitives (required)
  const StructureCells* structure = nullptr;  // optional: the "structure" block
  const Trace* trace = nullptr;               // optional: a "ray N" block for each of its rays
  std::string trace_name;                     // for messages about the trace
};

struct ExportSummary {
  std::vector<std::string> blocks;  // the top-level block names, in order
  std::vector<std::string> files;   // every file written, relative to the folder
  std::vector<size_t> visited;      // per ray: the cells in its "visited" block
  std::vector<size_t> tests;        // per ray: the primitive tests in its "tests" block
};

// Spheres are written tessellated: an icosphere of this many subdivisions (320 triangles) per sphere.
constexpr int kSphereSubdivisions = 2;

// Write into the existing folder dir (the caller makes it atomic: a temporary folder renamed into place).
// Throws InputError(dir, 0, ...) if VTK cannot write a file.
ExportSummary write_vtk_export(const std::string& dir, const ExportInput& input);

}  // namespace raystep::vtk_export
