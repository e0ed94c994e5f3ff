// The same ray, side by side (suite Compare): raystep-gui SCENE --compare A,B,... --pixel X,Y and a version 5
// trace opened on its own. At one slider position every view shows the same t (its walk's state brackets it,
// its ray is drawn up to it); the counters equal the per-structure traces of `raystep trace --accel NAME`;
// the chart ends at each walk's total; bad lists exit 2 with one line.
#include <cmath>
#include <map>

#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

const std::string kKnot = kSourceDir + "/scenes/torus_knot.json";
const std::string kCornell = kSourceDir + "/scenes/cornell.json";

json runCompare(const std::string& args, const std::string& tag, Rgb8Image* shot = nullptr) {
  const std::string st = kOut + "/" + tag + ".json", png = kOut + "/" + tag + ".png";
  GuiRun r = gui(args + " --dump-state '" + st + "' --screenshot '" + png + "' --quit", tag);
  EXPECT_EQ(r.code, 0) << r.err;
  if (shot) *shot = raystep::read_png_rgb8(png);
  return readJson(st)["compare"];
}

// Every view shows the same t: the timeline's, its ray drawn up to it, its walk at or before it and its next
// step beyond it; the table and the chart say what the view's dump says; one camera.
void expectSameT(const json& c) {
  const double t = c["t"].get<double>();
  const double expected =
      c["t_start"].get<double>() +
      (c["t_end"].get<double>() - c["t_start"].get<double>()) * c["slider"].get<double>() / 1000.0;
  EXPECT_NEAR(t, expected, 1e-4 * (1.0 + std::fabs(expected)));
  const json& views = c["views"];
  for (size_t i = 0; i < views.size(); ++i) {
    const json& v = views[i];
    const std::string name = v["structure"];
    EXPECT_EQ(v["step"], v["session_step"]) << name;
    EXPECT_NEAR(v["view"]["ray_mark"].get<double>(), t, 1e-5 * (1.0 + std::fabs(t))) << name;
    if (!v["entered"].is_null()) EXPECT_LE(v["entered"].get<double>(), t) << name;
    if (!v["next"].is_null()) EXPECT_GT(v["next"].get<double>(), t) << name;
    EXPECT_DOUBLE_EQ(v["at_t"]["cost"].get<double>(), v["at_t"]["cost_at"].get<double>()) << name;
    EXPECT_EQ(v["view"]["camera"], views[0]["view"]["camera"]) << name << ": not the same camera";
    const json& row = c["table"][i];
    EXPECT_EQ(row[0], name);
    EXPECT_EQ(row[1], std::to_string(v["at_t"]["steps"].get<int>()) + " / " +
                          std::to_string(v["total"]["steps"].get<int>()));
    EXPECT_EQ(row[5], std::to_string(std::lround(v["at_t"]["cost"].get<double>())));
    const json& line = c["chart"]["lines"][i];
    EXPECT_EQ(line["name"], name);
    EXPECT_DOUBLE_EQ(line["points"].back()[1].get<double>(), v["total"]["cost"].get<double>()) << name;
  }
  EXPECT_NEAR(c["chart"]["marker_t"].get<double>(), t, 1e-9);
}

#ifdef RAYSTEP_CLI_EXE
struct Counts {
  int steps = 0, primTests = 0, mailboxHits = 0, boxTests = 0;
};
// Counted in a single structure's trace (version 4), over its first events up to `last` (-1: all).
Counts countEvents(const json& ray, int last = -1) {
  Counts c;
  const json& ev = ray["events"];
  const int n = last < 0 ? int(ev.size()) : last + 1;
  for (int i = 0; i < n; ++i) {
    const std::string type = ev[size_t(i)]["type"];
    c.steps += type == "cell" || type == "node";
    c.primTests += type == "prim_test";
    c.mailboxHits += type == "mailbox_hit";
    c.boxTests += type == "box_test";
  }
  return c;
}

json singleTrace(const std::string& scene, const std::string& accel, const std::string& pixel) {
  const std::string out = kOut + "/compare-single-" + accel + ".json";
  const std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' trace '" + scene + "' --accel " + accel +
                          " --pixel " + pixel + " -o '" + out + "' > /dev/null";
  EXPECT_EQ(std::system(cmd.c_str()), 0) << cmd;
  return readJson(out);
}

