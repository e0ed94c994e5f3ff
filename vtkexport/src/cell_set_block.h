// A CellSet as a VTK unstructured grid: boxes as hexahedra, polytopes as polyhedra, each CellArray as cell
// data (vtkIntArray or vtkFloatArray). Private to the export library.
#pragma once

#include <vtkSmartPointer.h>
#include <vtkUnstructuredGrid.h>

#include "raystep/vtk_export/cell_set.h"

namespace raystep::vtk_export {

vtkSmartPointer<vtkUnstructuredGrid> cell_set_grid(const CellSet& cells);

}  // namespace raystep::vtk_export
