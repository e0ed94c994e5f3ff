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
#include "raystep/accel/bvh_names.h"
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
  const std::string& kindNow = session_->structure() ? session_->structure()->kind
                               : session_->trace()   ? session_->trace()->structure.kind
                                                     : std::string();
  const std::optional<BvhName> bvhName = parse_bvh_name(kindNow);
  const bool spatialSplits = bvhName && bvhName->builder == BvhBuilder::sbvh;
  if (d.haveTree && bvhLegend)
    d.legend->setText(
        walk + swatch(palette::currentCell, tr("current node")) +
        swatch(palette::bvhChildFirst, tr("first child tested")) +
        swatch(palette::bvhChildOther, tr("other child")) +
        swatch(palette::bvhOverlap, tr("children overlap")) + swatch(palette::stackNode, tr("on the stack")) +
        swatch(palette::visitedCell, tr("visited")) +
        swatch(palette::bvhSkipped, tr("skipped (beyond the hit)")) + hits +
        (session_->structure() ? swatch(palette::selectedNode, tr("selected in the tree")) : QString()) +
        "<br>" +
        (spatialSplits ? tr("Primitives of the current leaf (spatial splits: a primitive may sit in several "
                            "leaves, tested again in each; no mailbox): ")
                       : tr("Primitives of the current leaf (each in exactly one leaf: no mailbox): ")) +
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
  if (d.mesh && d.mesh->decimated())
    d.legend->setText(d.legend->text() +
                      tr("<br>The scene is drawn from a decimated copy (%L1 of its %L2 triangles) so that the "
                         "view stays responsive; the walk, its primitives and a click's pick use every triangle.")
                          .arg(qulonglong(d.mesh->displayTriangles()))
                          .arg(qulonglong(d.mesh->sceneTriangles())));
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
  // A decimated display copy is only near the surface: the ray tracer finds the primitive and the point the
  // click means, on the ray from the eye through the picked point.
  const StructureData* s = session_->structure();
  if (d.mesh && d.mesh->decimated() && s && s->accel) {
    double eye[3];
    d.base->GetActiveCamera()->GetPosition(eye);
    Ray ray;
    ray.origin = glm::vec3(float(eye[0]), float(eye[1]), float(eye[2]));
    ray.direction = d.picked - ray.origin;
    Hit hit;
    if (glm::length(ray.direction) > 0.f && s->accel->intersect(ray, &hit)) {
      d.picked = ray.at(hit.t);
      d.pickedPrim = hit.prim;
    }
  }
  Q_EMIT pointPicked(d.picked.x, d.picked.y, d.picked.z);
  return true;
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

void SceneView::setDormant(bool dormant) {
  if (d_->dormant == dormant) return;
  d_->dormant = dormant;
  if (!dormant && d_->stale) {
    d_->stale = false;
    updateStep();
  }
}

void SceneView::renderNow() {
  if (d_->dormant) {
    d_->stale = true;
    return;
  }
  d_->base->ResetCameraClippingRange();
  static const bool noBackdrop = std::getenv("RAYSTEP_GUI_NO_BACKDROP") != nullptr;  // for the tests' comparison
  d_->backdrop->prepare(!noBackdrop && d_->widget->isValid() && d_->widget->isVisible());
  d_->window->Render();  // draws, and has the widget show the new frame
}

QImage SceneView::grabView() { return d_->widget->grabFramebuffer(); }

double SceneView::lastUpdateMs() const { return d_->lastMs; }


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
