// The main window opening files and building structures: a scene, a mesh or a trace (read on a worker), the
// structure options and their keys, structures kept and prefetched for the next lesson step, the build.
#include "app/main_window.h"

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

void MainWindow::openFile(const QString& path) {
  if (isMultiTraceFile(path)) {  // several structures' walks: the side-by-side window
    std::shared_ptr<const MultiTrace> walks;
    try {
      walks = std::make_shared<const MultiTrace>(read_multi_trace_json(path.toStdString()));
    } catch (const std::exception& e) {
      if (scripted_ || inPlace_) throw;
      return showError(QString::fromStdString(e.what()));
    }
    compareWindow()->setWalks(walks, nullptr, {}, path);
    compare_->show();
    compare_->raise();
    return;
  }
  if (isTraceFile(path))
    openTrace(path);
  else
    openScene(path);
}

void MainWindow::openFileReportingErrors(const QString& path) {
  try {
    openFile(path);
  } catch (const std::exception& e) {
    showError(QString::fromStdString(e.what()));
  }
}

void MainWindow::openTrace(const QString& path) {
  // Read and validate on a worker (a big trace takes a second): on error nothing changes.
  std::string p = path.toStdString();
  runTask("open", tr("Reading %1...").arg(path), [this, p, path] {
    auto t0 = std::chrono::steady_clock::now();
    auto trace = std::make_shared<const Trace>(read_trace_json(p));
    double readMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
    return std::function<void()>([this, trace, readMs, path] { showTrace(trace, path, readMs); });
  });
}

void MainWindow::showTrace(std::shared_ptr<const Trace> trace, const QString& path, double readMs) {
  auto t0 = std::chrono::steady_clock::now();
  ++generation_["build"];  // a structure still being built for the previous scene is of no use now
  if (session_->scene()) session_->setScene(nullptr);
  pixelInspector_->canvas()->setBackdrop(QImage());  // no scene: no view inside the pixel
  session_->setTrace(trace, path);
  // A trace of an anti-aliased pixel shows its samples without the scene.
  if (trace->pixel)
    showPixelInspector();
  else
    hidePixelInspector();
  // The structure panel names the trace's kd-tree and its options (shown only: there is no scene to build
  // on).
  if (trace->structure.kind != "grid") {
    StructureOptions so;
    for (const TraceParam& p : trace->structure.params) {
      if (p.key == "t_i")
        so.kd.t_i = float(p.number);
      else if (p.key == "t_t")
        so.kd.t_t = float(p.number);
      else if (p.key == "empty_bonus")
        so.kd.empty_bonus = float(p.number);
      else if (p.key == "max_depth")
        so.kd.max_depth = int(p.number);
      else if (p.key == "leaf_size")
        so.kd.leaf_size = int(p.number);
      else if (p.key == "mailboxes")
        so.kd_mailboxes = p.text != "off";
    }
    structure_->setStructure(trace->structure.kind, so);
  }
  double showMs = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
  size_t events = 0;
  for (const TracedRay& r : trace->rays) events += r.events.size();
  QString structure = QString::fromStdString(trace->structure.kind);
  if (trace->structure.kind == "grid") {
    structure += QString(" %1x%2x%3")
                     .arg(trace->structure.resolution[0])
                     .arg(trace->structure.resolution[1])
                     .arg(trace->structure.resolution[2]);
    for (const TraceParam& p : trace->structure.params)
      if (p.is_text && p.key == "coarsened_from")
        structure += tr(" coarsened from %1").arg(QString::fromStdString(p.text));
  }
  structure_->setInfo(tr("Replaying %1 (%2 rays, %3 events; structure %4) without the scene.")
                          .arg(QFileInfo(path).fileName())
                          .arg(trace->rays.size())
                          .arg(events)
                          .arg(structure));
  imageView_->setStatus(tr("Trace replay: no picture (open the scene to render it)."));
  statusBar()->showMessage(tr("opened %1").arg(path) + took(tr(": read"), readMs) +
                           took(tr(", shown"), showMs));
  std::fprintf(stderr, "timing: trace %zu events read %.1f ms, shown %.1f ms\n", events, readMs, showMs);
  setWindowTitle(tr("raystep step-debugger - %1 (trace)").arg(QFileInfo(path).fileName()));
}

