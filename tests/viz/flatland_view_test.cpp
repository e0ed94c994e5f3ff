// The 2D view of a flatland scene (viz/src/flatland/flat_view.h): the lecture's picture of the walk painted
// from core's flat figure, with the stack as the slides write it, the tree beside it, a grid's tMax ticks and
// the mailbox's marks; dragging the ray traces it again (the step kept where it still exists) and gives the
// walk that the same ray given on the command line gives; "Export figure" writes `raystep figure`'s file.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>
#include <vector>
#include <string>

#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

const std::string kFlat = kSourceDir + "/scenes/flatland";

struct Snap {
  json state;
  Rgb8Image img;
  int code = -1;
  std::string err;
};

Snap snap(const std::string& args, const std::string& tag) {
  const std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json";
  GuiRun r = gui(args + " --window 1280x800 --screenshot '" + png + "' --dump-state '" + st + "' --quit", tag);
  Snap s;
  s.code = r.code;
  s.err = r.err;
  EXPECT_EQ(r.code, 0) << r.err;
  if (r.code != 0) return s;
  s.state = readJson(st);
  s.img = read_png_rgb8(png);
  return s;
}

bool captionHas(const json& flat, const std::string& text) {
  for (const json& line : flat["caption"])
    if (line.get<std::string>().find(text) != std::string::npos) return true;
  return false;
}

int items(const json& flat, const std::string& css) {
  return flat["walk_items"].contains(css) ? flat["walk_items"][css].get<int>() : 0;
}

// The figure's colours (core/src/figure/flat_figure.cpp) over white at their opacity.
json over_white(double r, double g, double b, double a) {
  auto c = [a](double v) { return int(std::lround(255.0 * (a * v + (1.0 - a)))); };
  return json::array({c(r), c(g), c(b)});
}

// The slides' kd-tree figure: at the walk's fourth node (LLL) the caption writes "Stack: LLR,R   Current:
// LLL", the 2D view fills LLL in the current node's yellow and outlines the two stacked nodes, and the tree is
// drawn beside it; the state panel's stack holds the same two nodes.
TEST(FlatView, KdWalkIsTheSlidesPictureAndStack) {
  Snap s = snap("'" + kFlat + "/kd_traversal.json' --accel kd --step-to node:4", "flat_kd_lll");
  ASSERT_EQ(s.code, 0);
  const json& f = s.state["flat"];
  EXPECT_TRUE(f["visible"].get<bool>());
  EXPECT_TRUE(f["ray_in_plane"].get<bool>());
  EXPECT_TRUE(captionHas(f, "Stack: LLR,R   Current: LLL")) << f["caption"];
  EXPECT_EQ(items(f, "current"), 1);
  EXPECT_EQ(items(f, "stacked"), 2);
  EXPECT_TRUE(f["tree_shown"].get<bool>());
  EXPECT_EQ(s.state["panels"]["stack"].size(), 2u) << s.state["panels"];
  // The current node's yellow fills part of the picture, inside its frame.
  const json& fr = f["frame_px"];
  const double x0 = fr[0].get<double>(), y0 = fr[1].get<double>();
  const double x1 = x0 + fr[2].get<double>(), y1 = y0 + fr[3].get<double>();
  const int yellow = countColor(s.img, over_white(1.0, 0.82, 0.2, 0.5), 0, 0, s.img.width, s.img.height, 3);
  EXPECT_GT(yellow, 400) << "the current node's fill";
  EXPECT_LT(yellow, (x1 - x0) * (y1 - y0)) << "not the whole picture";
}

// A grid walk: at each cell the caption gives tMax and tDelta and the picture ticks tMax on the ray; at a
// mailbox hit the shape skipped is marked in the mailbox's violet.
TEST(FlatView, GridWalkShowsTMaxTicksAndTheMailbox) {
  Snap cell = snap("'" + kFlat + "/mailbox.json' --accel grid --step-to cell:3", "flat_grid_cell");
  ASSERT_EQ(cell.code, 0);
  EXPECT_TRUE(captionHas(cell.state["flat"], "tMax x ")) << cell.state["flat"]["caption"];
  EXPECT_GE(items(cell.state["flat"], "tmax-x") + items(cell.state["flat"], "tmax-y"), 1);
  // The grid's lines in the structure's slate blue, across the picture.
  EXPECT_GT(countColor(cell.img, json::array({89, 115, 153}), 0, 0, cell.img.width, cell.img.height, 12), 600)
      << "the grid's lines";
  Snap hit = snap("'" + kFlat + "/mailbox.json' --accel grid --step-to mailbox_hit:1", "flat_grid_mailbox");
  ASSERT_EQ(hit.code, 0);
  EXPECT_EQ(hit.state["event_type"], "mailbox_hit");
  EXPECT_EQ(items(hit.state["flat"], "mailbox-hit"), 1);
  EXPECT_GE(items(hit.state["flat"], "mailboxed"), 1);
  EXPECT_GT(countColor(hit.img, json::array({115, 51, 166}), 0, 0, hit.img.width, hit.img.height, 6), 150)
      << "the skipped shape's violet";
}

