#include "scene_view.h"

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

#include "backdrop_cache.h"
#include "kd_tree_model.h"
#include "palette.h"
#include "scene_mesh.h"
#include "session.h"

namespace raystep::viz {
namespace {

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

constexpr size_t kMaxVisitedDrawn = 2000;
constexpr int kMaxLatticeCells = 16;  // per axis

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

}  // namespace

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
  }  double lastMs = 0.0;
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

SceneView::SceneView(Session* session, QWidget* parent) : QWidget(parent), d_(new Impl), session_(session) {
  auto* layout = new QVBoxLayout(this);
  layout->setContentsMargins(0, 0, 0, 0);
  layout->setSpacing(2);

  auto* bar = new QHBoxLayout;
  auto* translucent = d_->translucentCheck = new QCheckBox(tr("Translucent"));
  auto* follow = d_->followCheck = new QCheckBox(tr("Follow"));
  follow->setToolTip(tr("The camera follows the current cell (grid) or node (kd-tree)"));
  auto* fit = new QToolButton;
  fit->setText(tr("Fit view"));
  translucent->setObjectName("translucentCheck");
  follow->setObjectName("followCheck");
  bar->addWidget(new QLabel(tr("<b>3D view</b>")));
  bar->addStretch();
  bar->addWidget(translucent);
  bar->addWidget(follow);
  bar->addWidget(fit);
  layout->addLayout(bar);
  connect(translucent, &QCheckBox::toggled, this, &SceneView::setTranslucent);
  connect(follow, &QCheckBox::toggled, this, &SceneView::setFollowCell);
  connect(fit, &QToolButton::clicked, this, [this] {
    fitCamera();
    renderNow();
  });

  Impl& d = *d_;
  d.widget = new QVTKOpenGLNativeWidget(this);
  d.widget->setMinimumSize(320, 240);
  d.window->SetMultiSamples(0);  // exact colours on lines (the tests look for them)
  d.widget->setRenderWindow(d.window);
  d.window->SetNumberOfLayers(3);
  d.base->SetLayer(0);
  d.planes->SetLayer(1);
  d.overlay->SetLayer(2);
  for (vtkRenderer* r : {d.planes.Get(), d.overlay.Get()}) {
    r->SetActiveCamera(d.base->GetActiveCamera());
    r->InteractiveOff();
  }
  d.window->AddRenderer(d.base);
  d.window->AddRenderer(d.planes);
  d.window->AddRenderer(d.overlay);
  d.backdrop = std::make_unique<BackdropCache>(d.window, d.base, std::vector<vtkRenderer*>{d.planes, d.overlay});
  const QColor& bg = palette::background;
  d.base->SetBackground(bg.redF(), bg.greenF(), bg.blueF());
  vtkNew<vtkInteractorStyleTrackballCamera> style;
  d.window->GetInteractor()->SetInteractorStyle(style);
  {  // a drag or the wheel moved the camera: views sharing it (the side-by-side view) draw again
    vtkNew<vtkCallbackCommand> moved;
    moved->SetClientData(this);
    moved->SetCallback([](vtkObject*, unsigned long, void* self, void*) {
      Q_EMIT static_cast<SceneView*>(self)->cameraMoved();
    });
    style->AddObserver(vtkCommand::InteractionEvent, moved);
    style->AddObserver(vtkCommand::EndInteractionEvent, moved);
  }
  layout->addWidget(d.widget, 1);

  // Actors, made once; each step only changes their data.
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(d.sceneData);
    mapper->SetScalarModeToUseCellData();
    d.sceneActor = vtkSmartPointer<vtkActor>::New();
    d.sceneActor->SetMapper(mapper);
    d.sceneActor->GetProperty()->SetInterpolationToFlat();
    d.sceneActor->GetProperty()->SetAmbient(0.35);
    d.sceneActor->GetProperty()->SetDiffuse(0.65);
    d.sceneActor->GetProperty()->BackfaceCullingOn();  // look into closed rooms (Cornell box) from outside
    d.base->AddActor(d.sceneActor);
  }
  d.outlineActor = unlitActor(d.outlineData, palette::gridOutline, 1.f);
  d.base->AddActor(d.outlineActor);
  d.latticeActor = unlitActor(d.latticeData, palette::gridOutline, 1.f);
  d.latticeActor->GetProperty()->SetOpacity(0.13);
  d.base->AddActor(d.latticeActor);
  d.visitedActor = unlitActor(d.visitedData, palette::visitedCell, 2.f);
  d.visitedActor->GetProperty()->SetOpacity(0.55);
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputData(d.primData);
    mapper->SetScalarModeToUseCellData();
    d.primActor = vtkSmartPointer<vtkActor>::New();
    d.primActor->SetMapper(mapper);
    d.primActor->GetProperty()->SetLighting(false);
  }
  d.rayActor = unlitActor(d.rayData, palette::ray, 2.f);
  d.aheadActor = unlitActor(d.aheadData, palette::rayAhead, 2.f);
  d.segmentActor = unlitActor(d.segmentData, palette::segment, 6.f);
  d.segmentActor->GetProperty()->SetRenderLinesAsTubes(true);  // wide lines where the driver has none
  d.cellActor = unlitActor(d.cellData, palette::currentCell, 3.f);
  d.hitSphere->SetThetaResolution(16);
  d.hitSphere->SetPhiResolution(12);
  {
    vtkNew<vtkPolyDataMapper> mapper;
    mapper->SetInputConnection(d.hitSphere->GetOutputPort());
    d.hitActor = vtkSmartPointer<vtkActor>::New();
    d.hitActor->SetMapper(mapper);
    d.hitActor->GetProperty()->SetLighting(false);
  }
  d.stackActor = unlitActor(d.stackData, palette::stackNode, 3.f);
  d.testingActor = unlitActor(d.testingData, palette::primTesting, 3.f);
  d.splitActor = unlitActor(d.splitData, palette::splitPlane, 1.f);
  d.splitActor->GetProperty()->SetOpacity(0.35);
  // On a layer of its own: over the scene (which stays the same from step to step, see BackdropCache) and under
  // the walk, so that the translucent plane never tints the ray.
  d.planes->AddActor(d.splitActor);
  d.selectedActor = unlitActor(d.selectedData, palette::selectedNode, 3.f);
  d.overlay->AddActor(d.selectedActor);
  d.builtActor = unlitActor(d.builtData, palette::builtPlane, 1.5f);
  d.overlay->AddActor(d.builtActor);
  d.childFacesActor = cellColoredActor(d.childFacesData, 1.f);
  d.childFacesActor->GetProperty()->SetOpacity(0.22);
  d.planes->AddActor(d.childFacesActor);
  d.childEdgesActor = cellColoredActor(d.childEdgesData, 2.f);
  d.overlapActor = unlitActor(d.overlapData, palette::bvhOverlap, 3.f);
  d.skippedActor = unlitActor(d.skippedData, palette::bvhSkipped, 2.f);
  for (vtkActor* a : {d.childEdgesActor.Get(), d.overlapActor.Get(), d.skippedActor.Get()})
    d.overlay->AddActor(a);
  // A click without a drag picks the scene (a drag still turns the camera).
  d.picker->SetTolerance(0.0005);
  d.picker->PickFromListOn();
  d.picker->AddPickList(d.sceneActor);
  // (Watched in Qt: once the camera's style has the mouse, VTK gives the release to the style alone.)
  d.widget->installEventFilter(this);
  for (vtkActor* a : {d.stackActor.Get(), d.primActor.Get(), d.testingActor.Get(), d.visitedActor.Get(), d.rayActor.Get(), d.aheadActor.Get(), d.segmentActor.Get(),
                      d.cellActor.Get(), d.hitActor.Get()})
    d.overlay->AddActor(a);

  // The legend: every colour of the view and what it means (set for the structure in rebuildGeometry).
  d.legend = new QLabel;
  d.legend->setObjectName("legend");
  d.legend->setWordWrap(true);
  layout->addWidget(d.legend);

  connect(session_, &Session::sceneChanged, this, [this] {
    d_->meshSource = nullptr;  // another scene, even one allocated where the last one was
    rebuildGeometry();
    d_->saveHome();
    fitCamera();
    updateStep();
  });
  connect(session_, &Session::traceChanged, this, [this] {
    d_->indexNodes(session_->trace());
    d_->primBlockRay = nullptr;  // a new trace may live where the old one did
    // A trace opened on its own brings its own geometry; one traced in the scene changes only the walk.
    if (!session_->scene()) {
      d_->meshSource = nullptr;
      rebuildGeometry();
      d_->saveHome();
      fitCamera();
    }
  });
  connect(session_, &Session::structureChanged, this, [this] {
    rebuildGeometry();
    updateStep();
  });
  connect(session_, &Session::stepChanged, this, &SceneView::updateStep);
  connect(session_, &Session::selectedNodeChanged, this, [this] {
    updateSelected();
    renderNow();
  });
  rebuildGeometry();  // the legend
}