TEST(Compare, SameTAtTheSameSliderAndCountersEqualTheSingleTraces) {
  const std::vector<std::string> kinds = {"grid", "kd", "bvh", "octree"};
  std::map<std::string, json> single;
  for (const std::string& k : kinds) single[k] = singleTrace(kKnot, k, "200,100");
  int midWalk = 0;
  for (int slider : {0, 380, 1000}) {
    Rgb8Image shot;
    const json c = runCompare(
        "'" + kKnot + "' --compare grid,kd,bvh,octree --pixel 200,100 --slider " + std::to_string(slider),
        "compare-knot-" + std::to_string(slider), &shot);
    ASSERT_EQ(c["views"].size(), kinds.size());
    EXPECT_EQ(c["slider"].get<int>(), slider);
    expectSameT(c);
    for (size_t i = 0; i < kinds.size(); ++i) {
      const json& v = c["views"][i];
      ASSERT_EQ(v["structure"], kinds[i]);
      const json& ray = single[kinds[i]]["rays"][0];
      // The whole walk and the walk up to the event shown: as counted in `raystep trace --accel NAME`.
      ASSERT_EQ(v["events"].get<size_t>(), ray["events"].size()) << kinds[i];
      const Counts all = countEvents(ray), now = countEvents(ray, v["step"].get<int>());
      EXPECT_EQ(v["total"]["steps"].get<int>(), all.steps) << kinds[i];
      EXPECT_EQ(v["total"]["prim_tests"].get<int>(), all.primTests) << kinds[i];
      EXPECT_EQ(v["total"]["mailbox_hits"].get<int>(), all.mailboxHits) << kinds[i];
      EXPECT_EQ(v["total"]["box_tests"].get<int>(), all.boxTests) << kinds[i];
      EXPECT_DOUBLE_EQ(v["total"]["cost"].get<double>(), all.steps + 80.0 * all.primTests) << kinds[i];
      EXPECT_EQ(v["at_t"]["steps"].get<int>(), now.steps) << kinds[i];
      EXPECT_EQ(v["at_t"]["prim_tests"].get<int>(), now.primTests) << kinds[i];
      EXPECT_EQ(v["at_t"]["mailbox_hits"].get<int>(), now.mailboxHits) << kinds[i];
      EXPECT_EQ(v["at_t"]["box_tests"].get<int>(), now.boxTests) << kinds[i];
      EXPECT_DOUBLE_EQ(v["at_t"]["cost"].get<double>(), now.steps + 80.0 * now.primTests) << kinds[i];
      if (slider == 1000) {
        EXPECT_EQ(v["step"].get<size_t>() + 1, ray["events"].size()) << kinds[i] << ": not done at the end";
        EXPECT_EQ(v["event_type"], "ray_end");
      }
      const bool mid = now.steps > 0 && v["step"].get<size_t>() + 1 < ray["events"].size();
      midWalk += mid;
      // A walk under way: its current cell or node is drawn (yellow) inside its own view.
      if (mid) {
        const json& vp = v["view"]["viewport"];
        const json yellow = v["view"]["colors"]["current_cell"];
        EXPECT_GT(countColor(shot, yellow, vp[0], vp[1], vp[0].get<double>() + vp[2].get<double>(),
                             vp[1].get<double>() + vp[3].get<double>(), 10),
                  10)
            << kinds[i] << " at slider " << slider;
      }
    }
  }
  EXPECT_GE(midWalk, 4);  // the middle positions stop walks under way, not only before or after them
}

TEST(Compare, MultiTraceFileOpensSideBySide) {
  const std::string side = kOut + "/compare-side.json";
  const std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' trace '" + kCornell +
                          "' --accel grid,kd,bsp --pixel 100,150 -o '" + side + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const json file = readJson(side);
  ASSERT_EQ(file["version"].get<int>(), 5);
  const json live = runCompare("'" + kCornell + "' --compare grid,kd,bsp --pixel 100,150 --slider 500",
                               "compare-cornell-live");
  for (const std::string& how : {std::string("--trace '") + side + "'", "'" + side + "'"}) {
    const json c = runCompare(how + " --slider 500", "compare-cornell-file");
    ASSERT_EQ(c["views"].size(), 3u) << how;
    expectSameT(c);
    EXPECT_DOUBLE_EQ(c["t"].get<double>(), live["t"].get<double>()) << how;
    for (size_t i = 0; i < 3; ++i) {
      const json& v = c["views"][i];
      EXPECT_EQ(v["structure"], file["walks"][i]["structure"]["kind"]);
      EXPECT_EQ(v["events"].get<size_t>(), file["walks"][i]["rays"][0]["events"].size());
      // The file's walks are the live ones: the same state at the same t.
      EXPECT_EQ(v["step"], live["views"][i]["step"]) << how;
      EXPECT_EQ(v["at_t"], live["views"][i]["at_t"]) << how;
      EXPECT_EQ(v["total"], live["views"][i]["total"]) << how;
    }
  }
}
#endif