// Dragging the origin moves it where the mouse lets go (to a screen pixel) and traces the walk again with the
// step kept; the same ray given as --flat-ray gives the same walk. Dragging anywhere else aims the ray there.
TEST(FlatView, DraggingTheRayTracesItAgainAndKeepsTheStep) {
  Snap d = snap("'" + kFlat + "/mailbox.json' --accel grid --step 9 --drag-flat 0.3,1.45,0.6,3.2",
                "flat_drag_origin");
  ASSERT_EQ(d.code, 0);
  const json& f = d.state["flat"];
  const double ox = f["origin"][0].get<double>(), oy = f["origin"][1].get<double>();
  const double unitPx = f["frame_px"][2].get<double>() / 10.6;  // about the pixels per scene unit
  EXPECT_NEAR(ox, 0.6, 2.0 / unitPx);
  EXPECT_NEAR(oy, 3.2, 2.0 / unitPx);
  EXPECT_EQ(d.state["step"], 9);
  EXPECT_NEAR(d.state["ray_origin"][0].get<double>(), ox, 1e-6);
  EXPECT_EQ(d.state["ray_origin"][2].get<double>(), 0.0);
  EXPECT_EQ(d.state["ray_dir"][2].get<double>(), 0.0);
  char ray[160];
  std::snprintf(ray, sizeof ray, "%.9g,%.9g,%.9g,%.9g", ox, oy, f["direction"][0].get<double>(),
                f["direction"][1].get<double>());
  Snap g = snap("'" + kFlat + "/mailbox.json' --accel grid --step 9 --flat-ray " + ray, "flat_given_ray");
  ASSERT_EQ(g.code, 0);
  EXPECT_EQ(g.state["events"], d.state["events"]);
  EXPECT_EQ(g.state["flat"]["caption"], f["caption"]);
  EXPECT_EQ(g.state["flat"]["walk_items"], f["walk_items"]);

  // Aim: from a point off the origin the ray turns towards where the mouse is let go.
  Snap a = snap("'" + kFlat + "/mailbox.json' --accel grid --drag-flat 5,1,9.1,9.1", "flat_drag_aim");
  ASSERT_EQ(a.code, 0);
  const json& fa = a.state["flat"];
  EXPECT_NEAR(fa["origin"][0].get<double>(), 0.3, 1e-6);  // the scene's own origin, unmoved
  const double dx = 9.1 - 0.3, dy = 9.1 - 1.45, n = std::hypot(dx, dy);
  EXPECT_NEAR(fa["direction"][0].get<double>(), dx / n, 0.01);
  EXPECT_NEAR(fa["direction"][1].get<double>(), dy / n, 0.01);
  EXPECT_EQ(a.state["step"], 0);  // no step was shown: the walk starts at its first event
}

// The 2D SAH inspector's ways in: a right click selects the leaf under the pointer, the next one its parent
// (the tree view and the SAH chart follow); "Build so far" draws only the splits made up to the selected node;
// Crofton's random lines at a node meet each child in the share its perimeter ratio predicts.
TEST(FlatView, RightClickSelectsNodesAndCroftonLinesMatchThePerimeters) {
  const std::string scene = "'" + kFlat + "/kd_traversal.json' --accel kd";
  Snap lll = snap(scene + " --node-path LLL", "flat_select_lll");
  ASSERT_EQ(lll.code, 0);
  const json& region = lll.state["flat"]["selected_region"];
  ASSERT_GE(region.size(), 3u);
  double cx = 0, cy = 0;
  for (const json& q : region) cx += q[0].get<double>() / double(region.size()), cy += q[1].get<double>() / double(region.size());
  const std::string at = std::to_string(cx) + "," + std::to_string(cy);
  Snap picked = snap(scene + " --right-click-flat " + at, "flat_pick_leaf");
  ASSERT_EQ(picked.code, 0);
  EXPECT_EQ(picked.state["selected_node"], lll.state["selected_node"]);
  EXPECT_TRUE(picked.state["kd_panel"].get<bool>());  // the tree and the SAH inspector open
  Snap up = snap(scene + " --node-path LLL --right-click-flat " + at, "flat_pick_parent");
  ASSERT_EQ(up.code, 0);
  EXPECT_EQ(up.state["tree"]["selected_path"], "LL");

  // The build so far at LL: fewer split lines than the whole tree's.
  Snap whole = snap(scene + " --node-path LL", "flat_build_whole");
  Snap built = snap(scene + " --node-path LL --build-planes", "flat_build_ll");
  ASSERT_EQ(built.code, 0);
  EXPECT_TRUE(built.state["flat"]["build_so_far"].get<bool>());
  EXPECT_LT(built.state["flat"]["still_items"].get<int>(), whole.state["flat"]["still_items"].get<int>());

  // Crofton at L: of the lines meeting it, each child's share is its perimeter ratio (binomial 4 sigma).
  Snap lines = snap(scene + " --node-path L --crofton-lines", "flat_crofton");
  ASSERT_EQ(lines.code, 0);
  const json& c = lines.state["flat"]["crofton"];
  ASSERT_TRUE(c.is_object()) << lines.state["flat"];
  const double n = c["meeting_node"].get<double>();
  ASSERT_GT(n, 1000);
  ASSERT_EQ(c["share"].size(), 2u);
  for (size_t k = 0; k < 2; ++k) {
    const double p = c["ratio"][k].get<double>(), share = c["share"][k].get<double>();
    EXPECT_GT(p, 0.2);
    EXPECT_LT(p, 1.0);
    EXPECT_NEAR(share, p, 4.0 * std::sqrt(p * (1 - p) / n)) << "child " << k;
  }
  EXPECT_GT(c["lines_drawn"].get<int>(), 50);
  bool said = false;
  for (const json& line : lines.state["flat"]["caption"])
    said = said || line.get<std::string>().find("Crofton at node") != std::string::npos;
  EXPECT_TRUE(said);
}

