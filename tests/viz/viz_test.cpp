// raystep-gui in scripted mode, as a user would drive it: open the Cornell box, click a pixel, step, and
// look at the screenshot. The app dumps its camera and window-pixel projections of what it drew
// (--dump-state), and the test checks that the screenshot shows the current cell's highlight colour where
// the cell's box projects and the ray's colour along the projected ray. Run under Xvfb (CTest does).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <functional>
#include <sstream>
#include <string>

#include <nlohmann/json.hpp>

#include "raystep/io/image_io.h"
#include "raystep/trace/trace_file.h"

namespace {

using nlohmann::json;

const std::string kExe = RAYSTEP_GUI_EXE;
const std::string kScene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";
const std::string kOut = RAYSTEP_VIZ_ARTIFACTS;

struct GuiRun {
  int code = -1;
  std::string err;
};

// Runs raystep-gui with the arguments (and environment variables `env`, "NAME=value ..."); stderr is captured.
GuiRun gui(const std::string& args, const std::string& tag, const std::string& env = "") {
  std::string errFile = kOut + "/" + tag + ".stderr";
  std::string cmd = (env.empty() ? "" : "env " + env + " ") + "'" + kExe + "' " + args + " 2> '" + errFile + "'";
  GuiRun r;
  int status = std::system(cmd.c_str());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  std::ifstream in(errFile);
  std::stringstream ss;
  ss << in.rdbuf();
  r.err = ss.str();
  return r;
}

json readJson(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  return json::parse(in);
}

std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

bool near(const uint8_t* px, const json& rgb, int tol) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(int(px[k]) - rgb[size_t(k)].get<int>()) > tol) return false;
  return true;
}

// Pixels of colour rgb within the box [x0, x1] x [y0, y1] of the image.
int countColor(const raystep::Rgb8Image& img, const json& rgb, double x0, double y0, double x1, double y1, int tol) {
  int n = 0;
  for (int y = std::max(0, int(y0)); y <= std::min(img.height - 1, int(y1)); ++y)
    for (int x = std::max(0, int(x0)); x <= std::min(img.width - 1, int(x1)); ++x) n += near(img.at(x, y), rgb, tol);
  return n;
}

// The standard session: the Cornell box, pixel (160, 200) of its 320x320 picture.
const std::string kPixel = "'" + kScene + "' --pixel 160,200 --window 1280x800";

// What the 3D view should show: the current cell's colour inside its projected box, the ray's colours (walked,
// ahead, or the current interval's) near most of its projected samples.
void checkScreenshot(const std::string& png, const json& state, const std::string& box = "current_cell") {
  raystep::Rgb8Image img = raystep::read_png_rgb8(png);
  ASSERT_EQ(img.width, state["window"][0].get<int>());
  const json& view = state["view"];
  ASSERT_TRUE(view.contains(box));
  const json& corners = view[box]["projected_corners"];
  ASSERT_EQ(corners.size(), 8u);
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
  for (const json& c : corners) {
    x0 = std::min(x0, c[0].get<double>());
    x1 = std::max(x1, c[0].get<double>());
    y0 = std::min(y0, c[1].get<double>());
    y1 = std::max(y1, c[1].get<double>());
  }
  int inside = countColor(img, view["colors"]["current_cell"], x0 - 2, y0 - 2, x1 + 2, y1 + 2, 10);
  EXPECT_GT(inside, 20) << "current cell colour inside its projected box " << x0 << "," << y0 << " .. " << x1 << "," << y1;
  // ... and nowhere else in the 3D view (the legend, outside it, shows the colour too).
  const json& vp = view["viewport"];
  double vx0 = vp[0], vy0 = vp[1], vx1 = vx0 + vp[2].get<double>(), vy1 = vy0 + vp[3].get<double>();
  int all = countColor(img, view["colors"]["current_cell"], vx0, vy0, vx1 - 1, vy1 - 1, 10);
  EXPECT_GT(inside, all * 8 / 10) << "the highlight colour appears away from the current cell";
  int samples = 0, seen = 0;
  for (const json& s : view["ray"]["projected_samples"]) {
    double x = s[0], y = s[1];
    if (x < vx0 + 3 || y < vy0 + 3 || x > vx1 - 3 || y > vy1 - 3) continue;
    ++samples;
    int found = 0;
    for (const char* c : {"ray", "ray_ahead", "segment"})
      found += countColor(img, view["colors"][c], x - 2, y - 2, x + 2, y + 2, 12);
    seen += found > 0;
  }
  ASSERT_GE(samples, 5) << "the ray should cross the 3D view";
  EXPECT_GE(seen * 10, samples * 8) << seen << " of " << samples << " ray samples show the ray's colour";
}

