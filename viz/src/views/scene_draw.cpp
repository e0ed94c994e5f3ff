#include "views/scene_draw.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <limits>
#include <memory>
#include <map>
#include <unordered_map>
#include <unordered_set>

#include <QApplication>
#include <QCheckBox>
#include <QMouseEvent>
#include <QHBoxLayout>
#include <QJsonArray>
#include <QLabel>
#include <QToolButton>
#include <QSurfaceFormat>
#include <QVBoxLayout>

#include <QVTKOpenGLNativeWidget.h>
#include <vtkActor.h>
#include <vtkCallbackCommand.h>
#include <vtkCamera.h>
#include <vtkCellPicker.h>
#include <vtkCellArray.h>
#include <vtkCellData.h>
#include <vtkGenericOpenGLRenderWindow.h>
#include <vtkInteractorStyleTrackballCamera.h>
#include <vtkMath.h>
#include <vtkNew.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkPolyDataMapper.h>
#include <vtkProperty.h>
#include <vtkRenderWindowInteractor.h>
#include <vtkRenderer.h>
#include <vtkSmartPointer.h>
#include <vtkSphereSource.h>
#include <vtkUnsignedCharArray.h>

#include "raystep/accel/bsp_cell.h"
#include "raystep/replay/replay_state.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/bvh_choice.h"

#include "views/backdrop_cache.h"
#include "views/kd_tree_model.h"
#include "common/palette.h"
#include "views/scene_mesh.h"
#include "app/session.h"

namespace raystep::viz {

void setColor(vtkActor* a, const QColor& c) { a->GetProperty()->SetColor(c.redF(), c.greenF(), c.blueF()); }

// An actor drawn in exactly its colours: no lighting.
vtkSmartPointer<vtkActor> unlitActor(vtkPolyData* data, const QColor& c, float lineWidth) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetLighting(false);
  actor->GetProperty()->SetLineWidth(lineWidth);
  setColor(actor, c);
  return actor;
}

