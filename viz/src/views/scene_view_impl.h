// The 3D view's state (SceneView's private part), shared by scene_view.cpp (set-up, the structure, the selected
// node, picking, the camera), scene_view_walk.cpp (a step's walk) and scene_view_dump.cpp (the state for tests).
#pragma once

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
#include "views/scene_view.h"

namespace raystep::viz {

constexpr size_t kMaxVisitedDrawn = 2000;
constexpr int kMaxLatticeCells = 16;  // per axis

struct SceneView::Impl {
  bool conceal = false;  // setConceal
  QVTKOpenGLNativeWidget* widget = nullptr;
  QLabel* legend = nullptr;
  QCheckBox* translucentCheck = nullptr;
  QCheckBox* followCheck = nullptr;
  vtkNew<vtkGenericOpenGLRenderWindow> window;
  vtkNew<vtkRenderer> base;     // scene and grid outline, depth-tested together
  vtkNew<vtkRenderer> planes;   // the kd-tree's split plane, over the scene and under the walk
  vtkNew<vtkRenderer> overlay;  // the walk, drawn over the scene so that it is never hidden
  std::unique_ptr<BackdropCache> backdrop;  // the base layer as an image while only the walk changes

  vtkNew<vtkPolyData> sceneData, outlineData, latticeData, visitedData, cellData, primData, rayData, aheadData,
      segmentData;
  vtkSmartPointer<vtkActor> sceneActor, outlineActor, latticeActor, visitedActor, cellActor, primActor, rayActor, aheadActor,
      segmentActor;
  // kd-tree: the nodes waiting on the stack, the current node's split plane.
  vtkNew<vtkPolyData> stackData, splitData;
  vtkSmartPointer<vtkActor> stackActor, splitActor;
  // BVH: the current inner node's children's boxes (translucent faces under the walk, outlines over it, one
  // colour for the first child tested and one for the others), their pairwise overlaps outlined, and the
  // nodes skipped so far.
  vtkNew<vtkPolyData> childFacesData, childEdgesData, overlapData, skippedData;
  vtkSmartPointer<vtkActor> childFacesActor, childEdgesActor, overlapActor, skippedActor;
  bool bvh = false;
  std::vector<int32_t> childrenDrawn, overlapsDrawn;  // for the dump: children, and pairs (a, b) flattened
  // The primitive being tested: its outline (its face shows the test's result, known at the test's event, so
  // that a leaf's or cell's last test is seen with its result before the walk moves on).
  vtkNew<vtkPolyData> testingData;
  vtkSmartPointer<vtkActor> testingActor;
  vtkNew<vtkSphereSource> hitSphere;
  vtkSmartPointer<vtkActor> hitActor;
  // The node selected in the tree view (its box, in the live kd-tree), and the click that picks the scene.
  vtkNew<vtkPolyData> selectedData;
  vtkSmartPointer<vtkActor> selectedActor;
  int selectedDrawn = -1;
  // The kd-tree's build so far (setBuildPlanes): the planes of the inner nodes made before the selected one.
  vtkNew<vtkPolyData> builtData;
  vtkSmartPointer<vtkActor> builtActor;
  bool buildPlanes = false;
  int builtPlanes = 0;  // drawn, for the dump
  glm::vec3 selectedLo{0.f}, selectedHi{0.f};
  int selectedCellFaces = 0;  // a BSP node: its convex cell's faces as drawn (0: its box)
  vtkNew<vtkCellPicker> picker;
  QPoint pressAt;
  int pickCount = 0, missCount = 0;  // clicks that hit or missed the scene
  bool havePicked = false;
  glm::vec3 picked{0.f};
  int pickedPrim = -1;              // the primitive under the click (-1: unknown)
  // The scene's (or trace's) mesh: sceneData shares its arrays; its cells' primitive ids for picking.
  std::shared_ptr<const SceneMesh> mesh;