TEST(Viz, ScriptedScreenshotShowsCurrentCellAndRay) {
  for (const char* step : {"cell:1", "cell:3", "prim_test:1", "hit:1"}) {
    std::string tag = std::string("cornell_") + step;
    tag[tag.find(':')] = '_';
    std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json", tr = kOut + "/" + tag + ".trace.json";
    GuiRun r = gui(kPixel + " --step-to " + step + " --screenshot '" + png + "' --dump-state '" + st +
                    "' --export-trace '" + tr + "' --quit",
                tag);
    ASSERT_EQ(r.code, 0) << r.err;
    json state = readJson(st);
    checkScreenshot(png, state);
    // The panels show the event the trace holds at that step.
    raystep::Trace trace = raystep::read_trace_json(tr);
    const raystep::Event& e = trace.rays[0].events[size_t(state["step"].get<int>())];
    EXPECT_EQ(state["event_type"], raystep::event_type_name(e.type));
    EXPECT_EQ(state["event_list_row"], state["step"]);
    std::string cell = state["panels"]["cellLabel"];
    const json& cc = state["view"]["current_cell"]["cell"];
    std::string expect = "(" + std::to_string(cc[0].get<int>()) + ", " + std::to_string(cc[1].get<int>()) + ", " +
                         std::to_string(cc[2].get<int>()) + ")";
    EXPECT_NE(cell.find(expect), std::string::npos) << cell;
  }
}

// The kd-tree: the current node's highlight where its box projects, the ray along its projection.
TEST(Viz, KdScreenshotShowsCurrentNodeAndRay) {
  for (const char* step : {"push:1", "leaf:2"}) {
    std::string tag = std::string("cornell_kd_") + step;
    tag[tag.find(':')] = '_';
    std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json";
    GuiRun r = gui(kPixel + " --accel kd --step-to " + step + " --screenshot '" + png + "' --dump-state '" + st +
                       "' --quit",
                   tag);
    ASSERT_EQ(r.code, 0) << r.err;
    json state = readJson(st);
    checkScreenshot(png, state, "current_node");
  }
}

// Back N and forward N give the identical panels, 3D view and screenshot, for the grid and the kd-tree.
void checkBackAndForth(const std::string& accel, int k, int n) {
  const std::string base = kPixel + " --accel " + accel;
  auto snap = [&](const std::string& name, const std::string& steps) {
    std::string tag = accel + "_" + name;
    std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json";
    GuiRun r = gui(base + " " + steps + " --screenshot '" + png + "' --dump-state '" + st + "' --quit", tag);
    EXPECT_EQ(r.code, 0) << r.err;
    json j = readJson(st);
    return std::make_pair(j, raystep::read_png_rgb8(png));
  };
  auto a = snap("step_k", "--step " + std::to_string(k));
  auto b = snap("step_k_fwd_back", "--step " + std::to_string(k) + " --forward " + std::to_string(n) + " --back " +
                                       std::to_string(n));
  auto c = snap("step_kn_back", "--step " + std::to_string(k + n) + " --back " + std::to_string(n));
  // The same with the keyboard: End, Home, then Right k+2 times and Left twice.
  std::string keys = "End,Home";
  for (int i = 0; i < k + 2; ++i) keys += ",Right";
  keys += ",Left,Left";
  auto e = snap("step_k_keys", "--keys " + keys);
  EXPECT_EQ(a.first.dump(1), e.first.dump(1));
  EXPECT_TRUE(a.second.rgb == e.second.rgb) << "screenshots differ after the same steps by keyboard";
  EXPECT_EQ(a.first["step"], k);
  EXPECT_EQ(a.first.dump(1), b.first.dump(1));
  EXPECT_EQ(a.first.dump(1), c.first.dump(1));
  EXPECT_TRUE(a.second.rgb == b.second.rgb) << "screenshots differ after forward then back";
  EXPECT_TRUE(a.second.rgb == c.second.rgb) << "screenshots differ after stepping back";
  // And the state after k + n steps is really another one.
  auto d = snap("step_kn", "--step " + std::to_string(k + n));
  EXPECT_NE(a.first.dump(1), d.first.dump(1));
  EXPECT_NE(a.first["panels"].dump(), d.first["panels"].dump());
}

