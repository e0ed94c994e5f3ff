#include "lesson/lesson_enter.h"

#include <QApplication>
#include <QFileInfo>
#include <QThread>

#include "reports/aa_report_view.h"
#include "reports/bvol_report_view.h"
#include "reports/grid_sweep_view.h"
#include "views/image_view.h"
#include "views/kd_tree_model.h"
#include "app/main_window.h"
#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/lesson/tree_nodes.h"
#include "raystep/util/error.h"
#include "raystep/replay/replay_state.h"
#include "views/scene_view.h"
#include "flatland/flat_view.h"
#include "app/session.h"
#include "views/tree_view.h"

namespace raystep::viz {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

// Work in place while entering, whatever the window's mode, and back to it after (also on an error).
struct InPlace {
  explicit InPlace(MainWindow& w) : window(w), was(w.workInPlace()) { w.setWorkInPlace(true); }
  ~InPlace() { window.setWorkInPlace(was); }
  MainWindow& window;
  bool was;
};

// Layout and paint settle before what depends on the widgets' sizes (the dock before the chart draws).
void settle(MainWindow& w) {
  for (int i = 0; i < 3; ++i) QApplication::processEvents();
  w.sceneView()->renderNow();
}

bool samePath(const std::string& a, const std::string& b) {
  if (a == b) return true;
  QFileInfo fa(QString::fromStdString(a)), fb(QString::fromStdString(b));
  return fa.exists() && fb.exists() && fa.canonicalFilePath() == fb.canonicalFilePath();
}

// The report windows the step names (`report:`), opened and run on the scene; the others closed. Scripted,
// the run is waited for, so that a screenshot or a handout shows its result. A report already done is kept,
// except the bounding-volume report, which is quick and is run again for the step's scene.
void enterReports(MainWindow& w, const LessonState& st) {
  const QStringList named = QString::fromStdString(st.report).split(',', Qt::SkipEmptyParts);
  auto enter = [&](ReportWindow* v, const QString& name, bool rerun) {
    if (!named.contains(name)) {
      if (v->isVisible()) v->hide();
      return;
    }
    if (!w.session()->scene()) fail("report " + name.toStdString() + ": open a scene (a trace has none)");
    v->show();
    v->raise();
    if (rerun || v->state() != "done") {
      const QString error = v->start();
      if (!error.isEmpty()) fail("report " + name.toStdString() + ": " + error.toStdString());
    }
    if (w.scripted() && !v->waitForFinished(240000))
      fail("report " + name.toStdString() + ": the report did not finish in time");
  };
  // Made only when named (or made before): a step without reports opens no window.
  if (named.contains("aa") || w.findChild<AaReportView*>("aaReportView"))
    enter(w.aaReportView(), "aa", false);
  if (named.contains("grid-sweep") || w.findChild<GridSweepView*>("gridSweepView"))
    enter(w.gridSweepView(), "grid-sweep", false);
  if (named.contains("bvol") || w.findChild<BvolReportView*>("bvolReportView"))
    enter(w.bvolReportView(), "bvol", true);
}

}  // namespace

