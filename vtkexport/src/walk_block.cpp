#include "walk_block.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>

namespace raystep::vtk_export {

vtkSmartPointer<vtkPolyData> ray_path_polydata(const TracedRay& ray, const RayPath& path, size_t index) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  auto t = vtkSmartPointer<vtkFloatArray>::New();
  t->SetName("t");
  auto lines = vtkSmartPointer<vtkCellArray>::New();
  lines->InsertNextCell(vtkIdType(path.points.size()));
  for (size_t i = 0; i < path.points.size(); ++i) {
    const glm::vec3& p = path.points[i];
    lines->InsertCellPoint(points->InsertNextPoint(p.x, p.y, p.z));
    t->InsertNextValue(path.t[i]);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetLines(lines);
  poly->GetPointData()->AddArray(t);
  auto cell_int = [&](const char* name, int value) {
    auto a = vtkSmartPointer<vtkIntArray>::New();
    a->SetName(name);
    a->InsertNextValue(value);
    poly->GetCellData()->AddArray(a);
  };
  cell_int("ray", int(index));
  cell_int("kind", int(ray.kind));
  cell_int("depth", ray.depth);
  cell_int("pixel_x", ray.has_pixel ? ray.pixel[0] : -1);
  cell_int("pixel_y", ray.has_pixel ? ray.pixel[1] : -1);
  cell_int("sample", ray.sample);
  cell_int("hit", path.hit);
  cell_int("prim", path.prim);
  return poly;
}

}  // namespace raystep::vtk_export