TEST(Viz, StepBackAndForthGivesTheSameState) { checkBackAndForth("grid", 4, 9); }

// In the kd-tree the stack table and the current node are part of the state: step 3 is inside the walk with a
// node pushed, and the steps in between push and pop.
TEST(Viz, KdStepBackAndForthGivesTheSameState) {
  checkBackAndForth("kd", 3, 8);
  json st = readJson(kOut + "/kd_step_k.json");
  EXPECT_TRUE(st["panels"].contains("stack")) << st["panels"].dump();
  EXPECT_TRUE(st["view"].contains("current_node")) << st["view"].dump();
}

// The 3D view keeps the scene's layer as an image while only the walk changes (BackdropCache): what it shows
// is pixel for pixel what drawing everything gives, at a cell, at a node with its split plane, after steps
// that kept the image, after a camera change (the fit at the start) that made it anew, and after changes of
// what the image shows (a rebuilt tree).
TEST(Viz, BackdropImageDrawsLikeTheScene) {
  // Also after the image was taken: a node selected, the tree rebuilt with another t_i.
  for (const char* run : {"grid --step-to cell:3 --forward 3", "kd --step-to node:3", "kd --step-to leaf:2 --back 2",
                          "kd --step-to leaf:2 --node 1", "kd --step-to node:3 --edit-ti 40"}) {
    std::string tag = std::string("backdrop_") + std::to_string(std::hash<std::string>{}(run) % 1000);
    std::string args = kPixel + " --accel " + run + " --screenshot-3d ";
    std::string sa = kOut + "/" + tag + "_image.json", sb = kOut + "/" + tag + "_drawn.json";
    GuiRun a = gui(args + "'" + kOut + "/" + tag + "_image.png' --dump-state '" + sa + "' --quit", tag + "_image");
    GuiRun b = gui(args + "'" + kOut + "/" + tag + "_drawn.png' --dump-state '" + sb + "' --quit", tag + "_drawn",
                   "RAYSTEP_GUI_NO_BACKDROP=1");
    ASSERT_EQ(a.code, 0) << a.err;
    ASSERT_EQ(b.code, 0) << b.err;
    EXPECT_EQ(readJson(sa)["view"]["backdrop"], "image");
    EXPECT_EQ(readJson(sb)["view"]["backdrop"], "drawn");
    raystep::Rgb8Image ia = raystep::read_png_rgb8(kOut + "/" + tag + "_image.png");
    raystep::Rgb8Image ib = raystep::read_png_rgb8(kOut + "/" + tag + "_drawn.png");
    ASSERT_EQ(ia.width, ib.width);
    ASSERT_EQ(ia.height, ib.height);
    size_t differ = 0;
    for (size_t i = 0; i < ia.rgb.size(); ++i) differ += ia.rgb[i] != ib.rgb[i];
    EXPECT_EQ(differ, 0u) << run;
  }
}

#ifdef RAYSTEP_CLI_EXE
TEST(Viz, ExportedTraceIsTheCommandLinesTrace) {
  std::string gt = kOut + "/export_gui.trace.json", ct = kOut + "/export_cli.trace.json";
  GuiRun r = gui(kPixel + " --secondary --export-trace '" + gt + "' --quit", "export");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' trace '" + kScene + "' --pixel 160,200 --secondary -o '" + ct +
                    "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(gt), slurp(ct)) << "the GUI's export and `raystep trace` differ";
}
#endif

