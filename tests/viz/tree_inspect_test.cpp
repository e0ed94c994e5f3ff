// The tree inspectors for the octree, the general BSP tree and the wide BVH, scripted
// under Xvfb as the other GUI tests: the SAH inspector shows a BSP node's candidate planes by orientation,
// point for point core's record_bsp_sah_curve (the builder's own decision: the chosen plane is the tree's and
// the cheapest), its CSV is `raystep sah --accel bsp`'s, the picker shows one group or one direction; a click
// in the 3D view selects the leaf holding the picked point in every tree (its cell contains the point, it
// lists the picked primitive); the tree view lists a wide BVH node's up to 8 children and the selected one's
// box is drawn where it projects.
#include <gtest/gtest.h>

#include <cstdio>
#include <set>
#include <string>

#include <glm/geometric.hpp>

#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/accel/octree_build.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/io/scene_loader.h"
#include "viz_test_util.h"

namespace {

using namespace raystep::viztest;

const std::string kTilted = kSourceDir + "/scenes/tilted_plane.json";
const std::string kCornell = kSourceDir + "/scenes/cornell.json";

struct Snap {
  json state;
  raystep::Rgb8Image img;
};

Snap snap(const std::string& args, const std::string& tag, const std::string& shot = "--screenshot") {
  std::string png = kOut + "/" + tag + ".png", st = kOut + "/" + tag + ".json";
  GuiRun r =
      gui(args + " --window 1280x800 " + shot + " '" + png + "' --dump-state '" + st + "' --quit", tag);
  EXPECT_EQ(r.code, 0) << r.err;
  return {readJson(st), raystep::read_png_rgb8(png)};
}

const raystep::Geometry& tilted() {
  static const raystep::Scene scene = raystep::load_scene(kTilted);
  return scene.geometry;
}

const raystep::Geometry& cornell() {
  static const raystep::Scene scene = raystep::load_scene(kCornell);
  return scene.geometry;
}

bool has(const json& j, const std::string& text) {
  return j.get<std::string>().find(text) != std::string::npos;
}

// Node 1 of the tilted plane's BSP tree is split by a triangle's own plane: the chart shows every
// orientation, one series per direction, one legend entry per group, and the chosen plane; the numbers are
// core's.
TEST(TreeInspect, BspSahInspectorShowsTheCandidatesByOrientation) {
  const std::string csv = kOut + "/bsp_sah.csv";
  std::remove(csv.c_str());
  Snap s = snap("'" + kTilted + "' --accel bsp --panel sah --node 1 --export-sah '" + csv + "'", "bsp_sah",
                "--screenshot-sah");
  const json& sah = s.state["sah"];
  ASSERT_EQ(sah["structure"], "bsp") << sah.dump(1);
  EXPECT_EQ(sah["node"], 1);
  EXPECT_EQ(sah["orientation"], "all");
  EXPECT_TRUE(sah["orientation_picker_visible"].get<bool>());
  const raystep::BspOptions options;  // the GUI's defaults are the command line's
  const raystep::BspSahCurve curve = raystep::record_bsp_sah_curve(tilted(), options, 1);
  const raystep::BspTreeData tree = raystep::build_bsp(tilted(), options);
  ASSERT_FALSE(curve.leaf);
  ASSERT_EQ(curve.split.direction, -1) << "node 1 is split by an own plane (the scene's slant)";
  EXPECT_EQ(sah["candidates"].get<int>(), int(curve.candidates.size()));
  EXPECT_EQ(sah["n_prims"].get<int>(), int(curve.n_prims));
  // Point for point per direction.
  std::map<std::string, int> per;
  for (const raystep::BspCandidate& c : curve.candidates) ++per[raystep::bsp_direction_name(c.direction)];
  for (int d = -1; d < raystep::kBspKdopDirections; ++d) {
    const char* name = raystep::bsp_direction_name(d);
    EXPECT_EQ(sah["points"][name].get<int>(), per[name]) << name;
  }
  // The chosen plane is the tree's, the cheapest candidate, drawn.
  const json& chosen = sah["chosen"];
  EXPECT_EQ(chosen["index"].get<int>(), curve.chosen);
  EXPECT_EQ(chosen["name"], "own plane");
  EXPECT_EQ(chosen["source"], "primitive");
  for (int k = 0; k < 3; ++k) EXPECT_EQ(chosen["normal"][k].get<float>(), tree.nodes[1].plane.normal[k]) << k;
  EXPECT_EQ(chosen["offset"].get<float>(), tree.nodes[1].plane.offset);
  for (const raystep::BspCandidate& c : curve.candidates) EXPECT_GE(c.cost, chosen["cost"].get<double>());
  EXPECT_GT(chosen["x"].get<double>(), 0.0);
  EXPECT_LT(chosen["x"].get<double>(), 1.0);
  EXPECT_EQ(chosen["n_below"].get<int>(), int(curve.n_below));
  // One legend entry per group: x, y, z, the face diagonals, the body diagonals, the own planes.
  int legends = 0;
  std::set<std::string> labels;
  for (const json& series : sah["series"])
    if (series["legend"].get<bool>()) {
      ++legends;
      labels.insert(series["label"].get<std::string>().substr(0, 6));
    }
  EXPECT_EQ(legends, 6) << sah["series"].dump();
  EXPECT_TRUE(labels.count("face d") && labels.count("body d") && labels.count("own pl"))
      << sah["series"].dump();
  // The text says what was chosen and what the best axis plane (the kd-tree's choice) would have cost.
  EXPECT_TRUE(has(sah["text"], "split by the own plane of triangle " + std::to_string(curve.split.prim)))
      << sah["text"];
  EXPECT_TRUE(has(sah["text"], "best axis plane</b> (the kd-tree's choice)")) << sah["text"];
  EXPECT_TRUE(has(sah["title"], "triangle " + std::to_string(curve.split.prim) + "'s own plane"))
      << sah["title"];
  // Every group's colour on the chart.
  const json& colors = sah["colors"];
  for (const char* group : {"x", "y", "z", "face_diagonals", "body_diagonals", "own_planes", "chosen"})
    EXPECT_GT(countColor(s.img, colors[group], 0, 0, s.img.width - 1, s.img.height - 1, 8), 20) << group;
    // The exported CSV is the command line's.
#ifdef RAYSTEP_CLI_EXE
  const std::string cli = kOut + "/bsp_sah_cli.csv";
  std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' sah '" + kTilted + "' --accel bsp --node 1 -o '" +
                    cli + "' > /dev/null";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  EXPECT_EQ(slurp(csv), slurp(cli));
#endif
  EXPECT_FALSE(slurp(csv).empty());
  // The same node by its path (L: below the root's plane).
  Snap byPath = snap("'" + kTilted + "' --accel bsp --node-path L", "bsp_sah_path", "--screenshot-sah");
  EXPECT_EQ(byPath.state["sah"]["node"], 1);
  EXPECT_EQ(byPath.state["tree"]["selected_path"], "L");
}

// The picker: one group (its directions in shades of the group's colour, each in the legend), one direction
// alone, and a bad name exits 2. The node: the first split by a diagonal of the k-DOP.
TEST(TreeInspect, BspOrientationPickerShowsOneGroupOrDirection) {
  const raystep::BspOptions options;
  const raystep::BspTreeData tree = raystep::build_bsp(tilted(), options);
  uint32_t node = 0;
  while (node < tree.nodes.size() &&
         (tree.nodes[node].is_leaf() || tree.info[node].source == raystep::BspPlaneSource::axis ||
          tree.info[node].source == raystep::BspPlaneSource::primitive))
    ++node;
  ASSERT_LT(node, tree.nodes.size()) << "no node split by a diagonal";
  const raystep::BspSahCurve curve = raystep::record_bsp_sah_curve(tilted(), options, node);
  const int chosen = curve.split.direction;
  const bool face = chosen < 9;
  const std::string id = std::to_string(node);
  Snap group = snap("'" + kTilted + "' --accel bsp --panel sah --node " + id + " --sah-orientation " +
                        (face ? "face" : "body"),
                    "bsp_sah_group", "--screenshot-sah");
  const json& sah = group.state["sah"];
  ASSERT_EQ(sah["orientation"], face ? "face" : "body");
  std::map<int, int> per;
  for (const raystep::BspCandidate& c : curve.candidates) ++per[c.direction];
  for (int d = -1; d < raystep::kBspKdopDirections; ++d) {
    const bool in = face ? d >= 3 && d < 9 : d >= 9;
    EXPECT_EQ(sah["points"][raystep::bsp_direction_name(d)].get<int>(), in ? per[d] : 0) << d;
  }
  std::set<std::vector<int>> colours;
  for (const json& series : sah["series"]) {
    EXPECT_TRUE(series["legend"].get<bool>());
    colours.insert(series["color"].get<std::vector<int>>());
  }
  EXPECT_GT(sah["series"].size(), 1u);
  EXPECT_EQ(colours.size(), sah["series"].size()) << "each direction of the group its own shade";
  EXPECT_EQ(sah["chosen"]["name"], raystep::bsp_direction_name(chosen));
  EXPECT_GE(sah["chosen"]["x"].get<double>(), 0.0) << "the chosen plane is drawn with its group";

  // Another direction of the group alone: its one series; the chosen plane is not drawn, the text says so.
  int other = face ? 3 : 9;
  while (other == chosen || per[other] == 0) ++other;
  const std::string name = raystep::bsp_direction_name(other);
  Snap one = snap("'" + kTilted + "' --accel bsp --panel sah --node " + id + " --sah-orientation " + name,
                  "bsp_sah_one", "--screenshot-sah");
  EXPECT_EQ(one.state["sah"]["series"].size(), 1u);
  EXPECT_EQ(one.state["sah"]["points"][name].get<int>(), per[other]);
  EXPECT_LT(one.state["sah"]["chosen"]["x"].get<double>(), 0.0);
  EXPECT_TRUE(has(one.state["sah"]["text"], "not shown")) << one.state["sah"]["text"];

  GuiRun bad =
      gui("'" + kTilted + "' --accel bsp --panel sah --sah-orientation sideways --quit", "bsp_sah_bad");
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("error: --sah-orientation 'sideways'"), std::string::npos) << bad.err;
}