  // What the walk refers to: grid geometry and the primitives by id.
  bool haveGrid = false;
  const void* meshSource = nullptr;  // the scene (or trace) the scene mesh and `prims` were made from
  Bounds3 meshBounds;
  glm::vec3 gridLo{0.f}, gridHi{1.f};
  int res[3] = {1, 1, 1};
  // A tree (kd): its root box is gridLo..gridHi; its nodes are the trace's, by id (those the walk names).
  bool haveTree = false;
  const Trace* nodesOf = nullptr;
  std::unordered_map<int32_t, const TraceNode*> nodes;
  int32_t currentNode = -1;
  std::vector<int32_t> visitedNodes;
  // A trace opened alone: the primitives it lists, by id. A scene's are read from its geometry (primShape):
  // a map of every triangle of a 2-million-triangle mesh cost the GUI thread seconds and 190 MB.
  std::map<int32_t, PrimShape> prims;
  const Geometry* geometry = nullptr;
  bool primShape(int32_t id, PrimShape* out) const {
    if (geometry) {
      if (id < 0 || size_t(id) >= geometry->size()) return false;
      *out = shapeOf(*geometry, uint32_t(id));
      return true;
    }
    auto it = prims.find(id);
    if (it == prims.end()) return false;
    *out = it->second;
    return true;
  }
  // The current block's primitive shapes: which ray and block they were made for, cells per primitive.
  const void* primBlockRay = nullptr;
  int primBlock = -2;
  std::vector<int> primCells;
  float sceneRadius = 1.f;
  bool translucent = false, follow = false, followZoom = false;
  int32_t followedNode = -1;  // the kd node the camera last framed while following
  double scale = 1.0;
  std::vector<std::pair<vtkActor*, float>> lineWidths;  // each line actor's width at scale 1
  // The bounds the scene (or trace) was first framed with: "home" frames them again at the view's current
  // aspect (the fit depends on it when the view is taller than wide, and the layout may have changed since).
  double homeBounds[6] = {0, 0, 0, 0, 0, 0};
  bool haveHome = false;
  void saveHome() {
    base->ComputeVisiblePropBounds(homeBounds);
    haveHome = vtkMath::AreBoundsInitialized(homeBounds);
  }
  double lastMs = 0.0;
  bool dormant = false, stale = false;  // setDormant: skipped updates since
  // Drawn this step, for the dump.
  glm::vec3 rayFrom{0.f}, rayTo{0.f};
  bool rayDrawn = false;
  float rayMark = std::numeric_limits<float>::quiet_NaN();  // setRayMark: the ray bright up to here

  const TraceNode* node(int32_t id) const {
    auto it = nodes.find(id);
    return it == nodes.end() ? nullptr : it->second;
  }
  // General BSP tree: each node's convex cell (the root box cut by its ancestors' planes), made on demand.
  mutable std::unordered_map<int32_t, ConvexCell> bspCells;  // a cache: filled by const readers too
  bool bspTree = false;                                      // the trace's nodes carry planes
  const ConvexCell* bspCell(int32_t id) const {
    if (auto it = bspCells.find(id); it != bspCells.end()) return &it->second;
    const TraceNode* n = node(id);
    if (!n) return nullptr;
    ConvexCell cell;
    if (n->parent < 0) {
      cell = ConvexCell::box(n->box);
    } else {
      const TraceNode* p = node(n->parent);
      const ConvexCell* pc = p && p->has_plane ? bspCell(n->parent) : nullptr;
      if (!pc) return nullptr;
      ConvexCell below, above;
      pc->split(glm::dvec3(p->normal), double(p->offset), &below, &above);
      cell = n->id == p->id + 1 ? below : above;  // the child below is the next node (depth-first order)
    }
    return &bspCells.emplace(id, std::move(cell)).first->second;
  }
  void indexNodes(const Trace* t) {
    nodesOf = t;
    nodes.clear();
    bspCells.clear();
    bspTree = t && t->structure.kind == "bsp";
    if (t)
      for (const TraceNode& n : t->nodes) nodes[n.id] = &n;
  }
  glm::vec3 cellLo(const int c[3]) const {
    glm::vec3 size = (gridHi - gridLo) / glm::vec3(res[0], res[1], res[2]);
    return gridLo + glm::vec3(c[0], c[1], c[2]) * size;
  }
  glm::vec3 cellHi(const int c[3]) const {
    glm::vec3 size = (gridHi - gridLo) / glm::vec3(res[0], res[1], res[2]);
    return gridLo + glm::vec3(c[0] + 1, c[1] + 1, c[2] + 1) * size;
  }
  // Window coordinates (top-left origin) of a world point; false when behind the camera.
  bool project(const glm::vec3& p, QWidget* win, QPointF* out) const {
    base->SetWorldPoint(p.x, p.y, p.z, 1.0);
    base->WorldToDisplay();
    double d[3];
    base->GetDisplayPoint(d);
    if (d[2] < 0.0 || d[2] > 1.0) return false;
    double ratio = widget->devicePixelRatioF();
    QPointF local(d[0] / ratio, widget->height() - d[1] / ratio);
    *out = QPointF(widget->mapTo(win, QPoint(0, 0))) + local;
    return true;
  }
};

}  // namespace raystep::viz
