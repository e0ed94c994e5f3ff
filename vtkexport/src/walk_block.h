// A recorded ray's path as a VTK polyline: the points of RayPath with the ray parameter t as point data, the
// ray's index, kind, depth, pixel and result as cell data; and the primitives it tested. Private to the
// export library.
#pragma once

#include <cstddef>
#include <vector>

#include <vtkPolyData.h>
#include <vtkSmartPointer.h>

#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/walk_cells.h"

namespace raystep::vtk_export {

vtkSmartPointer<vtkPolyData> ray_path_polydata(const TracedRay& ray, const RayPath& path, size_t index);

// The primitives a ray tested, one triangle (or a sphere's icosphere) per test, with the test's seq, order,
// event type, primitive id, hit and t as cell data.
vtkSmartPointer<vtkPolyData> ray_tests_polydata(const std::vector<PrimitiveTest>& tests);

}  // namespace raystep::vtk_export
