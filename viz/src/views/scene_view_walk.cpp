// The 3D view at a step: the walk drawn over the scene (the ray walked and ahead, the current cell or node, the
// stack, the visited cells and nodes, the primitives by state, a BVH's children and an octree's child order).
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

void SceneView::updateBvhChildren() {
  Impl& d = *d_;
  const TracedRay* ray = session_->ray();
  const replay::ReplayState& s = session_->state();
  vtkNew<vtkPoints> fpts, epts, opts, kpts;
  vtkNew<vtkCellArray> fpolys, elines, olines, klines;
  vtkNew<vtkUnsignedCharArray> fcolors, ecolors;
  fcolors->SetNumberOfComponents(3);
  ecolors->SetNumberOfComponents(3);
  d.childrenDrawn.clear();
  d.overlapsDrawn.clear();
  d.bvh = ray && d.haveTree && replay::is_bvh_ray(session_->trace(), *ray);
  if (d.bvh) {
    // The children tested so far: a box hit filled, a box missed outlined only.
    replay::BvhChoice c = replay::bvh_choice(*ray, s);
    std::vector<const TraceNode*> hitBoxes;
    for (size_t k = 0; k < c.tests.size(); ++k) {
      const replay::BoxTestMark& m = c.tests[k];
      const TraceNode* n = d.node(m.child);
      if (!n || !m.done) continue;
      const QColor& col = k == 0 ? palette::bvhChildFirst : palette::bvhChildOther;
      d.childrenDrawn.push_back(m.child);
      int before = int(elines->GetNumberOfCells());
      addBoxEdges(epts, elines, n->box.lo, n->box.hi);
      appendColor(ecolors, col, int(elines->GetNumberOfCells()) - before);
      if (m.hit) {
        appendColor(fcolors, col, addBoxFaces(fpts, fpolys, n->box.lo, n->box.hi));
        hitBoxes.push_back(n);
      }
    }
    // Where two children's boxes overlap: their intersection, outlined (the tints add up inside it).
    for (size_t a = 0; a < hitBoxes.size(); ++a)
      for (size_t b = a + 1; b < hitBoxes.size(); ++b) {
        glm::vec3 lo = glm::max(hitBoxes[a]->box.lo, hitBoxes[b]->box.lo);
        glm::vec3 hi = glm::min(hitBoxes[a]->box.hi, hitBoxes[b]->box.hi);
        if (lo.x > hi.x || lo.y > hi.y || lo.z > hi.z) continue;
        addBoxEdges(opts, olines, lo, hi);
        d.overlapsDrawn.push_back(hitBoxes[a]->id);
        d.overlapsDrawn.push_back(hitBoxes[b]->id);
      }
    for (int32_t id : s.skipped_nodes)
      if (const TraceNode* n = d.node(id)) {
        glm::vec3 inset = 0.01f * (n->box.hi - n->box.lo);
        addBoxEdges(kpts, klines, n->box.lo + inset, n->box.hi - inset);
      }
  } else if (ray && d.haveTree && session_->trace() && replay::is_octree_ray(session_->trace(), *ray)) {
    // Octree: the current inner cell's children in the order the ray crosses them (Revelles), from orange
    // (the first, by the entry plane) to violet (the last before the ray leaves the cell); the next one to
    // be entered filled.
    replay::OctreeChoice c = replay::octree_choice(*session_->trace(), *ray, s);
    const size_t m = c.valid ? c.path.size() : 0;
    for (size_t k = 0; k < m; ++k) {
      const int32_t id = c.path[k].node;
      const TraceNode* n = d.node(id);
      if (!n) continue;
      // Concealed (a lesson asks which child comes first): all in the last colour, none filled.
      const double f = d.conceal ? 1.0 : m > 1 ? double(k) / double(m - 1) : 0.0;
      const QColor& a = palette::bvhChildFirst;
      const QColor& b = palette::bvhChildOther;
      QColor col(int(std::lround(a.red() + f * (b.red() - a.red()))),
                 int(std::lround(a.green() + f * (b.green() - a.green()))),
                 int(std::lround(a.blue() + f * (b.blue() - a.blue()))));
      d.childrenDrawn.push_back(id);
      glm::vec3 inset = 0.03f * (n->box.hi - n->box.lo);
      int before = int(elines->GetNumberOfCells());
      addBoxEdges(epts, elines, n->box.lo + inset, n->box.hi - inset);
      appendColor(ecolors, col, int(elines->GetNumberOfCells()) - before);
      if (int(k) == c.visited_so_far && !d.conceal)
        appendColor(fcolors, col, addBoxFaces(fpts, fpolys, n->box.lo, n->box.hi));
    }
  }
  d.childFacesData->SetPoints(fpts);
  d.childFacesData->SetPolys(fpolys);
  d.childFacesData->GetCellData()->SetScalars(fcolors);
  d.childFacesData->Modified();
  d.childEdgesData->SetPoints(epts);
  d.childEdgesData->SetLines(elines);
  d.childEdgesData->GetCellData()->SetScalars(ecolors);
  d.childEdgesData->Modified();
  d.overlapData->SetPoints(opts);
  d.overlapData->SetLines(olines);
  d.overlapData->Modified();
  d.skippedData->SetPoints(kpts);
  d.skippedData->SetLines(klines);
  d.skippedData->Modified();
}