// The 12 edges of a box as lines appended to pts/lines.
void addBoxEdges(vtkPoints* pts, vtkCellArray* lines, const glm::vec3& lo, const glm::vec3& hi) {
  vtkIdType base = pts->GetNumberOfPoints();
  for (int c = 0; c < 8; ++c)
    pts->InsertNextPoint(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
  static const int edges[12][2] = {{0, 1}, {2, 3}, {4, 5}, {6, 7}, {0, 2}, {1, 3},
                                   {4, 6}, {5, 7}, {0, 4}, {1, 5}, {2, 6}, {3, 7}};
  for (auto& e : edges) {
    vtkIdType ids[2] = {base + e[0], base + e[1]};
    lines->InsertNextCell(2, ids);
  }
}

// The outline of an axis-aligned plane (axis, position) across a box: its four edges.
void addPlaneEdges(vtkPoints* pts, vtkCellArray* lines, const Bounds3& box, int axis, float at) {
  const int u = (axis + 1) % 3, v = (axis + 2) % 3;
  const vtkIdType base = pts->GetNumberOfPoints();
  for (int c = 0; c < 4; ++c) {
    glm::vec3 p;
    p[axis] = at;
    p[u] = c == 1 || c == 2 ? box.hi[u] : box.lo[u];
    p[v] = c >= 2 ? box.hi[v] : box.lo[v];
    pts->InsertNextPoint(p.x, p.y, p.z);
  }
  for (int c = 0; c < 4; ++c) {
    vtkIdType ids[2] = {base + c, base + (c + 1) % 4};
    lines->InsertNextCell(2, ids);
  }
}

// A convex cell's edges (each face's outline), shrunk towards its centre by `inset` of its size.
void addCellEdges(vtkPoints* pts, vtkCellArray* lines, const ConvexCell& cell, float inset) {
  glm::dvec3 centre(0.0);
  size_t count = 0;
  for (size_t f = 0; f < cell.face_count(); ++f)
    for (size_t k = 0; k < cell.face_size(f); ++k, ++count) centre += cell.face(f)[k];
  if (count) centre /= double(count);
  for (size_t f = 0; f < cell.face_count(); ++f) {
    const glm::dvec3* v = cell.face(f);
    const size_t m = cell.face_size(f);
    vtkIdType base = pts->GetNumberOfPoints();
    for (size_t k = 0; k < m; ++k) {
      glm::dvec3 p = v[k] + double(inset) * (centre - v[k]);
      pts->InsertNextPoint(p.x, p.y, p.z);
    }
    for (size_t k = 0; k < m; ++k) {
      vtkIdType ids[2] = {base + vtkIdType(k), base + vtkIdType((k + 1) % m)};
      lines->InsertNextCell(2, ids);
    }
  }
}

// A BSP node's plane clipped to its cell: the face the cut leaves on the part below (its cap).
void addPlaneCap(vtkPoints* pts, vtkCellArray* polys, const ConvexCell& cell, const TraceNode& n) {
  ConvexCell below, above;
  const glm::dvec3 normal(n.normal);
  cell.split(normal, double(n.offset), &below, &above);
  double lo, hi;
  cell.extent(normal, &lo, &hi);
  const double tol = 1e-6 * std::max({std::fabs(lo), std::fabs(hi), hi - lo, 1e-30});
  for (size_t f = 0; f < below.face_count(); ++f) {
    const glm::dvec3* v = below.face(f);
    const size_t m = below.face_size(f);
    bool onPlane = m >= 3;
    for (size_t k = 0; k < m && onPlane; ++k) onPlane = std::fabs(glm::dot(normal, v[k]) - n.offset) <= tol;
    if (!onPlane) continue;
    std::vector<vtkIdType> ids;
    for (size_t k = 0; k < m; ++k) ids.push_back(pts->InsertNextPoint(v[k].x, v[k].y, v[k].z));
    polys->InsertNextCell(vtkIdType(ids.size()), ids.data());
    return;
  }
}

// The 6 faces of a box as quads appended to pts/polys; returns the number of cells added.
int addBoxFaces(vtkPoints* pts, vtkCellArray* polys, const glm::vec3& lo, const glm::vec3& hi) {
  vtkIdType base = pts->GetNumberOfPoints();
  for (int c = 0; c < 8; ++c)
    pts->InsertNextPoint(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
  static const int faces[6][4] = {{0, 2, 6, 4}, {1, 5, 7, 3}, {0, 4, 5, 1},
                                  {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 6, 7, 5}};
  for (auto& f : faces) {
    vtkIdType ids[4] = {base + f[0], base + f[1], base + f[2], base + f[3]};
    polys->InsertNextCell(4, ids);
  }
  return 6;
}

void appendColor(vtkUnsignedCharArray* colors, const QColor& c, int n) {
  for (int k = 0; k < n; ++k) colors->InsertNextTuple3(c.red(), c.green(), c.blue());
}

// An actor coloured per cell (unlit).
vtkSmartPointer<vtkActor> cellColoredActor(vtkPolyData* data, float lineWidth) {
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputData(data);
  mapper->SetScalarModeToUseCellData();
  auto actor = vtkSmartPointer<vtkActor>::New();
  actor->SetMapper(mapper);
  actor->GetProperty()->SetLighting(false);
  actor->GetProperty()->SetLineWidth(lineWidth);
  return actor;
}

// A sphere as the scene's mesh draws it (scene_mesh.h), appended to pts/tris.
void addSphere(vtkPoints* pts, vtkCellArray* tris, const glm::vec3& c, float r) {
  std::vector<glm::vec3> points;
  std::vector<int32_t> triangles;
  sphereMesh(c, r, &points, &triangles);
  const vtkIdType base = pts->GetNumberOfPoints();
  for (const glm::vec3& q : points) pts->InsertNextPoint(q.x, q.y, q.z);
  for (size_t t = 0; t < triangles.size(); t += 3) {
    vtkIdType ids[3] = {base + triangles[t], base + triangles[t + 1], base + triangles[t + 2]};
    tris->InsertNextCell(3, ids);
  }
}

void addPrim(vtkPoints* pts, vtkCellArray* tris, const PrimShape& p) {
  if (p.sphere) {
    addSphere(pts, tris, p.v[0], p.radius);
    return;
  }
  vtkIdType ids[3];
  for (int k = 0; k < 3; ++k) ids[k] = pts->InsertNextPoint(p.v[k].x, p.v[k].y, p.v[k].z);
  tris->InsertNextCell(3, ids);
}

QJsonArray jsonColor(const QColor& c) { return QJsonArray{c.red(), c.green(), c.blue()}; }

}  // namespace raystep::viz
