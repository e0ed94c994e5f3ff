#include "geometry_block.h"

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>

#include "raystep/vtk_export/vtk_export.h"

namespace raystep::vtk_export {

const Icosphere& unit_sphere() {
  static const Icosphere unit = make_icosphere(kSphereSubdivisions);
  return unit;
}

vtkSmartPointer<vtkPolyData> geometry_polydata(const Geometry& geometry) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto named = [](const char* name) {
    auto a = vtkSmartPointer<vtkIntArray>::New();
    a->SetName(name);
    return a;
  };
  auto primitive = named("primitive"), object = named("object"), material = named("material"),
       type = named("type");
  auto add_triangle = [&](uint32_t id, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
    const vtkIdType ids[3] = {points->InsertNextPoint(a.x, a.y, a.z), points->InsertNextPoint(b.x, b.y, b.z),
                              points->InsertNextPoint(c.x, c.y, c.z)};
    polys->InsertNextCell(3, ids);
    primitive->InsertNextValue(int(id));
    object->InsertNextValue(int(geometry.object_of(id)));
    material->InsertNextValue(int(geometry.material(id)));
    type->InsertNextValue(int(geometry.type(id)));
  };
  // One unit icosphere, scaled and moved onto each sphere.
  const Icosphere& unit = unit_sphere();
  for (uint32_t id = 0; id < geometry.size(); ++id) {
    if (geometry.type(id) == PrimType::triangle) {
      add_triangle(id, geometry.vertex(id, 0), geometry.vertex(id, 1), geometry.vertex(id, 2));
    } else {
      const Sphere& s = geometry.sphere(id);
      for (size_t t = 0; t < unit.triangles.size(); ++t)
        add_triangle(id, s.center + s.radius * unit.vertex(t, 0), s.center + s.radius * unit.vertex(t, 1),
                     s.center + s.radius * unit.vertex(t, 2));
    }
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  for (auto* a : {primitive.Get(), object.Get(), material.Get(), type.Get()})
    poly->GetCellData()->AddArray(a);
  return poly;
}

}  // namespace raystep::vtk_export
