// The BSP tree's SAH inspector (accel/bsp_sah_curve.h): the listener watches the build without changing it
// (the same tree bit for bit), the recorded curve of a node is the builder's own decision (the chosen plane
// is the tree's and the cheapest candidate; a leaf for no cheaper split has none below N t_i), each
// candidate's cost is C = t_t + t_i (S_b N_b + S_a N_a) / S with the areas of the cell's polytope rebuilt
// from the ancestors' planes, and the candidates come by orientation (the 13 k-DOP directions, the own
// planes).
#include <gtest/gtest.h>

#include <map>

#include <glm/geometric.hpp>
#include <glm/gtc/matrix_transform.hpp>

#include "raystep/accel/bsp_cell.h"
#include "raystep/accel/bsp_sah_curve.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

const BspDirections kDirections[] = {BspDirections::both, BspDirections::kdop, BspDirections::autopartition};

// Two boxes turned about slanted axes and a few small ones (bsp_test.cpp's slanted scene).
Geometry make_rotated_boxes() {
  Geometry g;
  g.begin_object("boxes", 0);
  glm::mat4 m = glm::rotate(glm::mat4(1.f), glm::radians(33.f), glm::normalize(glm::vec3(1.f, 2.f, 0.5f)));
  add_mesh(g, make_box(glm::vec3(-1.f), glm::vec3(1.f, 2.f, 0.5f)), m);
  glm::mat4 m2 = glm::rotate(glm::mat4(1.f), glm::radians(-61.f), glm::normalize(glm::vec3(-1.f, 0.3f, 1.f)));
  add_mesh(g, make_box(glm::vec3(-3.f), glm::vec3(3.f)), m2);
  for (int i = 0; i < 8; ++i) {
    glm::vec3 lo(float(i % 2) - 2.5f, float(i / 2 % 2) - 0.5f, float(i / 4) + 0.7f);
    add_mesh(g, make_box(lo, lo + glm::vec3(0.3f)), m * m2);
  }
  return g;
}

// Wants every node: all candidates and decisions of a whole build.
struct Everything final : BspBuildListener {
  struct Decision {
    bool leaf = false;
    BspLeafReason reason = BspLeafReason::few_primitives;
    BspCandidate chosen;
    uint32_t n_prims = 0;
  };
  std::map<uint32_t, std::vector<BspCandidate>> candidates;
  std::map<uint32_t, Decision> decisions;
  bool wants_candidates(uint32_t) const override { return true; }
  void candidate(uint32_t node, const BspCandidate& c) override { candidates[node].push_back(c); }
  void split(uint32_t node, const BspNodeInfo&, uint32_t n, const BspCandidate& chosen, uint32_t, uint32_t,
             float) override {
    EXPECT_FALSE(decisions.count(node)) << "node " << node << " decided twice";
    decisions[node] = Decision{false, BspLeafReason::few_primitives, chosen, n};
  }
  void leaf_made(uint32_t node, const BspNodeInfo&, uint32_t n, float, BspLeafReason reason) override {
    EXPECT_FALSE(decisions.count(node)) << "node " << node << " decided twice";
    decisions[node] = Decision{true, reason, BspCandidate{}, n};
  }
};

bool same_plane(const BspPlane& a, const BspPlane& b) {
  return a.normal.x == b.normal.x && a.normal.y == b.normal.y && a.normal.z == b.normal.z &&
         a.offset == b.offset;
}

// Index of the first cheapest candidate (the builder's tie rule: the first strictly cheaper one wins).
int first_minimum(const std::vector<BspCandidate>& cs) {
  int best = -1;
  for (size_t i = 0; i < cs.size(); ++i)
    if (best < 0 || cs[i].cost < cs[size_t(best)].cost) best = int(i);
  return best;
}

// A node's cell rebuilt from the root box and its ancestors' planes (below child = parent + 1).
ConvexCell cell_of(const BspTreeData& tree, uint32_t id) {
  std::vector<uint32_t> path{id};
  while (tree.info[path.back()].parent >= 0) path.push_back(uint32_t(tree.info[path.back()].parent));
  ConvexCell cell = ConvexCell::box(tree.bounds);
  for (size_t k = path.size() - 1; k > 0; --k) {
    const BspPlane& p = tree.nodes[path[k]].plane;
    ConvexCell below, above;
    cell.split(glm::dvec3(p.normal), double(p.offset), &below, &above);
    cell = path[k - 1] == path[k] + 1 ? below : above;
  }
  return cell;
}