void enterState(MainWindow& w, const LessonState& st) {
  InPlace inPlace(w);
  Session* s = w.session();
  ImageView* image = w.imageView();

  // The structure, the picture and the heat map: set on the panels first, so that opening or building takes
  // them; then made again only where they differ from what the window has.
  w.setStructureOptions(st.accel, st.structure);
  image->setAntiAliasing(st.aa.empty() ? QString("scene") : QString::fromStdString(st.aa));
  image->setHeatQuantity(st.heat.empty() ? QString("off") : QString::fromStdString(st.heat));
  image->setSecondaryRays(st.secondary);
  w.setImageSize(st.size ? (*st.size)[0] : 0, st.size ? (*st.size)[1] : 0);

  const QString scene = QString::fromStdString(st.scene);
  const bool isTrace = !st.scene.empty() && MainWindow::isTraceFile(scene);
  const SceneData* had = s->scene();
  const bool newFile = !st.scene.empty() &&
                       (isTrace ? s->traceSource() != scene || had : !had || !samePath(had->path, st.scene));
  if (newFile) {
    w.openFile(scene);  // builds, renders and computes the heat map with the settings above
  } else if (s->scene() && w.builtStructureKey() != w.structureOptionsKey()) {
    w.buildStructure();
  }
  if (s->scene()) {
    w.ensurePicture();
    w.ensureHeat();
  }

  // The traced pixel: traced again each time (the class may have clicked another pixel meanwhile).
  if (st.pixel) {
    const std::string text = std::to_string((*st.pixel)[0]) + "," + std::to_string((*st.pixel)[1]);
    if (!s->scene()) fail("--pixel needs a scene (a trace file already holds its rays)");
    if ((*st.pixel)[0] >= s->imageWidth() || (*st.pixel)[1] >= s->imageHeight())
      fail("--pixel " + text + ": outside the " + std::to_string(s->imageWidth()) + "x" +
           std::to_string(s->imageHeight()) + " image");
    w.tracePixel((*st.pixel)[0], (*st.pixel)[1]);
  } else if (s->scene() && s->scene()->scene.flat && s->scene()->scene.flat->has_ray) {
    // A 2D scene: its own ray's walk in the plane, the 2D view's (a step is the same state however the class
    // dragged the ray before).
    const Flatland& flat = *s->scene()->scene.flat;
    w.traceFlatRay(flat.ray_origin, flat.ray_direction, false);
  } else if (s->scene() && s->trace()) {
    s->setTrace(nullptr, QString());
  }
  if (st.ray != 0 || (s->trace() && s->rayIndex() != 0)) {
    if (!s->trace() || st.ray < 0 || st.ray >= int(s->trace()->rays.size()))
      fail("--ray " + std::to_string(st.ray) + ": no such ray in the trace");
    s->setRay(st.ray);
  }
  // An anti-aliased pixel's sample: its primary ray, as a click on it in the inspector chooses it.
  if (st.sample) {
    const std::string text = "--sample " + std::to_string(*st.sample);
    const TracePixel* px = s->pixel();
    if (!px) fail(text + ": no traced pixel (give --pixel)");
    const int n = int(px->sampling.samples.size());
    if (*st.sample >= n)
      fail(text + ": the pixel has " + std::to_string(n) + " sample" + (n == 1 ? "" : "s") + " (0.." +
           std::to_string(n - 1) + ")");
    if (!s->selectSample(*st.sample)) fail(text + ": the trace holds no ray of that sample");
  }
  switch (st.event.by) {
    case EventSpec::By::start:
      s->setStep(0);
      break;
    case EventSpec::By::index:
      if (st.event.index < 0 || st.event.index >= s->eventCount())
        fail("--step " + std::to_string(st.event.index) + ": the ray has " + std::to_string(s->eventCount()) +
             " events (0.." + std::to_string(s->eventCount() - 1) + ")");
      s->setStep(st.event.index);
      break;
    case EventSpec::By::nth: {
      int i = s->ray() ? replay::nth_event(*s->ray(), st.event.type, st.event.k) : -1;
      if (i < 0) fail("--step-to " + st.event.text + ": the ray has fewer such events");
      s->setStep(i);
      break;
    }
  }

  // The pixel inspector, at a square of adaptive sampling's subdivision (the whole pixel unless named).
  if (st.square) {
    const std::string text = "--square " + std::to_string(*st.square);
    const TracePixel* px = s->pixel();
    if (!px) fail(text + ": no traced pixel (give --pixel)");
    if (px->sampling.aa.mode != AntiAliasing::Mode::adaptive)
      fail(text + ": the pixel is not sampled adaptively (give --aa adaptive:T[:D])");
    const int n = s->squareCount();
    if (*st.square >= n)
      fail(text + ": the pixel's subdivision has " + std::to_string(n) + " squares (0.." +
           std::to_string(n - 1) + ")");
    s->setSquare(*st.square);
  } else if (s->squareCount() > 0) {
    s->setSquare(0);
  }
  if (st.inspect || st.sample || st.square)
    w.showPixelInspector();
  else if (s->scene())  // a trace with a pixel section shows its inspector when opened
    w.hidePixelInspector();
  image->setSampleOverlay(st.sample_overlay);

  // The picture: fitted, or zoomed on the traced pixel.
  ImageCanvas* canvas = image->canvas();
  canvas->setZoom(st.zoom ? *st.zoom : 0.0);
  // Zoomed in, centred on the traced pixel; fitted (zoom 0) or without a pixel, the whole picture centred,
  // not where an earlier step (or a click and drag) left it.
  if (st.zoom && *st.zoom > 0.0 && st.pixel)
    canvas->centreOn((*st.pixel)[0], (*st.pixel)[1]);
  else
    canvas->resetPan();

  // The tree's inspector (kd-tree or binary BVH): a node by id or path, or the root for `panel: sah`; closed
  // otherwise.
  const KdTree* kd = s->structure() ? s->structure()->kdTree() : nullptr;
  const Bvh* bvh = s->structure() ? s->structure()->bvh() : nullptr;
  int node = st.panel == "sah" ? 0 : -1;
  if (!st.panel.empty() || st.node.by != NodeSpec::By::none) {
    const char* what = st.node.by == NodeSpec::By::id     ? "--node"
                       : st.node.by == NodeSpec::By::path ? "--node-path"
                                                          : "--panel";
    // The octree, the wide BVH and the BSP tree: their tree view and a node by id (a path: the BSP tree's,
    // L below its plane and R above).
    const std::unique_ptr<TreeShape> other =
        !kd && !bvh && s->structure() ? treeShapeOf(*s->structure()) : nullptr;
    if (!kd && !bvh && !other)
      fail(std::string(what) +
           ": no tree (open a scene with --accel kd, kd-median, bvh, bvh-sweep, bvh-median, octree or "
           "bsp)");
    const size_t count = kd ? kd->data().nodes.size() : bvh ? bvh->data().nodes.size() : other->size();
    const std::string name = kd ? "kd-tree" : bvh ? "BVH" : other->name();
    if (st.node.by == NodeSpec::By::id) {
      if (st.node.id < 0 || size_t(st.node.id) >= count)
        fail("--node " + std::to_string(st.node.id) + ": the " + name + " has " + std::to_string(count) +
             " nodes (0.." + std::to_string(count - 1) + ")");
      node = st.node.id;
    }
    if (st.node.by == NodeSpec::By::path) {
      try {  // the lesson layer's paths (tree_nodes.h): L/R, or an octree's octant digits
        node = int(lesson_node_by_path(*s->structure()->accel, st.node.path));
      } catch (const InputError& e) {
        fail("--node-path '" + st.node.path + "': " + e.detail());
      }
    }
  }
  if (!st.panel.empty() || st.node.by != NodeSpec::By::none) {
    if (!w.kdPanelVisible()) {
      w.showKdPanel();
      settle(w);  // the dock laid out before the chart draws
    }
  } else {
    w.hideKdPanel();
  }
  s->setSelectedNode(node);
  w.treeView()->resetRows();

  // The 3D view: the scene framed as when it was opened, at the view's size once the panels have taken their
  // room for this state (the state column's scroll bar, the dock), then following if the state says so.
  // The 3D view is drawn once, below, with its final camera: not also by these paint events with the old one.
  SceneView* view = w.sceneView();
  view->setUpdatesEnabled(false);
  for (int i = 0; i < 3; ++i) QApplication::processEvents();
  view->setUpdatesEnabled(true);
  if (view->translucent() != st.translucent) view->setTranslucent(st.translucent);
  if (view->buildPlanes() != st.build_planes) view->setBuildPlanes(st.build_planes);
  w.flatView()->setBuildSoFar(st.build_planes);  // a 2D scene's build so far, Crofton's lines, the pixels
  w.flatView()->setCroftonLines(st.crofton_lines);
  w.flatView()->setAntiAliasingView(st.flat_aa);
  if (view->followCell()) view->setFollowCell(false);
  view->restoreHomeCamera();
  if (st.follow) view->setFollowCell(true);
  view->renderNow();

  enterReports(w, st);
}

}  // namespace raystep::viz
