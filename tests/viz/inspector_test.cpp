// The kd-tree's inspector in raystep-gui, run in scripted mode under Xvfb like viz_test.cpp: the SAH chart
// has one point per candidate that core's record_sah_curve gives for the node, per axis, and the same
// decision; the GUI's CSV export is the command line's `raystep sah`; the chart shows the three series'
// colours; the selected node's highlight is where its box projects in the 3D view; a click in the 3D view
// selects the leaf holding the picked point; a rebuild with another t_i keeps the node by its path; a bad
// node exits 2.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "raystep/accel/kdtree_build.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/io/scene_loader.h"
#include "viz_test_util.h"

namespace {

using namespace raystep::viztest;
using raystep::KdOptions;
using raystep::SahCurve;

const std::string kScene = kSourceDir + "/scenes/cornell.json";
const std::string kKd = "'" + kScene + "' --accel kd --window 1280x800";

const raystep::Geometry& cornell() {
  static const raystep::Scene scene = raystep::load_scene(kScene);
  return scene.geometry;
}

// The GUI's dump for a node chosen by the arguments, with the window's screenshot.
json inspect(const std::string& args, const std::string& tag) {
  std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json";
  GuiRun r = gui(kKd + " " + args + " --screenshot '" + png + "' --dump-state '" + st + "' --quit", tag);
  EXPECT_EQ(r.code, 0) << r.err;
  return r.code == 0 ? readJson(st) : json::object();
}

void expectSameCurve(const json& sah, const SahCurve& curve) {
  int per[3] = {0, 0, 0};
  for (const raystep::SahCandidate& c : curve.candidates) ++per[c.axis];
  ASSERT_TRUE(sah.contains("points")) << sah.dump();
  EXPECT_EQ(sah["node"].get<int>(), int(curve.node));
  EXPECT_EQ(sah["points"]["x"].get<int>(), per[0]);
  EXPECT_EQ(sah["points"]["y"].get<int>(), per[1]);
  EXPECT_EQ(sah["points"]["z"].get<int>(), per[2]);
  EXPECT_EQ(sah["candidates"].get<int>(), int(curve.candidates.size()));
  EXPECT_EQ(sah["n_prims"].get<int>(), int(curve.n_prims));
  EXPECT_FLOAT_EQ(sah["leaf_cost"].get<float>(), curve.leaf_cost);
  EXPECT_EQ(sah["leaf"].get<bool>(), curve.leaf);
  if (curve.leaf) {
    EXPECT_EQ(sah["leaf_reason"], raystep::leaf_reason_name(curve.leaf_reason));
  } else {
    ASSERT_TRUE(sah.contains("chosen"));
    EXPECT_EQ(sah["chosen"]["axis"], std::string(1, "xyz"[curve.axis]));
    EXPECT_FLOAT_EQ(sah["chosen"]["position"].get<float>(), curve.position);
    EXPECT_FLOAT_EQ(sah["chosen"]["cost"].get<float>(), curve.cost);
    EXPECT_EQ(sah["chosen"]["index"].get<int>(), curve.chosen);
  }
}

TEST(Inspector, ChartHasOnePointPerCandidate) {
  KdOptions options;  // the GUI's defaults are core's
  raystep::KdTreeData tree = raystep::build_kdtree(cornell(), options);
  // The root, an inner node below it, and the first leaf whose SAH search found planes (no_cheaper_split).
  int leafWithCandidates = -1;
  for (uint32_t n = 0; n < tree.nodes.size() && leafWithCandidates < 0; ++n)
    if (tree.nodes[n].is_leaf() && !raystep::record_sah_curve(cornell(), options, n).candidates.empty())
      leafWithCandidates = int(n);
  ASSERT_GE(leafWithCandidates, 0) << "the Cornell box's tree should have a leaf made by cost";
  for (int node : {0, 1, leafWithCandidates}) {
    json state = inspect("--node " + std::to_string(node), "inspector_node" + std::to_string(node));
    SahCurve curve = raystep::record_sah_curve(cornell(), options, uint32_t(node));
    SCOPED_TRACE("node " + std::to_string(node));
    expectSameCurve(state["sah"], curve);
    EXPECT_EQ(state["selected_node"].get<int>(), node);
    EXPECT_EQ(state["tree"]["current_row_node"].get<int>(), node) << "the tree view shows the node";
  }
  // By path: the node core finds at that path.
  json state = inspect("--node-path RL", "inspector_path_RL");
  uint32_t id = raystep::kd_node_by_path(tree, "RL");
  expectSameCurve(state["sah"], raystep::record_sah_curve(cornell(), options, id));
  EXPECT_EQ(state["tree"]["selected_path"], "RL");
}

TEST(Inspector, TreeViewMakesOnlyTheRowsShown) {
  // The torus knot's tree has thousands of nodes; going to a deep one opens only the branches on its path.
  std::string knot = kSourceDir + "/scenes/torus_knot.json";
  raystep::KdTreeData tree = raystep::build_kdtree(raystep::load_scene(knot).geometry, KdOptions{});
  uint32_t deep = 0;
  for (uint32_t n = 0; n < tree.nodes.size(); ++n)
    if (tree.info[n].depth > tree.info[deep].depth) deep = n;
  std::string st = kOut + "/inspector_knot.json";
  GuiRun r =
      gui("'" + knot + "' --accel kd --node " + std::to_string(deep) + " --dump-state '" + st + "' --quit",
          "inspector_knot");
  ASSERT_EQ(r.code, 0) << r.err;
  json s = readJson(st);
  EXPECT_EQ(s["tree"]["nodes"].get<size_t>(), tree.nodes.size());
  EXPECT_EQ(s["tree"]["current_row_node"].get<int>(), int(deep));
  // Two rows per level of the path and the root's: never the whole tree.
  EXPECT_LE(s["tree"]["rows_made"].get<int>(), 2 * tree.info[deep].depth + 3);
  EXPECT_LT(s["tree"]["rows_made"].get<size_t>() * 10, tree.nodes.size());
}

#ifdef RAYSTEP_CLI_EXE
TEST(Inspector, ExportedCsvIsTheCommandLinesCurve) {
  for (int node : {0, 2}) {
    std::string tag = "inspector_export" + std::to_string(node);
    std::string gcsv = kOut + "/" + tag + "_gui.csv", ccsv = kOut + "/" + tag + "_cli.csv";
    GuiRun r = gui(kKd + " --node " + std::to_string(node) + " --export-sah '" + gcsv + "' --quit", tag);
    ASSERT_EQ(r.code, 0) << r.err;
    std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' sah '" + kScene + "' --node " +
                      std::to_string(node) + " -o '" + ccsv + "' > /dev/null";
    ASSERT_EQ(std::system(cmd.c_str()), 0);
    std::string g = slurp(gcsv);
    EXPECT_FALSE(g.empty());
    EXPECT_EQ(g, slurp(ccsv)) << "the GUI's export and `raystep sah` differ for node " << node;
  }
}
#endif

TEST(Inspector, ScreenshotShowsTheThreeSeriesColours) {
  json state = inspect("--panel sah", "inspector_panel_sah");
  const json& sah = state["sah"];
  ASSERT_EQ(sah["node"].get<int>(), 0) << "--panel sah shows the root";
  ASSERT_TRUE(sah["visible"].get<bool>());
  raystep::Rgb8Image img = raystep::read_png_rgb8(kOut + "/inspector_panel_sah.png");
  // The same window with no node selected: the chart is empty, so any colour it shows then is not a series'.
  json empty = inspect("--panel kd", "inspector_panel_empty");
  ASSERT_FALSE(empty["sah"].contains("points"));
  ASSERT_EQ(empty["sah"]["viewport"], sah["viewport"]);
  raystep::Rgb8Image blank = raystep::read_png_rgb8(kOut + "/inspector_panel_empty.png");
  const json& vp = sah["viewport"];
  double x0 = vp[0], y0 = vp[1], x1 = x0 + vp[2].get<double>() - 1, y1 = y0 + vp[3].get<double>() - 1;
  ASSERT_GT(vp[2].get<int>(), 200);
  ASSERT_GT(vp[3].get<int>(), 120);
  for (const char* series : {"x", "y", "z", "leaf_cost"}) {
    if (series != std::string("leaf_cost")) ASSERT_GT(sah["points"][series].get<int>(), 0) << series;
    int n = countColor(img, sah["colors"][series], x0, y0, x1, y1, 24);
    EXPECT_GT(n, 40) << "the " << series << " series' colour in the chart";
    EXPECT_LT(countColor(blank, sah["colors"][series], x0, y0, x1, y1, 24), 5)
        << series << " in the empty chart";
  }
}

TEST(Inspector, SelectedNodeIsHighlightedWhereItsBoxProjects) {
  raystep::KdTreeData tree = raystep::build_kdtree(cornell(), KdOptions{});
  ASSERT_FALSE(tree.nodes[0].is_leaf());
  for (int node : {1, int(tree.nodes[0].above_child())}) {
    std::string tag = "inspector_highlight" + std::to_string(node);
    json state = inspect("--node " + std::to_string(node), tag);
    raystep::Rgb8Image img = raystep::read_png_rgb8(kOut + "/" + tag + ".png");
    const json& view = state["view"];
    ASSERT_TRUE(view.contains("selected_node")) << "node " << node;
    EXPECT_EQ(view["selected_node"]["node"].get<int>(), node);
    const json& corners = view["selected_node"]["projected_corners"];
    ASSERT_EQ(corners.size(), 8u);
    ScreenBox b = boxOf(corners);
    const json& color = view["colors"]["selected_node"];
    int inside = countColor(img, color, b.x0 - 2, b.y0 - 2, b.x1 + 2, b.y1 + 2, 10);
    EXPECT_GT(inside, 40) << "selected node " << node << "'s colour inside its projected box";
    const json& vp = view["viewport"];
    double vx0 = vp[0], vy0 = vp[1];
    int all =
        countColor(img, color, vx0, vy0, vx0 + vp[2].get<double>() - 1, vy0 + vp[3].get<double>() - 1, 10);
    EXPECT_GT(inside, all * 9 / 10) << "the selection colour appears away from the selected node";
  }
  // Nothing selected: the colour is nowhere in the 3D view.
  json none = inspect("", "inspector_highlight_none");
  raystep::Rgb8Image img = raystep::read_png_rgb8(kOut + "/inspector_highlight_none.png");
  const json& vp = none["view"]["viewport"];
  double vx0 = vp[0], vy0 = vp[1];
  EXPECT_FALSE(none["view"].contains("selected_node"));
  EXPECT_EQ(countColor(img, none["view"]["colors"]["selected_node"], vx0, vy0, vx0 + vp[2].get<double>() - 1,
                       vy0 + vp[3].get<double>() - 1, 10),
            0);
}

// The build split by split (--build-planes): the 3D view draws the plane of every inner node made before the
// selected one (the depth-first build order is the node ids'), in the built planes' colour, and none when off.
TEST(Inspector, BuildPlanesAreTheNodesSplitBeforeTheSelectedOne) {
  raystep::KdTreeData tree = raystep::build_kdtree(cornell(), KdOptions{});
  // The built planes' colour in the 3D view of a state (the scene's own pixels may come near it).
  auto planePixels = [](const json& view, const std::string& tag) {
    raystep::Rgb8Image img = raystep::read_png_rgb8(kOut + "/" + tag + ".png");
    const json& vp = view["viewport"];
    const double vx0 = vp[0], vy0 = vp[1];
    return countColor(img, view["colors"]["built_plane"], vx0, vy0, vx0 + vp[2].get<double>() - 1,
                      vy0 + vp[3].get<double>() - 1, 6);
  };
  const int node3 = 3;
  json off = inspect("--node " + std::to_string(node3), "inspector_build_planes_off");
  EXPECT_FALSE(off["view"].contains("build_planes"));
  const int background = planePixels(off["view"], "inspector_build_planes_off");
  for (int node : {0, node3, int(tree.nodes[0].above_child())}) {
    int inner = 0;
    for (int id = 0; id < node; ++id) inner += !tree.nodes[size_t(id)].is_leaf();
    const std::string tag = "inspector_build_planes" + std::to_string(node);
    json state = inspect("--node " + std::to_string(node) + " --build-planes", tag);
    const json& view = state["view"];
    ASSERT_TRUE(view.contains("build_planes")) << node;
    EXPECT_EQ(view["build_planes"].get<int>(), inner) << "node " << node;
    if (node == node3) {
      ASSERT_GT(inner, 0);
      EXPECT_GT(planePixels(view, tag), background + 30) << "the planes made before node 3 are drawn";
    }
  }
}

TEST(Inspector, ClickIn3DViewSelectsTheLeafHoldingThePoint) {
  // Where the 3D view is: from a first run; then click its centre (the back wall of the Cornell box).
  json first = inspect("--panel sah", "inspector_pick_layout");
  const json& vp = first["view"]["viewport"];
  int cx = vp[0].get<int>() + vp[2].get<int>() / 2, cy = vp[1].get<int>() + vp[3].get<int>() / 2;
  json state = inspect("--pick-3d " + std::to_string(cx) + "," + std::to_string(cy), "inspector_pick");
  ASSERT_TRUE(state["view"].contains("picked_point"));
  ASSERT_TRUE(state["view"].contains("selected_node"));
  const json& p = state["view"]["picked_point"];
  const json& sel = state["view"]["selected_node"];
  for (int a = 0; a < 3; ++a) {
    EXPECT_GE(p[a].get<double>(), sel["min"][a].get<double>() - 1e-4) << "axis " << a;
    EXPECT_LE(p[a].get<double>(), sel["max"][a].get<double>() + 1e-4) << "axis " << a;
  }
  int node = sel["node"].get<int>();
  raystep::KdTreeData tree = raystep::build_kdtree(cornell(), KdOptions{});
  EXPECT_TRUE(tree.nodes[size_t(node)].is_leaf()) << "node " << node;
  EXPECT_EQ(state["selected_node"].get<int>(), node);
  EXPECT_EQ(state["tree"]["current_row_node"].get<int>(), node);
  EXPECT_EQ(state["sah"]["node"].get<int>(), node);
  EXPECT_TRUE(state["sah"]["leaf"].get<bool>());
}

TEST(Inspector, RebuildWithAnotherCostKeepsTheNodeByPath) {
  // t_i edited in the structure panel: the tree is rebuilt, the node at the same path is selected and shown.
  json state = inspect("--node-path LR --edit-ti 20", "inspector_rebuild");
  KdOptions options;
  options.t_i = 20.f;
  raystep::KdTreeData tree = raystep::build_kdtree(cornell(), options);
  uint32_t id = raystep::kd_node_by_path(tree, "LR");
  EXPECT_EQ(state["tree"]["selected_path"], "LR");
  EXPECT_EQ(state["selected_node"].get<int>(), int(id));
  expectSameCurve(state["sah"], raystep::record_sah_curve(cornell(), options, id));
  EXPECT_FLOAT_EQ(state["sah"]["leaf_cost"].get<float>(), 20.f * state["sah"]["n_prims"].get<float>());
}

TEST(Inspector, BadNodeExits2) {
  struct Case {
    std::string args, message;
  };
  for (const Case& c :
       {Case{"--node 100000", "error: --node 100000: the kd-tree has"},
        Case{"--node -3", "error: --node -3: the kd-tree has"},
        Case{"--node-path LLLLLLLLLLLLLLLLLLLLLLLLLLLL", "error: --node-path 'LLLLLLLLLLLLLLLLLLLLLLLLLLLL'"},
        Case{"--node-path LXR", "error: --node-path 'LXR'"},
        Case{"--panel nonsense", "error: --panel 'nonsense'"}}) {
    GuiRun r = gui(kKd + " " + c.args + " --quit", "inspector_bad");
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << c.args << "\n" << r.err;
    size_t lines = 0;
    for (size_t at = r.err.find("error:"); at != std::string::npos; at = r.err.find("error:", at + 1))
      ++lines;
    EXPECT_EQ(lines, 1u) << "one error line: " << r.err;
  }
  // No kd-tree to look into: the grid.
  GuiRun r = gui("'" + kScene + "' --accel grid --node 1 --quit", "inspector_bad_grid");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("error: --node: no tree"), std::string::npos) << r.err;
}

}  // namespace