SceneView::~SceneView() = default;

void SceneView::prepareSurfaceFormat() { QSurfaceFormat::setDefaultFormat(QVTKOpenGLNativeWidget::defaultFormat()); }

void SceneView::rebuildGeometry() {
  Impl& d = *d_;
  d.primBlockRay = nullptr;
  d.primBlock = -2;
  d.haveGrid = false;
  // The scene's mesh is taken again only for another scene (or trace): a new structure over the same scene
  // changes the outline and the lattice. A scene's was made on the loading worker (SceneData::mesh).
  const void* source = session_->scene() ? static_cast<const void*>(session_->scene())
                                         : static_cast<const void*>(session_->trace());
  if (!source || source != d.meshSource) {
    d.prims.clear();
    d.geometry = nullptr;
    d.mesh.reset();
    if (const SceneData* sd = session_->scene()) {
      d.geometry = &sd->scene.geometry;
      d.mesh = sd->mesh ? sd->mesh : SceneMesh::fromScene(sd->scene);
    } else if (const Trace* t = session_->trace()) {
      d.mesh = SceneMesh::fromTrace(*t);
      for (const TracePrimitive& tp : t->primitives) d.prims[tp.id] = shapeOf(tp);
    }
    if (d.mesh)
      d.sceneData->ShallowCopy(d.mesh->data());
    else
      d.sceneData->Initialize();
    d.sceneData->Modified();
    d.meshSource = source;
    d.meshBounds = d.mesh ? d.mesh->bounds() : Bounds3();
  }
  Bounds3 bounds = d.meshBounds;

  // The structure: the scene's grid, or the one named by a trace opened on its own.
  const UniformGrid* liveGrid = session_->structure() ? session_->structure()->grid() : nullptr;
  if (liveGrid) {
    d.haveGrid = !liveGrid->empty();
    d.gridLo = liveGrid->bounds().lo;
    d.gridHi = liveGrid->bounds().hi;
    auto r = liveGrid->resolution();
    for (int a = 0; a < 3; ++a) d.res[a] = r[a];
  } else if (const Trace* t = session_->trace(); t && !session_->scene() && t->structure.kind == "grid") {
    d.haveGrid = true;
    d.gridLo = t->structure.bounds.lo;
    d.gridHi = t->structure.bounds.hi;
    for (int a = 0; a < 3; ++a) d.res[a] = t->structure.resolution[size_t(a)];
  }
  // A kd-tree: the scene's, or the one named by a trace opened on its own; its root box is outlined.
  d.haveTree = false;
  d.indexNodes(session_->trace());
  if (const KdTree* kd = session_->structure() ? session_->structure()->kdTree() : nullptr) {
    d.haveTree = !kd->data().nodes.empty();
    d.gridLo = kd->data().bounds.lo;
    d.gridHi = kd->data().bounds.hi;
  } else if (const Octree* oct = session_->structure() ? session_->structure()->octree() : nullptr) {
    d.haveTree = !oct->data().nodes.empty();  // the root cube
    d.gridLo = oct->data().bounds.lo;
    d.gridHi = oct->data().bounds.hi;
  } else if (const BspTree* bsp = session_->structure() ? session_->structure()->bsp() : nullptr) {
    d.haveTree = !bsp->data().nodes.empty();
    d.gridLo = bsp->data().bounds.lo;
    d.gridHi = bsp->data().bounds.hi;
  } else if (session_->structure() && replay::is_bvh_kind(session_->structure()->kind)) {
    // A BVH: its root box is the scene's bounds (tight around every primitive).
    const Bounds3& b = session_->structure()->scene->scene.geometry.bounds();
    d.haveTree = !b.empty();
    d.gridLo = b.lo;
    d.gridHi = b.hi;
  } else if (const Trace* t = session_->trace(); t && !session_->scene() && t->structure.kind != "grid") {
    d.haveTree = true;
    d.gridLo = t->structure.bounds.lo;
    d.gridHi = t->structure.bounds.hi;
  }
  vtkNew<vtkPoints> opts;
  vtkNew<vtkCellArray> olines;
  if (d.haveGrid || d.haveTree) {
    addBoxEdges(opts, olines, d.gridLo, d.gridHi);
    bounds.extend(Bounds3(d.gridLo, d.gridHi));
  }
  d.outlineData->SetPoints(opts);
  d.outlineData->SetLines(olines);
  d.outlineData->Modified();

  // The cell lattice, faint, when it is coarse enough to read (a fine grid would be a grey fog).
  vtkNew<vtkPoints> lpts;
  vtkNew<vtkCellArray> llines;
  const int* n = d.res;
  if (d.haveGrid && n[0] <= kMaxLatticeCells && n[1] <= kMaxLatticeCells && n[2] <= kMaxLatticeCells) {
    glm::vec3 size = (d.gridHi - d.gridLo) / glm::vec3(n[0], n[1], n[2]);
    for (int a = 0; a < 3; ++a) {
      int b = (a + 1) % 3, c = (a + 2) % 3;
      for (int i = 0; i <= n[b]; ++i)
        for (int j = 0; j <= n[c]; ++j) {
          glm::vec3 p0, p1;
          p0[a] = d.gridLo[a];
          p1[a] = d.gridHi[a];
          p0[b] = p1[b] = d.gridLo[b] + float(i) * size[b];
          p0[c] = p1[c] = d.gridLo[c] + float(j) * size[c];
          vtkIdType ids[2] = {lpts->InsertNextPoint(p0.x, p0.y, p0.z), lpts->InsertNextPoint(p1.x, p1.y, p1.z)};
          llines->InsertNextCell(2, ids);
        }
    }
  }
  d.latticeData->SetPoints(lpts);
  d.latticeData->SetLines(llines);
  d.latticeData->Modified();
  d.sceneRadius = bounds.empty() ? 1.f : 0.5f * glm::length(bounds.extent());

  auto swatch = [](const QColor& c, const QString& text) {
    return QString("<span style='background:%1'>&nbsp;&nbsp;&nbsp;&nbsp;</span>&nbsp;%2&nbsp;&nbsp; ")
        .arg(c.name(), text);
  };
  QString walk = swatch(palette::ray, tr("ray walked")) + swatch(palette::rayAhead, tr("ray ahead")) +
                 swatch(palette::segment, tr("current [tmin, tmax]"));
  QString hits = swatch(palette::hitCandidate, tr("nearest hit so far")) + swatch(palette::hitFinal, tr("accepted hit"));
  QString primStates = swatch(palette::primPending, tr("not reached")) + swatch(palette::primTesting, tr("being tested (outline)")) +
                       swatch(palette::primHit, tr("hit")) + swatch(palette::primMissed, tr("missed")) +
                       swatch(palette::primSkipped, tr("skipped (mailbox)"));
  const bool bvhLegend = (session_->structure() && replay::is_bvh_kind(session_->structure()->kind)) ||
                         (session_->trace() && replay::is_bvh_kind(session_->trace()->structure.kind));
  const bool octreeLegend = (session_->structure() && session_->structure()->kind == "octree") ||
                            (session_->trace() && session_->trace()->structure.kind == "octree");
  if (d.haveTree && bvhLegend)
    d.legend->setText(
        walk + swatch(palette::currentCell, tr("current node")) +
        swatch(palette::bvhChildFirst, tr("first child tested")) +
        swatch(palette::bvhChildOther, tr("other child")) +
        swatch(palette::bvhOverlap, tr("children overlap")) + swatch(palette::stackNode, tr("on the stack")) +
        swatch(palette::visitedCell, tr("visited")) +
        swatch(palette::bvhSkipped, tr("skipped (beyond the hit)")) + hits +
        (session_->structure() ? swatch(palette::selectedNode, tr("selected in the tree")) : QString()) +
        "<br>" + tr("Primitives of the current leaf (each in exactly one leaf: no mailbox): ") +
        swatch(palette::primPending, tr("not reached")) +
        swatch(palette::primTesting, tr("being tested (outline)")) + swatch(palette::primHit, tr("hit")) +
        swatch(palette::primMissed, tr("missed")));
  else if (d.haveTree && octreeLegend)
    d.legend->setText(walk + swatch(palette::currentCell, tr("current cell")) +
                      swatch(palette::bvhChildFirst, tr("its first child (entry plane)")) +
                      swatch(palette::bvhChildOther,
                             tr("its last child (orange to violet: the order the ray crosses them)")) +
                      swatch(palette::stackNode, tr("cells whose children are being walked")) +
                      swatch(palette::visitedCell, tr("visited")) + hits + "<br>" +
                      tr("Primitives of the current leaf cell: ") + primStates);
  else if (d.haveTree && ((session_->structure() && session_->structure()->kind == "bsp") || d.bspTree))
    d.legend->setText(walk + swatch(palette::currentCell, tr("current node's convex cell")) +
                      swatch(palette::splitPlane, tr("its plane, clipped to the cell")) +
                      swatch(palette::stackNode, tr("far child on the stack")) +
                      swatch(palette::visitedCell, tr("visited")) + hits + "<br>" +
                      tr("Primitives of the current leaf: ") + primStates);
  else if (d.haveTree)
    d.legend->setText(walk + swatch(palette::currentCell, tr("current node")) +
                      swatch(palette::splitPlane, tr("its split plane")) + swatch(palette::stackNode, tr("on the stack")) +
                      swatch(palette::visitedCell, tr("visited")) + hits +
                      (session_->structure() ? swatch(palette::selectedNode, tr("selected in the tree")) : QString()) +
                      (d.buildPlanes ? swatch(palette::builtPlane, tr("planes split before it (the build so far)"))
                                     : QString()) +
                      "<br>" + tr("Primitives of the current leaf: ") +
                      primStates);
  else
    d.legend->setText(walk + swatch(palette::currentCell, tr("current cell")) + swatch(palette::visitedCell, tr("visited")) +
                      hits + "<br>" + tr("Primitives of the current cell: ") + primStates);
  updateSelected();
}

