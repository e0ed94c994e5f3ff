#include "walk_block.h"

#include <limits>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkFloatArray.h>
#include <vtkIntArray.h>
#include <vtkPointData.h>
#include <vtkPoints.h>

#include "geometry_block.h"

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

vtkSmartPointer<vtkPolyData> ray_tests_polydata(const std::vector<PrimitiveTest>& tests) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto ints = [](const char* name) {
    auto a = vtkSmartPointer<vtkIntArray>::New();
    a->SetName(name);
    return a;
  };
  auto step = ints("step"), seq = ints("seq"), event = ints("event"), prim = ints("prim"), hit = ints("hit");
  auto t = vtkSmartPointer<vtkFloatArray>::New();
  t->SetName("t");
  const Icosphere& unit = unit_sphere();
  for (size_t i = 0; i < tests.size(); ++i) {
    const PrimitiveTest& test = tests[i];
    auto add_triangle = [&](const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
      const vtkIdType ids[3] = {points->InsertNextPoint(a.x, a.y, a.z),
                                points->InsertNextPoint(b.x, b.y, b.z),
                                points->InsertNextPoint(c.x, c.y, c.z)};
      polys->InsertNextCell(3, ids);
      step->InsertNextValue(int(i));
      seq->InsertNextValue(int(test.seq));
      event->InsertNextValue(int(test.type));
      prim->InsertNextValue(test.shape.id);
      hit->InsertNextValue(test.hit);
      t->InsertNextValue(test.hit ? test.t : std::numeric_limits<float>::quiet_NaN());
    };
    const TracePrimitive& p = test.shape;
    if (p.type == PrimType::triangle) {
      add_triangle(p.v[0], p.v[1], p.v[2]);
    } else {
      for (size_t k = 0; k < unit.triangles.size(); ++k)
        add_triangle(p.v[0] + p.radius * unit.vertex(k, 0), p.v[0] + p.radius * unit.vertex(k, 1),
                     p.v[0] + p.radius * unit.vertex(k, 2));
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  for (auto* a : {step.Get(), seq.Get(), event.Get(), prim.Get(), hit.Get()})
    poly->GetCellData()->AddArray(a);
  poly->GetCellData()->AddArray(t);
  return poly;
}

}  // namespace raystep::vtk_export
