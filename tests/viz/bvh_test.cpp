// The BVH in raystep-gui, scripted and under Xvfb as the other GUI tests: a BVH trace (two leaves whose boxes
// overlap, tests/viz/data/bvh_overlap_trace.json) opened alone and stepped to the children's box tests and to
// the skip, and the Cornell box built as a BVH from the command line. Checks the state panel's texts, what
// the 3D view says it drew and the screenshot's pixels where it drew them.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "raystep/io/image_io.h"
#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

const std::string kTrace = std::string(RAYSTEP_SOURCE_DIR) + "/tests/viz/data/bvh_overlap_trace.json";
const std::string kCornell = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";

bool has(const json& j, const std::string& text) {
  return j.get<std::string>().find(text) != std::string::npos;
}

struct Snap {
  json state;
  raystep::Rgb8Image img;
};

Snap snap(const std::string& args, const std::string& tag) {
  std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json";
  GuiRun r =
      gui(args + " --window 1280x800 --screenshot '" + png + "' --dump-state '" + st + "' --quit", tag);
  EXPECT_EQ(r.code, 0) << r.err;
  return {readJson(st), raystep::read_png_rgb8(png)};
}

// After the second box test: both children's boxes hit, their intervals in the state panel, the nearer first
// and the push; the 3D view draws both boxes in their two colours and outlines where they overlap.
TEST(Bvh, ChildrenBoxesOverlapInTheViewAndThePanel) {
  Snap s = snap("'" + kTrace + "' --step 3", "bvh_children");
  const json& p = s.state["panels"];
  EXPECT_EQ(s.state["event_type"], "box_test");
  EXPECT_TRUE(has(p["crossingLabel"], "child 1: [2.8, 3.2]")) << p["crossingLabel"];
  EXPECT_TRUE(has(p["crossingLabel"], "child 2: [2.9, 4]")) << p["crossingLabel"];
  EXPECT_TRUE(has(p["crossingLabel"], "nearer first</b>: enter 1; pushed 2")) << p["crossingLabel"];
  EXPECT_TRUE(has(p["ruleLabel"], "bounding volumes can overlap")) << p["ruleLabel"];
  EXPECT_TRUE(has(p["countersLabel"], "box tests 2")) << p["countersLabel"];
  const json& view = s.state["view"];
  ASSERT_TRUE(view.contains("bvh")) << view.dump(1);
  const json& drawn = view["bvh"]["children_drawn"];
  ASSERT_EQ(drawn.size(), 2u);
  EXPECT_EQ(view["bvh"]["overlaps_drawn"], json::array({json::array({1, 2})}));
  // Each child's outline colour where its box projects.
  const char* colours[2] = {"bvh_child_first", "bvh_child_other"};
  for (size_t k = 0; k < 2; ++k) {
    const ScreenBox b = boxOf(drawn[k]["projected_corners"]);
    int n = countColor(s.img, view["colors"][colours[k]], b.x0 - 2, b.y0 - 2, b.x1 + 2, b.y1 + 2, 12);
    EXPECT_GT(n, 20) << colours[k] << " inside its projected box " << b.x0 << "," << b.y0 << " .. " << b.x1
                     << "," << b.y1;
  }
  const json& vp = view["viewport"];
  EXPECT_GT(
      countColor(s.img, view["colors"]["bvh_overlap"], vp[0], vp[1],
                 vp[0].get<double>() + vp[2].get<double>(), vp[1].get<double>() + vp[3].get<double>(), 12),
      20)
      << "the overlap's outline";
}

// Before the box tests the order is not known yet: the panel says so and the view draws no child yet.
TEST(Bvh, OrderIsUnknownBeforeTheBoxTests) {
  Snap s = snap("'" + kTrace + "' --step 1", "bvh_node");
  EXPECT_TRUE(has(s.state["panels"]["crossingLabel"], "child 1: <i>?</i>"))
      << s.state["panels"]["crossingLabel"];
  EXPECT_TRUE(has(s.state["panels"]["crossingLabel"], "order: ?")) << s.state["panels"]["crossingLabel"];
  EXPECT_EQ(s.state["view"]["bvh"]["children_drawn"].size(), 0u);
}

// The skip: the stopping rule with its numbers, the node drawn as skipped, the leaf's Why without a mailbox.
TEST(Bvh, SkipShowsTheStoppingRule) {
  Snap s = snap("'" + kTrace + "' --step 9", "bvh_skip");
  EXPECT_EQ(s.state["event_type"], "skip");
  EXPECT_TRUE(has(s.state["panels"]["ruleLabel"], "skip: t_near = 2.9 > t of the nearest hit = 2.892"))
      << s.state["panels"]["ruleLabel"];
  EXPECT_EQ(s.state["view"]["bvh"]["skipped_nodes"], json::array({2}));
  EXPECT_TRUE(has(s.state["panels"]["countersLabel"], "skips 1")) << s.state["panels"]["countersLabel"];
  const json& view = s.state["view"];
  const json& vp = view["viewport"];
  EXPECT_GT(
      countColor(s.img, view["colors"]["bvh_skipped"], vp[0], vp[1],
                 vp[0].get<double>() + vp[2].get<double>(), vp[1].get<double>() + vp[3].get<double>(), 12),
      20)
      << "the skipped node's outline";
  Snap leaf = snap("'" + kTrace + "' --step 6", "bvh_leaf");
  EXPECT_TRUE(has(leaf.state["panels"]["ruleLabel"], "each primitive is in exactly one leaf"))
      << leaf.state["panels"]["ruleLabel"];
}