void SceneView::updateSelected() {
  Impl& d = *d_;
  vtkNew<vtkPoints> pts;
  vtkNew<vtkCellArray> lines;
  d.selectedDrawn = -1;
  std::unique_ptr<TreeShape> tree = session_->structure() ? treeShapeOf(*session_->structure()) : nullptr;
  int n = session_->selectedNode();
  if (tree && n >= 0 && size_t(n) < tree->size()) {
    // Drawn a little outside the node's box, so that it stays in view when the node is also the walk's current
    // one (whose yellow box lies on the same edges).
    const Bounds3 b = tree->box(uint32_t(n));
    glm::vec3 pad(0.006f * glm::length(b.hi - b.lo));
    d.selectedDrawn = n;
    d.selectedLo = b.lo - pad;
    d.selectedHi = b.hi + pad;
    d.selectedCellFaces = 0;
    if (const BspTree* bsp = session_->structure()->bsp()) {
      // A BSP node is a convex cell, not its bounding box: the root box cut by its ancestors' planes, drawn a
      // little outside as the box is.
      const BspTreeData& t = bsp->data();
      std::vector<uint32_t> path{uint32_t(n)};
      while (t.info[path.back()].parent >= 0) path.push_back(uint32_t(t.info[path.back()].parent));
      ConvexCell cell = ConvexCell::box(t.bounds);
      for (size_t k = path.size() - 1; k > 0 && !cell.empty(); --k) {
        const BspPlane& plane = t.nodes[path[k]].plane;
        ConvexCell below, above;
        cell.split(glm::dvec3(plane.normal), double(plane.offset), &below, &above);
        cell = path[k - 1] == path[k] + 1 ? below : above;
      }
      if (!cell.empty()) {
        d.selectedCellFaces = int(cell.face_count());
        addCellEdges(pts, lines, cell, -0.006f);
      } else {
        addBoxEdges(pts, lines, d.selectedLo, d.selectedHi);
      }
    } else {
      addBoxEdges(pts, lines, d.selectedLo, d.selectedHi);
    }
  }
  // The build so far: the builder works depth first, so the nodes made before the selected one are those with
  // smaller ids. Their planes pale green, the selected node's own plane in its colour.
  vtkNew<vtkPoints> bpts;
  vtkNew<vtkCellArray> blines;
  d.builtPlanes = 0;
  const KdTree* kd = session_->structure() ? session_->structure()->kdTree() : nullptr;
  if (d.buildPlanes && kd && n >= 0 && size_t(n) < kd->data().nodes.size()) {
    const KdTreeData& t = kd->data();
    for (int id = 0; id <= n; ++id) {
      const KdNode& node = t.nodes[size_t(id)];
      if (node.is_leaf()) continue;
      addPlaneEdges(id == n ? pts.Get() : bpts.Get(), id == n ? lines.Get() : blines.Get(), t.info[size_t(id)].box,
                    node.axis(), node.split);
      d.builtPlanes += id < n;
    }
  }
  d.builtData->SetPoints(bpts);
  d.builtData->SetLines(blines);
  d.builtData->Modified();
  d.selectedData->SetPoints(pts);
  d.selectedData->SetLines(lines);
  d.selectedData->Modified();
}

