// The main window's background work: runTask (a newer task of a kind supersedes an older one; in the scripted
// mode the work runs in place), the SAH curves of the selected node, rendering, the heat map, tracing a clicked
// pixel, the pixel inspector, exporting a trace and the side-by-side view.
#include "app/main_window.h"

#include <cmath>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>

#include <QAction>
#include <QApplication>
#include <QDockWidget>
#include <QFileDialog>
#include <QFileInfo>
#include <QFutureWatcher>
#include <QMenuBar>
#include <QMessageBox>
#include <QScreen>
#include <QScrollArea>
#include <QSplitter>
#include <QStatusBar>
#include <QStyle>
#include <QThread>
#include <QTimer>
#include <QVBoxLayout>
#include <QtConcurrent>
#include <optional>

#include "reports/aa_report_view.h"
#include "reports/bvol_report_view.h"
#include "lesson/classroom_layout.h"
#include "compare/compare_window.h"
#include "views/event_list.h"
#include "reports/grid_sweep_view.h"
#include "app/heartbeat.h"
#include "views/image_view.h"
#include "views/kd_tree_model.h"
#include "lesson/lesson_pane.h"
#include "inspect/pixel_inspector.h"
#include "flatland/flat_view.h"
#include "raystep/figure/figure_file.h"
#include "raystep/scene/flatland.h"
#include "raystep/trace/record_trace.h"
#include "lesson/presenter.h"
#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_figure.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/trace/trace_file.h"
#include "raystep/util/error.h"
#include "inspect/sah_chart.h"
#include "views/scene_view.h"
#include "app/session.h"
#include "views/state_panel.h"
#include "views/structure_panel.h"
#include "views/timeline.h"
#include "views/tree_pick.h"
#include "views/tree_view.h"
#include "app/settle.h"

