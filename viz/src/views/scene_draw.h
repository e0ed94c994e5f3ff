// The 3D view's drawing pieces (scene_view*.cpp only): unlit actors, a box's edges and faces, a plane's outline
// across a box, a BSP cell's edges and its plane's cap, spheres and primitives as the scene's mesh draws them,
// per-cell colours.
#pragma once

#include <QColor>
#include <QJsonArray>

#include <vtkActor.h>
#include <vtkCellArray.h>
#include <vtkPoints.h>
#include <vtkPolyData.h>
#include <vtkSmartPointer.h>
#include <vtkUnsignedCharArray.h>

#include "raystep/accel/bsp_cell.h"
#include "raystep/geometry/bounds.h"
#include "raystep/trace/trace_file.h"
#include "views/scene_mesh.h"

namespace raystep::viz {

void setColor(vtkActor* a, const QColor& c);
// An actor drawn in exactly its colours: no lighting.
vtkSmartPointer<vtkActor> unlitActor(vtkPolyData* data, const QColor& c, float lineWidth);
// The 12 edges of a box as lines appended to pts/lines.
void addBoxEdges(vtkPoints* pts, vtkCellArray* lines, const glm::vec3& lo, const glm::vec3& hi);
// The outline of an axis-aligned plane (axis, position) across a box: its four edges.
void addPlaneEdges(vtkPoints* pts, vtkCellArray* lines, const Bounds3& box, int axis, float at);
// A convex cell's edges (each face's outline), shrunk towards its centre by `inset` of its size.
void addCellEdges(vtkPoints* pts, vtkCellArray* lines, const ConvexCell& cell, float inset);
// A BSP node's plane clipped to its cell: the face the cut leaves on the part below (its cap).
void addPlaneCap(vtkPoints* pts, vtkCellArray* polys, const ConvexCell& cell, const TraceNode& n);
// The 6 faces of a box as quads appended to pts/polys; returns the number of cells added.
int addBoxFaces(vtkPoints* pts, vtkCellArray* polys, const glm::vec3& lo, const glm::vec3& hi);
void appendColor(vtkUnsignedCharArray* colors, const QColor& c, int n);
// An actor coloured per cell (unlit).
vtkSmartPointer<vtkActor> cellColoredActor(vtkPolyData* data, float lineWidth);
// A sphere as the scene's mesh draws it (scene_mesh.h), appended to pts/tris.
void addSphere(vtkPoints* pts, vtkCellArray* tris, const glm::vec3& c, float r);
void addPrim(vtkPoints* pts, vtkCellArray* tris, const PrimShape& p);
QJsonArray jsonColor(const QColor& c);

}  // namespace raystep::viz
