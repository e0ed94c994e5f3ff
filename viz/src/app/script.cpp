#include "app/script.h"

#include <array>
#include <chrono>
#include <climits>
#include <cmath>
#include <cstdio>
#include <regex>

#include <QApplication>
#include <QCommandLineParser>
#include <QDir>
#include <QDoubleSpinBox>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QMouseEvent>
#include <QOpenGLWidget>
#include <QScreen>
#include <QSlider>
#include <QTest>
#include <QThread>
#include <QTreeView>
#include <map>

#include "compare/compare_window.h"
#include "views/event_list.h"
#include "flatland/flat_view.h"
#include "lesson/handout.h"
#include "views/image_view.h"
#include "views/kd_tree_model.h"
#include "lesson/lesson_enter.h"
#include "lesson/classroom_layout.h"
#include "app/main_window.h"
#include "inspect/pixel_inspector.h"
#include "lesson/presenter.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/heatmap.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/util/error.h"
#include "raystep/replay/side_by_side.h"
#include "reports/report_script.h"
#include "inspect/sah_chart.h"
#include "views/scene_view.h"
#include "app/session.h"
#include "views/state_panel.h"
#include "views/structure_panel.h"
#include "views/timeline.h"
#include "views/tree_view.h"
#include "app/settle.h"

