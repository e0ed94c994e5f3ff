// A CellSet as a VTK unstructured grid: boxes as hexahedra, polytopes as polyhedra, each CellArray as cell
// data (vtkIntArray or vtkFloatArray). Private to the export library.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include "raystep/vtk_export/cell_set.h"
#include "raystep/vtk_export/structure_cells.h"

namespace raystep::vtk_export {

vtkSmartPointer<vtkUnstructuredGrid> cell_set_grid(const CellSet& cells);

// The BSP planes clipped to their cells as polygons, with node and depth as cell data (a plane that misses
// its cell, which rounding alone can cause, is left out).
vtkSmartPointer<vtkPolyData> plane_polydata(const std::vector<PlanePolygon>& planes);

}  // namespace raystep::vtk_export
