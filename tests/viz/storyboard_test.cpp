// The storyboard contract: `raystep replay --step N --format json` says what the debugger's state panel
// says at the same step (the Why text, the event, the cell or node, the stack, the mailbox, the nearest hit,
// the counters), on a grid, a kd-tree and an 8-wide BVH, and for each walk of a multi-walk trace in the
// side-by-side view.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <regex>
#include <string>

#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

const std::string kCli = RAYSTEP_CLI_EXE;
const std::string kCornell = kSourceDir + "/scenes/cornell.json";

int run(const std::string& cmd) {
  return std::system((cmd + " > /dev/null").c_str());
}

json replayState(const std::string& trace, int walk, int step, const std::string& tag) {
  const std::string out = kOut + "/" + tag + ".replay.json";
  EXPECT_EQ(run("'" + kCli + "' replay '" + trace + "' --walk " + std::to_string(walk) + " --step " +
                std::to_string(step) + " --format json -o '" + out + "'"),
            0);
  json doc = readJson(out);
  EXPECT_EQ(doc.value("format", ""), "raystep-replay");
  EXPECT_EQ(doc.value("version", 0), 1);
  return doc["walks"][0]["rays"][0]["states"][0];
}

std::string htmlEscaped(const std::string& s) {
  std::string o;
  for (char c : s)
    o += c == '<' ? "&lt;" : c == '>' ? "&gt;" : c == '&' ? "&amp;" : c == '"' ? "&quot;" : std::string(1, c);
  return o;
}

// "name 12" pairs of a counters label ("cells 11<br>primitive tests 1 &nbsp; hits 1 &nbsp; mailbox hits 0").
int counter(const std::string& label, const std::string& name) {
  std::smatch m;
  const std::regex re("(^|[ ;>])" + name + " ([0-9]+)");
  EXPECT_TRUE(std::regex_search(label, m, re)) << name << " in " << label;
  return m.size() > 2 ? std::stoi(m[2]) : -1;
}

int leadingInt(const std::string& s) {
  std::smatch m;
  EXPECT_TRUE(std::regex_search(s, m, std::regex("-?[0-9]+"))) << s;
  return m.empty() ? -1 : std::stoi(m[0]);
}

void expectPanelIsState(const json& panels, const json& s, const std::string& kind) {
  SCOPED_TRACE(kind + " step " + std::to_string(s.value("step", -1)));
  EXPECT_EQ(panels.value("ruleLabel", ""), s.value("why", "?"));
  EXPECT_EQ(panels.value("eventLabel", ""), "<b>Event</b> " + htmlEscaped(s.value("line", "?")));
  const std::string counters = panels.value("countersLabel", "");
  const json& k = s["counters"];
  EXPECT_EQ(counter(counters, "primitive tests"), k["prim_tests"]);
  EXPECT_EQ(counter(counters, "hits"), k["prim_hits"]);
  EXPECT_EQ(counter(counters, "mailbox hits"), k["mailbox_hits"]);
  if (kind == "grid") EXPECT_EQ(counter(counters, "cells"), k["cells"]);
  if (kind != "grid") {
    EXPECT_EQ(counter(counters, "nodes"), k["nodes"]);
    EXPECT_EQ(counter(counters, "pushes"), k["pushes"]);
    EXPECT_EQ(counter(counters, "pops"), k["pops"]);
  }
  if (kind == "bvh8") {
    EXPECT_EQ(counter(counters, "box tests"), k["box_tests"]);
    EXPECT_EQ(counter(counters, "skips"), int(s["skipped_nodes"].size()));
  }
  if (s["cell"].is_null()) {
    if (kind == "grid") EXPECT_NE(panels.value("cellLabel", "").find("not in the grid"), std::string::npos);
  } else {
    const json& c = s["cell"]["index"];
    EXPECT_EQ(panels.value("cellLabel", ""), "<b>(" + std::to_string(int(c[0])) + ", " +
                                                 std::to_string(int(c[1])) + ", " +
                                                 std::to_string(int(c[2])) + ")</b>");
  }
  if (s["nearest"].is_null()) {
    EXPECT_EQ(panels.value("nearestLabel", "").rfind("none", 0), 0u) << panels.value("nearestLabel", "");
  } else {
    const std::string nearest = panels.value("nearestLabel", "");
    EXPECT_EQ(leadingInt(nearest), s["nearest"]["prim"]);
    const std::string status = s["nearest"]["status"];
    EXPECT_NE(nearest.find("(" + status), std::string::npos) << nearest << " vs " << status;
  }
  if (kind != "grid") {
    if (!s["node"].is_null()) EXPECT_EQ(leadingInt(panels.value("nodeLabel", "")), s["node"]["id"]);
    // The stack, top first in the panel, bottom first in the storyboard.
    const json& rows = panels["stack"];
    const json& stack = s["stack"];
    ASSERT_EQ(rows.size(), stack.size());
    for (size_t r = 0; r < rows.size(); ++r) {
      const json& e = stack[stack.size() - 1 - r];
      EXPECT_EQ(leadingInt(rows[r][0]), e["node"]);
      EXPECT_EQ(std::stoi(std::string(rows[r][1])), e["depth"]);
    }
  }
  const json& rows = panels["mailbox"];
  const json& mailbox = s["mailbox"];
  ASSERT_EQ(rows.size(), mailbox.size());
  for (size_t r = 0; r < rows.size(); ++r) {
    EXPECT_EQ(std::stoi(std::string(rows[r][0])), mailbox[r]["prim"]);
    EXPECT_EQ(std::string(rows[r][2]).rfind("hit", 0) == 0, bool(mailbox[r]["hit"]));
    EXPECT_EQ(std::stoi(std::string(rows[r][3])), mailbox[r]["skips"]);
  }
}

