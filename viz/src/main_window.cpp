#include "main_window.h"

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

#include "aa_report_view.h"
#include "bvol_report_view.h"
#include "classroom_layout.h"
#include "compare_window.h"
#include "event_list.h"
#include "grid_sweep_view.h"
#include "heartbeat.h"
#include "image_view.h"
#include "kd_tree_model.h"
#include "lesson_pane.h"
#include "pixel_inspector.h"
#include "presenter.h"
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
#include "sah_chart.h"
#include "scene_view.h"
#include "session.h"
#include "state_panel.h"
#include "structure_panel.h"
#include "timeline.h"
#include "tree_pick.h"
#include "tree_view.h"
#include "settle.h"

namespace raystep::viz {
// A trace names its format in its first key; anything else is a scene or a mesh.
bool MainWindow::isTraceFile(const QString& path) {
  std::ifstream in(path.toStdString(), std::ios::binary);
  std::string head(4096, '\0');
  in.read(&head[0], long(head.size()));
  head.resize(size_t(in.gcount()));
  return head.find("\"raystep-trace\"") != std::string::npos;
}

MainWindow::MainWindow() : session_(new Session(this)) {
  setWindowTitle("raystep step-debugger");
  structure_ = new StructurePanel;
  imageView_ = new ImageView(session_);
  sceneView_ = new SceneView(session_);
  timeline_ = new Timeline(session_, this);
  statePanel_ = new StatePanel(session_);
  eventList_ = new EventList(session_);

  auto* left = leftSplit_ = new QSplitter(Qt::Vertical);
  left->addWidget(structure_);
  left->addWidget(imageView_);
  left->setStretchFactor(0, 0);
  left->setStretchFactor(1, 1);
  left->setSizes({200, 500});
  auto* stateScroll = new QScrollArea;
  stateScroll->setWidget(statePanel_);
  stateScroll->setWidgetResizable(true);
  auto* right = rightSplit_ = new QSplitter(Qt::Vertical);
  right->addWidget(stateScroll);
  right->addWidget(statePanel_->mailboxWidget());
  right->addWidget(eventList_);
  right->setSizes({440, 110, 180});
  auto* columns = columns_ = new QSplitter(Qt::Horizontal);
  columns->addWidget(left);
  columns->addWidget(sceneView_);
  columns->addWidget(right);
  columns->setStretchFactor(0, 0);
  columns->setStretchFactor(1, 1);
  columns->setStretchFactor(2, 0);
  columns->setSizes({340, 560, 360});

  auto* central = new QWidget;
  auto* layout = new QVBoxLayout(central);
  layout->setContentsMargins(4, 4, 4, 0);
  layout->addWidget(columns, 1);
  layout->addWidget(timeline_);
  setCentralWidget(central);

  // kd-tree: the nodes and the SAH inspector, in a dock below (shown when a kd-tree is built).
  treeView_ = new TreeView(session_);
  sahChart_ = new SahChart;
  auto* kdSplit = kdSplit_ = new QSplitter(Qt::Horizontal);
  kdSplit->addWidget(treeView_);
  kdSplit->addWidget(sahChart_);
  kdSplit->setStretchFactor(0, 0);
  kdSplit->setStretchFactor(1, 1);
  kdSplit->setSizes({440, 840});
  kdDock_ = new QDockWidget(tr("kd-tree: nodes and SAH inspector"), this);
  kdDock_->setObjectName("kdDock");
  kdDock_->setWidget(kdSplit);
  kdDock_->setFeatures(QDockWidget::DockWidgetClosable | QDockWidget::DockWidgetMovable |
                       QDockWidget::DockWidgetFloatable);
  addDockWidget(Qt::BottomDockWidgetArea, kdDock_);
  kdDock_->hide();
  // The traced pixel's samples, in a dock below (beside the kd dock when both are open).
  pixelInspector_ = new PixelInspector(session_);
  pixelDock_ = new QDockWidget(tr("Pixel inspector: the traced pixel's samples"), this);
  pixelDock_->setObjectName("pixelDock");
  pixelDock_->setWidget(pixelInspector_);
  pixelDock_->setFeatures(QDockWidget::DockWidgetClosable | QDockWidget::DockWidgetMovable |
                          QDockWidget::DockWidgetFloatable);
  addDockWidget(Qt::BottomDockWidgetArea, pixelDock_);
  pixelDock_->hide();
  connect(pixelDock_, &QDockWidget::visibilityChanged, this, [this](bool visible) {
    if (visible) drawPixelBackdrop();  // opened from the View menu too
  });
  buildMenus();
  statusBar()->showMessage(tr("Open a scene or a trace (File > Open)."));

  connect(structure_, &StructurePanel::buildRequested, this, &MainWindow::buildStructure);
  connect(structure_, &StructurePanel::buildRequested, this, [this] { compareBuilt_.clear(); });
  connect(imageView_, &ImageView::renderRequested, this, &MainWindow::renderPicture);
  connect(imageView_, &ImageView::heatRequested, this, &MainWindow::computeHeat);
  connect(imageView_, &ImageView::pixelClicked, this, [this](int x, int y) {
    try {
      tracePixel(x, y);
      // Reports > Compare...: the clicked pixel through the structures picked, while their window is open.
      if (!compareKinds_.isEmpty() && (!compare_ || compare_->viewCount() == 0 || compare_->isVisible()))
        comparePixel(compareKinds_, x, y);
      // An anti-aliased pixel opens its inspector (without anti-aliasing it stays as the user left it).
      if (const TracePixel* px = session_->pixel(); px && px->sampling.aa.mode != AntiAliasing::Mode::none)
        showPixelInspector();
    } catch (const std::exception& e) {
      showError(QString::fromStdString(e.what()));
    }
  });
  connect(structure_, &StructurePanel::kdCostsEdited, this, [this] {
    if (session_->scene() && structure_->accelName() != "grid") buildStructure();
  });
  connect(treeView_, &TreeView::nodeChosen, session_, &Session::setSelectedNode);
  connect(sceneView_, &SceneView::pointPicked, this, [this](float x, float y, float z) {
    // Any tree (kd-tree, binary BVH, octree, BSP tree): the leaf holding the picked point of the picked
    // primitive, in the tree view, the 3D view and the SAH inspector.
    const StructureData* structure = session_->structure();
    if (!structure) return;
    int leaf = leafAtPick(*structure, glm::vec3(x, y, z), sceneView_->pickedPrimitive());
    if (leaf < 0) return;
    showKdPanel();
    session_->setSelectedNode(leaf);
  });
  connect(session_, &Session::selectedNodeChanged, this, &MainWindow::showSahCurve);
  connect(session_, &Session::structureChanged, this, [this] {
    // A tree (kd-tree, BVH, octree, BSP tree) has the tree view; most have the SAH inspector too.
    const bool kd = session_->structure() && treeShapeOf(*session_->structure());
    const bool isBvh = session_->structure() && session_->structure()->bvh();
    const bool isOctree = session_->structure() && session_->structure()->octree();
    const bool isBsp = session_->structure() && session_->structure()->bsp();
    const bool isWide = session_->structure() && session_->structure()->wideBvh();
    // The octree and the wide BVH: their nodes are browsable; the SAH inspector is the kd-tree's, the binary
    // BVH's and the BSP tree's (its candidate planes by orientation).
    kdDock_->setWindowTitle(
        isBvh    ? tr("BVH: nodes and SAH inspector")
        : isWide ? tr("wide BVH: nodes, up to %1 children each (collapsed from the binary "
                      "BVH: no SAH inspector)")
                       .arg(session_->structure()->wideBvh()->width())
        : isOctree ? tr("octree: cells (no SAH inspector: centre splits)")
        : isBsp    ? tr("BSP tree: nodes and SAH inspector (candidate planes by orientation)")
                   : tr("kd-tree: nodes and SAH inspector"));
    // The dock takes a third of the height: opened by itself only where the walk's views keep their room.
    if (kd && height() >= 900)
      showKdPanel();
    else if (kd && !kdDock_->isVisible())
      statusBar()->showMessage(
          isBvh ? tr("BVH built: View > tree and SAH inspector shows its nodes and binned SAH curves")
          : isBsp
              ? tr("BSP tree built: View > tree and SAH inspector, or a click on the scene in the 3D view, "
                   "shows its nodes and their candidate planes by orientation")
          : isOctree || isWide
              ? tr("Built: View > tree, or a click on the scene in the 3D view, shows its nodes")
              : tr("kd-tree built: View > kd-tree and SAH inspector, or a click on the scene in the "
                   "3D view, shows its nodes and SAH curves"));
    else if (!kd)
      hideKdPanel();
    showSahCurve();
  });
  connect(session_, &Session::stepChanged, this, [this] {
    if (session_->eventCount())
      statusBar()->showMessage(tr("step %1 of %2").arg(session_->step()).arg(session_->eventCount() - 1) +
                               took(tr(" drawn"), sceneView_->lastUpdateMs()));
  });
}

// The presenter first, while the timeline and the shortcuts it gives back their keys to still exist.
MainWindow::~MainWindow() {
  delete presenter_;
}

void MainWindow::buildMenus() {
  QMenu* file = menuBar()->addMenu(tr("&File"));
  file->addAction(
      tr("&Open scene or trace..."), this,
      [this] {
        QString path = QFileDialog::getOpenFileName(this, tr("Open a scene, a mesh or a trace"), QString(),
                                                    tr("Scenes and traces (*.json *.obj);;All files (*)"));
        if (!path.isEmpty()) openFileReportingErrors(path);
      },
      QKeySequence::Open);
  file->addAction(tr("Open &lesson..."), this, [this] {
    QString path = QFileDialog::getOpenFileName(this, tr("Open a lesson"), "lessons",
                                                tr("Lessons (*.md);;All files (*)"));
    if (!path.isEmpty()) openLessonReportingErrors(path);
  });
  file->addAction(tr("Export &trace..."), this, [this] {
    if (!session_->trace()) return showError(tr("No trace to export: click a pixel first."));
    QString path =
        QFileDialog::getSaveFileName(this, tr("Export trace"), "trace.json", tr("Traces (*.json)"));
    if (!path.isEmpty()) exportTrace(path);
  });
  file->addAction(tr("Screenshot of the &window..."), this, [this] {
    QString path = QFileDialog::getSaveFileName(this, tr("Screenshot"), "raystep.png", tr("PNG (*.png)"));
    if (!path.isEmpty() && !grab().save(path, "PNG")) showError(tr("Cannot write %1").arg(path));
  });
  file->addAction(tr("Screenshot of the &3D view..."), this, [this] {
    QString path = QFileDialog::getSaveFileName(this, tr("Screenshot"), "raystep-3d.png", tr("PNG (*.png)"));
    if (!path.isEmpty() && !sceneView_->grabView().save(path, "PNG"))
      showError(tr("Cannot write %1").arg(path));
  });
  file->addAction(tr("Export &SAH curve (CSV)..."), this, [this] {
    if (!sahChart_->curve() && !sahChart_->bspCurve())
      return showError(tr("No SAH curve: select a kd-tree, BVH or BSP node first."));
    QString name = QString("sah-node%1.csv").arg(session_->selectedNode());
    QString path = QFileDialog::getSaveFileName(this, tr("Export SAH curve"), name, tr("CSV (*.csv)"));
    if (!path.isEmpty()) exportSahCsv(path);
  });
  file->addAction(tr("Screenshot of the SAH &chart..."), this, [this] {
    if (!sahChart_->curve() && !sahChart_->bspCurve())
      return showError(tr("No SAH curve: select a kd-tree, BVH or BSP node first."));
    QString path = QFileDialog::getSaveFileName(this, tr("Screenshot"), "raystep-sah.png", tr("PNG (*.png)"));
    if (!path.isEmpty() && !sahChart_->saveChart(path)) showError(tr("Cannot write %1").arg(path));
  });
  file->addSeparator();
  file->addAction(tr("&Quit"), this, &QWidget::close, QKeySequence::Quit);
  QMenu* view = menuBar()->addMenu(tr("&View"));
  QAction* dock = kdDock_->toggleViewAction();
  dock->setText(tr("kd-tree and SAH &inspector"));
  view->addAction(dock);
  QAction* pixel = pixelDock_->toggleViewAction();
  pixel->setText(tr("&Pixel inspector (the traced pixel's samples)"));
  view->addAction(pixel);
  view->addSeparator();
  QAction* full = view->addAction(tr("&Full screen"), this, [this] {
    if (isFullScreen())
      showNormal();
    else
      showFullScreen();
  });
  full->setShortcut(QKeySequence(Qt::Key_F5));
  full->setShortcutContext(Qt::WindowShortcut);
  full->setObjectName("fullScreenAction");
  addAction(full);  // works with the menu bar hidden too
  QMenu* scale = view->addMenu(tr("Presenter &scale"));
  for (double s : {1.0, 1.25, 1.5, 2.0})
    scale->addAction(s == 1.0   ? tr("1 (desk)")
                     : s == 1.5 ? tr("1.5 (lecture room)")
                                : QString::number(s),
                     this, [this, s] { setPresenterScale(s); });
  // The instructor's laptop shows the narration, the projector the debugger.
  QAction* narration = view->addAction(tr("&Narration in its own window"));
  narration->setCheckable(true);
  narration->setObjectName("narrationWindowAction");
  connect(narration, &QAction::toggled, this, [this](bool on) {
    if (classroom_) classroom_->setNarrationWindow(on);
  });
  // The reports on the current scene: opened (and run, the first time) in windows of their own.
  QMenu* reports = menuBar()->addMenu(tr("&Reports"));
  reports->addAction(tr("&Anti-aliasing: error against rays..."), this, [this] {
    AaReportView* v = aaReportView();
    v->show();
    v->raise();
    if (v->state() == "idle" && session_->structure()) v->start();
  });
  reports->addAction(tr("&Compare structures on one ray (side by side)..."), this, [this] {
    const QStringList kinds = pickCompareStructures(
        this, compareKinds_.isEmpty() ? QStringList{"grid", "kd", "bvh"} : compareKinds_);
    if (!kinds.isEmpty()) setCompareStructures(kinds);
  });
  reports->addAction(tr("&Grid sweep: density d against cost..."), this, [this] {
    GridSweepView* v = gridSweepView();
    v->show();
    v->raise();
    if (v->state() == "idle" && session_->scene()) v->start();
  });
  reports->addAction(tr("&Bounding volumes: kinds against false positives..."), this, [this] {
    BvolReportView* v = bvolReportView();
    v->show();
    v->raise();
    if (v->state() == "idle" && session_->scene()) v->start();
  });
}

AaReportView* MainWindow::aaReportView() {
  if (!aaReport_) aaReport_ = new AaReportView(session_, this);
  return aaReport_;
}

BvolReportView* MainWindow::bvolReportView() {
  if (!bvolReport_) bvolReport_ = new BvolReportView(session_, this);
  return bvolReport_;
}

GridSweepView* MainWindow::gridSweepView() {
  if (!gridSweep_) {
    gridSweep_ = new GridSweepView(session_, this);
    connect(gridSweep_, &GridSweepView::densityChosen, this, &MainWindow::buildGridAtDensity);
  }
  return gridSweep_;
}

void MainWindow::buildGridAtDensity(float density) {
  if (!session_->scene()) return;
  StructureOptions o = structure_->options();
  o.grid.density = density;
  o.grid.resolution.reset();  // the density rule, not an explicit resolution
  structure_->setStructure("grid", o);
  buildStructure();
}

Presenter* MainWindow::openLesson(const Lesson& lesson) {
  if (!lessonDock_) {
    lessonPane_ = new LessonPane;
    lessonDock_ = new QDockWidget(tr("Lesson"), this);
    lessonDock_->setObjectName("lessonDock");
    lessonDock_->setWidget(lessonPane_);
    lessonDock_->setFeatures(QDockWidget::DockWidgetMovable | QDockWidget::DockWidgetFloatable);
    // On the right, full height: the debugger's columns and the kd dock below them keep their places.
    setCorner(Qt::TopRightCorner, Qt::RightDockWidgetArea);
    setCorner(Qt::BottomRightCorner, Qt::RightDockWidgetArea);
    addDockWidget(Qt::RightDockWidgetArea, lessonDock_);
    ClassroomParts parts;
    parts.picture = leftSplit_;
    parts.structure = structure_;
    parts.view3d = sceneView_;
    parts.state = rightSplit_;
    parts.columns = columns_;
    parts.treeDock = kdDock_;
    parts.treeSplit = kdSplit_;
    parts.pixelDock = pixelDock_;
    parts.lessonDock = lessonDock_;
    classroom_ = std::make_unique<ClassroomLayout>(*this, parts);
  }
  delete presenter_;
  presenter_ = new Presenter(*this, lessonPane_, lesson);
  lessonDock_->show();
  lessonPane_->setScale(scale_);
  setWindowTitle(tr("raystep - lesson: %1").arg(QString::fromStdString(lesson.title)));
  if (scale_ == 1.0)
    statusBar()->showMessage(
        tr("Presenting to a room? View > Presenter scale 1.5 (or --scale 1.5) is readable from "
           "the back; F5: full screen."));
  return presenter_;
}

void MainWindow::arrangeForStep(const LessonState& step) {
  if (!classroom_ || scale_ <= 1.0) return;
  // The mailbox table when the current event is a primitive's test (the table lists the ray's tests).
  bool tested = false;
  if (const TracedRay* r = session_->ray(); r && session_->step() >= 0 && session_->step() < int(r->events.size())) {
    const EventType t = r->events[size_t(session_->step())].type;
    tested = t == EventType::prim_test || t == EventType::mailbox_hit || t == EventType::hit_deferred;
  }
  classroom_->arrange(lesson_figure(step), session_->ray() != nullptr, tested, !step.panel.empty() && step.panel != "none");
}

void MainWindow::fitLessonPane() {
  if (!lessonDock_) return;
  if (scale_ > 1.0) return;  // the classroom layout keeps the window within the screen
  // The pane's width comes on top of the debugger's: the central widget keeps the width the window had. The
  // pane is held at its width while the window grows (else the central widget would take the growth).
  // Where the screen has no room for both, the window stays within it and the pane takes its width from the
  // debugger (a projector's 1920 x 1080 full screen).
  const int pane = int((scale_ > 1.0 ? 380 : 440) * scale_);
  const int separator = style()->pixelMetric(QStyle::PM_DockWidgetSeparatorExtent);
  const QScreen* screen = QApplication::primaryScreen();
  const int room = screen ? screen->availableGeometry().width() : 1 << 20;
  const int debuggerWidth = std::min(width(), room - pane - separator);
  lessonPane_->setFixedWidth(pane);
  resize(debuggerWidth + pane + separator, height());
  settleWindowSystem();  // the X server confirms the size asynchronously
}

void MainWindow::releaseLessonPaneWidth() {
  if (!lessonPane_ || scale_ > 1.0) return;
  lessonPane_->setMinimumWidth(200);
  lessonPane_->setMaximumWidth(QWIDGETSIZE_MAX);
}

void MainWindow::openLessonReportingErrors(const QString& path) {
  try {
    // All of it checked before anything changes; its numbers computed and written in (lesson_numbers.h).
    Lesson lesson = lesson_with_numbers(parse_lesson(path.toStdString()));
    bool hadPane = lessonDock_ && lessonDock_->isVisible();
    Presenter* p = openLesson(lesson);
    if (!hadPane) fitLessonPane();
    p->goToReportingErrors(0);
  } catch (const std::exception& e) {
    showError(QString::fromStdString(e.what()));
  }
}

void MainWindow::setPresenterScale(double scale) {
  QFont f = QApplication::font();
  if (baseFontPt_ <= 0) baseFontPt_ = f.pointSize() > 0 ? f.pointSize() : 9;
  scale_ = scale;
  f.setPointSizeF(baseFontPt_ * scale);
  QApplication::setFont(f);
  sceneView_->setScale(scale);
  sahChart_->setScale(scale);
  eventList_->setScale(scale);
  statePanel_->setScale(scale);
  structure_->setCompact(scale > 1.0);
  timeline_->setCompact(scale > 1.0);
  imageView_->setCompact(scale > 1.0);
  if (scale > 1.0)
    leftSplit_->setSizes({structure_->sizeHint().height(), 10000});  // the picture takes the rest
  if (lessonPane_) lessonPane_->setScale(scale);
  if (presenter_ && presenter_->current() >= 0) {
    if (scale > 1.0)
      arrangeForStep(presenter_->lesson().steps[size_t(presenter_->current())].state);
    else if (classroom_)
      classroom_->release();
  }
}

void MainWindow::showKdPanel() {
  if (kdDock_->isVisible()) return;
  kdDock_->show();
  resizeDocks({kdDock_}, {int(250 * scale_)}, Qt::Vertical);
  // Below 900 pixels the dock leaves the state column too little room for the node, t* and the stack: the
  // mailbox table (the event list says the same per test) gives its room up while the dock is open.
  if (height() < 900) rightSplit_->setSizes({1000, 0, int(110 * scale_)});
}

void MainWindow::hideKdPanel() {
  if (!kdDock_->isVisible()) return;
  kdDock_->hide();
  rightSplit_->setSizes({440, 110, 180});
}

bool MainWindow::kdPanelVisible() const {
  return kdDock_->isVisible();
}

QString MainWindow::pictureKeyNow() const {
  return QString("%1 %2x%3 %4")
      .arg(quintptr(session_->structure()))
      .arg(session_->imageWidth())
      .arg(session_->imageHeight())
      .arg(imageView_->antiAliasing());
}

QString MainWindow::heatKeyNow() const {
  // The samples and error maps depend on the anti-aliasing too; the traversal counts do not.
  const QString q = imageView_->heatQuantity();
  return QString("%1 %2x%3 %4 %5")
      .arg(quintptr(session_->structure()))
      .arg(session_->imageWidth())
      .arg(session_->imageHeight())
      .arg(q)
      .arg(q == "samples" || q == "error" ? imageView_->antiAliasing() : QString());
}

void MainWindow::ensurePicture() {
  if (session_->structure() && pictureKey_ != pictureKeyNow()) renderPicture();
}

void MainWindow::ensureHeat() {
  if (heatKey_ != heatKeyNow()) computeHeat();
}

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
               "children's overlap %8 (each primitive in one leaf)")
                .arg(QString::fromStdString(built->kind))
                .arg(st.nodes)
                .arg(st.leaves)
                .arg(st.max_depth)
                .arg(st.mean_leaf_prims, 0, 'f', 2)
                .arg(st.max_leaf_prims)
                .arg(st.sah_cost, 0, 'f', 1)
                .arg(st.overlap, 0, 'f', 3) +
            took(tr(", built"), built->buildMs));
      } else if (built->kind == "bvh4" || built->kind == "bvh8") {
        structure_->setInfo(tr("%1: the binned BVH collapsed into %2-wide nodes, %3 KiB")
                                .arg(QString::fromStdString(built->kind))
                                .arg(built->kind == "bvh4" ? 4 : 8)
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

void MainWindow::renderPicture() {
  auto grid = session_->structureShared();
  if (!grid) return;
  std::string aa = imageView_->antiAliasing().toStdString();
  int w = session_->imageWidth(), h = session_->imageHeight();
  QString key = pictureKeyNow();
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
