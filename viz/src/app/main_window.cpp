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
#include <QStackedWidget>
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
#include "flatland/flat_view.h"
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
  flatView_ = new FlatView(session_);
  centreStack_ = new QStackedWidget;
  centreStack_->addWidget(sceneView_);
  centreStack_->addWidget(flatView_);
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
  columns->addWidget(centreStack_);
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
  // A 2D scene: the 2D view in the middle, and its ray's walk traced as soon as the structure is built (the
  // scene's own ray, or the one dragged there before the rebuild).
  connect(session_, &Session::sceneChanged, this, [this] {
    const bool flat = session_->scene() && session_->scene()->scene.flat;
    sceneView_->setDormant(flat);
    centreStack_->setCurrentWidget(flat ? static_cast<QWidget*>(flatView_) : sceneView_);
  });
  connect(session_, &Session::structureChanged, this, [this] {
    const SceneData* scene = session_->scene();
    if (!scene || !scene->scene.flat || !session_->structure()) return;
    const TracedRay* r = session_->ray();
    const bool inPlane = r && r->ray.direction.z == 0.f;
    if (scene->scene.flat->has_ray || inPlane)
      traceFlatRay(flatView_->rayOrigin(), flatView_->rayDirection(), false);
  });
  connect(flatView_, &FlatView::nodePicked, this, [this](int node) {  // a right click in the 2D view
    showKdPanel();
    session_->setSelectedNode(node);
  });
  connect(flatView_, &FlatView::rayMoved, this, [this](QPointF o, QPointF d) {
    traceFlatRay(glm::vec2(float(o.x()), float(o.y())), glm::vec2(float(d.x()), float(d.y())), true);
  });
  connect(session_, &Session::stepChanged, this, [this] {
    if (session_->eventCount())
      statusBar()->showMessage(tr("step %1 of %2").arg(session_->step()).arg(session_->eventCount() - 1) +
                               took(tr(" drawn"), sceneView_->lastUpdateMs()));
  });
}

QImage MainWindow::grabMiddleView() const {
  if (session_->scene() && session_->scene()->scene.flat) return flatView_->grab().toImage();
  return sceneView_->grabView();
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
  file->addAction(tr("Export &figure of the 2D view (SVG, PDF, PNG)..."), this, [this] {
    if (!session_->scene() || !session_->scene()->scene.flat)
      return showError(tr("A figure draws a 2D scene (\"dimensions\": 2): open one of scenes/flatland."));
    QString path = QFileDialog::getSaveFileName(this, tr("Export figure"), "figure.svg",
                                                tr("Figures (*.svg *.pdf *.png)"));
    if (!path.isEmpty()) exportFigure(path);
  });
  file->addAction(tr("Screenshot of the &window..."), this, [this] {
    QString path = QFileDialog::getSaveFileName(this, tr("Screenshot"), "raystep.png", tr("PNG (*.png)"));
    if (!path.isEmpty() && !grab().save(path, "PNG")) showError(tr("Cannot write %1").arg(path));
  });
  file->addAction(tr("Screenshot of the &3D view..."), this, [this] {
    QString path = QFileDialog::getSaveFileName(this, tr("Screenshot"), "raystep-3d.png", tr("PNG (*.png)"));
    if (!path.isEmpty() && !grabMiddleView().save(path, "PNG"))
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
    parts.view3d = centreStack_;  // the 3D view, or the 2D view of a 2D scene
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
  flatView_->setScale(scale);
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

}  // namespace raystep::viz