void SceneView::updateStep() {
  auto t0 = std::chrono::steady_clock::now();
  Impl& d = *d_;
  if (d.dormant) {
    d.stale = true;
    return;
  }
  const TracedRay* ray = session_->ray();
  const replay::ReplayState& s = session_->state();
  // A tree node's outline: a BSP node's convex cell, any other node's box; inset (a node on the stack) by a
  // fraction of its size, so that it keeps an outline of its own beside its parent's and sibling's.
  auto addNodeEdges = [&d](vtkPoints* pts, vtkCellArray* lines, const TraceNode& n, float inset) {
    if (d.bspTree)
      if (const ConvexCell* cell = d.bspCell(n.id)) return addCellEdges(pts, lines, *cell, inset);
    glm::vec3 in = inset * (n.box.hi - n.box.lo);
    addBoxEdges(pts, lines, n.box.lo + in, n.box.hi - in);
  };

  // Cells: the current one highlighted, the visited ones faded.
  vtkNew<vtkPoints> vpts, cpts;
  vtkNew<vtkCellArray> vlines, clines;
  if (ray && d.haveGrid) {
    // The most recent visited cells only: a walk through tens of thousands of cells would bury the view
    // (and the software renderer) in lines; the ray itself shows where the walk came from.
    size_t first = s.visited_cell_events.size() > kMaxVisitedDrawn ? s.visited_cell_events.size() - kMaxVisitedDrawn : 0;
    for (size_t v = first; v < s.visited_cell_events.size(); ++v) {
      int i = s.visited_cell_events[v];
      const Event& e = ray->events[size_t(i)];
      addBoxEdges(vpts, vlines, d.cellLo(e.cell), d.cellHi(e.cell));
    }
    if (s.cell_event >= 0) {
      const Event& e = ray->events[size_t(s.cell_event)];
      addBoxEdges(cpts, clines, d.cellLo(e.cell), d.cellHi(e.cell));
    }
  }
  // kd-tree: the current node (the last one visited or popped; at a push, still the inner node being split),
  // its split plane clipped to its box, the nodes on the stack, the nodes visited before.
  vtkNew<vtkPoints> stpts, sppts;
  vtkNew<vtkCellArray> stlines, sptris;
  d.currentNode = -1;
  d.visitedNodes.clear();
  if (ray && d.haveTree) {
    if (d.nodesOf != session_->trace()) d.indexNodes(session_->trace());
    if (s.node_event >= 0) d.currentNode = ray->events[size_t(s.node_event)].node;
    d.visitedNodes = s.visited_nodes;
    std::unordered_set<int32_t> onStack;
    for (const replay::StackEntry& se : s.stack) onStack.insert(se.node);
    size_t first = d.visitedNodes.size() > kMaxVisitedDrawn ? d.visitedNodes.size() - kMaxVisitedDrawn : 0;
    for (size_t v = first; v < d.visitedNodes.size(); ++v) {
      int32_t id = d.visitedNodes[v];
      const TraceNode* n = d.node(id);
      if (n && id != d.currentNode && !onStack.count(id)) addNodeEdges(vpts, vlines, *n, 0.f);
    }
    // A far child shares faces with its parent and its sibling, whose outlines are drawn over it: inset by 2%
    // of its size, the box waiting on the stack keeps an outline of its own.
    for (const replay::StackEntry& se : s.stack)
      if (const TraceNode* n = d.node(se.node)) addNodeEdges(stpts, stlines, *n, 0.02f);
    // BVH: a popped node that is skipped is drawn as skipped (sage), not as the node the walk is in.
    const bool skippedNow =
        std::find(s.skipped_nodes.begin(), s.skipped_nodes.end(), d.currentNode) != s.skipped_nodes.end();
    if (const TraceNode* n = skippedNow ? nullptr : d.node(d.currentNode)) {
      addNodeEdges(cpts, clines, *n, 0.f);
      if (n->has_plane) {  // a BSP node's plane, clipped to its convex cell
        if (const ConvexCell* cell = d.bspCell(n->id)) addPlaneCap(sppts, sptris, *cell, *n);
      } else if (!n->leaf &&
                 n->children.empty()) {  // a kd node's plane (a BVH node has children's boxes instead)
        int a = n->axis, b = (a + 1) % 3, c = (a + 2) % 3;
        vtkIdType ids[4];
        for (int k = 0; k < 4; ++k) {
          glm::vec3 p;
          p[a] = n->split;
          p[b] = (k == 1 || k == 2) ? n->box.hi[b] : n->box.lo[b];
          p[c] = k >= 2 ? n->box.hi[c] : n->box.lo[c];
          ids[k] = sppts->InsertNextPoint(p.x, p.y, p.z);
        }
        sptris->InsertNextCell(4, ids);
      }
    }
  }
  updateBvhChildren();
  d.stackData->SetPoints(stpts);
  d.stackData->SetLines(stlines);
  d.stackData->Modified();
  d.splitData->SetPoints(sppts);
  d.splitData->SetPolys(sptris);
  d.splitData->Modified();
  d.visitedData->SetPoints(vpts);
  d.visitedData->SetLines(vlines);
  d.visitedData->Modified();
  d.cellData->SetPoints(cpts);
  d.cellData->SetLines(clines);
  d.cellData->Modified();

  // The current cell's primitives by state. Their shapes change only when the walk enters another cell;
  // within a cell a step changes only their colours.
  const void* blockKey = ray;
  if (blockKey != d.primBlockRay || s.block_event != d.primBlock) {
    d.primBlockRay = blockKey;
    d.primBlock = s.block_event;
    vtkNew<vtkPoints> ppts;
    vtkNew<vtkCellArray> ptris;
    d.primCells.clear();
    for (const replay::PrimMark& m : s.prims) {
      PrimShape shape;
      vtkIdType before = ptris->GetNumberOfCells();
      if (d.primShape(m.prim, &shape)) addPrim(ppts, ptris, shape);
      d.primCells.push_back(int(ptris->GetNumberOfCells() - before));
    }
    d.primData->SetPoints(ppts);
    d.primData->SetPolys(ptris);
    vtkNew<vtkUnsignedCharArray> pcolors;
    pcolors->SetNumberOfComponents(3);
    pcolors->SetNumberOfTuples(ptris->GetNumberOfCells());
    d.primData->GetCellData()->SetScalars(pcolors);
  }
  {
    auto* pcolors = vtkUnsignedCharArray::SafeDownCast(d.primData->GetCellData()->GetScalars());
    vtkIdType cell = 0;
    vtkNew<vtkPoints> tpts;
    vtkNew<vtkCellArray> tlines;
    for (size_t i = 0; i < s.prims.size() && i < d.primCells.size(); ++i) {
      const replay::PrimMark& m = s.prims[i];
      QColor c = m.state == replay::PrimState::pending   ? palette::primPending
                 : m.state == replay::PrimState::testing ? (m.hit ? palette::primHit : palette::primMissed)
                 : m.state == replay::PrimState::hit     ? palette::primHit
                 : m.state == replay::PrimState::missed  ? palette::primMissed
                                                 : palette::primSkipped;
      if (PrimShape p; m.state == replay::PrimState::testing && d.primShape(m.prim, &p)) {
        if (p.sphere) {  // three great circles
          for (int axis = 0; axis < 3; ++axis) {
            vtkIdType first = tpts->GetNumberOfPoints();
            const int n = 48;
            for (int k = 0; k <= n; ++k) {
              double a = 2.0 * M_PI * k / n;
              glm::vec3 q(0.f);
              q[(axis + 1) % 3] = float(std::cos(a)) * p.radius;
              q[(axis + 2) % 3] = float(std::sin(a)) * p.radius;
              q += p.v[0];
              tpts->InsertNextPoint(q.x, q.y, q.z);
              if (k > 0) {
                vtkIdType seg[2] = {first + k - 1, first + k};
                tlines->InsertNextCell(2, seg);
              }
            }
          }
        } else {
          vtkIdType ids[4];
          for (int k = 0; k < 3; ++k) ids[k] = tpts->InsertNextPoint(p.v[k].x, p.v[k].y, p.v[k].z);
          ids[3] = ids[0];
          tlines->InsertNextCell(4, ids);
        }
      }
      unsigned char rgb[3] = {(unsigned char)c.red(), (unsigned char)c.green(), (unsigned char)c.blue()};
      for (int k = 0; k < d.primCells[i]; ++k) pcolors->SetTypedTuple(cell++, rgb);
    }
    pcolors->Modified();
    d.testingData->SetPoints(tpts);
    d.testingData->SetLines(tlines);
    d.testingData->Modified();
  }
  d.primData->Modified();
  // Translucent, so that a big hit triangle does not hide the cells and the ray behind it.
  d.primActor->GetProperty()->SetOpacity(0.6);

  // The ray, from its origin to where the walk ends (the final hit, or the grid's exit), and its interval now.
  vtkNew<vtkPoints> rpts, apts, spts;
  vtkNew<vtkCellArray> rlines, alines, slines;
  d.rayDrawn = false;
  if (ray && !ray->events.empty()) {
    const Event& last = ray->events.back();
    float tEnd = last.prim >= 0 ? last.t : 0.f;
    if (last.prim < 0) {
      float t0r, t1r;
      SlabRay slab(ray->ray);
      if ((d.haveGrid || d.haveTree) && intersect_slabs(Bounds3(d.gridLo, d.gridHi), slab, &t0r, &t1r)) tEnd = t1r;
      else tEnd = 2.f * d.sceneRadius / std::max(1e-12f, glm::length(ray->ray.direction));
    }
    float tStart = std::max(ray->ray.tmin, 0.f);
    tEnd = std::min(tEnd, ray->ray.tmax);
    d.rayFrom = ray->ray.at(tStart);
    d.rayTo = ray->ray.at(tEnd);
    d.rayDrawn = true;
    // Bright up to the end of the current interval (where the walk has got to), dark beyond it.
    // The current interval is drawn on its own (thick), so the bright part stops where it starts.
    float tNow = s.has_interval ? std::clamp(s.t_max, tStart, tEnd) : tStart;
    if (s.ended) tNow = tEnd;
    float tWalked = s.has_interval && !s.ended ? std::clamp(s.t_min, tStart, tEnd) : tNow;
    if (std::isfinite(d.rayMark)) tNow = tWalked = std::clamp(d.rayMark, tStart, tEnd);  // the compare's t
    glm::vec3 now = ray->ray.at(tNow), walked = ray->ray.at(tWalked);
    if (tWalked > tStart) {
      vtkIdType ids[2] = {rpts->InsertNextPoint(d.rayFrom.x, d.rayFrom.y, d.rayFrom.z),
                          rpts->InsertNextPoint(walked.x, walked.y, walked.z)};
      rlines->InsertNextCell(2, ids);
    }
    if (tNow < tEnd) {
      vtkIdType ids[2] = {apts->InsertNextPoint(now.x, now.y, now.z),
                          apts->InsertNextPoint(d.rayTo.x, d.rayTo.y, d.rayTo.z)};
      alines->InsertNextCell(2, ids);
    }
    if (s.has_interval) {
      float a = std::max(s.t_min, tStart), b = std::min(s.t_max, std::isfinite(s.t_max) ? s.t_max : tEnd);
      glm::vec3 pa = ray->ray.at(a), pb = ray->ray.at(b);
      vtkIdType sids[2] = {spts->InsertNextPoint(pa.x, pa.y, pa.z), spts->InsertNextPoint(pb.x, pb.y, pb.z)};
      slines->InsertNextCell(2, sids);
    }
  }
  d.rayData->SetPoints(rpts);
  d.rayData->SetLines(rlines);
  d.rayData->Modified();
  d.aheadData->SetPoints(apts);
  d.aheadData->SetLines(alines);
  d.aheadData->Modified();
  d.segmentData->SetPoints(spts);
  d.segmentData->SetLines(slines);
  d.segmentData->Modified();

  // The nearest hit so far: orange while it may still be beaten, magenta once accepted.
  if (ray && s.nearest_prim >= 0) {
    glm::vec3 p = ray->ray.at(s.nearest_t);
    d.hitSphere->SetCenter(p.x, p.y, p.z);
    d.hitSphere->SetRadius(0.03 * d.sceneRadius * d.scale);
    setColor(d.hitActor, s.accepted ? palette::hitFinal : palette::hitCandidate);
    d.hitActor->SetVisibility(true);
  } else {
    d.hitActor->SetVisibility(false);
  }

  const TraceNode* followNode = d.haveTree ? d.node(d.currentNode) : nullptr;
  if (d.follow && ray && ((s.cell_event >= 0 && d.haveGrid) || followNode)) {
    glm::vec3 lo = followNode ? followNode->box.lo : d.cellLo(ray->events[size_t(s.cell_event)].cell);
    glm::vec3 hi = followNode ? followNode->box.hi : d.cellHi(ray->events[size_t(s.cell_event)].cell);
    glm::vec3 c = 0.5f * (lo + hi);
    vtkCamera* cam = d.base->GetActiveCamera();
    double fp[3], pos[3];
    cam->GetFocalPoint(fp);
    cam->GetPosition(pos);
    glm::dvec3 offset(pos[0] - fp[0], pos[1] - fp[1], pos[2] - fp[2]);
    // Grid: on switching follow on, come close enough that about a dozen cells fill the view (cells are all
    // alike). Tree: whenever the current node changes, frame about three times its size: nodes shrink by
    // orders of magnitude on the way down to a leaf and grow again at a pop.
    const bool newNode = followNode && d.currentNode != d.followedNode;
    if (d.followZoom || newNode) {
      d.followZoom = false;
      d.followedNode = followNode ? d.currentNode : -1;
      double span = (followNode ? 3.0 : 12.0) * glm::length(glm::dvec3(hi - lo));
      double dist = 0.5 * span / std::tan(0.5 * cam->GetViewAngle() * M_PI / 180.0);
      if (followNode) {
        if (dist > 0.0) offset = glm::normalize(offset) * dist;
      } else if (dist < glm::length(offset)) {
        offset = glm::normalize(offset) * dist;
      }
    }
    cam->SetFocalPoint(c.x, c.y, c.z);
    cam->SetPosition(c.x + offset.x, c.y + offset.y, c.z + offset.z);
    d.base->ResetCameraClippingRange();
  }
  auto t1 = std::chrono::steady_clock::now();
  renderNow();
  d.lastMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  if (getenv("RAYSTEP_GUI_PROFILE"))
    fprintf(stderr, "update %.1f ms render %.1f ms\n", std::chrono::duration<double, std::milli>(t1 - t0).count(),
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count());
}


}  // namespace raystep::viz