void MainWindow::openScene(const QString& path) {
  std::string p = path.toStdString();
  runTask("open", tr("Loading %1...").arg(path), [this, p, path] {
    auto scene = loadSceneData(p);
    return std::function<void()>([this, scene, path] {
      session_->setScene(scene);
      setWindowTitle(tr("raystep step-debugger - %1").arg(QFileInfo(path).fileName()));
      buildStructure();
    });
  });
}

void MainWindow::setStructureOptions(const std::string& accelName, const StructureOptions& o) {
  structure_->setStructure(accelName, o);
}

QString MainWindow::builtStructureKey() const {
  return session_->structure() ? builtKey_ : QString();
}

QString MainWindow::structureOptionsKey() const {
  return structureKey(structure_->accelName(), structure_->options());
}

QString MainWindow::structureKey(const std::string& accelName, const StructureOptions& o) {
  QString res = o.grid.resolution ? QString("%1,%2,%3")
                                        .arg((*o.grid.resolution)[0])
                                        .arg((*o.grid.resolution)[1])
                                        .arg((*o.grid.resolution)[2])
                                  : QString("-");
  return QString("%1 %2 %3 %4 %5 %6 %7 %8 %9 %10")
      .arg(QString::fromStdString(accelName))
      .arg(double(o.grid.density), 0, 'g', 9)
      .arg(res)
      .arg(o.grid.exact_insert)
      .arg(double(o.kd.t_i), 0, 'g', 9)
      .arg(double(o.kd.t_t), 0, 'g', 9)
      .arg(double(o.kd.empty_bonus), 0, 'g', 9)
      .arg(o.kd.max_depth)
      .arg(o.kd.leaf_size)
      .arg(o.kd_mailboxes);
}

void MainWindow::setImageSize(int w, int h) {
  sizeW_ = w;
  sizeH_ = h;
  // With a structure built, the picture takes the new size at once (the caller renders it again).
  if (const StructureData* built = session_->structure())
    session_->setImageSize(w > 0 ? w : built->scene->scene.render.width,
                           h > 0 ? h : built->scene->scene.render.height);
}

void MainWindow::keepStructure(const KeptStructure& k) {
  kept_.erase(std::remove_if(kept_.begin(), kept_.end(),
                             [&](const KeptStructure& o) { return o.scene != k.scene || o.key == k.key; }),
              kept_.end());
  kept_.push_back(k);
  if (kept_.size() > 4) kept_.erase(kept_.begin());
}

void MainWindow::prefetchStructure(const std::string& accelName, const StructureOptions& o) {
  auto scene = session_->sceneShared();
  if (!scene) return;
  const QString key = structureKey(accelName, o);
  for (const KeptStructure& k : kept_)
    if (k.scene == scene && k.key == key) return;
  for (const Prefetch& f : prefetches_)
    if (f.scene == scene && f.key == key) return;
  auto future = QtConcurrent::run([scene, accelName, o] { return buildStructureData(scene, accelName, o); });
  prefetches_.push_back({scene, key, future});
  auto* watcher = new QFutureWatcher<std::shared_ptr<const StructureData>>(this);
  connect(watcher, &QFutureWatcher<std::shared_ptr<const StructureData>>::finished, this,
          [this, watcher, scene, key] {
            watcher->deleteLater();
            prefetches_.erase(
                std::remove_if(prefetches_.begin(), prefetches_.end(),
                               [&](const Prefetch& f) { return f.scene == scene && f.key == key; }),
                prefetches_.end());
            std::shared_ptr<const StructureData> built;
            try {
              built = watcher->result();
            } catch (...) {  // a build that fails is reported when the step itself builds it
              return;
            }
            if (scene == session_->sceneShared()) keepStructure({scene, key, built});
          });
  watcher->setFuture(future);
}

void MainWindow::waitForPrefetches() {
  while (!prefetches_.empty()) {
    prefetches_.front().built.waitForFinished();
    QApplication::processEvents();  // the watchers keep what was built
  }
}