namespace raystep::viz {
namespace {

[[noreturn]] void fail(const std::string& what) {
  throw InputError("", 0, what);
}

std::vector<int> parseInts(const QString& option, const QString& spec, int n, int lo) {
  QStringList parts = spec.split(',');
  std::vector<int> out;
  for (const QString& p : parts) {
    bool ok = false;
    int v = p.toInt(&ok);
    if (!ok || v < lo) break;
    out.push_back(v);
  }
  if (int(out.size()) != n || parts.size() != n)
    fail("--" + option.toStdString() + " '" + spec.toStdString() + "': expected " + std::to_string(n) +
         " comma-separated whole numbers >= " + std::to_string(lo));
  return out;
}

void parseSize(const QString& option, const QString& spec, int* w, int* h) {
  static const std::regex re("([0-9]{1,5})x([0-9]{1,5})");
  std::smatch m;
  std::string s = spec.toStdString();
  if (std::regex_match(s, m, re)) {
    *w = std::stoi(m[1]);
    *h = std::stoi(m[2]);
    if (*w >= 1 && *h >= 1 && *w <= 16384 && *h <= 16384) return;
  }
  fail("--" + option.toStdString() + " '" + s + "': expected WxH with 1 <= W, H <= 16384");
}

void settle(MainWindow& w) {
  settleWindowSystem();
  w.sceneView()->renderNow();
  QApplication::processEvents();
}

void writeJson(const QString& path, const QJsonObject& o) {
  QFile f(path);
  if (!f.open(QIODevice::WriteOnly | QIODevice::Truncate)) fail("cannot write " + path.toStdString());
  f.write(QJsonDocument(o).toJson(QJsonDocument::Indented));
}

QJsonObject dumpState(MainWindow& w) {
  Session* s = w.session();
  QJsonObject o;
  o["ray"] = s->rayIndex();
  o["step"] = s->step();
  o["events"] = s->eventCount();
  o["event_type"] = s->state().event ? event_type_name(s->state().event->type) : "";
  o["event_list_row"] = w.eventList()->currentRow();
  o["panels"] = w.statePanel()->dumpState();
  o["structure_info"] = w.structurePanel()->info();
  o["view"] = w.sceneView()->dumpState();
  o["flat"] = w.flatView()->dumpState();
  o["sah"] = w.sahChart()->dumpState();
  o["selected_node"] = s->selectedNode();
  if (std::unique_ptr<TreeShape> shape = s->structure() ? treeShapeOf(*s->structure()) : nullptr) {
    QJsonObject tree{{"nodes", int(shape->size())},
                     {"rows_made", w.treeView()->expandedCount()},
                     {"structure", shape->name()}};
    QModelIndex cur = w.treeView()->view()->currentIndex();
    tree["current_row_node"] = KdTreeModel::nodeOf(cur);
    if (s->selectedNode() >= 0) {
      tree["selected_path"] = QString::fromStdString(shape->path(uint32_t(s->selectedNode())));
      tree["selected_what"] = shape->what(uint32_t(s->selectedNode()));
    }
    tree["root_what"] = w.treeView()->view()->model()->index(0, KdTreeModel::WhatColumn).data().toString();
    // The current row's children as the tree view lists them (a wide BVH node: up to 8), and the headers.
    const QAbstractItemModel* model = w.treeView()->view()->model();
    QJsonArray children;
    for (int r = 0; cur.isValid() && r < model->rowCount(cur.siblingAtColumn(0)); ++r) {
      QModelIndex c = model->index(r, 0, cur.siblingAtColumn(0));
      children.append(QJsonObject{{"node", KdTreeModel::nodeOf(c)},
                                  {"side", c.data().toString()},
                                  {"what", c.siblingAtColumn(KdTreeModel::WhatColumn).data().toString()},
                                  {"last", c.siblingAtColumn(KdTreeModel::CostColumn).data().toString()},
                                  {"tooltip", c.data(Qt::ToolTipRole).toString()}});
    }
    tree["current_children"] = children;
    tree["headers"] = QJsonArray{model->headerData(KdTreeModel::WhatColumn, Qt::Horizontal).toString(),
                                 model->headerData(KdTreeModel::CostColumn, Qt::Horizontal).toString()};
    o["tree"] = tree;
  }
  o["window"] = QJsonArray{w.width(), w.height()};
  if (w.classroom() && w.classroom()->active()) o["classroom"] = w.classroom()->dumpState();
  // The picture's zoom and the pixel the view is centred on. A centred pixel puts the canvas's middle near
  // its own middle (x + 0.5), a fitted picture near a pixel corner; a canvas one screen pixel taller moves it
  // by half a screen pixel. A quarter pixel's nudge keeps both away from the edges of the pixel squares.
  const ImageCanvas* canvas = w.imageView()->canvas();
  const QPointF c = canvas->centre();
  o["image"] = QJsonObject{{"zoom", canvas->zoomSetting()},
                           {"centre_pixel", QJsonArray{int(std::floor(c.x() + 0.25)), int(std::floor(c.y() + 0.25))}}};
  o["full_screen"] = w.isFullScreen();
  o["scale"] = w.presenterScale();
  o["kd_panel"] = w.kdPanelVisible();
  QJsonObject inspector = w.pixelInspector()->dumpState();
  inspector["visible"] = w.pixelInspectorVisible();
  o["inspector"] = inspector;
  o["sample_overlay"] =
      QJsonObject{{"on", w.imageView()->sampleOverlay()}, {"pixels_drawn", canvas->overlayPixelsDrawn()}};
  o["heat"] = QJsonObject{{"quantity", w.imageView()->heatQuantity()},
                          {"error_available", w.imageView()->errorHeatAvailable()},
                          {"error_why_not", w.imageView()->errorHeatWhyNot()},
                          {"error_item_enabled", w.imageView()->errorItemEnabled()},
                          {"error_item_tooltip", w.imageView()->errorItemToolTip()},
                          {"max", s->heat() ? double(s->heat()->max_value) : 0.0},
                          {"unit", s->heat() ? s->heat()->unit : 0.0}};
  if (const TracedRay* r = s->ray()) {
    o["ray_origin"] = QJsonArray{double(r->ray.origin.x), double(r->ray.origin.y), double(r->ray.origin.z)};
    o["ray_dir"] =
        QJsonArray{double(r->ray.direction.x), double(r->ray.direction.y), double(r->ray.direction.z)};
    o["ray_sample"] = r->sample;
    o["ray_kind"] = ray_kind_name(r->kind);
  }
  if (const Trace* t = s->trace()) o["trace_rays"] = int(t->rays.size());
  o["last_error"] = w.lastError();
  if (w.presenter()) o["lesson"] = w.presenter()->dumpState();
  if (CompareWindow* cw = w.compareWindowIfMade(); cw && cw->isVisible()) o["compare"] = cw->dumpState();
  addReportState(w, o);
  return o;
}

void defineOptions(QCommandLineParser& p) {
  p.setApplicationDescription("raystep-gui: step through one ray's walk through an acceleration structure.");
  p.addHelpOption();
  p.addPositionalArgument("file", "A scene (.json), a mesh (.obj) or a trace written by `raystep trace`.");
  auto opt = [&](const QString& name, const QString& help, const QString& value = QString()) {
    p.addOption(QCommandLineOption(name, help, value));
  };
  opt("accel",
      "Acceleration structure: grid, kd (SAH), kd-median, bvh (binned SAH), bvh-sweep, bvh-median, bvh4, "
      "bvh8, octree or bsp (the general BSP tree).",
      "NAME");
  opt("ti", "kd, BVH and BSP: t_i, the cost of a ray-primitive test (default 80).", "T");
  opt("tt", "kd, BVH and BSP: t_t, the cost of a traversal step (default 1).", "T");
  opt("empty-bonus", "kd: bonus in [0,1) for splits that cut off empty space (default 0).", "B");
  opt("max-depth",
      "kd: depth limit (0: max(8, 1.2 log2 N); with an empty bonus 8 + 1.3 log2 N); BVH: depth limit (0: "
      "64); BSP as kd; octree 0..20 (0: automatic).",
      "D");
  opt("leaf-size", "kd: a node with at most this many primitives is a leaf (default 1).", "N");
  opt("mailbox", "kd: mailboxes on | off (default on).", "MODE");
  opt("bins", "BVH (binned SAH): bins per axis, 2..256 (default 16).", "N");
  opt("bvh-leaf", "BVH: a node with at most this many primitives is a leaf (default 1).", "N");
  opt("bvh-max-leaf", "BVH: a node with more primitives is always split when it can be (default 16).", "N");
  opt("bvh-order", "Binary BVH: the nearer child by entry (t_near) or by axis (the direction's sign).",
      "ORDER");
  opt("octree-leaf", "Octree: a cell with at most K primitives is a leaf (default 8).", "K");
  opt("bsp-directions",
      "BSP tree: candidate plane normals: both (the 13 k-DOP directions and the primitives' own planes), "
      "kdop or autopartition (default both).",
      "SET");
  opt("bsp-candidates", "BSP tree: candidate positions per direction, 1..4096 (default 16).", "N");
  opt("grid-res", "Explicit grid resolution.", "NX,NY,NZ");
  opt("grid-density", "Grid density d: max(nx,ny,nz) = d*cbrt(n).", "D");
  opt("grid-insert", "Grid insertion: exact or bbox.", "MODE");
  opt("aa", "Anti-aliasing of the picture: none|regular:K|jitter:K|random:N|adaptive:T[:D], +tent for the tent filter.", "SPEC");
  opt("heat",
      "Heat map overlay: cells (cells or nodes visited), tests, mailbox, boxes (BVH: bounding-box tests), "
      "samples (the anti-aliasing's rays per pixel) or error (against the exact reference, where the scene "
      "has one).",
      "Q");
  opt("size", "Picture size (default: the scene's); --pixel refers to it.", "WxH");
  opt("pixel", "Trace this pixel's rays.", "X,Y");
  opt("secondary", "Trace the pixel's secondary rays too.");
  opt("ray", "Show this ray of the trace (0: the primary).", "I");
  opt("sample", "An anti-aliased pixel: replay sample N's ray (its primary ray; 0-based).", "N");
  opt("inspect", "Open the pixel inspector (the traced pixel's samples, average, exact value and error).");
  opt("square", "Adaptive sampling: step the pixel inspector to square N of the subdivision (0: the pixel).",
      "N");
  opt("sample-overlay", "Draw each visible pixel's sample positions on the picture (at zoom 8 and more).");
  opt("click-sample", "Then click sample N on the pixel inspector's canvas, as a user would.", "N");
  opt("step", "Go to event N.", "N");
  opt("step-to",
      "Go to the K-th event of a kind (cell, prim_test, mailbox_hit, hit_deferred, hit_accepted or hit, "
      "ray_end, node, push, pop, leaf).",
      "KIND:K");
  opt("forward", "Then step forward N times.", "N");
  opt("back", "Then step back N times.", "N");
  opt("keys",
      "Then press these keys, comma-separated: Right, Left, Space, Home, End, PageDown, PageUp, F5, "
      "Shift+Right, Shift+Left, Period, Comma, Ctrl+Right, Ctrl+Left, Ctrl+Home, Ctrl+End (in a lesson "
      "Right/Left/PageDown/PageUp/Home/End move between steps and Shift+Right/Left or . and , step the "
      "events; "
      "Ctrl with the arrows, Home and End steps adaptive sampling's squares in the pixel inspector).",
      "LIST");
  opt("zoom", "Image zoom: screen pixels per picture pixel, centred on the traced pixel (0: fit, the whole picture).", "Z");
  opt("translucent", "Draw the scene translucent.");
  opt("build-planes",
      "kd-tree: the build so far in the 3D view, the split planes of every node made before the selected one "
      "(the builder's depth-first order is the node ids').");
  opt("follow", "Let the 3D camera follow the current cell.");
  opt("window", "Window size (default 1280x800).", "WxH");
  opt("panel",
      "Show a panel: sah (the kd-tree's nodes and the SAH inspector; the root unless --node), or kd (the "
      "same with no node selected).",
      "NAME");
  opt("node", "Select a tree's node ID (kd-tree, BVH, octree, BSP tree): tree view, 3D view, SAH inspector.",
      "ID");
  opt("node-path",
      "A tree: select the node at this path from the root: kd-tree and BSP tree L below, R above (e.g. LRL); "
      "binary BVH L first child, R second; octree one octant digit 0..7 per level (e.g. 03).",
      "PATH");
  opt("pick-3d",
      "Click the 3D view at window pixel X,Y (selects the tree's leaf holding the picked point: kd-tree, "
      "BVH, octree or BSP tree).",
      "X,Y");
  opt("sah-orientation",
      "BSP tree: the SAH inspector's candidate planes by orientation: all, axes, face, body, own, or one "
      "direction (x, y, z, x+y, x-y, x+z, x-z, y+z, y-z, x+y+z, x+y-z, x-y+z, -x+y+z).",
      "NAME");
  opt("edit-ti", "Then type t_i into the structure panel, as a user would (the kd-tree is rebuilt).", "T");
  opt("export-sah", "Write the selected node's SAH curve as CSV (the columns of `raystep sah`).", "FILE");
  opt("screenshot-sah", "Write a PNG of the SAH chart.", "FILE");
  opt("open-bad", "After the set-up, open FILE through the GUI path (errors go to a dialog).", "FILE");
  opt("export-trace", "Write the current trace (the JSON of `raystep trace`).", "FILE");
  opt("screenshot", "Write a PNG of the window.", "FILE");
  opt("screenshot-3d", "Write a PNG of the 3D view.", "FILE");
  opt("dump-state", "Write what the panels and the 3D view show (JSON).", "FILE");
  opt("narration-window",
      "lesson: the narration (the lesson pane) in a window of its own, on the second screen when there is "
      "one (the instructor's laptop); the projector keeps the debugger.");
  opt("scale", "Presenter scale for fonts, line widths and markers (default 1; a lecture room wants 1.5).",
      "S");
  opt("lesson", "Present a lesson (lessons/*.md): the lesson pane beside the debugger.", "FILE");
  opt("lesson-step", "lesson: enter step N (1-based).", "N");
  opt("lesson-walk", "lesson: enter these steps in this order, e.g. 1,2,3 or 5,4,3,2,1.", "LIST");
  opt("dump-state-dir",
      "lesson: after each step of --lesson-walk write DIR/step-N.json (as --dump-state) and "
      "DIR/step-N.png (as --screenshot-3d).",
      "DIR");
  opt("export-handout", "lesson: write each step's figure and an index.html a student can read alone.",
      "DIR");
  opt("predict", "lesson: type this prediction into the step's question and reveal the answer.", "ANSWER");
  opt("predict-next",
      "lesson: Predict mode: for each of these predictions (;-separated: i,j,k or a node id, or "
      "stop), predict the next cell or node, then step there.",
      "LIST");
  opt("open-lesson-bad", "After the set-up, open a lesson through the GUI path (errors go to a dialog).",
      "FILE");
  opt("compare",
      "The same ray side by side: with a scene and --pixel X,Y, the walks of 2 to 4 structures (e.g. "
      "grid,kd,bvh) "
      "in one window, with one camera, one timeline over t, their counters and their cost against t.",
      "LIST");
  opt("trace",
      "Open a trace written by `raystep trace` (a version 5 trace of several structures opens side by side).",
      "FILE");
  opt("compare-pick",
      "Then pick these structures in Reports > Compare... (the traced pixel, if any, opens side by side).",
      "LIST");
  opt("click-pixel", "Then click pixel X,Y of the picture, as a user would.", "X,Y");
  opt("drag-view",
      "Side by side: drag the mouse across view I by DX,DY pixels from its centre, as a user turns the "
      "camera.",
      "I:DX,DY");
  opt("at-t", "Side by side: move the timeline to the ray parameter t.", "T");
  opt("slider", "Side by side: move the timeline's slider to position N (0 .. 1000), as a user drags it.",
      "N");
  defineReportOptions(p);
  opt("flat-ray",
      "A 2D scene: trace the ray in the plane from OX,OY along DX,DY (the 2D view's ray; the step is kept).",
      "OX,OY,DX,DY");
  opt("drag-flat",
      "A 2D scene: drag the mouse in the 2D view from FROMX,FROMY to TOX,TOY (scene units), as a user drags "
      "the ray: from the ray's origin it moves the origin, from anywhere else it aims the ray.",
      "FROMX,FROMY,TOX,TOY");
  opt("export-figure", "A 2D scene: write the 2D view's figure at the step (.svg, .pdf or .png).", "FILE");
  opt("right-click-flat",
      "A 2D scene: right-click the 2D view at X,Y (scene units): selects the leaf there (again: its parent), "
      "for the SAH inspector.",
      "X,Y");
  opt("flat-aa",
      "A 2D scene: the 2D view shows the picture's pixels over the scene (sampled with --aa, the exact "
      "coverage, the error per pixel) instead of the walk.");
  opt("crofton-lines",
      "A 2D scene: throw Crofton's random lines at the selected node (the share meeting each child against "
      "its perimeter ratio).");
  opt("quit", "Quit when done (scripted mode).");
}

}  // namespace

bool printHelpIfAsked(const QStringList& arguments) {
  QCommandLineParser p;
  defineOptions(p);
  p.parse(arguments);
  if (!p.isSet("help")) return false;
  std::printf("%s", p.helpText().toLocal8Bit().constData());
  return true;
}

namespace {

// The debugger state the options name, in the lessons' vocabulary: each option that is a lesson key is
// applied as that key (core's apply_setting: one set of values and messages), in the documented order.
LessonState stateFromOptions(const QCommandLineParser& p) {
  LessonState st;
  QStringList files = p.positionalArguments();
  if (files.size() > 1) fail("give one scene or trace file");
  // The file as given: a scene, a mesh or a trace; opening it says what is wrong with it.
  if (!files.isEmpty()) st.scene = files[0].toStdString();
  if (p.isSet("trace")) {
    if (!files.isEmpty()) fail("give --trace FILE or a file, not both");
    st.scene = p.value("trace").toStdString();
  }
  if (p.isSet("step") && p.isSet("step-to")) fail("give --step or --step-to, not both");
  if (p.isSet("node") && p.isSet("node-path")) fail("give --node or --node-path, not both");
  static const QStringList flags = {"secondary", "follow",         "translucent", "build-planes",
                                    "inspect",   "sample-overlay", "crofton-lines", "flat-aa"};
  for (const std::string& key : lesson_setting_keys()) {
    const QString name = QString::fromStdString(key);
    // --report: the report options' own (report_script.cpp), run and waited for after the state is entered.
    if (key == "scene" || key == "show" || key == "report" || !p.isSet(name)) continue;
    const std::string value = flags.contains(name) ? std::string("on") : p.value(name).toStdString();
    if (key == "node") {  // any whole number: the tree's size decides (the message names its range)
      bool ok = false;
      qlonglong id = p.value(name).toLongLong(&ok);
      if (ok && id >= INT_MIN && id <= INT_MAX) {
        st.node = NodeSpec{NodeSpec::By::id, int(id), ""};
        continue;
      }
    }
    try {
      apply_setting(st, key, value, "");
    } catch (const InputError& e) {
      fail("--" + e.detail());  // "--pixel '1': expected ...": the option as the user typed it
    }
  }
  return st;
}

// The keys --keys can press, through Qt's key handling (shortcuts included), as from the keyboard.
const std::map<QString, std::pair<Qt::Key, Qt::KeyboardModifiers>>& namedKeys() {
  static const std::map<QString, std::pair<Qt::Key, Qt::KeyboardModifiers>> keys = {
      {"Right", {Qt::Key_Right, Qt::NoModifier}},
      {"Left", {Qt::Key_Left, Qt::NoModifier}},
      {"Space", {Qt::Key_Space, Qt::NoModifier}},
      {"Home", {Qt::Key_Home, Qt::NoModifier}},
      {"End", {Qt::Key_End, Qt::NoModifier}},
      {"PageDown", {Qt::Key_PageDown, Qt::NoModifier}},
      {"PageUp", {Qt::Key_PageUp, Qt::NoModifier}},
      {"F5", {Qt::Key_F5, Qt::NoModifier}},
      {"Shift+Right", {Qt::Key_Right, Qt::ShiftModifier}},
      {"Shift+Left", {Qt::Key_Left, Qt::ShiftModifier}},
      {"Period", {Qt::Key_Period, Qt::NoModifier}},
      {"Comma", {Qt::Key_Comma, Qt::NoModifier}},
      {"Ctrl+Right", {Qt::Key_Right, Qt::ControlModifier}},
      {"Ctrl+Left", {Qt::Key_Left, Qt::ControlModifier}},
      {"Ctrl+Home", {Qt::Key_Home, Qt::ControlModifier}},
      {"Ctrl+End", {Qt::Key_End, Qt::ControlModifier}}};
  return keys;
}

void pressKeys(MainWindow& window, const QString& list) {
  // Window shortcuts fire only in the active window; without a window manager nobody activates it.
  QApplication::setActiveWindow(&window);
  window.activateWindow();
  QApplication::processEvents();
  for (const QString& k : list.split(',')) {
    auto it = namedKeys().find(k.trimmed());
    if (it == namedKeys().end()) {
      QStringList names;
      for (const auto& [name, key] : namedKeys()) names << name;
      fail("--keys: unknown key '" + k.toStdString() + "' (" + names.join(", ").toStdString() + ")");
    }
    QTest::keyClick(&window, it->second.first, it->second.second);
    QApplication::processEvents();
  }
  window.timeline()->setPlaying(false);  // a Space may have started playback: stop where it is
}

// What the scripted mode writes at the end: the trace, screenshots, the SAH curve, the state dump.
void writeOutputs(MainWindow& window, const QCommandLineParser& p) {
  Session* s = window.session();
  if (p.isSet("export-trace")) {
    if (!s->trace()) fail("--export-trace: no trace (give --pixel)");
    window.exportTrace(p.value("export-trace"));
  }
  if (p.isSet("export-figure")) window.exportFigure(p.value("export-figure"));
  if (p.isSet("screenshot") && !window.grab().save(p.value("screenshot"), "PNG"))
    fail("cannot write " + p.value("screenshot").toStdString());
  if (p.isSet("screenshot-3d") && !window.grabMiddleView().save(p.value("screenshot-3d"), "PNG"))
    fail("cannot write " + p.value("screenshot-3d").toStdString());
  if (p.isSet("screenshot-sah") && !window.sahChart()->saveChart(p.value("screenshot-sah")))
    fail("cannot write " + p.value("screenshot-sah").toStdString());
  if (p.isSet("export-sah")) {
    if (!window.sahChart()->curve() && !window.sahChart()->bspCurve())
      fail("--export-sah: no SAH curve (give --node, --node-path or --panel sah)");
    window.exportSahCsv(p.value("export-sah"));
  }
  writeReportOutputs(window, p);
  if (p.isSet("dump-state")) writeJson(p.value("dump-state"), dumpState(window));
}

// The scripted-only actions after the state: steps, keys, a click in the 3D view, an edit, a bad file.
// "A,B,C,D": four finite numbers.
std::array<float, 4> parseFour(const QString& option, const QString& spec, const char* expected) {
  const QStringList parts = spec.split(',');
  std::array<float, 4> v{};
  bool ok = parts.size() == 4;
  for (int i = 0; ok && i < 4; ++i) {
    const double x = parts[i].trimmed().toDouble(&ok);
    ok = ok && std::isfinite(x) && std::fabs(x) < 1e30;
    v[size_t(i)] = float(x);
  }
  if (!ok) fail("--" + option.toStdString() + " '" + spec.toStdString() + "': expected " + expected);
  return v;
}

// A 2D scene: the ray in the plane given, or dragged in the 2D view with the mouse as a user would.
void moveFlatRay(MainWindow& window, const QCommandLineParser& p) {
  const SceneData* scene = window.session()->scene();
  for (const char* name : {"flat-ray", "drag-flat", "right-click-flat", "crofton-lines", "flat-aa"})
    if (p.isSet(name) && (!scene || !scene->scene.flat))
      fail(std::string("--") + name + ": for a 2D scene (\"dimensions\": 2); this scene is 3D");
  if (p.isSet("flat-ray")) {
    const auto v = parseFour("flat-ray", p.value("flat-ray"), "OX,OY,DX,DY (a direction other than 0,0)");
    if (v[2] == 0.f && v[3] == 0.f) fail("--flat-ray: the direction is (0, 0)");
    window.traceFlatRay({v[0], v[1]}, {v[2], v[3]}, true);
  }
  if (p.isSet("right-click-flat")) {  // a right click in the 2D view at a point of the plane
    const QStringList xy = p.value("right-click-flat").split(',');
    bool okx = false, oky = false;
    const double x = xy.size() == 2 ? xy[0].toDouble(&okx) : 0, y = xy.size() == 2 ? xy[1].toDouble(&oky) : 0;
    if (!okx || !oky || !std::isfinite(x) || !std::isfinite(y))
      fail("--right-click-flat '" + p.value("right-click-flat").toStdString() + "': expected X,Y in the scene's units");
    QWidget* view = window.flatView();
    const QPointF at = window.flatView()->toWidget({float(x), float(y)});
    QMouseEvent press(QEvent::MouseButtonPress, at, view->mapToGlobal(at.toPoint()), Qt::RightButton,
                      Qt::RightButton, Qt::NoModifier);
    QApplication::sendEvent(view, &press);
    QMouseEvent release(QEvent::MouseButtonRelease, at, view->mapToGlobal(at.toPoint()), Qt::RightButton,
                        Qt::NoButton, Qt::NoModifier);
    QApplication::sendEvent(view, &release);
    QApplication::processEvents();
  }
  if (p.isSet("drag-flat")) {  // press, move with the button held, release, in the 2D view
    const auto v = parseFour("drag-flat", p.value("drag-flat"), "FROMX,FROMY,TOX,TOY in the scene's units");
    QWidget* view = window.flatView();
    const QPointF a = window.flatView()->toWidget({v[0], v[1]}), b = window.flatView()->toWidget({v[2], v[3]});
    auto send = [view](QEvent::Type type, const QPointF& at, Qt::MouseButton button, Qt::MouseButtons held) {
      QMouseEvent e(type, at, view->mapToGlobal(at.toPoint()), button, held, Qt::NoModifier);
      QApplication::sendEvent(view, &e);
      QApplication::processEvents();
    };
    // Each move: the walk traced again and the view painted (send's processEvents paints the update, once).
    double total = 0, worst = 0;
    const int moves = 10;
    send(QEvent::MouseButtonPress, a, Qt::LeftButton, Qt::LeftButton);
    for (int k = 1; k <= moves; ++k) {
      const auto t0 = std::chrono::steady_clock::now();
      send(QEvent::MouseMove, a + (b - a) * k / double(moves), Qt::NoButton, Qt::LeftButton);
      const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      total += ms;
      worst = std::max(worst, ms);
    }
    send(QEvent::MouseButtonRelease, b, Qt::LeftButton, Qt::NoButton);
    std::fprintf(stderr, "timing: drag %d moves, mean %.1f ms, max %.1f ms per move (traced and painted)\n", moves,
                 total / moves, worst);
  }
}

void runActions(MainWindow& window, const QCommandLineParser& p) {
  Session* s = window.session();
  moveFlatRay(window, p);
  // One key press at a time, as a user would.
  for (auto [name, delta] : {std::pair{"forward", 1}, std::pair{"back", -1}}) {
    if (!p.isSet(name)) continue;
    bool ok = false;
    int n = p.value(name).toInt(&ok);
    if (!ok || n < 0) fail(std::string("--") + name + " expects a count >= 0");
    double total = 0, worst = 0;
    for (int i = 0; i < n; ++i) {
      auto t0 = std::chrono::steady_clock::now();
      s->stepBy(delta);
      auto t1 = std::chrono::steady_clock::now();
      QApplication::processEvents();
      if (getenv("RAYSTEP_GUI_PROFILE"))
        std::fprintf(
            stderr, "step handlers %.1f ms, paint %.1f ms\n",
            std::chrono::duration<double, std::milli>(t1 - t0).count(),
            std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count());
      double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
      total += ms;
      worst = std::max(worst, ms);
    }
    if (n > 0)
      std::fprintf(stderr, "timing: %d steps %s, mean %.1f ms, max %.1f ms per step\n", n, name, total / n,
                   worst);
  }
  if (p.isSet("keys")) pressKeys(window, p.value("keys"));
  if (p.isSet("compare-pick")) {  // the dialog's OK, with these boxes ticked
    const std::vector<std::string> kinds = replay::parse_side_by_side_list(p.value("compare-pick").toStdString());
    QStringList list;
    for (const std::string& k : kinds) list << QString::fromStdString(k);
    window.setCompareStructures(list);
  }
  if (p.isSet("click-pixel")) {  // a click on the picture where the pixel is drawn
    std::vector<int> at = parseInts("click-pixel", p.value("click-pixel"), 2, 0);
    settle(window);
    ImageCanvas* canvas = window.imageView()->canvas();
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->widgetPosOf(at[0], at[1]));
    QApplication::processEvents();
  }
  if (p.isSet("pick-3d")) {  // a click in the 3D view selects the tree's leaf holding the picked point
    if (!s->structure() || !treeShapeOf(*s->structure()))
      fail("--pick-3d: no tree (open a scene with --accel kd, kd-median, bvh, octree or bsp)");
    window.showKdPanel();
    settle(window);
    std::vector<int> at = parseInts("pick-3d", p.value("pick-3d"), 2, 0);
    if (!window.sceneView()->pickAt(QPoint(at[0], at[1])))
      fail("--pick-3d " + p.value("pick-3d").toStdString() + ": no geometry under that pixel of the 3D view");
  }
  if (p.isSet("sah-orientation") && !window.sahChart()->setBspOrientation(p.value("sah-orientation")))
    fail("--sah-orientation '" + p.value("sah-orientation").toStdString() +
         "': all, axes, face, body, own, or a direction (x, y, z, x+y, ..., -x+y+z)");
  if (p.isSet("edit-ti")) {  // through the spin box: the rebuild starts once the value has rested
    bool ok = false;
    double ti = p.value("edit-ti").toDouble(&ok);
    if (!ok || !std::isfinite(ti) || ti <= 0 || ti > 1e4)
      fail("--edit-ti '" + p.value("edit-ti").toStdString() + "': out of range");
    auto* spin = window.findChild<QDoubleSpinBox*>("kdTi");
    if (!spin) fail("--edit-ti: no t_i box");
    spin->setValue(ti);
    for (int i = 0; i < 1000 && window.structurePanel()->costsEditPending(); ++i) {
      QApplication::processEvents();
      QThread::msleep(5);
    }
    QApplication::processEvents();
  }
  if (p.isSet("click-sample")) {  // a click on the inspector's canvas, where the sample is drawn
    bool ok = false;
    const int n = p.value("click-sample").toInt(&ok);
    const TracePixel* px = s->pixel();
    if (!px) fail("--click-sample: no traced pixel (give --pixel)");
    if (!ok || n < 0 || n >= int(px->sampling.samples.size()))
      fail("--click-sample '" + p.value("click-sample").toStdString() + "': the pixel has " +
           std::to_string(px->sampling.samples.size()) + " samples");
    window.showPixelInspector();
    settle(window);
    PixelCanvas* canvas = window.pixelInspector()->canvas();
    QTest::mouseClick(canvas, Qt::LeftButton, Qt::NoModifier, canvas->samplePos(n).toPoint());
    QApplication::processEvents();
  }
  if (p.isSet("open-bad")) window.openFileReportingErrors(p.value("open-bad"));
  if (p.isSet("open-lesson-bad")) window.openLessonReportingErrors(p.value("open-lesson-bad"));
  runReportActions(window, p);
}

void finish(MainWindow& window) {
  settle(window);
  window.sahChart()->renderNow();
  QApplication::processEvents();
  if (getenv("RAYSTEP_GUI_PROFILE"))
    for (QWidget* w : window.findChildren<QWidget*>())
      if (w->minimumSizeHint().width() > 250)
        std::fprintf(stderr, "min width %d: %s %s\n", w->minimumSizeHint().width(),
                     w->metaObject()->className(), w->objectName().toLocal8Bit().constData());
}

double msSince(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
}

// 1-based step numbers, comma-separated: "1,2,3", "5,4,3,2,1", "3,7,1".
std::vector<int> parseStepList(const QString& option, const QString& spec, int steps) {
  std::vector<int> out;
  for (const QString& part : spec.split(',')) {
    bool ok = false;
    int n = part.trimmed().toInt(&ok);
    if (!ok || n < 1 || n > steps)
      fail("--" + option.toStdString() + " '" + spec.toStdString() + "': steps are 1.." +
           std::to_string(steps));
    out.push_back(n);
  }
  return out;
}

// The lesson modes: present (interactive), enter one step or walk a list of them (scripted, for tests and
// slides), export the handout.
int runLesson(MainWindow& window, const QCommandLineParser& p, bool quit, bool anyScript) {
  // A damaged lesson is reported with its file and line before anything is shown.
  Lesson lesson = lesson_with_numbers(parse_lesson(p.value("lesson").toStdString()));
  Presenter* presenter = window.openLesson(lesson);
  if (p.isSet("narration-window")) window.classroom()->setNarrationWindow(true);
  if (!anyScript) {
    // Presenting: the whole screen (a projector's), unless --window says otherwise.
    if (!p.isSet("window"))
      if (const QScreen* screen = QApplication::primaryScreen())
        window.resize(screen->availableGeometry().size());
    window.fitLessonPane();
    window.show();
    settle(window);
    window.releaseLessonPaneWidth();
    presenter->goToReportingErrors(0);
    return -1;
  }
  window.setScripted(true);
  // Scripted steps are entered alone, unless the benchmark of entering steps asks for the presenter's
  // prefetch (then each step waits for it first, as the class's reading time would).
  const bool prefetch = getenv("RAYSTEP_GUI_PREFETCH") != nullptr;
  presenter->setPrefetch(prefetch);
  window.fitLessonPane();
  window.show();
  settle(window);
  const int steps = int(lesson.steps.size());
  auto enter = [&](int n) {  // 1-based
    if (prefetch) {
      auto w0 = std::chrono::steady_clock::now();
      window.waitForPrefetches();
      if (getenv("RAYSTEP_GUI_PROFILE"))
        std::fprintf(stderr, "timing: prefetch done after %.1f ms more\n", msSince(w0));
    }
    auto t0 = std::chrono::steady_clock::now();
    presenter->goTo(n - 1);
    double ms = msSince(t0);
    if (getenv("RAYSTEP_GUI_PROFILE")) std::fprintf(stderr, "timing: entering step %d: %.1f ms\n", n, ms);
  };
  if (p.isSet("lesson-walk")) {
    std::vector<int> walk = parseStepList("lesson-walk", p.value("lesson-walk"), steps);
    QString dir = p.value("dump-state-dir");
    if (!dir.isEmpty() && !QDir().mkpath(dir)) fail("cannot make " + dir.toStdString());
    for (int n : walk) {
      enter(n);
      if (dir.isEmpty()) continue;
      finish(window);
      QString base = QString("%1/step-%2").arg(dir).arg(n);
      writeJson(base + ".json", dumpState(window));
      if (!window.grabMiddleView().save(base + ".png", "PNG"))
        fail("cannot write " + base.toStdString() + ".png");
    }
  } else if (p.isSet("lesson-step")) {
    bool ok = false;
    int n = p.value("lesson-step").toInt(&ok);
    if (!ok || n < 1 || n > steps)
      fail("--lesson-step '" + p.value("lesson-step").toStdString() + "': the lesson has steps 1.." +
           std::to_string(steps));
    enter(n);
  } else if (!p.isSet("export-handout")) {
    enter(1);
  }
  if (p.isSet("predict")) presenter->predictAndReveal(p.value("predict"));
  if (p.isSet("predict-next"))  // Predict mode: each prediction, then the step it is about
    for (const QString& guess : p.value("predict-next").split(';')) presenter->predictNext(guess);
  runActions(window, p);
  if (p.isSet("export-handout")) exportHandout(window, *presenter, p.value("export-handout"));
  finish(window);
  writeOutputs(window, p);
  window.setScripted(false);
  return quit ? 0 : -1;
}

// The side-by-side view alone: --compare LIST over a scene's pixel, or a version 5 trace; then the scripted
// actions on its timeline and its outputs.
int runCompare(MainWindow& window, const QCommandLineParser& p, bool quit, bool anyScript, int ww, int wh) {
  CompareWindow* cw = window.compareWindow();
  if (p.isSet("compare")) {
    // The list first: a wrong one costs nothing (no scene read, nothing built).
    const std::vector<std::string> kinds = replay::parse_side_by_side_list(p.value("compare").toStdString());
    LessonState st = stateFromOptions(p);
    if (st.scene.empty() || MainWindow::isTraceFile(QString::fromStdString(st.scene)))
      fail("--compare needs a scene or a mesh (a trace of several structures opens with --trace FILE)");
    if (!st.pixel) fail("--compare needs --pixel X,Y");
    std::shared_ptr<const SceneData> scene = loadSceneData(st.scene);
    const int w = st.size ? (*st.size)[0] : scene->scene.render.width;
    const int h = st.size ? (*st.size)[1] : scene->scene.render.height;
    const int px = (*st.pixel)[0], py = (*st.pixel)[1];
    if (px >= w || py >= h)
      fail("--pixel " + std::to_string(px) + "," + std::to_string(py) + ": outside the " + std::to_string(w) +
           "x" + std::to_string(h) + " image");
    std::vector<std::shared_ptr<const StructureData>> built;
    for (const std::string& k : kinds) built.push_back(buildStructureData(scene, k, st.structure));
    cw->setWalks(recordComparePixel(built, w, h, px, py, st.secondary), scene, built,
                 QString::fromStdString(st.scene));
  } else {
    const QString path = p.isSet("trace") ? p.value("trace") : p.positionalArguments().value(0);
    if (p.isSet("trace") && !p.positionalArguments().isEmpty()) fail("give --trace FILE or a file, not both");
    cw->setWalks(std::make_shared<const MultiTrace>(read_multi_trace_json(path.toStdString())), nullptr, {},
                 path);
  }
  cw->resize(ww, wh);
  cw->show();
  if (!anyScript) return -1;
  settleWindowSystem();
  if (p.isSet("ray")) {
    bool ok = false;
    const int r = p.value("ray").toInt(&ok);
    if (!ok || r < 0 || r >= cw->rayCount())
      fail("--ray " + p.value("ray").toStdString() + ": no such ray in the walks");
    cw->setRay(r);
  }
  if (p.isSet("at-t")) {
    bool ok = false;
    const double t = p.value("at-t").toDouble(&ok);
    if (!ok || !std::isfinite(t)) fail("--at-t '" + p.value("at-t").toStdString() + "': expected a number");
    cw->setT(t);
  }
  if (p.isSet("slider")) {
    bool ok = false;
    const int pos = p.value("slider").toInt(&ok);
    if (!ok || pos < 0 || pos > 1000)
      fail("--slider '" + p.value("slider").toStdString() + "': expected 0 .. 1000");
    cw->findChild<QSlider*>("compareSlider")->setValue(pos);  // as a drag moves it
  }
  if (p.isSet("drag-view")) {  // press, move with the button held, release: the trackball turns the camera
    static const std::regex re("([0-9]+):(-?[0-9]{1,4}),(-?[0-9]{1,4})");
    std::smatch m;
    const std::string spec = p.value("drag-view").toStdString();
    if (!std::regex_match(spec, m, re) || std::stoi(m[1]) >= cw->viewCount())
      fail("--drag-view '" + spec + "': expected I:DX,DY with I a view (0.." +
           std::to_string(cw->viewCount() - 1) + ")");
    QWidget* gl = cw->view(std::stoi(m[1]))->findChild<QOpenGLWidget*>();
    if (!gl) fail("--drag-view: the view has no OpenGL widget");
    const QPoint c(gl->width() / 2, gl->height() / 2), d(std::stoi(m[2]), std::stoi(m[3]));
    auto send = [gl](QEvent::Type type, const QPoint& at, Qt::MouseButton button, Qt::MouseButtons held) {
      QMouseEvent e(type, at, gl->mapToGlobal(at), button, held, Qt::NoModifier);
      QApplication::sendEvent(gl, &e);
      QApplication::processEvents();
    };
    send(QEvent::MouseButtonPress, c, Qt::LeftButton, Qt::LeftButton);
    for (int k = 1; k <= 10; ++k) send(QEvent::MouseMove, c + d * k / 10, Qt::NoButton, Qt::LeftButton);
    send(QEvent::MouseButtonRelease, c + d, Qt::LeftButton, Qt::NoButton);
  }
  settleWindowSystem();
  cw->renderNow();
  QApplication::processEvents();
  if (p.isSet("screenshot") && !cw->grab().save(p.value("screenshot"), "PNG"))
    fail("cannot write " + p.value("screenshot").toStdString());
  if (p.isSet("dump-state")) writeJson(p.value("dump-state"), QJsonObject{{"compare", cw->dumpState()}});
  return quit ? 0 : -1;
}

}  // namespace