// A click on the back wall of the Cornell box in the 3D view selects, in each tree, a leaf whose cell holds
// the picked point and which lists the picked primitive; the tree view's row and the selection follow.
TEST(TreeInspect, ClickIn3DViewSelectsTheLeafInEveryTree) {
  json first = snap("'" + kCornell + "' --accel octree --panel kd", "pick_layout").state;
  const json& vp = first["view"]["viewport"];
  const int cx = vp[0].get<int>() + vp[2].get<int>() / 2, cy = vp[1].get<int>() + vp[3].get<int>() / 2;
  const std::string at = std::to_string(cx) + "," + std::to_string(cy);
  for (const char* accel : {"octree", "bsp", "bvh", "bvh8", "kd"}) {
    SCOPED_TRACE(accel);
    json st =
        snap("'" + kCornell + "' --accel " + accel + " --pick-3d " + at, std::string("pick_") + accel).state;
    ASSERT_TRUE(st["view"].contains("picked_point")) << st["view"].dump();
    ASSERT_TRUE(st["view"].contains("selected_node")) << "nothing selected";
    const int node = st["selected_node"].get<int>();
    const int prim = st["view"]["picked_primitive"].get<int>();
    ASSERT_GE(prim, 0);
    EXPECT_EQ(st["view"]["selected_node"]["node"].get<int>(), node);
    EXPECT_EQ(st["tree"]["current_row_node"].get<int>(), node);
    EXPECT_TRUE(has(st["tree"]["selected_what"], "leaf")) << st["tree"]["selected_what"];
    EXPECT_TRUE(st["kd_panel"].get<bool>());
    glm::vec3 p;
    for (int a = 0; a < 3; ++a) p[a] = st["view"]["picked_point"][a].get<float>();
    // The leaf lists the primitive and its cell (or box) holds the point, by core's own tree.
    auto lists = [&](const std::vector<uint32_t>& index, uint32_t first, uint32_t count) {
      for (uint32_t i = first; i < first + count; ++i)
        if (index[i] == uint32_t(prim)) return true;
      return false;
    };
    const float tol = 1e-4f;
    auto inside = [&](const raystep::Bounds3& b) {
      for (int a = 0; a < 3; ++a)
        if (!(p[a] >= b.lo[a] - tol && p[a] <= b.hi[a] + tol)) return false;
      return true;
    };
    const std::string name = accel;
    if (name == "octree") {
      raystep::OctreeData t = raystep::build_octree(cornell(), raystep::OctreeOptions{});
      ASSERT_LT(size_t(node), t.nodes.size());
      EXPECT_TRUE(t.nodes[size_t(node)].is_leaf());
      EXPECT_TRUE(lists(t.prim_index, t.nodes[size_t(node)].first, t.nodes[size_t(node)].prim_count()));
      EXPECT_TRUE(inside(t.info[size_t(node)].box));
    } else if (name == "bsp") {
      raystep::BspTreeData t = raystep::build_bsp(cornell(), raystep::BspOptions{});
      ASSERT_LT(size_t(node), t.nodes.size());
      EXPECT_TRUE(t.nodes[size_t(node)].is_leaf());
      EXPECT_TRUE(
          lists(t.prim_index, t.nodes[size_t(node)].first_prim(), t.nodes[size_t(node)].prim_count()));
      // Drawn as its convex cell, not its box.
      EXPECT_GE(st["view"]["selected_node"]["cell_faces"].get<int>(), 4);
      // The point is on the leaf's side of every ancestor's plane (within the pick's rounding).
      for (int32_t k = node; t.info[size_t(k)].parent >= 0; k = t.info[size_t(k)].parent) {
        const int32_t parent = t.info[size_t(k)].parent;
        const raystep::BspPlane& plane = t.nodes[size_t(parent)].plane;
        const double d = glm::dot(glm::dvec3(plane.normal), glm::dvec3(p)) - double(plane.offset);
        if (k == parent + 1)
          EXPECT_LE(d, 1e-4) << "below node " << parent << "'s plane";
        else
          EXPECT_GE(d, -1e-4) << "above node " << parent << "'s plane";
      }
    } else if (name == "bvh") {
      raystep::BvhData t = raystep::build_bvh(cornell(), raystep::BvhOptions{});
      ASSERT_LT(size_t(node), t.nodes.size());
      EXPECT_TRUE(t.nodes[size_t(node)].is_leaf());
      EXPECT_TRUE(
          lists(t.prim_index, t.nodes[size_t(node)].first_prim(), t.nodes[size_t(node)].prim_count()));
      EXPECT_TRUE(inside(t.nodes[size_t(node)].box));
    } else if (name == "bvh8") {
      raystep::WideBvh w(8);
      w.build(cornell());
      raystep::WideBvhView v = w.describe();
      ASSERT_LT(size_t(node), v.nodes.size());
      EXPECT_TRUE(v.nodes[size_t(node)].leaf);
      const std::vector<uint32_t>& prims = v.nodes[size_t(node)].prims;
      EXPECT_NE(std::find(prims.begin(), prims.end(), uint32_t(prim)), prims.end());
      EXPECT_TRUE(inside(v.nodes[size_t(node)].box));
    }
  }
}