void SceneView::setBuildPlanes(bool on) {
  if (d_->buildPlanes == on) return;
  d_->buildPlanes = on;
  rebuildGeometry();  // the legend names them
  updateStep();
}

bool SceneView::buildPlanes() const {
  return d_->buildPlanes;
}

bool SceneView::eventFilter(QObject* watched, QEvent* event) {
  if (watched == d_->widget) {
    auto* m = static_cast<QMouseEvent*>(event);
    if (event->type() == QEvent::MouseButtonPress && m->button() == Qt::LeftButton) {
      d_->pressAt = m->pos();
    } else if (event->type() == QEvent::MouseButtonRelease && m->button() == Qt::LeftButton &&
               (m->pos() - d_->pressAt).manhattanLength() <= 3) {
      double ratio = d_->widget->devicePixelRatioF();
      pickDisplay(int(std::lround(m->pos().x() * ratio)), int(std::lround((d_->widget->height() - m->pos().y()) * ratio)));
    }
  }
  return QWidget::eventFilter(watched, event);  // the camera still gets the mouse
}

int SceneView::pickedPrimitive() const {
  return d_->havePicked ? d_->pickedPrim : -1;
}

bool SceneView::pickAt(const QPoint& at) {
  // A click as the mouse makes it: through Qt and VTK's interactor to the click observer.
  QPoint local = d_->widget->mapFrom(window(), at);
  int before = d_->pickCount;
  QMouseEvent press(QEvent::MouseButtonPress, local, d_->widget->mapToGlobal(local), Qt::LeftButton, Qt::LeftButton,
                    Qt::NoModifier);
  QMouseEvent release(QEvent::MouseButtonRelease, local, d_->widget->mapToGlobal(local), Qt::LeftButton, Qt::NoButton,
                      Qt::NoModifier);
  QApplication::sendEvent(d_->widget, &press);
  QApplication::sendEvent(d_->widget, &release);
  if (d_->pickCount != before) return true;
  if (d_->missCount == 0) {  // the click did not reach the observer (no interactor yet): pick directly
    std::fprintf(stderr, "note: 3D view picked without a click (the click did not reach VTK)\n");
    double ratio = d_->widget->devicePixelRatioF();
    return pickDisplay(int(std::lround(local.x() * ratio)), int(std::lround((d_->widget->height() - local.y()) * ratio)));
  }
  d_->missCount = 0;
  return false;
}

