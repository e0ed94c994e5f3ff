// The scene's primitives as one VTK polygon mesh: its triangles, and each sphere tessellated as an
// icosphere, with the primitive id, object, material and type of every triangle as cell data. Private to
// the export library.
#pragma once

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "raystep/geometry/icosphere.h"
#include "raystep/scene/geometry.h"

namespace raystep::vtk_export {

vtkSmartPointer<vtkPolyData> geometry_polydata(const Geometry& geometry);

// The unit icosphere (kSphereSubdivisions) that stands for a sphere wherever one is drawn.
const Icosphere& unit_sphere();

}  // namespace raystep::vtk_export