int runCommandLine(MainWindow& window, const QStringList& arguments) {
  QCommandLineParser p;
  defineOptions(p);
  if (!p.parse(arguments)) {
    std::fprintf(stderr, "error: %s\n", p.errorText().toLocal8Bit().constData());
    return 2;
  }
  if (p.isSet("help")) {
    std::printf("%s", p.helpText().toLocal8Bit().constData());
    return 0;
  }
  const bool quit = p.isSet("quit");
  const QStringList scripted = {
      "pixel",         "step",           "step-to",         "forward",        "back",         "screenshot",
      "screenshot-3d", "dump-state",     "export-trace",    "open-bad",       "panel",        "node",
      "node-path",     "pick-3d",        "export-sah",      "screenshot-sah", "edit-ti",      "lesson-step",
      "lesson-walk",   "export-handout", "open-lesson-bad", "predict",        "predict-next", "inspect",
      "sample",        "square",         "sample-overlay",  "click-sample",   "compare-pick", "click-pixel",
      "sah-orientation", "flat-ray",     "drag-flat",       "export-figure",  "right-click-flat", "crofton-lines", "flat-aa"};
  bool anyScript = quit;
  for (const QString& s : reportScriptOptions()) anyScript = anyScript || p.isSet(s);
  for (const QString& s : scripted) anyScript = anyScript || p.isSet(s);

  try {
    int ww = 1280, wh = 800;
    if (p.isSet("window")) parseSize("window", p.value("window"), &ww, &wh);
    window.resize(ww, wh);
    if (p.isSet("scale")) {
      bool ok = false;
      double scale = p.value("scale").toDouble(&ok);
      if (!ok || !(scale >= 0.5 && scale <= 4.0))
        fail("--scale '" + p.value("scale").toStdString() + "': expected 0.5 .. 4");
      window.setPresenterScale(scale);
    }
    if (p.isSet("lesson")) {
      if (!p.positionalArguments().isEmpty())
        fail("--lesson names the scenes itself: give no scene or trace file");
      return runLesson(window, p, quit, anyScript);
    }
    const QString file = p.isSet("trace") ? p.value("trace") : p.positionalArguments().value(0);
    if (p.isSet("compare") || (!file.isEmpty() && isMultiTraceFile(file)))
      return runCompare(window, p, quit,
                        anyScript || p.isSet("at-t") || p.isSet("slider") || p.isSet("drag-view"), ww, wh);
    LessonState st = stateFromOptions(p);

    if (!anyScript) {  // interactive: open in the background and return to the event loop
      window.setStructureOptions(st.accel, st.structure);
      if (!st.aa.empty()) window.imageView()->setAntiAliasing(QString::fromStdString(st.aa));
      if (!st.heat.empty()) window.imageView()->setHeatQuantity(QString::fromStdString(st.heat));
      if (st.size) window.setImageSize((*st.size)[0], (*st.size)[1]);
      window.imageView()->setSecondaryRays(st.secondary);
      if (st.translucent) window.sceneView()->setTranslucent(true);
      if (st.build_planes) window.sceneView()->setBuildPlanes(true);
      if (st.follow) window.sceneView()->setFollowCell(true);
      window.show();
      if (!st.scene.empty()) window.openFileReportingErrors(QString::fromStdString(st.scene));
      return -1;
    }

    window.setScripted(true);
    window.show();
    settle(window);  // laid out before the picture is fitted and the 3D view framed
    enterState(window, st);
    runActions(window, p);
    finish(window);
    writeOutputs(window, p);
    window.setScripted(false);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return quit ? 0 : -1;
}

}  // namespace raystep::viz