bool SceneView::pickDisplay(int x, int y) {
  Impl& d = *d_;
  if (!d.picker->Pick(x, y, 0.0, d.base) || d.picker->GetCellId() < 0) {
    ++d.missCount;
    return false;
  }
  ++d.pickCount;
  double p[3];
  d.picker->GetPickPosition(p);
  d.havePicked = true;
  d.picked = glm::vec3(float(p[0]), float(p[1]), float(p[2]));
  const vtkIdType cell = d.picker->GetCellId();
  d.pickedPrim = d.mesh && size_t(cell) < d.mesh->cellPrim().size() ? d.mesh->cellPrim()[size_t(cell)] : -1;
  Q_EMIT pointPicked(d.picked.x, d.picked.y, d.picked.z);
  return true;
}

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

void SceneView::setTranslucent(bool on) {
  d_->translucentCheck->setChecked(on);  // when set from elsewhere (scripted mode)
  d_->translucent = on;
  d_->sceneActor->GetProperty()->SetOpacity(on ? 0.35 : 1.0);
  updateStep();
}

void SceneView::setConceal(bool on) {
  if (d_->conceal == on) return;
  d_->conceal = on;
  updateStep();
}

void SceneView::setFollowCell(bool on) {
  d_->followCheck->setChecked(on);
  d_->follow = on;
  d_->followZoom = on;
  d_->followedNode = -1;
  updateStep();
}