TEST(BspSahCurve, ListeningChangesNothingAndTheChosenPlaneIsTheCheapest) {
  int inner = 0, leaves_searched = 0, bounded = 0;
  for (int scene = 0; scene < 2; ++scene) {
    const Geometry g = scene == 0 ? test::make_soup(41, 300, 3) : make_rotated_boxes();
    for (BspDirections dirs : kDirections) {
      BspOptions o;
      o.directions = dirs;
      const BspTreeData plain = build_bsp(g, o);
      Everything all;
      const BspTreeData heard = build_bsp(g, o, all);
      // The same tree, bit for bit.
      ASSERT_EQ(plain.nodes.size(), heard.nodes.size());
      for (size_t i = 0; i < plain.nodes.size(); ++i) {
        ASSERT_EQ(plain.nodes[i].count, heard.nodes[i].count) << i;
        ASSERT_EQ(plain.nodes[i].child_or_first, heard.nodes[i].child_or_first) << i;
        ASSERT_TRUE(same_plane(plain.nodes[i].plane, heard.nodes[i].plane)) << i;
        ASSERT_EQ(plain.info[i].cost, heard.info[i].cost) << i;
      }
      ASSERT_EQ(plain.prim_index, heard.prim_index);
      ASSERT_EQ(all.decisions.size(), plain.nodes.size());
      for (const auto& [id, d] : all.decisions) {
        const std::vector<BspCandidate>& cs = all.candidates[id];
        const BspNode& n = plain.nodes[id];
        const float leaf_cost = o.t_i * float(d.n_prims);
        for (const BspCandidate& c : cs) bounded += c.bounded;
        ASSERT_EQ(d.leaf, n.is_leaf()) << id;
        if (!d.leaf) {
          ++inner;
          // The tree's plane is the chosen candidate's, marked once, and no candidate is cheaper.
          ASSERT_TRUE(same_plane(d.chosen.plane, n.plane)) << id;
          int marked = 0, at = -1;
          for (size_t i = 0; i < cs.size(); ++i)
            if (cs[i].chosen) ++marked, at = int(i);
          ASSERT_EQ(marked, 1) << id;
          EXPECT_TRUE(same_plane(cs[size_t(at)].plane, n.plane)) << id;
          EXPECT_EQ(first_minimum(cs), at)
              << "node " << id << ": the chosen plane is not the curve's minimum";
          EXPECT_FALSE(cs[size_t(at)].bounded);
          EXPECT_LT(cs[size_t(at)].cost, double(leaf_cost)) << id;
          EXPECT_EQ(float(cs[size_t(at)].cost), plain.info[id].cost) << id;
        } else {
          for (const BspCandidate& c : cs) EXPECT_FALSE(c.chosen) << id;
          if (d.reason == BspLeafReason::no_cheaper_split) {
            if (!cs.empty()) ++leaves_searched;
            for (const BspCandidate& c : cs) EXPECT_GE(c.cost, double(o.t_i) * d.n_prims) << id;
          }
          if (d.reason == BspLeafReason::few_primitives || d.reason == BspLeafReason::max_depth)
            EXPECT_TRUE(cs.empty()) << id;
        }
      }
    }
  }
  EXPECT_GT(inner, 100);
  EXPECT_GT(leaves_searched, 5);
  EXPECT_GT(bounded, 100);  // the builder's shortcut was taken, and those candidates are in the curves too
}