// Steps worth comparing: the first primitive test, a step with the stack at its fullest, the middle and the
// last.
std::vector<int> interestingSteps(const json& events) {
  int firstTest = -1, deepest = -1, depth = 0, most = -1;
  for (size_t i = 0; i < events.size(); ++i) {
    const std::string type = events[i]["type"];
    if (type == "prim_test" && firstTest < 0) firstTest = int(i);
    depth += type == "push" ? 1 : type == "pop" ? -1 : 0;
    if (depth > most) most = depth, deepest = int(i);
  }
  std::vector<int> steps;
  for (int k : {firstTest, deepest, int(events.size()) / 2, int(events.size()) - 1})
    if (k >= 0 && std::find(steps.begin(), steps.end(), k) == steps.end()) steps.push_back(k);
  return steps;
}

TEST(Storyboard, ReplayOutputIsTheStatePanelOnGridKdAndBvh8) {
  int compared = 0;
  for (const std::string accel : {"grid", "kd", "bvh8"}) {
    const std::string trace = kOut + "/storyboard_" + accel + ".trace.json";
    ASSERT_EQ(run("'" + kCli + "' trace '" + kCornell + "' --accel " + accel +
                  " --pixel 160,200 --size 320x240 -o '" + trace + "'"),
              0);
    const json events = readJson(trace)["rays"][0]["events"];
    ASSERT_GT(events.size(), 5u);
    for (int step : interestingSteps(events)) {
      const std::string tag = "storyboard_" + accel + "_" + std::to_string(step);
      const std::string st = kOut + "/" + tag + ".state.json";
      GuiRun r = gui("'" + trace + "' --window 1280x800 --step " + std::to_string(step) + " --dump-state '" +
                         st + "' --quit",
                     tag);
      ASSERT_EQ(r.code, 0) << r.err;
      const json gui = readJson(st);
      ASSERT_EQ(gui["step"], step);
      expectPanelIsState(gui["panels"], replayState(trace, 0, step, tag), accel);
      ++compared;
    }
  }
  EXPECT_GE(compared, 9);
}

TEST(Storyboard, ReplayOutputIsEachSideBySideWalksState) {
  const std::string trace = kOut + "/storyboard_multi.trace.json";
  ASSERT_EQ(run("'" + kCli + "' trace '" + kCornell +
                "' --accel grid,kd,bvh --pixel 160,200 --size 320x240 -o '" + trace + "'"),
            0);
  int compared = 0;
  for (const char* slider : {"300", "1000"}) {
    const std::string tag = std::string("storyboard_multi_") + slider, st = kOut + "/" + tag + ".state.json";
    GuiRun r = gui(
        "'" + trace + "' --window 1280x800 --slider " + slider + " --dump-state '" + st + "' --quit", tag);
    ASSERT_EQ(r.code, 0) << r.err;
    const json views = readJson(st)["compare"]["views"];
    ASSERT_EQ(views.size(), 3u);
    for (size_t w = 0; w < views.size(); ++w) {
      const json& v = views[w];
      const int step = v["session_step"];
      const json s = replayState(trace, int(w), step, tag + "_" + std::to_string(w));
      SCOPED_TRACE(std::string(v["structure"]) + " step " + std::to_string(step));
      EXPECT_EQ(s["step"], step);
      EXPECT_EQ(v["event_type"], s["type"]);
      EXPECT_EQ(v["at_t"]["prim_tests"], s["counters"]["prim_tests"]);
      EXPECT_EQ(v["at_t"]["mailbox_hits"], s["counters"]["mailbox_hits"]);
      EXPECT_EQ(v["at_t"]["box_tests"], s["counters"]["box_tests"]);
      EXPECT_EQ(int(v["at_t"]["steps"]), int(s["counters"]["cells"]) + int(s["counters"]["nodes"]));
      if (v["view"].contains("stack_nodes")) {
        json stack = json::array();
        for (const json& e : s["stack"]) stack.push_back(e["node"]);
        EXPECT_EQ(v["view"]["stack_nodes"], stack);
      }
      ++compared;
    }
  }
  EXPECT_EQ(compared, 6);
}

}  // namespace
}  // namespace raystep::viztest