// The Cornell box built as a BVH from the command line and a pixel's ray replayed: the structure panel's
// line, the tree, the skip's rule, and the current node's highlight where its box projects.
TEST(Bvh, CornellBvhFromTheCommandLine) {
  Snap s = snap("'" + kCornell + "' --accel bvh --pixel 100,220 --step-to skip:1", "bvh_cornell_skip");
  EXPECT_EQ(s.state["structure_info"].get<std::string>().rfind("bvh: ", 0), 0u) << s.state["structure_info"];
  EXPECT_EQ(s.state["tree"]["structure"], "BVH");
  EXPECT_EQ(s.state["event_type"], "skip");
  EXPECT_TRUE(has(s.state["panels"]["ruleLabel"], "> t of the nearest hit = "))
      << s.state["panels"]["ruleLabel"];
  EXPECT_FALSE(s.state["view"]["bvh"]["skipped_nodes"].empty());
  // At the second box test of the root: both children drawn, each in its colour where it projects.
  Snap c =
      snap("'" + kCornell + "' --accel bvh --pixel 100,220 --step-to box_test:3", "bvh_cornell_children");
  const json& view = c.state["view"];
  ASSERT_EQ(view["bvh"]["children_drawn"].size(), 2u) << view.dump(1);
  const ScreenBox cur = boxOf(view["current_node"]["projected_corners"]);
  EXPECT_GT(
      countColor(c.img, view["colors"]["current_cell"], cur.x0 - 2, cur.y0 - 2, cur.x1 + 2, cur.y1 + 2, 12),
      20);
  const ScreenBox other = boxOf(view["bvh"]["children_drawn"][1]["projected_corners"]);
  EXPECT_GT(countColor(c.img, view["colors"]["bvh_child_other"], other.x0 - 2, other.y0 - 2, other.x1 + 2,
                       other.y1 + 2, 12),
            20);
}

// The SAH inspector on a BVH node: the binned curve (bins - 1 candidates per axis), the chosen bin, the CSV
// of raystep sah --accel bvh.
TEST(Bvh, SahInspectorShowsTheBinnedCurve) {
  const std::string csv = kOut + "/bvh_sah.csv";
  std::remove(csv.c_str());
  Snap s = snap("'" + kCornell + "' --accel bvh --bins 8 --panel sah --node 3 --export-sah '" + csv + "'",
                "bvh_sah");
  const json& sah = s.state["sah"];
  EXPECT_EQ(sah["structure"], "bvh");
  EXPECT_EQ(sah["node"], 3);
  for (const char* a : {"x", "y", "z"}) EXPECT_LE(sah["points"][a].get<int>(), 7) << a;
  EXPECT_GT(sah["candidates"].get<int>(), 0);
  EXPECT_TRUE(sah.contains("chosen_bin"));
  EXPECT_EQ(s.state["tree"]["selected_path"], "LR");
  std::ifstream in(csv);
  std::string header;
  std::getline(in, header);
  EXPECT_EQ(header.rfind("axis,bin,position,n_left,n_right", 0), 0u) << header;
}

// The heat map of bounding-box tests: counted for the BVH, none for the kd-tree (which tests planes, not
// boxes).
TEST(Bvh, BoxTestHeatMap) {
  Snap b = snap("'" + kCornell + "' --accel bvh --heat boxes", "bvh_heat_boxes");
  EXPECT_EQ(b.state["heat"]["quantity"], "boxes");
  EXPECT_GT(b.state["heat"]["max"].get<double>(), 2.0);
  Snap k = snap("'" + kCornell + "' --accel kd --heat boxes", "kd_heat_boxes");
  EXPECT_EQ(k.state["heat"]["max"].get<double>(), 0.0);
}

// The wide BVH's walk: a node's up to 8 children tested one after the other, each row in the panel, the boxes
// hit so far drawn with their overlaps.
TEST(Bvh, WideNodeShowsEveryChild) {
  Snap s = snap("'" + kCornell + "' --accel bvh8 --pixel 100,220 --step-to box_test:4", "bvh8_children");
  const json& p = s.state["panels"];
  EXPECT_TRUE(has(p["nodeLabel"], "(a wide node)")) << p["nodeLabel"];
  const std::string rows = p["crossingLabel"];
  size_t children = 0;
  for (size_t at = rows.find("child "); at != std::string::npos; at = rows.find("child ", at + 1)) ++children;
  EXPECT_GT(children, 2u) << rows;
  EXPECT_EQ(s.state["view"]["bvh"]["children_drawn"].size(), 4u);
}

// Bad BVH option values: exit code 2 and one line "error: ..." (beside Qt's own note about the environment
// and the scripted mode's timings of what was done before).
TEST(Bvh, BadOptionsExit2WithOneLine) {
  for (const char* args : {"--accel bvh9", "--accel bvh --bins 1", "--accel bvh --bins 300",
                           "--accel bvh --bvh-order sideways", "--accel bvh --bvh-leaf 0",
                           "--accel bvh --node 100000", "--accel bvh --node-path LLLLLLLLLLLLLLLLLLLL"}) {
    GuiRun r = gui("'" + kCornell + "' " + args + " --quit", "bvh_bad_option");
    EXPECT_EQ(r.code, 2) << args;
    const std::vector<std::string> lines = errorLines(r.err);
    std::string errors;
    for (const std::string& line : lines) errors += line + "\n";
    EXPECT_EQ(lines.size(), 1u) << args << ": " << errors;
    EXPECT_EQ(errors.rfind("error: ", 0), 0u) << args << ": " << errors;
  }
}

}  // namespace
}  // namespace raystep::viztest