TEST(BspSahCurve, CostsAreTheFormulaOverTheCellsPolytopeAreas) {
  const Geometry g = make_rotated_boxes();
  for (BspDirections dirs : kDirections) {
    BspOptions o;
    o.directions = dirs;
    o.candidates = 8;
    const BspTreeData tree = build_bsp(g, o);
    int checked = 0;
    for (uint32_t id = 0; id < tree.nodes.size() && checked < 12; ++id) {
      if (tree.nodes[id].is_leaf()) continue;
      ++checked;
      SCOPED_TRACE("node " + std::to_string(id) + ", directions " + bsp_directions_name(dirs));
      const BspSahCurve curve = record_bsp_sah_curve(g, o, id);
      // The node as the whole build made it.
      EXPECT_EQ(curve.node, id);
      EXPECT_FALSE(curve.leaf);
      EXPECT_EQ(curve.info.depth, tree.info[id].depth);
      EXPECT_EQ(curve.info.parent, tree.info[id].parent);
      EXPECT_EQ(curve.info.area, tree.info[id].area);
      EXPECT_EQ(curve.info.box.lo, tree.info[id].box.lo);
      EXPECT_EQ(curve.info.box.hi, tree.info[id].box.hi);
      ASSERT_GE(curve.chosen, 0);
      EXPECT_TRUE(same_plane(curve.split.plane, tree.nodes[id].plane));
      EXPECT_TRUE(same_plane(curve.candidates[size_t(curve.chosen)].plane, tree.nodes[id].plane));
      EXPECT_EQ(first_minimum(curve.candidates), curve.chosen);
      // The children's counts are the children's N.
      EXPECT_EQ(record_bsp_sah_curve(g, o, id + 1).n_prims, curve.n_below);
      EXPECT_EQ(record_bsp_sah_curve(g, o, tree.nodes[id].above_child()).n_prims, curve.n_above);
      EXPECT_GE(curve.n_below + curve.n_above, curve.n_prims);
      const ConvexCell cell = cell_of(tree, id);
      const double S = cell.area();
      EXPECT_NEAR(S, double(curve.info.area), 1e-6 * S);
      std::map<int, int> per_direction;
      for (const BspCandidate& c : curve.candidates) {
        ++per_direction[c.direction];
        // Strictly inside the cell along its normal, and the cell's extent is the rebuilt cell's.
        const glm::dvec3 n(c.plane.normal);
        double lo, hi;
        cell.extent(n, &lo, &hi);
        EXPECT_NEAR(c.cell_min, lo, 1e-9 * (1 + std::abs(lo)));
        EXPECT_NEAR(c.cell_max, hi, 1e-9 * (1 + std::abs(hi)));
        EXPECT_GT(double(c.plane.offset), c.cell_min);
        EXPECT_LT(double(c.plane.offset), c.cell_max);
        // The areas of the two parts of the rebuilt cell, and the cost from them.
        ConvexCell below, above;
        cell.split(n, double(c.plane.offset), &below, &above);
        // (the builder's shortcut, split_areas, agrees with the built parts to rounding: bsp_build_test.cpp)
        EXPECT_NEAR(c.area_below, below.area(), 1e-7 * S);
        EXPECT_NEAR(c.area_above, above.area(), 1e-7 * S);
        EXPECT_NEAR(c.area_node, S, 1e-9 * S);
        EXPECT_GE(c.area_below + c.area_above, S * (1 - 1e-9));  // Crofton: the cap counts twice
        const double C =
            double(o.t_t) + double(o.t_i) * (below.area() * c.n_below + above.area() * c.n_above) / S;
        EXPECT_NEAR(c.cost, C, 1e-7 * C);
        EXPECT_LE(c.n_below, curve.n_prims);
        EXPECT_LE(c.n_above, curve.n_prims);
        EXPECT_GE(c.n_below + c.n_above, curve.n_prims);
        // By orientation: a k-DOP direction's normal is that direction's, an own plane passes through its
        // triangle's centroid.
        if (c.direction >= 0) {
          EXPECT_NE(dirs, BspDirections::autopartition);
          EXPECT_EQ(c.plane.normal, bsp_kdop_direction(c.direction));
          EXPECT_EQ(c.source, c.direction < 3   ? BspPlaneSource::axis
                              : c.direction < 9 ? BspPlaneSource::face_diagonal
                                                : BspPlaneSource::body_diagonal);
        } else {
          EXPECT_NE(dirs, BspDirections::kdop);
          EXPECT_EQ(c.source, BspPlaneSource::primitive);
          ASSERT_LT(c.prim, g.size());
          glm::dvec3 centroid = (glm::dvec3(g.vertex(c.prim, 0)) + glm::dvec3(g.vertex(c.prim, 1)) +
                                 glm::dvec3(g.vertex(c.prim, 2))) /
                                3.0;
          EXPECT_NEAR(glm::dot(n, centroid), double(c.plane.offset), 1e-5);
          EXPECT_NEAR(glm::dot(n, glm::normalize(glm::cross(
                                      glm::dvec3(g.vertex(c.prim, 1)) - glm::dvec3(g.vertex(c.prim, 0)),
                                      glm::dvec3(g.vertex(c.prim, 2)) - glm::dvec3(g.vertex(c.prim, 0))))),
                      1.0, 1e-6);
        }
      }
      for (const auto& [dir, count] : per_direction)
        EXPECT_LE(count, o.candidates) << "direction " << dir;  // the cap per direction (and own planes)
      if (id == 0 && dirs == BspDirections::both) {
        EXPECT_EQ(per_direction.size(), size_t(kBspKdopDirections + 1)) << "every orientation at the root";
      }
    }
    EXPECT_EQ(checked, 12);
  }
}

