#include "cell_set_block.h"

#include <algorithm>
#include <vector>

#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkCellType.h>
#include <vtkFloatArray.h>
#include <vtkIdList.h>
#include <vtkIntArray.h>
#include <vtkPoints.h>

namespace raystep::vtk_export {

vtkSmartPointer<vtkUnstructuredGrid> cell_set_grid(const CellSet& cells) {
  auto grid = vtkSmartPointer<vtkUnstructuredGrid>::New();
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  grid->Allocate(vtkIdType(cells.size()));
  for (const Bounds3& b : cells.boxes()) {
    // VTK's hexahedron: the lower face counter-clockwise seen from inside, then the upper face.
    const float x[2] = {b.lo.x, b.hi.x}, y[2] = {b.lo.y, b.hi.y}, z[2] = {b.lo.z, b.hi.z};
    const int corner[8][3] = {{0, 0, 0}, {1, 0, 0}, {1, 1, 0}, {0, 1, 0},
                              {0, 0, 1}, {1, 0, 1}, {1, 1, 1}, {0, 1, 1}};
    vtkIdType ids[8];
    for (int c = 0; c < 8; ++c)
      ids[c] = points->InsertNextPoint(x[corner[c][0]], y[corner[c][1]], z[corner[c][2]]);
    grid->InsertNextCell(VTK_HEXAHEDRON, 8, ids);
  }
  for (const ConvexCell& cell : cells.polytopes()) {
    // Nothing to draw (a BSP node whose cell is empty or a sliver too thin for floats): an empty cell, so
    // that the cell keeps its place (a walk has one cell per event).
    if (cell.faces.size() < 4) {
      grid->InsertNextCell(VTK_EMPTY_CELL, 0, nullptr);
      continue;
    }
    // A polyhedron: its points, each once (faces share their corners), then its faces as
    // [n, id0 .. id(n-1)] runs over those points.
    auto faces = vtkSmartPointer<vtkIdList>::New();
    std::vector<vtkIdType> ids;
    std::vector<glm::vec3> seen;
    for (const std::vector<glm::vec3>& face : cell.faces) {
      faces->InsertNextId(vtkIdType(face.size()));
      for (const glm::vec3& p : face) {
        auto it = std::find(seen.begin(), seen.end(), p);
        if (it == seen.end()) {
          seen.push_back(p);
          ids.push_back(points->InsertNextPoint(p.x, p.y, p.z));
          faces->InsertNextId(ids.back());
        } else {
          faces->InsertNextId(ids[size_t(it - seen.begin())]);
        }
      }
    }
    grid->InsertNextCell(VTK_POLYHEDRON, vtkIdType(ids.size()), ids.data(), vtkIdType(cell.faces.size()),
                         faces->GetPointer(0));
  }
  grid->SetPoints(points);
  for (const CellArray& a : cells.arrays()) {
    vtkSmartPointer<vtkDataArray> array;
    if (a.integer) {
      auto ints = vtkSmartPointer<vtkIntArray>::New();
      ints->SetNumberOfValues(vtkIdType(a.values.size()));
      for (size_t i = 0; i < a.values.size(); ++i) ints->SetValue(vtkIdType(i), int(a.values[i]));
      array = ints;
    } else {
      auto floats = vtkSmartPointer<vtkFloatArray>::New();
      floats->SetNumberOfValues(vtkIdType(a.values.size()));
      for (size_t i = 0; i < a.values.size(); ++i) floats->SetValue(vtkIdType(i), float(a.values[i]));
      array = floats;
    }
    array->SetName(a.name.c_str());
    grid->GetCellData()->AddArray(array);
  }
  return grid;
}

vtkSmartPointer<vtkPolyData> plane_polydata(const std::vector<PlanePolygon>& planes) {
  auto points = vtkSmartPointer<vtkPoints>::New();
  points->SetDataTypeToFloat();
  auto polys = vtkSmartPointer<vtkCellArray>::New();
  auto node = vtkSmartPointer<vtkIntArray>::New(), depth = vtkSmartPointer<vtkIntArray>::New();
  node->SetName("node");
  depth->SetName("depth");
  for (const PlanePolygon& p : planes) {
    if (p.corners.size() < 3) continue;
    polys->InsertNextCell(vtkIdType(p.corners.size()));
    for (const glm::vec3& c : p.corners) polys->InsertCellPoint(points->InsertNextPoint(c.x, c.y, c.z));
    node->InsertNextValue(p.node);
    depth->InsertNextValue(p.depth);
  }
  auto poly = vtkSmartPointer<vtkPolyData>::New();
  poly->SetPoints(points);
  poly->SetPolys(polys);
  poly->GetCellData()->AddArray(node);
  poly->GetCellData()->AddArray(depth);
  return poly;
}

}  // namespace raystep::vtk_export