void SceneView::fitCamera() {
  double b[6];
  d_->base->ComputeVisiblePropBounds(b);
  fitCameraTo(b);
}

void SceneView::fitCameraTo(const double* bounds) {
  Impl& d = *d_;
  vtkCamera* cam = d.base->GetActiveCamera();
  double b[6];
  std::copy(bounds, bounds + 6, b);
  if (!vtkMath::AreBoundsInitialized(b)) return;
  glm::vec3 c(0.5 * (b[0] + b[1]), 0.5 * (b[2] + b[3]), 0.5 * (b[4] + b[5]));
  // Look from the front, a little from the right and above, as the scene camera does (+z towards the viewer).
  glm::vec3 dir = glm::normalize(glm::vec3(0.55f, 0.45f, 1.f));
  if (const SceneData* sd = session_->scene()) {
    glm::vec3 v = sd->scene.camera.eye - sd->scene.camera.look_at;
    if (glm::length(v) > 0.f) {
      v = glm::normalize(v);
      glm::vec3 up = glm::normalize(sd->scene.camera.up);
      glm::vec3 right = glm::normalize(glm::cross(up, v));
      dir = glm::normalize(v + 0.5f * right + 0.35f * up);
      cam->SetViewUp(up.x, up.y, up.z);
    }
  } else {
    cam->SetViewUp(0, 1, 0);
  }
  cam->SetFocalPoint(c.x, c.y, c.z);
  cam->SetPosition(c.x + dir.x, c.y + dir.y, c.z + dir.z);
  cam->SetViewAngle(30);
  d.base->ResetCamera(b);
  cam->Zoom(1.15);
  d.base->ResetCameraClippingRange();
}

