// The 3D view's state for the scripted mode's --dump-state: the camera, the colours, the current cell or node
// and its projected corners, the stack and the visited nodes.
#include "views/scene_view.h"

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
#include "views/scene_draw.h"
#include "views/scene_view_impl.h"

namespace raystep::viz {

QJsonObject SceneView::dumpState() const {
  const Impl& d = *d_;
  QJsonObject o;
  vtkCamera* cam = d.base->GetActiveCamera();
  double pos[3], fp[3], up[3];
  cam->GetPosition(pos);
  cam->GetFocalPoint(fp);
  cam->GetViewUp(up);
  o["camera"] = QJsonObject{{"position", QJsonArray{pos[0], pos[1], pos[2]}},
                            {"focal_point", QJsonArray{fp[0], fp[1], fp[2]}},
                            {"view_up", QJsonArray{up[0], up[1], up[2]}},
                            {"view_angle", cam->GetViewAngle()}};
  QWidget* win = window();
  QPoint off = d.widget->mapTo(win, QPoint(0, 0));
  o["viewport"] = QJsonArray{off.x(), off.y(), d.widget->width(), d.widget->height()};
  o["colors"] = QJsonObject{{"current_cell", jsonColor(palette::currentCell)},
                            {"visited_cell", jsonColor(palette::visitedCell)},
                            {"ray", jsonColor(palette::ray)},
                            {"ray_ahead", jsonColor(palette::rayAhead)},
                            {"segment", jsonColor(palette::segment)},
                            {"hit_final", jsonColor(palette::hitFinal)},
                            {"hit_candidate", jsonColor(palette::hitCandidate)},
                            {"stack_node", jsonColor(palette::stackNode)},
                            {"split_plane", jsonColor(palette::splitPlane)},
                            {"selected_node", jsonColor(palette::selectedNode)},
                            {"built_plane", jsonColor(palette::builtPlane)},
                            {"bvh_child_first", jsonColor(palette::bvhChildFirst)},
                            {"bvh_child_other", jsonColor(palette::bvhChildOther)},
                            {"bvh_overlap", jsonColor(palette::bvhOverlap)},
                            {"bvh_skipped", jsonColor(palette::bvhSkipped)}};
  const TracedRay* ray = session_->ray();
  const replay::ReplayState& s = session_->state();
  if (ray && s.cell_event >= 0 && d.haveGrid) {
    const Event& e = ray->events[size_t(s.cell_event)];
    glm::vec3 lo = d.cellLo(e.cell), hi = d.cellHi(e.cell);
    QJsonArray corners;
    for (int c = 0; c < 8; ++c) {
      QPointF p;
      glm::vec3 w(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
      if (d.project(w, win, &p)) corners.append(QJsonArray{p.x(), p.y()});
    }
    o["current_cell"] = QJsonObject{{"cell", QJsonArray{e.cell[0], e.cell[1], e.cell[2]}},
                                    {"min", QJsonArray{lo.x, lo.y, lo.z}},
                                    {"max", QJsonArray{hi.x, hi.y, hi.z}},
                                    {"projected_corners", corners}};
  }
  auto projectBox = [&](const glm::vec3& lo, const glm::vec3& hi) {
    QJsonArray corners;
    for (int c = 0; c < 8; ++c) {
      QPointF p;
      glm::vec3 w(c & 1 ? hi.x : lo.x, c & 2 ? hi.y : lo.y, c & 4 ? hi.z : lo.z);
      if (d.project(w, win, &p)) corners.append(QJsonArray{p.x(), p.y()});
    }
    return corners;
  };
  if (d.selectedDrawn >= 0)
    o["selected_node"] = QJsonObject{{"node", d.selectedDrawn},
                                     {"min", QJsonArray{d.selectedLo.x, d.selectedLo.y, d.selectedLo.z}},
                                     {"max", QJsonArray{d.selectedHi.x, d.selectedHi.y, d.selectedHi.z}},
                                     {"projected_corners", projectBox(d.selectedLo, d.selectedHi)},
                                     {"cell_faces", d.selectedCellFaces}};
  if (d.buildPlanes) o["build_planes"] = d.builtPlanes;
  if (d.havePicked) o["picked_point"] = QJsonArray{d.picked.x, d.picked.y, d.picked.z};
  if (d.havePicked) o["picked_primitive"] = d.pickedPrim;
  if (const TraceNode* n = d.haveTree ? d.node(d.currentNode) : nullptr) {
    QJsonObject cn{{"node", n->id},
                   {"depth", n->depth},
                   {"leaf", n->leaf},
                   {"min", QJsonArray{n->box.lo.x, n->box.lo.y, n->box.lo.z}},
                   {"max", QJsonArray{n->box.hi.x, n->box.hi.y, n->box.hi.z}},
                   {"projected_corners", projectBox(n->box.lo, n->box.hi)}};
    if (!n->leaf && n->has_plane) {
      cn["normal"] = QJsonArray{n->normal.x, n->normal.y, n->normal.z};
      cn["offset"] = n->offset;
    } else if (!n->leaf && n->axis >= 0) {
      cn["axis"] = replay::axis_name(n->axis);
      cn["split"] = n->split;
    }
    // A BSP node: its convex cell as drawn (faces, vertices) and its plane's polygon clipped to it.
    if (const ConvexCell* cell = d.bspTree ? d.bspCell(n->id) : nullptr) {
      QJsonArray verts;
      for (size_t f = 0; f < cell->face_count(); ++f)
        for (size_t k = 0; k < cell->face_size(f); ++k)
          verts.append(QJsonArray{cell->face(f)[k].x, cell->face(f)[k].y, cell->face(f)[k].z});
      cn["cell_faces"] = int(cell->face_count());
      cn["cell_vertices"] = verts;
      cn["plane_polygon_points"] = int(d.splitData->GetNumberOfPoints());
    }
    o["current_node"] = cn;
    QJsonArray stack, vis;
    for (const replay::StackEntry& se : s.stack) stack.append(se.node);
    for (int32_t id : d.visitedNodes) vis.append(id);
    o["stack_nodes"] = stack;
    o["visited_nodes"] = vis;
    if (!n->children.empty()) {
      QJsonArray children;
      for (int32_t c : n->children) children.append(c);
      cn["children"] = children;
      o["current_node"] = cn;
    }
  }
  if (!d.bvh && !d.childrenDrawn.empty()) {  // octree: the current cell's children in crossing order
    QJsonArray drawn;
    for (int32_t c : d.childrenDrawn) drawn.append(c);
    o["octree_children_drawn"] = drawn;
  }
  if (d.bvh) {
    QJsonArray drawn, overlaps, skipped;
    for (int32_t c : d.childrenDrawn) {
      const TraceNode* n = d.node(c);
      drawn.append(QJsonObject{{"node", c},
                               {"min", QJsonArray{n->box.lo.x, n->box.lo.y, n->box.lo.z}},
                               {"max", QJsonArray{n->box.hi.x, n->box.hi.y, n->box.hi.z}},
                               {"projected_corners", projectBox(n->box.lo, n->box.hi)}});
    }
    for (size_t k = 0; k + 1 < d.overlapsDrawn.size(); k += 2)
      overlaps.append(QJsonArray{d.overlapsDrawn[k], d.overlapsDrawn[k + 1]});
    for (int32_t id : s.skipped_nodes) skipped.append(id);
    o["bvh"] =
        QJsonObject{{"children_drawn", drawn}, {"overlaps_drawn", overlaps}, {"skipped_nodes", skipped}};
  }
  QJsonArray visited;
  for (int i : s.visited_cell_events) {
    const Event& e = ray->events[size_t(i)];
    visited.append(QJsonArray{e.cell[0], e.cell[1], e.cell[2]});
  }
  o["visited_cells"] = visited;
  QJsonArray prims;
  for (const replay::PrimMark& m : s.prims) prims.append(QJsonObject{{"prim", m.prim}, {"state", replay::prim_state_name(m.state)}});
  o["prims"] = prims;
  if (d.rayDrawn) {
    QJsonArray samples;
    for (int i = 1; i < 24; ++i) {
      glm::vec3 w = d.rayFrom + (d.rayTo - d.rayFrom) * (float(i) / 24.f);
      QPointF p;
      if (d.project(w, win, &p)) samples.append(QJsonArray{p.x(), p.y()});
    }
    o["ray"] = QJsonObject{{"from", QJsonArray{d.rayFrom.x, d.rayFrom.y, d.rayFrom.z}},
                           {"to", QJsonArray{d.rayTo.x, d.rayTo.y, d.rayTo.z}},
                           {"projected_samples", samples}};
    if (std::isfinite(d.rayMark)) o["ray_mark"] = double(d.rayMark);
  }
  o["hit_marker"] = d.hitActor->GetVisibility() ? (s.accepted ? "accepted" : "candidate") : "none";
  o["backdrop"] = d.backdrop->cached() ? "image" : "drawn";  // the scene's layer kept as an image, or drawn
  return o;
}


}  // namespace raystep::viz