void MainWindow::buildStructure() {
  auto scene = session_->sceneShared();
  if (!scene) return showError(tr("Open a scene first: a trace replays the structure it recorded."));
  std::string kind = structure_->accelName();
  StructureOptions o = structure_->options();
  QString key = structureOptionsKey();
  QString what = kind == "grid" ? tr("Building the grid...") : tr("Building the kd-tree...");
  // A structure built before for this scene with the same options is used again: a lesson that goes back
  // and forth between a grid and a kd-tree (or two costs) builds each once.
  std::shared_ptr<const StructureData> kept;
  for (const KeptStructure& k : kept_)
    if (k.scene == scene && k.key == key) kept = k.built;
  // A prefetch of this very structure underway: wait for it rather than build it twice.
  std::optional<QFuture<std::shared_ptr<const StructureData>>> pending;
  for (const Prefetch& f : prefetches_)
    if (!kept && f.scene == scene && f.key == key) pending = f.built;
  runTask("build", what, [this, scene, kind, o, key, kept, pending] {
    auto built = kept ? kept : pending ? pending->result() : buildStructureData(scene, kind, o);
    return std::function<void()>([this, built, scene, key, kept] {
      if (scene != session_->sceneShared()) return;  // built for a scene since replaced
      builtKey_ = key;
      // Kept: the last few structures of this scene (those of another scene are let go).
      keepStructure({scene, key, built});
      // Rebuilt with other settings: the same pixel is traced again through the new structure.
      const Trace* old = session_->trace();
      bool retrace = old && session_->scene() && !old->rays.empty() && old->rays[0].has_pixel;
      int px = retrace ? old->rays[0].pixel[0] : 0, py = retrace ? old->rays[0].pixel[1] : 0;
      // The selected node is kept by its path from the root (L/R): as deep as the new tree goes along it.
      std::string selectedPath;
      bool hadSelection = false;
      if (const KdTree* oldKd = session_->structure() ? session_->structure()->kdTree() : nullptr;
          oldKd && session_->selectedNode() >= 0) {
        selectedPath = kdNodePath(oldKd->data(), uint32_t(session_->selectedNode()));
        hadSelection = true;
      }
      session_->setStructure(built);
      if (const KdTree* newKd = built->kdTree(); newKd && hadSelection) {
        for (;; selectedPath.pop_back()) {
          try {
            session_->setSelectedNode(int(kd_node_by_path(newKd->data(), selectedPath)));
            break;
          } catch (const InputError&) {  // the new tree is shallower here: its deepest node on the path
            if (selectedPath.empty()) break;
          }
        }
      }
      size_t n = std::max<size_t>(1, built->scene->scene.geometry.size());
      if (const UniformGrid* grid = built->grid()) {
        auto r = grid->resolution();
        // A coarsened grid says so: the density rule's resolution would have exceeded the reference budget.
        QString coarsened;
        if (grid->coarsened()) {
          auto q = grid->requested_resolution();
          coarsened = tr(" (coarsened from %1 x %2 x %3: %4)")
                          .arg(q[0])
                          .arg(q[1])
                          .arg(q[2])
                          .arg(QString::fromUtf8(to_string(grid->coarsening())));
        }
        structure_->setInfo(tr("grid %1 x %2 x %3%4, %5 references (%6 per primitive)")
                                .arg(r[0])
                                .arg(r[1])
                                .arg(r[2])
                                .arg(coarsened)
                                .arg(grid->reference_count())
                                .arg(double(grid->reference_count()) / n, 0, 'f', 2) +
                            took(tr(", built"), built->buildMs));
      } else if (const Bvh* bvh = built->bvh()) {
        BvhStats st = bvh_stats(bvh->data(), bvh->options());
        structure_->setInfo(
            tr("%1: %2 nodes, %3 leaves, depth %4, %5 primitives per leaf (max %6), SAH cost %7, "
               "children's overlap %8 (%9)")
                .arg(QString::fromStdString(built->kind))
                .arg(st.nodes)
                .arg(st.leaves)
                .arg(st.max_depth)
                .arg(st.mean_leaf_prims, 0, 'f', 2)
                .arg(st.max_leaf_prims)
                .arg(st.sah_cost, 0, 'f', 1)
                .arg(st.overlap, 0, 'f', 3)
                .arg(st.references == n ? tr("each primitive in one leaf")
                                        : tr("%1 references, %2 per primitive")
                                              .arg(st.references)
                                              .arg(double(st.references) / double(n), 0, 'f', 3)) +
            took(tr(", built"), built->buildMs));
      } else if (const WideBvh* wide = dynamic_cast<const WideBvh*>(built->accel.get())) {
        structure_->setInfo(tr("%1: the %2 BVH collapsed into %3-wide nodes, %4 KiB")
                                .arg(QString::fromStdString(built->kind))
                                .arg(wide->options().builder == BvhBuilder::sbvh ? tr("spatial-split") : tr("binned"))
                                .arg(wide->width())
                                .arg(double(built->accel->memory_bytes()) / 1024.0, 0, 'f', 1) +
                            took(tr(", built"), built->buildMs));
      } else if (const Octree* oct = built->octree()) {
        OctreeStats st = octree_stats(oct->data());
        structure_->setInfo(tr("octree: %1 cells, %2 leaves (%3 empty), depth %4 (limit %5), %6 references "
                               "(%7 per primitive), at most %8 per leaf")
                                .arg(st.nodes)
                                .arg(st.leaves)
                                .arg(st.empty_leaves)
                                .arg(st.max_depth)
                                .arg(octree_max_depth(oct->options(), n))
                                .arg(st.references)
                                .arg(double(st.references) / n, 0, 'f', 2)
                                .arg(st.max_leaf_prims) +
                            took(tr(", built"), built->buildMs));
      } else if (const BspTree* bsp = built->bsp()) {
        BspTreeStats st = bsp_tree_stats(bsp->data(), bsp->options());
        structure_->setInfo(
            tr("BSP tree: %1 nodes, %2 leaves (%3 empty), depth %4, %5 references (%6 per primitive), SAH "
               "cost %7; planes: %8 axis, %9 face diagonal, %10 body diagonal, %11 primitive")
                .arg(st.nodes)
                .arg(st.leaves)
                .arg(st.empty_leaves)
                .arg(st.max_depth)
                .arg(st.references)
                .arg(double(st.references) / n, 0, 'f', 2)
                .arg(st.sah_cost, 0, 'f', 1)
                .arg(st.inner_by_source[0])
                .arg(st.inner_by_source[1])
                .arg(st.inner_by_source[2])
                .arg(st.inner_by_source[3]) +
            took(tr(", built"), built->buildMs));
      } else if (const KdTree* kd = built->kdTree()) {
        KdTreeStats st = kd_tree_stats(kd->data(), kd->options());
        structure_->setInfo(
            tr("%1: %2 nodes, %3 leaves (%4 empty), depth %5, %6 references (%7 per primitive), "
               "SAH cost %8")
                .arg(QString::fromStdString(built->kind))
                .arg(st.nodes)
                .arg(st.leaves)
                .arg(st.empty_leaves)
                .arg(st.max_depth)
                .arg(st.references)
                .arg(double(st.references) / n, 0, 'f', 2)
                .arg(st.sah_cost, 0, 'f', 1) +
            took(tr(", built"), built->buildMs));
      }
      if ((scripted_ || Heartbeat::enabled()) && !kept)
        std::fprintf(stderr, "timing: %s build %.1f ms\n", built->kind.c_str(), built->buildMs);
      auto* grid = built.get();
      session_->setImageSize(sizeW_ > 0 ? sizeW_ : grid->scene->scene.render.width,
                             sizeH_ > 0 ? sizeH_ : grid->scene->scene.render.height);
      if (retrace && px < session_->imageWidth() && py < session_->imageHeight()) tracePixel(px, py);
      renderPicture();
      if (imageView_->heatQuantity() != "off") computeHeat();
    });
  });
}

}  // namespace raystep::viz
