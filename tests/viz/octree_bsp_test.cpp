// The octree and the general BSP tree in raystep-gui, scripted and under Xvfb as the other GUI tests: a scene
// opened with --accel octree or bsp, a pixel traced, the walk stepped to an inner node. The trace the GUI
// exports is the reference: the state panel must name that node, its interval and (BSP) its plane and
// t* = (d - n.o) / (n.dir) or (octree) the child the ray enters first; the 3D view must draw the BSP node's
// convex cell (inside its ancestors' half-spaces) with its plane clipped to it, and the octree cell's
// children in the order the trace visits them.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <string>

#include "viz_test_util.h"

namespace {

using namespace raystep::viztest;

const std::string kTilted = kSourceDir + "/scenes/tilted_plane.json";
const std::string kCornell = kSourceDir + "/scenes/cornell.json";

bool has(const json& j, const std::string& text) {
  return j.get<std::string>().find(text) != std::string::npos;
}

std::string fmt(double v, int digits = 5) {  // as the panels (5 digits) and Why (4) print a number
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

bool slanted(const json& node) {  // a plane that is not the kd-tree's
  if (!node.contains("normal")) return false;
  for (const json& c : node["normal"])
    if (std::fabs(c.get<double>()) == 1.0) return false;
  return true;
}

const json* nodeOf(const json& trace, int id) {
  for (const json& n : trace["geometry"]["nodes"])
    if (n["id"] == id) return &n;
  return nullptr;
}

// The 1-based number among the ray's node events of the first event at an inner node at least minDepth deep
// (and, if asked, with a slanted plane), and that event; 0 if none.
int innerNodeEvent(const json& trace, int minDepth, json* event, bool needSlanted = false) {
  int k = 0;
  const json& events = trace["rays"][0]["events"];
  for (size_t i = 0; i + 1 < events.size(); ++i) {
    if (events[i]["type"] != "node") continue;
    ++k;
    const json* n = nodeOf(trace, events[i]["node"].get<int>());
    if (n && !(*n)["leaf"].get<bool>() && (*n)["depth"].get<int>() >= minDepth &&
        (!needSlanted || slanted(*n))) {
      *event = events[i];
      return k;
    }
  }
  return 0;
}

TEST(OctreeBsp, BspStepShowsThePlaneTStarAndTheConvexCell) {
  const std::string base = "'" + kTilted + "' --accel bsp --pixel 160,130 --window 1280x800";
  const std::string tracePath = kOut + "/bsp_trace.json";
  GuiRun r = gui(base + " --export-trace '" + tracePath + "' --quit", "bsp_export");
  ASSERT_EQ(r.code, 0) << r.err;
  json trace = readJson(tracePath);
  ASSERT_EQ(trace["structure"]["kind"], "bsp");
  json e;
  int k = innerNodeEvent(trace, 2, &e, true);
  ASSERT_GT(k, 0) << "no inner node with a slanted plane at depth 2 or more on the ray";
  const json* n = nodeOf(trace, e["node"].get<int>());
  ASSERT_NE(n, nullptr);

  const std::string st = kOut + "/bsp_node.json", png = kOut + "/bsp_node.png";
  r = gui(base + " --step-to node:" + std::to_string(k) + " --dump-state '" + st + "' --screenshot-3d '" +
              png + "' --quit",
          "bsp_node");
  ASSERT_EQ(r.code, 0) << r.err;
  json s = readJson(st);
  EXPECT_EQ(s["event_type"], "node");
  EXPECT_TRUE(has(s["structure_info"], "BSP tree:")) << s["structure_info"];
  const json& p = s["panels"];
  // The node, its interval and its plane, as the trace has them.
  EXPECT_TRUE(has(p["nodeLabel"], "<b>" + std::to_string(e["node"].get<int>()) + "</b>")) << p["nodeLabel"];
  EXPECT_TRUE(has(p["nodeLabel"], "[t_min, t_max] = [" + fmt(e["t_min"].get<double>()) + ", " +
                                      fmt(e["t_max"].get<double>()) + "]"))
      << p["nodeLabel"] << " " << e.dump();
  EXPECT_TRUE(has(p["nodeLabel"], "plane n = (")) << p["nodeLabel"];
  // t* = (d - n.o) / (n.dir) from the trace's plane and ray.
  const json& ray = trace["rays"][0];
  double no = 0, nd = 0;
  for (int a = 0; a < 3; ++a) {
    no += (*n)["normal"][a].get<double>() * ray["origin"][a].get<double>();
    nd += (*n)["normal"][a].get<double>() * ray["direction"][a].get<double>();
  }
  const double tStar = ((*n)["offset"].get<double>() - no) / nd;
  EXPECT_TRUE(has(p["crossingLabel"], "<b>" + fmt(float(tStar)) + "</b> = (d - n.o) / (n.dir)"))
      << p["crossingLabel"] << " t* " << tStar;
  EXPECT_TRUE(has(p["ruleLabel"], "t* = (d - n.o) / (n.dir) = " + fmt(float(tStar), 4))) << p["ruleLabel"];
  EXPECT_FALSE(has(p["ruleLabel"], "splits x at")) << p["ruleLabel"];
  // The 3D view: the node's convex cell inside every ancestor's half-space, and its plane's polygon.
  const json& cn = s["view"]["current_node"];
  EXPECT_EQ(cn["node"], e["node"]);
  ASSERT_TRUE(cn.contains("normal")) << cn.dump();
  EXPECT_GE(cn["cell_faces"].get<int>(), 4);
  EXPECT_GE(cn["plane_polygon_points"].get<int>(), 3);
  int checked = 0;
  for (const json* c = n; (*c)["parent"].get<int>() >= 0;) {
    const json* parent = nodeOf(trace, (*c)["parent"].get<int>());
    ASSERT_NE(parent, nullptr);
    const bool below = (*c)["id"].get<int>() == (*parent)["id"].get<int>() + 1;
    for (const json& v : cn["cell_vertices"]) {
      double side = -(*parent)["offset"].get<double>(), scale = std::fabs((*parent)["offset"].get<double>());
      for (int a = 0; a < 3; ++a) {
        side += (*parent)["normal"][a].get<double>() * v[a].get<double>();
        scale += std::fabs(v[a].get<double>());
      }
      EXPECT_TRUE(below ? side <= 1e-6 * scale : side >= -1e-6 * scale)
          << "vertex " << v.dump() << " on the wrong side of node " << (*parent)["id"] << "'s plane";
      ++checked;
    }
    c = parent;
  }
  EXPECT_GT(checked, 0);
  // The current cell's yellow and the plane's pale yellow are on the screen.
  raystep::Rgb8Image img = raystep::read_png_rgb8(png);
  EXPECT_GT(countColor(img, s["view"]["colors"]["current_cell"], 0, 0, img.width, img.height, 10), 30);
}

TEST(OctreeBsp, OctreeStepShowsTheCellAndItsChildOrder) {
  const std::string base =
      "'" + kCornell + "' --accel octree --octree-leaf 4 --pixel 100,150 --window 1280x800";
  const std::string tracePath = kOut + "/octree_trace.json";
  GuiRun r = gui(base + " --export-trace '" + tracePath + "' --quit", "octree_export");
  ASSERT_EQ(r.code, 0) << r.err;
  json trace = readJson(tracePath);
  ASSERT_EQ(trace["structure"]["kind"], "octree");
  json e;
  int k = innerNodeEvent(trace, 1, &e);
  ASSERT_GT(k, 0) << "no inner cell below the root on the ray";
  const json* n = nodeOf(trace, e["node"].get<int>());
  ASSERT_NE(n, nullptr);
  ASSERT_EQ((*n)["children"].size(), 8u);
  // The children the trace visits under this cell, in order: node events one level down before its pop.
  std::vector<int> visited;
  const json& events = trace["rays"][0]["events"];
  bool in = false;
  for (const json& x : events) {
    if (x["type"] == "node" && x["node"] == e["node"])
      in = true;
    else if (in && x["type"] == "pop" && x["node"] == e["node"])
      break;
    else if (in && x["type"] == "node" && x["depth"].get<int>() == e["depth"].get<int>() + 1)
      visited.push_back(x["node"].get<int>());
  }
  ASSERT_FALSE(visited.empty());

  const std::string st = kOut + "/octree_node.json", png = kOut + "/octree_node.png";
  r = gui(base + " --step-to node:" + std::to_string(k) + " --dump-state '" + st + "' --screenshot-3d '" +
              png + "' --quit",
          "octree_node");
  ASSERT_EQ(r.code, 0) << r.err;
  json s = readJson(st);
  EXPECT_TRUE(has(s["structure_info"], "octree:")) << s["structure_info"];
  const json& p = s["panels"];
  EXPECT_TRUE(
      has(p["nodeLabel"], "<b>" + std::to_string(e["node"].get<int>()) + "</b> (inner cell, 8 children)"))
      << p["nodeLabel"];
  EXPECT_TRUE(has(p["nodeLabel"], "[t_min, t_max] = [" + fmt(e["t_min"].get<double>()) + ", " +
                                      fmt(e["t_max"].get<double>()) + "]"))
      << p["nodeLabel"];
  EXPECT_TRUE(has(p["crossingLabel"], "entry plane")) << p["crossingLabel"];
  EXPECT_TRUE(has(p["crossingLabel"], "<br>1. " + std::to_string(visited[0]) + " [")) << p["crossingLabel"];
  EXPECT_TRUE(has(p["ruleLabel"], "Entry plane")) << p["ruleLabel"];
  EXPECT_TRUE(has(p["ruleLabel"], "First child: " + std::to_string(visited[0]))) << p["ruleLabel"];
  EXPECT_FALSE(has(p["ruleLabel"], "far child")) << p["ruleLabel"];
  // The 3D view draws the children in the trace's order (the planes' order begins with the visited ones).
  const json& drawn = s["view"]["octree_children_drawn"];
  ASSERT_GE(drawn.size(), visited.size());
  for (size_t i = 0; i < visited.size(); ++i) EXPECT_EQ(drawn[i], visited[i]) << i;
  raystep::Rgb8Image img = raystep::read_png_rgb8(png);
  EXPECT_GT(countColor(img, s["view"]["colors"]["bvh_child_first"], 0, 0, img.width, img.height, 10), 20)
      << "the first child's outline";
}

// The panel's options reach the build: a smaller K gives more cells; k-DOP directions alone no primitive
// planes, autopartition alone only primitive planes (the info line counts the planes by source).
TEST(OctreeBsp, OctreeAndBspOptionsReachTheBuild) {
  auto info = [](const std::string& args, const std::string& tag) {
    const std::string st = kOut + "/" + tag + ".json";
    GuiRun r = gui(args + " --dump-state '" + st + "' --quit", tag);
    EXPECT_EQ(r.code, 0) << r.err;
    return readJson(st)["structure_info"].get<std::string>();
  };
  auto cells = [](const std::string& text) { return std::stoi(text.substr(text.find(": ") + 2)); };
  const std::string fine = info("'" + kCornell + "' --accel octree --octree-leaf 1", "octree_k1");
  const std::string coarse = info("'" + kCornell + "' --accel octree --octree-leaf 16", "octree_k16");
  EXPECT_GT(cells(fine), cells(coarse)) << fine << " / " << coarse;
  const std::string kdop = info("'" + kTilted + "' --accel bsp --bsp-directions kdop", "bsp_kdop");
  EXPECT_NE(kdop.find(", 0 primitive"), std::string::npos) << kdop;
  const std::string own = info("'" + kTilted + "' --accel bsp --bsp-directions autopartition", "bsp_auto");
  EXPECT_NE(own.find("planes: 0 axis, 0 face diagonal, 0 body diagonal"), std::string::npos) << own;
}

// --node-path (core's tree_nodes.h: path to id) selects the node whose path the tree view finds back from its
// parents (the model's id to path), and the 3D view draws that node; --node ID selects it by id.
TEST(OctreeBsp, NodePathSelectsTheOctreesAndBspTreesNode) {
  struct Case {
    std::string args, path;
  };
  for (const Case& c :
       {Case{"'" + kCornell + "' --accel octree --octree-leaf 2", "03"},
        Case{"'" + kCornell + "' --accel octree --octree-leaf 2", "0"},
        Case{"'" + kTilted + "' --accel bsp", "LR"}, Case{"'" + kTilted + "' --accel bsp", "RL"}}) {
    const std::string tag = "node_path_" + c.path, st = kOut + "/" + tag + ".json";
    GuiRun r = gui(c.args + " --node-path " + c.path + " --dump-state '" + st + "' --quit", tag);
    ASSERT_EQ(r.code, 0) << c.args << ": " << r.err;
    const json s = readJson(st);
    const int node = s["selected_node"].get<int>();
    EXPECT_GT(node, 0) << c.args << " " << c.path;
    EXPECT_EQ(s["tree"]["selected_path"], c.path) << c.args;
    EXPECT_EQ(s["tree"]["current_row_node"], node);
    EXPECT_EQ(s["view"]["selected_node"]["node"], node);
    // The same node by id.
    const std::string st2 = kOut + "/" + tag + "_id.json";
    r = gui(c.args + " --node " + std::to_string(node) + " --dump-state '" + st2 + "' --quit", tag + "_id");
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_EQ(readJson(st2)["tree"]["selected_path"], c.path);
  }
}

TEST(OctreeBsp, OctreeBspBadOptionsExit2) {
  for (const std::string& args :
       {std::string("--accel octree --octree-leaf 0"), std::string("--accel bsp --bsp-directions sideways"),
        std::string("--accel bsp --bsp-candidates 0")}) {
    GuiRun r = gui("'" + kTilted + "' " + args + " --quit", "octree_bsp_bad");
    EXPECT_EQ(r.code, 2) << args << ": " << r.err;
    const std::string name = args.substr(args.rfind("--"), args.rfind(' ') - args.rfind("--"));
    EXPECT_NE(r.err.find(name), std::string::npos) << args << ": " << r.err;
  }
}

}  // namespace