// From the main window: pick the structures (Reports > Compare...'s OK), then click a pixel of the picture
// (at zoom 2, where a click lands on the pixel it aims at).
TEST(Compare, PickThenClickAPixelOpensTheSameView) {
  const std::string st = kOut + "/compare-click.json";
  GuiRun r =
      gui("'" + kCornell + "' --zoom 2 --compare-pick grid,kd,bvh --click-pixel 100,150 --dump-state '" + st +
              "' --quit",
          "compare-click");
  ASSERT_EQ(r.code, 0) << r.err;
  const json clicked = readJson(st)["compare"];
  ASSERT_TRUE(clicked.is_object()) << "no side-by-side window after the click";
  const json live =
      runCompare("'" + kCornell + "' --compare grid,kd,bvh --pixel 100,150", "compare-click-live");
  EXPECT_NE(clicked["header"].get<std::string>().find("pixel (100, 150)"), std::string::npos);
  ASSERT_EQ(clicked["views"].size(), 3u);
  EXPECT_EQ(clicked["t"], live["t"]);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_EQ(clicked["views"][i]["structure"], live["views"][i]["structure"]);
    EXPECT_EQ(clicked["views"][i]["total"], live["views"][i]["total"]);
    EXPECT_EQ(clicked["views"][i]["at_t"], live["views"][i]["at_t"]);
  }
}

// One camera: a drag in one view turns every view's camera, the same way.
TEST(Compare, DragInOneViewMovesEveryView) {
  const std::string args = "'" + kCornell + "' --compare grid,kd --pixel 100,150";
  const json still = runCompare(args, "compare-still");
  const json dragged = runCompare(args + " --drag-view 1:80,-30", "compare-dragged");
  ASSERT_EQ(dragged["views"].size(), 2u);
  const json& before = still["views"][0]["view"]["camera"];
  const json& after = dragged["views"][0]["view"]["camera"];
  EXPECT_NE(before["position"], after["position"]) << "dragging view 1 did not move view 0's camera";
  EXPECT_EQ(dragged["views"][1]["view"]["camera"], after);
  EXPECT_EQ(still["views"][1]["view"]["camera"], before);
}

TEST(Compare, BadCompareListsExit2WithOneLine) {
  const std::string damaged = kOut + "/compare-damaged.json";
  {
    std::ofstream out(damaged);
    out << "{\"format\": \"raystep-trace\", \"version\": 5, \"scene\": {\"path\": \"x\", \"hash\": "
           "\"fnv1a64:0000000000000000\", \"primitives\": 1}, \"walks\": []}\n";
  }
  const std::pair<std::string, std::string> cases[] = {
      {"'" + kCornell + "' --compare grid --pixel 1,1", "--compare 'grid': give 2 to 4"},
      {"'" + kCornell + "' --compare grid,kd,grid --pixel 1,1", "grid is listed twice"},
      {"'" + kCornell + "' --compare grid,quadtree --pixel 1,1", "unknown structure 'quadtree'"},
      {"'" + kCornell + "' --compare grid,kd,bvh,octree,bsp --pixel 1,1", "at most 4"},
      {"'" + kCornell + "' --compare kd,brute --pixel 1,1", "brute records no events"},
      {"'" + kCornell + "' --compare grid,kd", "--compare needs --pixel"},
      {"'" + kCornell + "' --compare grid,kd --pixel 9999,1", "outside the"},
      {"--trace '" + damaged + "'", "compare-damaged.json"}};
  for (const auto& [args, says] : cases) {
    GuiRun r = gui(args + " --quit", "compare_bad");
    EXPECT_EQ(r.code, 2) << args;
    std::istringstream lines(r.err);
    std::string line, errors;
    int n = 0;
    while (std::getline(lines, line))
      if (line.rfind("QStandardPaths", 0) != 0 && line.rfind("timing: ", 0) != 0) {
        ++n;
        errors += line + "\n";
      }
    EXPECT_EQ(n, 1) << args << ": " << errors;
    EXPECT_EQ(errors.rfind("error: ", 0), 0u) << args << ": " << errors;
    EXPECT_NE(errors.find(says), std::string::npos) << args << ": " << errors;
  }
}

}  // namespace
}  // namespace raystep::viztest