namespace raystep::viz {

void MainWindow::showBvhSahCurve() {
  auto structure = session_->structureShared();
  const Bvh* bvh = structure->bvh();
  int node = session_->selectedNode();
  if (node < 0) {
    sahChart_->showMessage(tr("Select a node in the tree to see its binned SAH cost curve."));
    return;
  }
  sahChart_->showMessage(tr("Recording the SAH curve of node %1...").arg(node));
  BvhOptions options = bvh->options();
  QString path = QString::fromStdString(bvhNodePath(bvh->data(), uint32_t(node)));
  runTask(
      "sah", tr("Recording the SAH curve of node %1...").arg(node), [this, structure, options, node, path] {
        auto t0 = std::chrono::steady_clock::now();
        auto curve = std::make_shared<const BvhSahCurve>(
            record_bvh_sah_curve(structure->scene->scene.geometry, options, uint32_t(node)));
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return std::function<void()>([this, structure, options, node, path, curve, ms] {
          if (structure != session_->structureShared() || node != session_->selectedNode()) return;  // stale
          sahChart_->setBvhCurve(curve, path, options.t_i, options.t_t);
          statusBar()->showMessage(
              tr("SAH curve of BVH node %1: %2 candidates").arg(node).arg(curve->candidates.size()) +
              took(tr(", recorded"), ms));
        });
      });
}

void MainWindow::showBspSahCurve() {
  auto structure = session_->structureShared();
  const BspTree* bsp = structure->bsp();
  int node = session_->selectedNode();
  if (node < 0) {
    sahChart_->showMessage(
        tr("Select a node in the tree (or click the scene in the 3D view) to see its "
           "candidate planes by orientation."));
    return;
  }
  sahChart_->showMessage(tr("Recording the SAH candidates of node %1...").arg(node));
  BspOptions options = bsp->options();
  std::unique_ptr<TreeShape> shape = treeShapeOf(*structure);
  QString path = QString::fromStdString(shape->path(uint32_t(node)));
  // The builder runs again up to this node with a listener (the same code that built the tree).
  runTask("sah", tr("Recording the SAH candidates of node %1...").arg(node),
          [this, structure, options, node, path] {
            auto t0 = std::chrono::steady_clock::now();
            auto curve = std::make_shared<const BspSahCurve>(
                record_bsp_sah_curve(structure->scene->scene.geometry, options, uint32_t(node)));
            double ms =
                std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
            return std::function<void()>([this, structure, options, node, path, curve, ms] {
              if (structure != session_->structureShared() || node != session_->selectedNode())
                return;  // stale
              sahChart_->setBspCurve(curve, path, options.t_i, options.t_t);
              statusBar()->showMessage(
                  tr("SAH candidates of BSP node %1: %2 planes").arg(node).arg(curve->candidates.size()) +
                  took(tr(", recorded"), ms));
            });
          });
}

void MainWindow::showSahCurve() {
  auto structure = session_->structureShared();
  if (structure && structure->bvh()) return showBvhSahCurve();
  if (structure && structure->bsp()) return showBspSahCurve();
  const KdTree* kd = structure ? structure->kdTree() : nullptr;
  int node = session_->selectedNode();
  if (!kd || node < 0) {
    // The trees without a curve of their own say why, so that the empty chart does not read as a fault.
    const bool octree = structure && structure->octree(), wide = structure && structure->wideBvh();
    sahChart_->showMessage(
        kd       ? tr("Select a node in the tree (or click the scene in the 3D view) to see its SAH "
                            "cost curve.")
        : octree ? tr("An octree splits every cell at its centre into eight: there is no plane to choose, so "
                      "no SAH curve. The tree lists each cell's octants and primitives.")
        : wide   ? tr("A wide BVH is the binary BVH's tree collapsed into nodes of up to %1 children: its "
                        "choices are the binary BVH's (open the scene with --accel bvh to see their SAH "
                        "curves). The tree lists each node's children and primitives.")
                     .arg(structure->wideBvh()->width())
               : tr("The SAH inspector shows kd-tree, binary BVH and BSP tree nodes: build one of them."));
    return;
  }
  sahChart_->showMessage(tr("Recording the SAH curve of node %1...").arg(node));
  KdOptions options = kd->options();
  QString path = QString::fromStdString(kdNodePath(kd->data(), uint32_t(node)));
  // The builder runs again with a listener for this node alone: as long as a build, so off the GUI thread.
  runTask(
      "sah", tr("Recording the SAH curve of node %1...").arg(node), [this, structure, options, node, path] {
        auto t0 = std::chrono::steady_clock::now();
        auto curve = std::make_shared<const SahCurve>(
            record_sah_curve(structure->scene->scene.geometry, options, uint32_t(node)));
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        return std::function<void()>([this, structure, options, node, path, curve, ms] {
          if (structure != session_->structureShared() || node != session_->selectedNode()) return;  // stale
          sahChart_->setCurve(curve, path, options.t_i, options.t_t, options.empty_bonus);
          statusBar()->showMessage(
              tr("SAH curve of node %1: %2 candidates").arg(node).arg(curve->candidates.size()) +
              took(tr(", recorded"), ms));
        });
      });
}

void MainWindow::exportSahCsv(const QString& path) {
  try {
    if (!sahChart_->curve() && !sahChart_->bspCurve())
      throw InputError("", 0, "no SAH curve: select a kd-tree, BVH or BSP node first");
    if (sahChart_->bspCurve())
      write_bsp_sah_csv(path.toStdString(),
                        *sahChart_->bspCurve());  // the columns of raystep sah --accel bsp
    else if (sahChart_->bvhCurve())
      write_bvh_sah_csv(path.toStdString(),
                        *sahChart_->bvhCurve());  // the columns of raystep sah --accel bvh
    else
      write_sah_csv(path.toStdString(), *sahChart_->curve());
    statusBar()->showMessage(tr("wrote %1").arg(path));
  } catch (const std::exception& e) {
    if (scripted_) throw;
    showError(QString::fromStdString(e.what()));
  }
}

QString MainWindow::took(const QString& what, double ms) const {
  // Scripted runs leave times out of the window, so that screenshots of the same state are identical.
  return scripted_ ? QString() : tr("%1 in %2 ms").arg(what).arg(ms, 0, 'f', ms < 10 ? 1 : 0);
}

void MainWindow::showError(const QString& message) {
  lastError_ = message;
  std::fprintf(stderr, "error: %s\n", message.toLocal8Bit().constData());
  auto* box = new QMessageBox(QMessageBox::Critical, tr("raystep"), message, QMessageBox::Ok, this);
  box->setAttribute(Qt::WA_DeleteOnClose);
  box->setObjectName("errorDialog");
  box->open();  // window-modal, does not block: the window stays alive behind it
  if (scripted_) QTimer::singleShot(0, box, &QMessageBox::accept);
}

void MainWindow::runTask(const QString& kind, const QString& what,
                         std::function<std::function<void()>()> work) {
  if (scripted_ || inPlace_) {
    work()();  // errors propagate to the script
    return;
  }
  int gen = ++generation_[kind];
  ++running_;
  structure_->setBusy(true);
  statusBar()->showMessage(what);
  auto* watcher = new QFutureWatcher<std::function<void()>>(this);
  connect(watcher, &QFutureWatcher<std::function<void()>>::finished, this, [this, watcher, gen, kind] {
    watcher->deleteLater();
    std::function<void()> done = watcher->result();
    if (--running_ == 0) structure_->setBusy(false);
    if (gen != generation_[kind]) return;  // a later request of the same kind superseded this one
    try {
      done();
    } catch (const std::exception& e) {  // never let an exception out of a Qt slot
      showError(QString::fromStdString(e.what()));
    }
  });
  watcher->setFuture(QtConcurrent::run([work, this]() -> std::function<void()> {
    try {
      return work();
    } catch (const std::exception& e) {
      QString msg = QString::fromStdString(e.what());
      return [this, msg] {
        statusBar()->clearMessage();  // not "Loading ..." under the error any more
        showError(msg);
      };
    }
  }));
}


void MainWindow::renderPicture() {
  auto grid = session_->structureShared();
  if (!grid) return;
  std::string aa = imageView_->antiAliasing().toStdString();
  int w = session_->imageWidth(), h = session_->imageHeight();
  QString key = pictureKeyNow();
  flatView_->setAntiAliasing(imageView_->antiAliasing());  // the 2D view's pixels sample as the picture
  imageView_->setStatus(tr("Rendering %1x%2 (%3)...").arg(w).arg(h).arg(QString::fromStdString(aa)));
  runTask("render", tr("Rendering..."), [this, grid, aa, w, h, key] {
    double ms = 0;
    RayCounts rays;
    QImage img = viz::renderPicture(*grid, aa, w, h, &ms, &rays);
    return std::function<void()>([this, grid, img, ms, w, h, aa, key, rays] {
      if (grid != session_->structureShared()) return;  // made for a structure since replaced
      session_->setPicture(img);
      pictureKey_ = key;
      // The lecture's m^2 k^2 n 2^d, as this picture really spent it.
      QLocale l;
      // "scene" names the scene file's own setting: say which it is.
      const std::string aaText =
          aa.empty() || aa == "scene" ? "the scene's " + to_string(grid->scene->scene.render.aa) : aa;
      imageView_->setStatus(
          tr("%1x%2, anti-aliasing %3").arg(w).arg(h).arg(QString::fromStdString(aaText)) +
          took(tr(", rendered"), ms) +
          tr(". Rays: %1 primary, %2 shadow, %3 reflected, %4 refracted (%5 in all). Click a "
             "pixel to trace its ray.")
              .arg(l.toString(qulonglong(rays.primary)), l.toString(qulonglong(rays.shadow)),
                   l.toString(qulonglong(rays.reflected)), l.toString(qulonglong(rays.refracted)),
                   l.toString(qulonglong(rays.total()))));
      // The traced pixel follows the picture's anti-aliasing: the inspector shows the samples the picture
      // used.
      if (const TracePixel* px = session_->pixel(); px && session_->scene() && session_->trace()) {
        AntiAliasing now;
        try {
          now = antiAliasingOf(grid->scene->scene, aa);
        } catch (const std::exception&) {
          now = px->sampling.aa;
        }
        if (to_string(now) != to_string(px->sampling.aa) && px->sampling.x < w && px->sampling.y < h)
          tracePixel(px->sampling.x, px->sampling.y);
      }
      // The new anti-aliasing's samples or error.
      if (imageView_->heatQuantity() == "samples" || imageView_->heatQuantity() == "error") ensureHeat();
      if (scripted_ || Heartbeat::enabled()) std::fprintf(stderr, "timing: render %dx%d %.1f ms\n", w, h, ms);
    });
  });
}

void MainWindow::computeHeat() {
  auto grid = session_->structureShared();
  QString q = imageView_->heatQuantity();
  if (!grid || q == "off") {
    session_->setHeat(nullptr);
    heatKey_ = heatKeyNow();
    return;
  }
  QString key = heatKeyNow();
  HeatQuantity quantity = parse_heat_quantity(q.toStdString());
  std::string aa = imageView_->antiAliasing().toStdString();
  int w = session_->imageWidth(), h = session_->imageHeight();
  runTask("heat", tr("Computing the heat map..."), [this, grid, quantity, aa, w, h, key] {
    double ms = 0;
    auto heat = std::make_shared<const HeatMap>(viz::computeHeat(*grid, quantity, aa, w, h, &ms));
    return std::function<void()>([this, grid, heat, ms, key] {
      if (grid != session_->structureShared()) return;
      session_->setHeat(heat);
      heatKey_ = key;
      statusBar()->showMessage(
          tr("heat map %1x%2").arg(heat->width).arg(heat->height) + took("", ms) +
          tr(" (max %1, mean %2)").arg(heat->max_value).arg(heat->mean_value, 0, 'f', 2));
      std::fprintf(stderr, "timing: heat map %dx%d %.1f ms\n", heat->width, heat->height, ms);
    });
  });
}

void MainWindow::tracePixel(int x, int y) {
  const StructureData* grid = session_->structure();
  if (!grid) return showError(tr("The structure is not built yet."));
  int w = session_->imageWidth(), h = session_->imageHeight();
  if (x < 0 || y < 0 || x >= w || y >= h)
    throw InputError("", 0,
                     "--pixel " + std::to_string(x) + "," + std::to_string(y) + ": outside the " +
                         std::to_string(w) + "x" + std::to_string(h) + " image");
  // Every sample's rays with anti-aliasing (the pixel's trace then holds its samples); the centre ray
  // without.
  const AntiAliasing aa = antiAliasingOf(grid->scene->scene, imageView_->antiAliasing().toStdString());
  auto trace =
      std::make_shared<const Trace>(viz::tracePixel(*grid, aa, w, h, x, y, imageView_->secondaryRays()));
  std::shared_ptr<const TracePixel> centre;
  if (!trace->pixel) centre = std::make_shared<const TracePixel>(centrePixel(*grid, w, h, x, y));
  // The scene inside the pixel, beneath the samples: 4096 more rays, cast only while the inspector is open (a
  // lesson step that does not show it stays as fast as before); before the trace, whose legend mentions it.
  pixelInspector_->canvas()->setBackdrop(
      pixelDock_->isVisible() ? pixelBackdrop(*grid, w, h, x, y, 64, PixelCanvas::viewReach(aa)) : QImage());
  session_->setTrace(trace, tr("pixel (%1, %2)").arg(x).arg(y), centre);
}

void MainWindow::traceFlatRay(glm::vec2 origin, glm::vec2 direction, bool keepStep) {
  const StructureData* s = session_->structure();
  const SceneData* scene = session_->scene();
  if (!s || !s->accel || !scene || !scene->scene.flat || s->scene.get() != scene) return;
  if (!std::isfinite(origin.x) || !std::isfinite(origin.y) || !std::isfinite(direction.x) ||
      !std::isfinite(direction.y) || (direction.x == 0.f && direction.y == 0.f))
    throw InputError("", 0, "a ray in the plane needs a finite origin and a direction other than (0, 0)");
  const int step = keepStep && session_->trace() ? session_->step() : 0;
  const auto t0 = std::chrono::steady_clock::now();
  auto trace = std::make_shared<const Trace>(
      record_trace(scene->scene.geometry, *s->accel,
                   {RayRequest{flat_ray(origin, direction), RayKind::primary, 0, false, {0, 0}}}, scene->path,
                   scene->hash));
  session_->setTrace(trace,
                     tr("ray in the plane from (%1, %2) along (%3, %4)")
                         .arg(double(origin.x), 0, 'g', 4)
                         .arg(double(origin.y), 0, 'g', 4)
                         .arg(double(direction.x), 0, 'g', 3)
                         .arg(double(direction.y), 0, 'g', 3),
                     nullptr, step);
  if (std::getenv("RAYSTEP_GUI_PROFILE"))  // the trace and every view's update but the 2D view's painting
    std::fprintf(stderr, "ray in the plane traced and shown in %.2f ms\n",
                 std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count());
}

void MainWindow::exportFigure(const QString& path) {
  try {
    if (!session_->scene() || !session_->scene()->scene.flat)
      throw InputError("", 0, "a figure draws a 2D scene (\"dimensions\": 2); this scene is 3D");
    write_figure(path.toStdString(), flatView_->figure(), 640);  // `raystep figure`'s default width
    statusBar()->showMessage(tr("wrote %1").arg(path));
  } catch (const std::exception& e) {
    if (scripted_) throw;
    showError(QString::fromStdString(e.what()));
  }
}

void MainWindow::drawPixelBackdrop() {
  const StructureData* grid = session_->structure();
  const TracePixel* px = session_->pixel();
  if (!grid || !px || !session_->scene() || pixelInspector_->canvas()->hasBackdrop()) return;
  const int w = session_->imageWidth(), h = session_->imageHeight();
  if (px->sampling.x >= w || px->sampling.y >= h) return;
  pixelInspector_->setBackdrop(
      pixelBackdrop(*grid, w, h, px->sampling.x, px->sampling.y, 64, PixelCanvas::viewReach(px->sampling.aa)));
}

void MainWindow::showPixelInspector() {
  if (pixelDock_->isVisible()) return;
  pixelDock_->show();
  resizeDocks({pixelDock_}, {int(280 * scale_)}, Qt::Vertical);
  // Below 900 pixels the dock leaves the picture a strip: the structure panel gives up what it can spare
  // (down to its minimum) while the inspector is open. (Presenter scales above 1 are compact already: the
  // picture has the column.)
  if (height() < 900 && scale_ == 1.0) leftSplit_->setSizes({130, 1000});
  drawPixelBackdrop();
}

void MainWindow::hidePixelInspector() {
  if (!pixelDock_->isVisible()) return;
  pixelDock_->hide();
  if (scale_ == 1.0) leftSplit_->setSizes({200, 500});
  pixelInspector_->setBackdrop(QImage());  // traced again when the inspector opens: as a fresh window has it
}

bool MainWindow::pixelInspectorVisible() const {
  return pixelDock_->isVisible();
}

void MainWindow::exportTrace(const QString& path) {
  try {
    write_trace_json(path.toStdString(), *session_->trace());
    statusBar()->showMessage(tr("wrote %1").arg(path));
  } catch (const std::exception& e) {
    if (scripted_) throw;
    showError(QString::fromStdString(e.what()));
  }
}

CompareWindow* MainWindow::compareWindow() {
  if (!compare_) compare_ = new CompareWindow(this);
  return compare_;
}

void MainWindow::setCompareStructures(const QStringList& kinds) {
  compareKinds_ = kinds;
  const TracedRay* r = session_->scene() ? session_->ray() : nullptr;
  if (r && r->has_pixel)
    comparePixel(kinds, r->pixel[0], r->pixel[1]);
  else
    statusBar()->showMessage(
        tr("Click a pixel of the picture: its ray through %1 opens side by side.").arg(kinds.join(", ")));
}

void MainWindow::comparePixel(const QStringList& kinds, int x, int y) {
  std::shared_ptr<const SceneData> scene = session_->sceneShared();
  if (!scene) return showError(tr("Open a scene first: the structures are built over it."));
  // Built once per scene and options (a build asked for in the structure panel forgets them): the next pixel
  // clicked walks the same structures.
  for (const auto& [key, b] : compareBuilt_)
    if (b->scene != scene) {
      compareBuilt_.clear();
      break;
    }
  std::vector<std::shared_ptr<const StructureData>> kept;
  for (const QString& k : kinds) kept.push_back(compareBuilt_.count(k) ? compareBuilt_[k] : nullptr);
  const StructureOptions options = structure_->options();
  const int w = session_->imageWidth(), h = session_->imageHeight();
  const bool secondary = imageView_->secondaryRays();
  // The builds and the walks off the GUI thread (a kd-tree or BSP tree over a big mesh takes seconds).
  runTask("compare", tr("Building %1 for the side-by-side view...").arg(kinds.join(", ")),
          [this, scene, kinds, kept, options, w, h, x, y, secondary] {
            std::vector<std::shared_ptr<const StructureData>> built = kept;
            for (int i = 0; i < kinds.size(); ++i)
              if (!built[size_t(i)])
                built[size_t(i)] = buildStructureData(scene, kinds[i].toStdString(), options);
            auto walks = recordComparePixel(built, w, h, x, y, secondary);
            return std::function<void()>([this, scene, kinds, built, walks, x, y] {
              if (session_->sceneShared() != scene) return;  // another scene meanwhile
              for (int i = 0; i < kinds.size(); ++i) compareBuilt_[kinds[i]] = built[size_t(i)];
              compareWindow()->setWalks(walks, scene, built, QString::fromStdString(scene->path));
              compare_->show();
              compare_->raise();
              statusBar()->showMessage(
                  tr("Pixel (%1, %2) side by side through %3.").arg(x).arg(y).arg(kinds.join(", ")));
            });
          });
}

}  // namespace raystep::viz