// The wide BVH in the tree view: the root lists its up to 8 children (each with its primitive count and, in
// its tooltip, its box), the tree's path names child numbers; a child selected by id is drawn where its box
// projects on the 3D view.
TEST(TreeInspect, WideBvhTreeListsEveryChildAndHighlightsTheSelectedBox) {
  for (int width : {8, 4}) {
    SCOPED_TRACE(width);
    const std::string accel = "bvh" + std::to_string(width);
    raystep::WideBvh w(width);
    w.build(cornell());
    const raystep::WideBvhView v = w.describe();
    ASSERT_GT(v.nodes[0].children.size(), 2u);
    Snap root = snap("'" + kCornell + "' --accel " + accel + " --node 0", "wide_root_" + accel);
    const json& tree = root.state["tree"];
    EXPECT_EQ(tree["structure"], width == 8 ? "8-wide BVH" : "4-wide BVH");
    EXPECT_EQ(tree["nodes"].get<size_t>(), v.nodes.size());
    EXPECT_EQ(tree["headers"][1], "prims");
    const json& rows = tree["current_children"];
    ASSERT_EQ(rows.size(), v.nodes[0].children.size());
    EXPECT_LE(rows.size(), size_t(width));
    size_t sum = 0;
    for (size_t r = 0; r < rows.size(); ++r) {
      EXPECT_EQ(rows[r]["node"].get<int>(), v.nodes[0].children[r]) << r;
      EXPECT_EQ(rows[r]["side"], "child " + std::to_string(r + 1) + "/" + std::to_string(rows.size()));
      EXPECT_TRUE(has(rows[r]["tooltip"], "box (")) << rows[r];
      sum += std::stoul(rows[r]["last"].get<std::string>());
    }
    EXPECT_EQ(sum, cornell().size()) << "each primitive in one leaf: the children's counts add up to N";
    // The last child, selected: its box highlighted in the 3D view.
    const int child = v.nodes[0].children.back();
    Snap sel = snap("'" + kCornell + "' --accel " + accel + " --node " + std::to_string(child),
                    "wide_child_" + accel, "--screenshot");
    EXPECT_EQ(sel.state["tree"]["selected_path"], std::to_string(v.nodes[0].children.size()));
    const json& drawn = sel.state["view"]["selected_node"];
    ASSERT_EQ(drawn["node"].get<int>(), child);
    const raystep::Bounds3& b = v.nodes[size_t(child)].box;
    for (int a = 0; a < 3; ++a) {
      EXPECT_LE(drawn["min"][a].get<float>(), b.lo[a]);
      EXPECT_GE(drawn["max"][a].get<float>(), b.hi[a]);
    }
    ScreenBox sb = boxOf(drawn["projected_corners"]);
    const json& color = sel.state["view"]["colors"]["selected_node"];
    EXPECT_GT(countColor(sel.img, color, sb.x0 - 2, sb.y0 - 2, sb.x1 + 2, sb.y1 + 2, 10), 40);
  }
}

}  // namespace