// *Anti-aliasing* in the 2D view: the picture's pixels over the polygon sampled with the picture's
// anti-aliasing, the exact coverage and the error; sixteen jittered samples a pixel err less than one.
TEST(FlatView, AntiAliasingShowsThePixelsAndTheirError) {
  const std::string scene = "'" + kFlat + "/aliasing_polygon.json'";
  Snap one = snap(scene + " --aa none --flat-aa", "flat_aa_none");
  Snap many = snap(scene + " --aa jitter:4 --flat-aa", "flat_aa_jitter4");
  ASSERT_EQ(one.code, 0);
  ASSERT_EQ(many.code, 0);
  const json &a = one.state["flat"]["aa"], &b = many.state["flat"]["aa"];
  ASSERT_TRUE(a.is_object() && b.is_object()) << one.state["flat"];
  EXPECT_TRUE(one.state["flat"]["anti_aliasing"].get<bool>());
  EXPECT_EQ(a["pixels"], 24 * 16);
  EXPECT_EQ(b["samples"].get<double>(), 16.0 * 24 * 16);
  EXPECT_TRUE(a["exact"].get<bool>());
  EXPECT_LT(b["mean_abs_error"].get<double>(), 0.5 * a["mean_abs_error"].get<double>());
  EXPECT_TRUE(captionHas(many.state["flat"], "jitter:4: 24x16 pixels"));
  // The exact panel's greys between the polygon's white and the background's black: pixels of mid grey.
  EXPECT_GT(countColor(many.img, json::array({128, 128, 128}), 0, 0, many.img.width, many.img.height, 60), 200);
}

#ifdef RAYSTEP_CLI_EXE
// "Export figure" writes the file `raystep figure` writes for the same ray and step.
TEST(FlatView, ExportedFigureIsTheCommandLinesFigure) {
  const std::string gui_svg = kOut + "/flat_export.svg", cli_svg = kOut + "/flat_export_cli.svg";
  std::remove(gui_svg.c_str());
  GuiRun r = gui("'" + kFlat + "/kd_traversal.json' --accel kd --step 7 --export-figure '" + gui_svg + "' --quit",
                 "flat_export");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' figure '" + kFlat +
                          "/kd_traversal.json' --accel kd --step 7 -o '" + cli_svg + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string a = slurp(gui_svg), b = slurp(cli_svg);
  EXPECT_FALSE(a.empty());
  EXPECT_EQ(a, b);
  EXPECT_NE(a.find("Stack: LLR,R   Current: LLL"), std::string::npos);
}
#endif

// The 2D options on a 3D scene, a direction of (0, 0) and malformed numbers: one line, exit 2.
TEST(FlatView, BadFlatOptionsExit2) {
  struct Case {
    std::string args, says;
  };
  const std::string cornell = kSourceDir + "/scenes/cornell.json";
  for (const Case& c : std::vector<Case>{
           {"'" + cornell + "' --flat-ray 0,0,1,0", "--flat-ray: for a 2D scene"},
           {"'" + cornell + "' --export-figure /tmp/raystep-never.svg", "a figure draws a 2D scene"},
           {"'" + kFlat + "/mailbox.json' --flat-ray 1,1,0,0", "the direction is (0, 0)"},
           {"'" + kFlat + "/mailbox.json' --flat-ray 1,1,x,0", "expected OX,OY,DX,DY"},
           {"'" + kFlat + "/mailbox.json' --drag-flat 1,1,2", "expected FROMX,FROMY,TOX,TOY"}}) {
    GuiRun r = gui(c.args + " --quit", "flat_bad");
    EXPECT_EQ(r.code, 2) << c.args << "\n" << r.err;
    EXPECT_NE(r.err.find(c.says), std::string::npos) << c.args << "\n" << r.err;
    const std::vector<std::string> errors = errorLines(r.err);
    ASSERT_EQ(errors.size(), 1u) << c.args << ": " << r.err;
    EXPECT_EQ(errors[0].rfind("error: ", 0), 0u) << c.args << ": " << errors[0];
  }
}

}  // namespace
}  // namespace raystep::viztest