// A trace exported by the GUI, opened on its own, replays like the scene it came from.
void checkTraceReplays(const std::string& accel, const std::string& stepTo, const std::string& box) {
  std::string tag = "replay_" + accel;
  std::string tr = kOut + "/" + tag + ".trace.json", st1 = kOut + "/" + tag + "_scene.json",
              st2 = kOut + "/" + tag + "_trace.json", png = kOut + "/" + tag + "_trace.png";
  GuiRun r1 = gui(kPixel + " --accel " + accel + " --step-to " + stepTo + " --export-trace '" + tr + "' --dump-state '" +
                      st1 + "' --quit",
                  tag + "1");
  ASSERT_EQ(r1.code, 0) << r1.err;
  GuiRun r2 = gui("'" + tr + "' --window 1280x800 --step-to " + stepTo + " --screenshot '" + png + "' --dump-state '" +
                      st2 + "' --quit",
                  tag + "2");
  ASSERT_EQ(r2.code, 0) << r2.err;
  json a = readJson(st1), b = readJson(st2);
  EXPECT_EQ(a["step"], b["step"]);
  EXPECT_EQ(a["panels"], b["panels"]);
  // The same cell or node (the camera fits what there is to show, so the projections differ).
  json boxA = a["view"][box], boxB = b["view"][box];
  boxA.erase("projected_corners");
  boxB.erase("projected_corners");
  EXPECT_EQ(boxA, boxB);
  EXPECT_EQ(a["view"]["visited_cells"], b["view"]["visited_cells"]);
  EXPECT_EQ(a["view"]["visited_nodes"], b["view"]["visited_nodes"]);
  EXPECT_EQ(a["view"]["stack_nodes"], b["view"]["stack_nodes"]);
  checkScreenshot(png, b, box);
}

TEST(Viz, TraceFileReplaysLikeTheScene) { checkTraceReplays("grid", "cell:4", "current_cell"); }
TEST(Viz, KdTraceFileReplaysLikeTheScene) { checkTraceReplays("kd", "push:2", "current_node"); }

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

TEST(Viz, MalformedTraceInScriptedModeExits2) {
  // A real trace, cut in the middle of its events.
  std::string tr = kOut + "/cut_source.trace.json";
  ASSERT_EQ(gui(kPixel + " --export-trace '" + tr + "' --quit", "cut0").code, 0);
  std::string text = slurp(tr);
  std::string bad = kOut + "/cut.trace.json";
  writeFile(bad, text.substr(0, text.size() / 2));
  std::string png = kOut + "/cut.png";
  GuiRun r = gui("'" + bad + "' --step 2 --screenshot '" + png + "' --quit", "cut");
  EXPECT_EQ(r.code, 2);
  EXPECT_EQ(r.err.find("error: " + bad + ":"), r.err.rfind('\n', r.err.find("error: ")) + 1) << r.err;
  EXPECT_NE(r.err.find("error: " + bad + ":"), std::string::npos) << r.err;
  std::ifstream shot(png);
  EXPECT_FALSE(shot.good()) << "nothing is written on error";

  // An unknown event type names its line.
  std::string unknown = text;
  size_t at = unknown.find("\"type\":\"cell\"");
  ASSERT_NE(at, std::string::npos);
  unknown.replace(at, 13, "\"type\":\"cellz\"");
  std::string bad2 = kOut + "/unknown_event.trace.json";
  writeFile(bad2, unknown);
  GuiRun r2 = gui("'" + bad2 + "' --quit", "unknown_event");
  EXPECT_EQ(r2.code, 2);
  EXPECT_NE(r2.err.find("error: " + bad2 + ":"), std::string::npos) << r2.err;
  EXPECT_NE(r2.err.find("cellz"), std::string::npos) << r2.err;
}

TEST(Viz, MalformedSceneInScriptedModeExits2) {
  std::string bad = kOut + "/bad_scene.json";
  writeFile(bad, "{\n  \"objects\": [\n    { \"type\": \"sphere\", \"radius\": -1 }\n  ]\n}\n");
  GuiRun r = gui("'" + bad + "' --pixel 1,1 --quit", "bad_scene");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("error: " + bad + ":"), std::string::npos) << r.err;
  GuiRun r2 = gui("'" + kOut + "/does_not_exist.json' --quit", "missing_scene");
  EXPECT_EQ(r2.code, 2);
  EXPECT_NE(r2.err.find("error: "), std::string::npos) << r2.err;
}

