#include "script.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <regex>

#include <QApplication>
#include <QCommandLineParser>
#include <QFile>
#include <QJsonArray>
#include <QJsonDocument>
#include <QJsonObject>
#include <QDoubleSpinBox>
#include <QMouseEvent>
#include <QTreeView>
#include <QTest>
#include <QThread>
#include <map>

#include "event_list.h"
#include "main_window.h"
#include "replay.h"
#include "scene_view.h"
#include "session.h"
#include "state_panel.h"
#include "structure_panel.h"
#include "image_view.h"
#include "kd_tree_model.h"
#include "sah_chart.h"
#include "timeline.h"
#include "tree_view.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/heatmap.h"
#include "raystep/util/error.h"

namespace raystep::viz {
namespace {

[[noreturn]] void fail(const std::string& what) { throw InputError("", 0, what); }

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
  for (int i = 0; i < 5; ++i) {
    QApplication::processEvents();
    QThread::msleep(5);
  }
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
  o["sah"] = w.sahChart()->dumpState();
  o["selected_node"] = s->selectedNode();
  if (const KdTree* kd = s->structure() ? s->structure()->kdTree() : nullptr) {
    QJsonObject tree{{"nodes", int(kd->data().nodes.size())}, {"rows_made", w.treeView()->expandedCount()}};
    QModelIndex cur = w.treeView()->view()->currentIndex();
    tree["current_row_node"] = KdTreeModel::nodeOf(cur);
    if (s->selectedNode() >= 0)
      tree["selected_path"] = QString::fromStdString(kdNodePath(kd->data(), uint32_t(s->selectedNode())));
    o["tree"] = tree;
  }
  o["window"] = QJsonArray{w.width(), w.height()};
  o["last_error"] = w.lastError();
  return o;
}

void defineOptions(QCommandLineParser& p) {
  p.setApplicationDescription("raystep-gui: step through one ray's walk through an acceleration structure.");
  p.addHelpOption();
  p.addPositionalArgument("file", "A scene (.json), a mesh (.obj) or a trace written by `raystep trace`.");
  auto opt = [&](const QString& name, const QString& help, const QString& value = QString()) {
    p.addOption(QCommandLineOption(name, help, value));
  };
  opt("accel", "Acceleration structure: grid, kd (SAH) or kd-median.", "NAME");
  opt("ti", "kd: t_i, the cost of a ray-primitive test (default 80).", "T");
  opt("tt", "kd: t_t, the cost of a traversal step (default 1).", "T");
  opt("empty-bonus", "kd: bonus in [0,1) for splits that cut off empty space (default 0).", "B");
  opt("max-depth", "kd: depth limit (0: max(8, 1.2 log2 N); with an empty bonus 8 + 1.3 log2 N).", "D");
  opt("leaf-size", "kd: a node with at most this many primitives is a leaf (default 1).", "N");
  opt("mailbox", "kd: mailboxes on | off (default on).", "MODE");
  opt("grid-res", "Explicit grid resolution.", "NX,NY,NZ");
  opt("grid-density", "Grid density d: max(nx,ny,nz) = d*cbrt(n).", "D");
  opt("grid-insert", "Grid insertion: exact or bbox.", "MODE");
  opt("aa", "Anti-aliasing of the picture: none|regular:K|jitter:K|random:N|adaptive:T[:D].", "SPEC");
  opt("heat", "Heat map overlay: cells, tests or mailbox.", "Q");
  opt("size", "Picture size (default: the scene's); --pixel refers to it.", "WxH");
  opt("pixel", "Trace this pixel's rays.", "X,Y");
  opt("secondary", "Trace the pixel's secondary rays too.");
  opt("ray", "Show this ray of the trace (0: the primary).", "I");
  opt("step", "Go to event N.", "N");
  opt("step-to", "Go to the K-th event of a kind (cell, prim_test, mailbox_hit, hit_deferred, hit_accepted or hit, "
                 "ray_end, node, push, pop, leaf).", "KIND:K");
  opt("forward", "Then step forward N times.", "N");
  opt("back", "Then step back N times.", "N");
  opt("keys", "Then press these keys, comma-separated: Right, Left, Space, Home, End.", "LIST");
  opt("zoom", "Image zoom: screen pixels per picture pixel (0: fit), centred on the traced pixel.", "Z");
  opt("translucent", "Draw the scene translucent.");
  opt("follow", "Let the 3D camera follow the current cell.");
  opt("window", "Window size (default 1280x800).", "WxH");
  opt("panel", "Show a panel: sah (the kd-tree's nodes and the SAH inspector; the root unless --node), or kd (the "
               "same with no node selected).", "NAME");
  opt("node", "kd-tree: select node ID (tree view, 3D view, SAH inspector).", "ID");
  opt("node-path", "kd-tree: select the node at this path from the root (L below, R above), e.g. LRL.", "PATH");
  opt("pick-3d", "Click the 3D view at window pixel X,Y (selects the kd-tree leaf holding the picked point).", "X,Y");
  opt("edit-ti", "Then type t_i into the structure panel, as a user would (the kd-tree is rebuilt).", "T");
  opt("export-sah", "Write the selected node's SAH curve as CSV (the columns of `raystep sah`).", "FILE");
  opt("screenshot-sah", "Write a PNG of the SAH chart.", "FILE");
  opt("open-bad", "After the set-up, open FILE through the GUI path (errors go to a dialog).", "FILE");
  opt("export-trace", "Write the current trace (the JSON of `raystep trace`).", "FILE");
  opt("screenshot", "Write a PNG of the window.", "FILE");
  opt("screenshot-3d", "Write a PNG of the 3D view.", "FILE");
  opt("dump-state", "Write what the panels and the 3D view show (JSON).", "FILE");
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
  const QStringList scripted = {"pixel", "step", "step-to", "forward", "back", "screenshot", "screenshot-3d",
                                "dump-state", "export-trace", "open-bad", "panel", "node", "node-path",
                                "pick-3d", "export-sah", "screenshot-sah", "edit-ti"};
  bool anyScript = quit;
  for (const QString& s : scripted) anyScript = anyScript || p.isSet(s);

  try {
    int ww = 1280, wh = 800;
    if (p.isSet("window")) parseSize("window", p.value("window"), &ww, &wh);
    window.resize(ww, wh);
    std::string accel = p.isSet("accel") ? p.value("accel").toStdString() : "grid";
    if (accel != "grid" && accel != "kd" && accel != "kd-median")
      fail("--accel '" + accel + "': the debugger replays grid, kd or kd-median");
    StructureOptions so;
    auto number = [&](const char* name, double lo, double hi, bool loOpen, bool hiOpen) {
      bool ok = false;
      double v = p.value(name).toDouble(&ok);
      if (!ok || !std::isfinite(v) || (loOpen ? v <= lo : v < lo) || (hiOpen ? v >= hi : v > hi))
        fail(std::string("--") + name + " '" + p.value(name).toStdString() + "': out of range");
      return v;
    };
    if (p.isSet("ti")) so.kd.t_i = float(number("ti", 0.0, 1e4, true, false));
    if (p.isSet("tt")) so.kd.t_t = float(number("tt", 0.0, 1e4, false, false));  // t_t >= 0, as in core
    if (p.isSet("empty-bonus")) so.kd.empty_bonus = float(number("empty-bonus", 0.0, 1.0, false, true));
    if (p.isSet("max-depth")) so.kd.max_depth = int(number("max-depth", 0, kKdMaxDepth, false, false));
    if (p.isSet("leaf-size")) so.kd.leaf_size = int(number("leaf-size", 1, 1e6, false, false));
    if (p.isSet("mailbox")) {
      QString m = p.value("mailbox");
      if (m != "on" && m != "off") fail("--mailbox '" + m.toStdString() + "': expected on or off");
      so.kd_mailboxes = m == "on";
    }
    GridOptions& g = so.grid;
    if (p.isSet("grid-density")) {
      bool ok = false;
      g.density = p.value("grid-density").toFloat(&ok);
      if (!ok || !(g.density > 0.f && g.density <= 64.f)) fail("--grid-density must be in (0, 64]");
    }
    if (p.isSet("grid-res")) {
      std::vector<int> r = parseInts("grid-res", p.value("grid-res"), 3, 1);
      for (int v : r)
        if (v > 4096) fail("--grid-res: each of NX,NY,NZ must be 1..4096");
      g.resolution = std::array<int, 3>{r[0], r[1], r[2]};
    }
    if (p.isSet("grid-insert")) {
      QString m = p.value("grid-insert");
      if (m != "exact" && m != "bbox") fail("--grid-insert '" + m.toStdString() + "': expected exact or bbox");
      g.exact_insert = m == "exact";
    }
    window.setStructureOptions(accel, so);
    if (p.isSet("aa")) {
      parse_antialiasing(p.value("aa").toStdString());  // throws on a bad spec
      window.imageView()->setAntiAliasing(p.value("aa"));
    }
    if (p.isSet("heat")) {
      parse_heat_quantity(p.value("heat").toStdString());
      window.imageView()->setHeatQuantity(p.value("heat"));
    }
    if (p.isSet("size")) {
      int w, h;
      parseSize("size", p.value("size"), &w, &h);
      window.setImageSize(w, h);
    }
    if (p.isSet("secondary")) window.imageView()->setSecondaryRays(true);
    if (p.isSet("translucent")) window.sceneView()->setTranslucent(true);
    if (p.isSet("follow")) window.sceneView()->setFollowCell(true);

    QStringList files = p.positionalArguments();
    if (files.size() > 1) fail("give one scene or trace file");
    if (!anyScript) {  // interactive: open in the background and return to the event loop
      window.show();
      if (!files.isEmpty()) window.openFileReportingErrors(files[0]);
      return -1;
    }

    window.setScripted(true);
    window.show();
    if (!files.isEmpty()) window.openFile(files[0]);
    Session* s = window.session();
    if (p.isSet("pixel")) {
      std::vector<int> px = parseInts("pixel", p.value("pixel"), 2, 0);
      if (!s->scene()) fail("--pixel needs a scene (a trace file already holds its rays)");
      if (px[0] >= s->imageWidth() || px[1] >= s->imageHeight())
        fail("--pixel " + p.value("pixel").toStdString() + ": outside the " + std::to_string(s->imageWidth()) + "x" +
             std::to_string(s->imageHeight()) + " image");
      // A click on the picture, as a user makes it (when the pixel is big enough on screen to hit it).
      settle(window);
      ImageCanvas* canvas = window.imageView()->canvas();
      QPoint at = canvas->widgetPosOf(px[0], px[1]);
      if (canvas->zoom() >= 1.0 && canvas->rect().contains(at)) {
        QMouseEvent press(QEvent::MouseButtonPress, at, canvas->mapToGlobal(at), Qt::LeftButton, Qt::LeftButton,
                          Qt::NoModifier);
        QMouseEvent release(QEvent::MouseButtonRelease, at, canvas->mapToGlobal(at), Qt::LeftButton, Qt::NoButton,
                            Qt::NoModifier);
        QApplication::sendEvent(canvas, &press);
        QApplication::sendEvent(canvas, &release);
      }
      const Trace* t = s->trace();
      if (!t || t->rays.empty() || !t->rays[0].has_pixel || t->rays[0].pixel[0] != px[0] || t->rays[0].pixel[1] != px[1])
      {
        std::fprintf(stderr, "note: pixel traced without a click (the picture is shown smaller than 1:1)\n");
        window.tracePixel(px[0], px[1]);
      }
    }
    if (p.isSet("ray")) {
      bool ok = false;
      int r = p.value("ray").toInt(&ok);
      if (!ok || !s->trace() || r < 0 || r >= int(s->trace()->rays.size())) fail("--ray: no such ray in the trace");
      s->setRay(r);
    }
    if (p.isSet("step") && p.isSet("step-to")) fail("give --step or --step-to, not both");
    if (p.isSet("step")) {
      bool ok = false;
      int n = p.value("step").toInt(&ok);
      if (!ok || n < 0 || n >= s->eventCount())
        fail("--step " + p.value("step").toStdString() + ": the ray has " + std::to_string(s->eventCount()) +
             " events (0.." + std::to_string(s->eventCount() - 1) + ")");
      s->setStep(n);
    }
    if (p.isSet("step-to")) {
      QStringList kk = p.value("step-to").split(':');
      bool ok = kk.size() == 2;
      int k = ok ? kk[1].toInt(&ok) : 0;
      EventType type;
      std::string name = kk[0].toStdString();
      if (name == "hit") name = "hit_accepted";
      if (!ok || k < 1 || !parse_event_type(name, &type))
        fail("--step-to '" + p.value("step-to").toStdString() + "': expected KIND:K, K >= 1");
      int i = s->ray() ? nthEvent(*s->ray(), type, k) : -1;
      if (i < 0) fail("--step-to " + p.value("step-to").toStdString() + ": the ray has fewer such events");
      s->setStep(i);
    }
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
          std::fprintf(stderr, "step handlers %.1f ms, paint %.1f ms\n",
                       std::chrono::duration<double, std::milli>(t1 - t0).count(),
                       std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t1).count());
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        total += ms;
        worst = std::max(worst, ms);
      }
      if (n > 0) std::fprintf(stderr, "timing: %d steps %s, mean %.1f ms, max %.1f ms per step\n", n, name, total / n, worst);
    }
    if (p.isSet("keys")) {  // through Qt's key handling, shortcuts included, as from the keyboard
      static const std::map<QString, Qt::Key> keys = {
          {"Right", Qt::Key_Right}, {"Left", Qt::Key_Left}, {"Space", Qt::Key_Space}, {"Home", Qt::Key_Home},
          {"End", Qt::Key_End}};
      // Window shortcuts fire only in the active window; without a window manager nobody activates it.
      QApplication::setActiveWindow(&window);
      window.activateWindow();
      QApplication::processEvents();
      for (const QString& k : p.value("keys").split(',')) {
        auto it = keys.find(k.trimmed());
        if (it == keys.end()) fail("--keys: unknown key '" + k.toStdString() + "' (Right, Left, Space, Home, End)");
        QTest::keyClick(&window, it->second);
        QApplication::processEvents();
      }
      window.timeline()->setPlaying(false);  // a Space may have started playback: stop where it is
    }
    if (p.isSet("zoom")) {
      bool ok = false;
      double z = p.value("zoom").toDouble(&ok);
      if (!ok || z < 0 || z > 64) fail("--zoom must be 0 (fit) .. 64");
      ImageCanvas* canvas = window.imageView()->canvas();
      canvas->setZoom(z);
      const Trace* t = s->trace();
      if (t && !t->rays.empty() && t->rays[0].has_pixel) canvas->centreOn(t->rays[0].pixel[0], t->rays[0].pixel[1]);
    }
    // The kd-tree's inspector: a node by id or path, or the root for --panel sah; or a click in the 3D view.
    if (p.isSet("panel") && p.value("panel") != "sah" && p.value("panel") != "kd")
      fail("--panel '" + p.value("panel").toStdString() + "': expected sah or kd");
    if (p.isSet("node") && p.isSet("node-path")) fail("give --node or --node-path, not both");
    if (p.isSet("panel") || p.isSet("node") || p.isSet("node-path") || p.isSet("pick-3d")) {
      const char* what = p.isSet("node") ? "--node" : p.isSet("node-path") ? "--node-path" : p.isSet("panel") ? "--panel" : "--pick-3d";
      const KdTree* kd = s->structure() ? s->structure()->kdTree() : nullptr;
      if (!kd) fail(std::string(what) + ": no kd-tree (open a scene with --accel kd or kd-median)");
      size_t count = kd->data().nodes.size();
      int node = p.isSet("panel") && p.value("panel") == "sah" ? 0 : -1;
      if (p.isSet("node")) {
        bool ok = false;
        qlonglong id = p.value("node").toLongLong(&ok);
        if (!ok || id < 0 || size_t(id) >= count)
          fail("--node " + p.value("node").toStdString() + ": the kd-tree has " + std::to_string(count) + " nodes (0.." +
               std::to_string(count - 1) + ")");
        node = int(id);
      }
      if (p.isSet("node-path")) {
        try {
          node = int(kd_node_by_path(kd->data(), p.value("node-path").toStdString()));
        } catch (const InputError& e) {
          std::string why = e.detail();  // core names the command line's option: "--path 'LRL': ..."
          if (size_t colon = why.find("': "); why.rfind("--path", 0) == 0 && colon != std::string::npos) why = why.substr(colon + 3);
          fail("--node-path '" + p.value("node-path").toStdString() + "': " + why);
        }
      }
      window.showKdPanel();
      settle(window);  // the dock laid out before the chart draws
      if (node >= 0) s->setSelectedNode(node);
      if (p.isSet("pick-3d")) {
        std::vector<int> at = parseInts("pick-3d", p.value("pick-3d"), 2, 0);
        settle(window);
        if (!window.sceneView()->pickAt(QPoint(at[0], at[1])))
          fail("--pick-3d " + p.value("pick-3d").toStdString() + ": no geometry under that pixel of the 3D view");
      }
    }
    if (p.isSet("edit-ti")) {  // through the spin box: the rebuild starts once the value has rested
      double ti = number("edit-ti", 0.0, 1e4, true, false);
      auto* spin = window.findChild<QDoubleSpinBox*>("kdTi");
      if (!spin) fail("--edit-ti: no t_i box");
      spin->setValue(ti);
      for (int i = 0; i < 1000 && window.structurePanel()->costsEditPending(); ++i) {
        QApplication::processEvents();
        QThread::msleep(5);
      }
      QApplication::processEvents();
    }
    if (p.isSet("open-bad")) window.openFileReportingErrors(p.value("open-bad"));
    settle(window);
    window.sahChart()->renderNow();
    QApplication::processEvents();
    if (getenv("RAYSTEP_GUI_PROFILE"))
      for (QWidget* w : window.findChildren<QWidget*>())
        if (w->minimumSizeHint().width() > 250)
          std::fprintf(stderr, "min width %d: %s %s\n", w->minimumSizeHint().width(), w->metaObject()->className(),
                       w->objectName().toLocal8Bit().constData());
    if (p.isSet("export-trace")) {
      if (!s->trace()) fail("--export-trace: no trace (give --pixel)");
      window.exportTrace(p.value("export-trace"));
    }
    if (p.isSet("screenshot") && !window.grab().save(p.value("screenshot"), "PNG"))
      fail("cannot write " + p.value("screenshot").toStdString());
    if (p.isSet("screenshot-3d") && !window.sceneView()->grabView().save(p.value("screenshot-3d"), "PNG"))
      fail("cannot write " + p.value("screenshot-3d").toStdString());
    if (p.isSet("screenshot-sah") && !window.sahChart()->saveChart(p.value("screenshot-sah")))
      fail("cannot write " + p.value("screenshot-sah").toStdString());
    if (p.isSet("export-sah")) {
      if (!window.sahChart()->curve()) fail("--export-sah: no SAH curve (give --node, --node-path or --panel sah)");
      window.exportSahCsv(p.value("export-sah"));
    }
    if (p.isSet("dump-state")) writeJson(p.value("dump-state"), dumpState(window));
    window.setScripted(false);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return quit ? 0 : -1;
}

}  // namespace raystep::viz