void SceneView::setScale(double scale) {
  Impl& d = *d_;
  if (d.lineWidths.empty())
    for (vtkActor* a : {d.outlineActor.Get(), d.latticeActor.Get(), d.visitedActor.Get(), d.testingActor.Get(), d.rayActor.Get(),
                        d.aheadActor.Get(), d.segmentActor.Get(), d.cellActor.Get(), d.stackActor.Get(),
                        d.splitActor.Get(), d.selectedActor.Get(), d.builtActor.Get()})
      d.lineWidths.push_back({a, a->GetProperty()->GetLineWidth()});
  d.scale = scale;
  for (auto& [actor, width] : d.lineWidths) actor->GetProperty()->SetLineWidth(float(width * scale));
  updateStep();
}

void SceneView::restoreHomeCamera() {
  d_->followedNode = -1;
  if (d_->haveHome) fitCameraTo(d_->homeBounds);
}

bool SceneView::translucent() const { return d_->translucent; }
bool SceneView::followCell() const { return d_->follow; }

void SceneView::renderNow() {
  d_->base->ResetCameraClippingRange();
  static const bool noBackdrop = std::getenv("RAYSTEP_GUI_NO_BACKDROP") != nullptr;  // for the tests' comparison
  d_->backdrop->prepare(!noBackdrop && d_->widget->isValid() && d_->widget->isVisible());
  d_->window->Render();  // draws, and has the widget show the new frame
}

QImage SceneView::grabView() { return d_->widget->grabFramebuffer(); }

double SceneView::lastUpdateMs() const { return d_->lastMs; }

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

void SceneView::setCompact(bool on) {
  if (QLayout* bar = layout()->itemAt(0)->layout())
    for (int i = 0; i < bar->count(); ++i)
      if (QWidget* w = bar->itemAt(i)->widget()) w->setVisible(!on);
  d_->legend->setVisible(!on);
  d_->widget->setMinimumSize(on ? QSize(200, 150) : QSize(320, 240));  // four side by side on a laptop
}

void SceneView::shareCamera(SceneView* leader) {
  vtkCamera* cam = leader->d_->base->GetActiveCamera();
  for (vtkRenderer* r : {d_->base.Get(), d_->planes.Get(), d_->overlay.Get()}) r->SetActiveCamera(cam);
}

void SceneView::setRayMark(float t) {
  d_->rayMark = t;
  updateStep();
}

}  // namespace raystep::viz