TEST(Viz, BadFileThroughTheGuiKeepsTheWindow) {
  std::string bad = kOut + "/gui_bad.trace.json";
  writeFile(bad, "{\"format\":\"raystep-trace\",\"version\":1,\n\"rays\": [ {\"origin\": [0, 0, null]}\n");
  std::string png = kOut + "/gui_bad.png", st = kOut + "/gui_bad.json", st0 = kOut + "/gui_bad_before.json";
  ASSERT_EQ(gui(kPixel + " --step 5 --dump-state '" + st0 + "' --quit", "gui_bad0").code, 0);
  GuiRun r = gui(kPixel + " --step 5 --open-bad '" + bad + "' --screenshot '" + png + "' --dump-state '" + st + "' --quit",
              "gui_bad");
  EXPECT_EQ(r.code, 0) << r.err;  // the app went on
  EXPECT_NE(r.err.find("error: " + bad + ":"), std::string::npos) << r.err;
  json before = readJson(st0), after = readJson(st);
  EXPECT_NE(after["last_error"].get<std::string>().find(bad), std::string::npos);
  // It kept what it had: the same trace, step and drawing.
  EXPECT_EQ(before["panels"], after["panels"]);
  EXPECT_EQ(before["view"], after["view"]);
  checkScreenshot(png, after);
}

// Without a display: --help still prints the usage; anything else says what is missing and exits 2 (Qt alone
// would abort).
TEST(Viz, WithoutADisplayHelpWorksAndTheRestExits2) {
  std::string out = kOut + "/nodisplay_help.txt";
  GuiRun help = gui("--help > '" + out + "'", "nodisplay_help", "-u DISPLAY");
  EXPECT_EQ(help.code, 0) << help.err;
  std::string usage = slurp(out);
  EXPECT_NE(usage.find("--accel"), std::string::npos) << usage;
  EXPECT_NE(usage.find("--screenshot"), std::string::npos) << usage;
  GuiRun run = gui("'" + kScene + "' --quit", "nodisplay_run", "-u DISPLAY");
  EXPECT_EQ(run.code, 2);
  EXPECT_EQ(run.err.rfind("error: ", 0), 0u) << run.err;
  EXPECT_NE(run.err.find("DISPLAY"), std::string::npos) << run.err;
}

// 100,000 copies of one triangle: the structure panel says that the reference budget coarsened the grid; an
// explicit resolution past the budget is refused with one line and exit 2, as on the command line.
TEST(Viz, CoarsenedGridSaysSoInTheStructurePanel) {
  std::string mesh = kOut + "/copies.obj", st = kOut + "/copies.json";
  std::string obj = "v 0 0 0\nv 1 0.2 0.1\nv 0.3 1 1\n";
  for (int i = 0; i < 100000; ++i) obj += "f 1 2 3\n";
  writeFile(mesh, obj);
  GuiRun r = gui("'" + mesh + "' --accel grid --size 16x12 --dump-state '" + st + "' --quit", "copies");
  ASSERT_EQ(r.code, 0) << r.err;
  std::string info = readJson(st)["structure_info"];
  EXPECT_NE(info.find("(coarsened from 139 x 139 x 139: reference budget)"), std::string::npos) << info;
  EXPECT_EQ(info.rfind("grid ", 0), 0u) << info;
  GuiRun x = gui("'" + mesh + "' --grid-res 64,64,64 --size 16x12 --quit", "copies_explicit");
  EXPECT_EQ(x.code, 2);
  EXPECT_NE(x.err.find("error: grid resolution 64x64x64 would test"), std::string::npos) << x.err;
}

TEST(Viz, BadOptionsExit2) {
  for (const char* args : {"--pixel 400,1", "--pixel 1", "--step 100000", "--step-to teleport:1", "--grid-res 0,1,1",
                           "--grid-insert fuzzy", "--aa sometimes", "--accel quadtree", "--size 0x3"}) {
    GuiRun r = gui("'" + kScene + "' " + args + " --quit", "bad_option");
    EXPECT_EQ(r.code, 2) << args;
    EXPECT_EQ(r.err.rfind("error: ", 0) == 0 || r.err.find("\nerror: ") != std::string::npos, true) << args << ": " << r.err;
  }
}

}  // namespace