TEST(BspSahCurve, LeavesNodesAndPaths) {
  const Geometry g = test::make_soup(43, 120, 2);
  BspOptions o;
  const BspTreeData tree = build_bsp(g, o);
  ASSERT_GT(tree.nodes.size(), 10u);
  // A leaf: its reason, no chosen plane.
  uint32_t leaf = 0;
  while (!tree.nodes[leaf].is_leaf()) ++leaf;
  const BspSahCurve lc = record_bsp_sah_curve(g, o, leaf);
  EXPECT_TRUE(lc.leaf);
  EXPECT_EQ(lc.chosen, -1);
  EXPECT_EQ(lc.n_prims, tree.nodes[leaf].prim_count());
  EXPECT_FLOAT_EQ(lc.leaf_cost, o.t_i * float(lc.n_prims));
  // Leaf rules: a leaf of at most leaf_size primitives searched nothing.
  o.leaf_size = 1000;
  const BspSahCurve root_leaf = record_bsp_sah_curve(g, o, 0);
  EXPECT_TRUE(root_leaf.leaf);
  EXPECT_EQ(root_leaf.leaf_reason, BspLeafReason::few_primitives);
  EXPECT_TRUE(root_leaf.candidates.empty());
  o.leaf_size = 1;
  o.t_i = 0.001f;  // a split can never pay for t_t
  const BspSahCurve cheap = record_bsp_sah_curve(g, o, 0);
  EXPECT_TRUE(cheap.leaf);
  EXPECT_EQ(cheap.leaf_reason, BspLeafReason::no_cheaper_split);
  EXPECT_FALSE(cheap.candidates.empty());
  o.t_i = 80.f;
  // No such node.
  try {
    record_bsp_sah_curve(g, o, uint32_t(tree.nodes.size()));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("--node " + std::to_string(tree.nodes.size())), std::string::npos)
        << e.what();
    EXPECT_NE(std::string(e.what()).find("0.." + std::to_string(tree.nodes.size() - 1)), std::string::npos)
        << e.what();
  }
  // Paths: L below (the next node), R above.
  EXPECT_EQ(bsp_node_by_path(tree, ""), 0u);
  EXPECT_EQ(bsp_node_by_path(tree, "L"), 1u);
  EXPECT_EQ(bsp_node_by_path(tree, "r"), tree.nodes[0].above_child());
  EXPECT_THROW(bsp_node_by_path(tree, "LX"), InputError);
  EXPECT_THROW(bsp_node_by_path(tree, std::string(80, 'L')), InputError);
  // Direction names and normals.
  EXPECT_STREQ(bsp_direction_name(0), "x");
  EXPECT_STREQ(bsp_direction_name(3), "x+y");
  EXPECT_STREQ(bsp_direction_name(12), "-x+y+z");
  EXPECT_STREQ(bsp_direction_name(-1), "own plane");
  EXPECT_NEAR(glm::length(bsp_kdop_direction(12)), 1.0, 1e-6);
  EXPECT_NEAR(bsp_kdop_direction(12).x, -1.0 / std::sqrt(3.0), 1e-6);
}

}  // namespace
}  // namespace raystep
