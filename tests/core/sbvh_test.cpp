// The spatial-split BVH (BvhBuilder::sbvh): every point of every primitive lies in the box of a leaf that
// lists it (the invariant that makes the walk find every hit), at large and small scale and on slivers; the
// references stay within the budget; without a budget it is the binned tree; its SAH cost is below the binned
// builder's where triangles are long; it agrees with brute force; the same tree for every thread count; its
// listener tells spatial and object candidates and the one taken.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>

#include <tbb/global_control.h>

#include "raystep/accel/brute_force.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_names.h"
#include "raystep/accel/bvh_quality.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/structure_options.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/io/scene_loader.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "ray_battery.h"
#include "test_budget.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::count_disagreements;

BvhData sbvh(const Geometry& g, BvhOptions o = {}) {
  o.builder = BvhBuilder::sbvh;
  return build_bvh(g, o);
}

// Long thin triangles crossing each other in a box (where object splits overlap most), scaled and moved.
Geometry slivers(uint32_t seed, int count, float scale, glm::vec3 offset) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f), w(0.001f, 0.05f);
  g.begin_object("slivers", 0);
  for (int i = 0; i < count; ++i) {
    glm::vec3 a(u(rng), u(rng), u(rng));
    glm::vec3 b(u(rng), u(rng), u(rng));
    glm::vec3 side(w(rng), w(rng), w(rng));
    g.add_triangle(offset + scale * a, offset + scale * b, offset + scale * (a + side));
  }
  return g;
}

// Points of a triangle: its vertices, points along its edges and inside.
std::vector<glm::vec3> points_of(const Geometry& g, uint32_t id) {
  std::vector<glm::vec3> out;
  const glm::vec3 &a = g.vertex(id, 0), &b = g.vertex(id, 1), &c = g.vertex(id, 2);
  const int n = 12;
  for (int i = 0; i <= n; ++i)
    for (int j = 0; i + j <= n; ++j) {
      const float u = float(i) / n, v = float(j) / n;
      out.push_back(a + u * (b - a) + v * (c - a));
    }
  return out;
}

// The box of `b` grown by the rounding of the points (points_of computes them in float).
bool holds(const Bounds3& b, const glm::vec3& p) {
  for (int k = 0; k < 3; ++k) {
    const float slack = 4e-7f * (std::fabs(b.lo[k]) + std::fabs(b.hi[k]));
    if (p[k] < b.lo[k] - slack || p[k] > b.hi[k] + slack) return false;
  }
  return true;
}

// The SBVH's layout: ids in preorder, boxes the union of the children's, each leaf's ids strictly increasing
// (a primitive once per leaf), every primitive referenced, at most (1 + budget) N references, and every
// point of every triangle in the box of a leaf that lists it.
void check_sbvh(const Geometry& g, const BvhData& d, const BvhOptions& o, const std::string& what) {
  ASSERT_EQ(d.nodes.size(), d.info.size()) << what;
  ASSERT_GE(d.prim_index.size(), g.size()) << what;
  EXPECT_LE(double(d.prim_index.size()), (1.0 + o.spatial_budget) * double(g.size())) << what;
  std::vector<std::vector<uint32_t>> leaves_of(g.size());
  uint32_t next = 0;
  for (size_t i = 0; i < d.nodes.size(); ++i) {
    const BvhNode& n = d.nodes[i];
    if (n.is_leaf()) {
      ASSERT_EQ(n.first_prim(), next) << what;
      next += n.prim_count();
      EXPECT_EQ(n.prim_count(), d.info[i].prims) << what;
      EXPECT_FALSE(n.box.empty()) << what << " leaf " << i;
      for (uint32_t k = 0; k < n.prim_count(); ++k) {
        const uint32_t id = d.prim_index[n.first_prim() + k];
        ASSERT_LT(id, g.size()) << what;
        if (k > 0) EXPECT_LT(d.prim_index[n.first_prim() + k - 1], id) << what;
        leaves_of[id].push_back(uint32_t(i));
        // A leaf's box lies within its primitives' bounds (clipped, never grown).
        const Bounds3 pb = g.prim_bounds(id);
        EXPECT_TRUE(n.box.overlaps(pb)) << what << " leaf " << i << " prim " << id;
      }
    } else {
      const uint32_t l = uint32_t(i) + 1, r = n.second_child();
      ASSERT_GT(r, l) << what;
      ASSERT_LT(r, d.nodes.size()) << what;
      EXPECT_EQ(d.info[l].parent, int32_t(i)) << what;
      EXPECT_EQ(d.info[r].parent, int32_t(i)) << what;
      const Bounds3 both = union_of(d.nodes[l].box, d.nodes[r].box);
      EXPECT_EQ(both.lo, n.box.lo) << what << " node " << i;
      EXPECT_EQ(both.hi, n.box.hi) << what << " node " << i;
    }
  }
  EXPECT_EQ(next, d.prim_index.size()) << what;
  int uncovered = 0;
  for (uint32_t id = 0; id < g.size(); ++id) {
    ASSERT_FALSE(leaves_of[id].empty()) << what << ": primitive " << id << " is in no leaf";
    if (g.type(id) != PrimType::triangle) continue;
    for (const glm::vec3& p : points_of(g, id)) {
      bool in = false;
      for (uint32_t leaf : leaves_of[id]) in = in || holds(d.nodes[leaf].box, p);
      if (!in) ++uncovered;
    }
  }
  EXPECT_EQ(uncovered, 0) << what << ": points of primitives outside every leaf that lists them";
}

size_t spatial_splits(const Geometry& g, const BvhOptions& o) {
  struct Count final : BvhBuildListener {
    size_t spatial = 0, inner = 0;
    bool wants_candidates(uint32_t) const override { return false; }
    void candidate(uint32_t, const BvhCandidate&) override {}
    void split(uint32_t, const BvhNode&, const BvhNodeInfo&, const BvhCandidate& c, float) override {
      ++inner;
      spatial += c.spatial;
    }
    void leaf_made(uint32_t, const BvhNode&, const BvhNodeInfo&, float, BvhLeafReason) override {}
  } count;
  BvhOptions s = o;
  s.builder = BvhBuilder::sbvh;
  build_bvh(g, s, count);
  return count.spatial;
}

TEST(Sbvh, EveryPointOfEveryPrimitiveIsInALeafThatListsIt) {
  for (float scale : {1.f, 1e-6f, 1e6f}) {
    const glm::vec3 offset = scale == 1.f ? glm::vec3(0.f) : glm::vec3(3.f * scale, -7.f * scale, 1e3f * scale);
    Geometry g = slivers(3, 800, scale, offset);
    for (float budget : {1.f, 0.1f}) {
      BvhOptions o;
      o.spatial_budget = budget;
      const std::string what = "scale " + std::to_string(scale) + " budget " + std::to_string(budget);
      check_sbvh(g, sbvh(g, o), o, what);
      EXPECT_GT(spatial_splits(g, o), 0u) << what;
    }
  }
  Geometry soup = test::make_soup(4, 500, 6);
  check_sbvh(soup, sbvh(soup), BvhOptions{}, "soup with spheres");
  Geometry sphere;
  add_to_geometry(make_icosphere(3), sphere);
  check_sbvh(sphere, sbvh(sphere), BvhOptions{}, "icosphere");
}

// Spatial splits lower the SAH cost where object splits overlap, never raise it much anywhere, and without
// a budget the builder is the binned one, node for node.
TEST(Sbvh, CheaperThanBinnedAndBinnedWithoutABudget) {
  BvhOptions o;
  o.leaf_size = 1;
  BvhOptions b = o;
  b.builder = BvhBuilder::binned;
  Geometry g = slivers(5, 2000, 1.f, glm::vec3(0.f));
  const double binned = bvh_stats(build_bvh(g, b), b).sah_cost;
  const double spatial = bvh_stats(sbvh(g, o), o).sah_cost;
  EXPECT_LT(spatial, 0.9 * binned) << "binned " << binned << ", sbvh " << spatial;
  // The same in the quality metrics, whose SAH is bvh_stats's; and spatial splits cut the surface that lies
  // in boxes of subtrees without its triangle (EPO).
  const BvhQuality qb = tree_quality(bvh_view(build_bvh(g, b)), g, b.t_i, b.t_t);
  const BvhQuality qs = tree_quality(bvh_view(sbvh(g, o)), g, o.t_i, o.t_t);
  EXPECT_NEAR(qb.sah_cost, binned, 1e-6 * binned);
  EXPECT_NEAR(qs.sah_cost, spatial, 1e-6 * spatial);
  EXPECT_LT(qs.epo, 0.9 * qb.epo) << "binned " << qb.epo << ", sbvh " << qs.epo;
  EXPECT_GT(qs.references, g.size());
  EXPECT_EQ(qb.references, g.size());

  std::vector<std::string> paths = {std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json"};
  const std::string bunny = std::string(RAYSTEP_SOURCE_DIR) + "/../shared/meshes/stanford-bunny.obj";
  if (std::filesystem::exists(bunny)) paths.push_back(bunny);
  for (const std::string& path : paths) {
    Scene scene = load_scene(path);
    const double c_binned = bvh_stats(build_bvh(scene.geometry, b), b).sah_cost;
    const double c_spatial = bvh_stats(sbvh(scene.geometry, o), o).sah_cost;
    EXPECT_LT(c_spatial, c_binned) << path;
  }

  BvhOptions none = o;
  none.spatial_budget = 0.f;
  const BvhData a = build_bvh(g, b), z = sbvh(g, none);
  ASSERT_EQ(a.nodes.size(), z.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].box.lo, z.nodes[i].box.lo) << i;
    EXPECT_EQ(a.nodes[i].box.hi, z.nodes[i].box.hi) << i;
    EXPECT_EQ(a.nodes[i].index, z.nodes[i].index) << i;
    EXPECT_EQ(a.nodes[i].bits, z.nodes[i].bits) << i;
  }
  EXPECT_EQ(a.prim_index, z.prim_index);
}

// Rays lying in the planes where the tree's children meet (a spatial split's plane: the left box ends where the
// right one starts), parallel to an axis, with +0 and -0 in the other components: they pass through the
// triangles' cross-sections, the points the two sides' clipped boxes share.
std::vector<Ray> plane_rays(const BvhData& d, size_t count, uint32_t seed) {
  std::vector<Ray> rays;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const Bounds3 root = d.nodes[0].box;
  for (size_t i = 0; i < d.nodes.size() && rays.size() < count; ++i) {
    const BvhNode& n = d.nodes[i];
    if (n.is_leaf()) continue;
    const int a = n.axis();
    const Bounds3& l = d.nodes[i + 1].box;
    const Bounds3& r = d.nodes[n.second_child()].box;
    if (l.hi[a] != r.lo[a]) continue;
    for (int k = 0; k < 4; ++k) {
      const int along = (a + 1 + k % 2) % 3;
      glm::vec3 o = n.box.lo + (n.box.hi - n.box.lo) * glm::vec3(u(rng), u(rng), u(rng));
      o[a] = l.hi[a];
      o[along] = k < 2 ? root.lo[along] - 1.f : root.hi[along] + 1.f;
      glm::vec3 dir(k % 2 ? -0.f : 0.f);
      dir[along] = k < 2 ? 1.f : -1.f;
      rays.push_back(Ray{o, dir});
    }
  }
  return rays;
}

TEST(Sbvh, AgreesWithBruteForceOnSliversAndHardRays) {
  for (float scale : {1.f, 1e5f}) {
    Geometry g = slivers(7, 1500, scale, glm::vec3(scale, 0.f, 0.f));
    BruteForce brute;
    brute.build(g);
    std::vector<Ray> rays = random_rays(g.bounds(), test::budget(20000), 3);
    std::vector<Ray> edges = edge_rays(g, test::budget(6000), 4);
    std::vector<Ray> hard = plane_rays(sbvh(g), test::budget(8000), 5);
    EXPECT_GT(hard.size(), 100u);
    rays.insert(rays.end(), edges.begin(), edges.end());
    rays.insert(rays.end(), hard.begin(), hard.end());
    for (const std::string& name : {"bvh-sbvh", "bvh4-sbvh", "bvh8-sbvh"}) {
      auto accel = make_accelerator(name, StructureOptions{});
      accel->build(g);
      EXPECT_EQ(accel->name(), name);
      EXPECT_EQ(count_disagreements(*accel, brute, rays), 0) << name << " scale " << scale;
    }
  }
}

// Watertight on a closed mesh: no edge-aimed ray from inside slips between the clipped references.
TEST(Sbvh, NoLeaksOnAClosedMesh) {
  Geometry g;
  add_to_geometry(make_icosphere(4), g);
  std::vector<Ray> edges = edge_rays(g, test::budget(20000), 6);
  for (const std::string& name : {"bvh-sbvh", "bvh8-sbvh"}) {
    auto accel = make_accelerator(name, StructureOptions{});
    accel->build(g);
    EXPECT_EQ(test::count_leaks(*accel, edges, edges.size()), 0) << name;
  }
}

// The same tree whatever the thread count: the parallel subtrees start at 4096 references.
TEST(Sbvh, DeterministicAcrossThreadCounts) {
  Geometry g = slivers(9, 12000, 1.f, glm::vec3(0.f));
  BvhOptions one;
  one.threads = 1;
  BvhOptions two;
  two.threads = 2;
  const BvhData a = sbvh(g, one), b = sbvh(g, two);
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  EXPECT_EQ(0, std::memcmp(a.nodes.data(), b.nodes.data(), a.nodes.size() * sizeof(BvhNode)));
  EXPECT_EQ(a.prim_index, b.prim_index);
  for (size_t i = 0; i < a.info.size(); ++i) {
    EXPECT_EQ(a.info[i].parent, b.info[i].parent);
    EXPECT_EQ(a.info[i].prims, b.info[i].prims);
  }
  // With a listener the build runs on one thread: the same tree again.
  struct Quiet final : BvhBuildListener {
    bool wants_candidates(uint32_t) const override { return false; }
    void candidate(uint32_t, const BvhCandidate&) override {}
    void split(uint32_t, const BvhNode&, const BvhNodeInfo&, const BvhCandidate&, float) override {}
    void leaf_made(uint32_t, const BvhNode&, const BvhNodeInfo&, float, BvhLeafReason) override {}
  } quiet;
  BvhOptions heard = two;
  heard.builder = BvhBuilder::sbvh;
  const BvhData c = build_bvh(g, heard, quiet);
  ASSERT_EQ(a.nodes.size(), c.nodes.size());
  EXPECT_EQ(0, std::memcmp(a.nodes.data(), c.nodes.data(), a.nodes.size() * sizeof(BvhNode)));
}

// The SAH inspector's curve of an SBVH node holds both kinds of candidate; a node split spatially has its
// chosen candidate among the spatial ones, with more references on its two sides than the node has, and its
// children's references add up to that.
TEST(Sbvh, TheCurveShowsSpatialAndObjectCandidates) {
  Geometry g = slivers(11, 400, 1.f, glm::vec3(0.f));
  BvhOptions o;
  o.builder = BvhBuilder::sbvh;
  const BvhData tree = build_bvh(g, o);
  int spatial_nodes = 0;
  for (uint32_t node = 0; node < tree.nodes.size() && spatial_nodes < 3; ++node) {
    if (tree.nodes[node].is_leaf()) continue;
    const BvhSahCurve curve = record_bvh_sah_curve(g, o, node);
    ASSERT_GE(curve.chosen, 0) << node;
    size_t object = 0, spatial = 0, chosen = 0;
    for (const BvhCandidate& c : curve.candidates) {
      (c.spatial ? spatial : object) += 1;
      chosen += c.chosen;
    }
    EXPECT_EQ(chosen, 1u) << node;
    EXPECT_GT(object, 0u) << node;
    const BvhCandidate& c = curve.candidates[size_t(curve.chosen)];
    if (!c.spatial) continue;
    ++spatial_nodes;
    EXPECT_GT(spatial, 0u) << node;
    EXPECT_GT(c.n_left + c.n_right, curve.info.prims) << node;
    const uint32_t l = node + 1, r = tree.nodes[node].second_child();
    EXPECT_LE(tree.info[l].prims + tree.info[r].prims, c.n_left + c.n_right) << node;
    EXPECT_GT(tree.info[l].prims + tree.info[r].prims, curve.info.prims) << node;
  }
  EXPECT_GT(spatial_nodes, 0);
}

TEST(Sbvh, NamesAndBadOptions) {
  for (const std::string& name : bvh_names()) {
    std::optional<BvhName> n = parse_bvh_name(name);
    ASSERT_TRUE(n) << name;
    EXPECT_EQ(bvh_name(*n), name);
    EXPECT_EQ(make_accelerator(name, StructureOptions{})->name(), name);
  }
  EXPECT_FALSE(parse_bvh_name("bvh8-sweep"));
  EXPECT_FALSE(parse_bvh_name("bvh16"));
  EXPECT_TRUE(is_wide_bvh_name("bvh8-sbvh"));
  EXPECT_FALSE(is_wide_bvh_name("bvh-sbvh"));
  Geometry g = test::make_soup(1, 10, 0);
  auto bad = [&](auto change) {
    BvhOptions o;
    o.builder = BvhBuilder::sbvh;
    change(o);
    EXPECT_THROW(build_bvh(g, o), InputError);
  };
  bad([](BvhOptions& o) { o.spatial_alpha = std::nanf(""); });
  bad([](BvhOptions& o) { o.spatial_alpha = -1.f; });
  bad([](BvhOptions& o) { o.spatial_budget = -0.5f; });
  bad([](BvhOptions& o) { o.spatial_budget = 17.f; });
  Geometry empty;
  BvhOptions o;
  o.builder = BvhBuilder::sbvh;
  EXPECT_EQ(build_bvh(empty, o).nodes.size(), 1u);
}

}  // namespace
}  // namespace raystep

namespace raystep {
namespace {

// EPO by hand: a unit square of two triangles in the plane z = 0 and a third triangle standing across it, each
// group in a leaf of its own. Flat boxes hold no area of the other group; a leaf box grown to hold the
// standing triangle counts that triangle's whole area at the leaf's cost, t_i N.
TEST(BvhQuality, EpoCountsSurfaceInBoxesOfOtherSubtrees) {
  Geometry g;
  g.begin_object("o", 0);
  // Triangle 0 and 1: the square [0,1]^2 at z = 0; triangle 2: a vertical triangle at x = 0.5 reaching from
  // z = -1 to z = 1 over y in [0, 1], crossing the square.
  g.add_triangle({0, 0, 0}, {1, 0, 0}, {1, 1, 0});
  g.add_triangle({0, 0, 0}, {1, 1, 0}, {0, 1, 0});
  g.add_triangle({0.5f, 0, -1}, {0.5f, 1, -1}, {0.5f, 0, 1});
  // The tree by hand: root -> (leaf {0, 1}, leaf {2}).
  WideBvhView t;
  t.nodes.resize(3);
  t.nodes[0].box = g.bounds();
  t.nodes[0].children = {1, 2};
  t.nodes[1].leaf = true;
  t.nodes[1].depth = 1;
  t.nodes[1].prims = {0, 1};
  t.nodes[1].box = union_of(g.prim_bounds(0), g.prim_bounds(1));  // [0,1]^2 x {0}
  t.nodes[2].leaf = true;
  t.nodes[2].depth = 1;
  t.nodes[2].prims = {2};
  t.nodes[2].box = g.prim_bounds(2);  // {0.5} x [0,1] x [-1,1]
  const BvhQuality q = tree_quality(t, g, 80.f, 1.f);
  // Leaf 1's flat box holds the standing triangle's segment at z = 0: no area. Leaf 2's box (the plane
  // x = 0.5) holds no area of the square either (a segment). Nothing overlaps in area: EPO 0.
  EXPECT_EQ(q.epo, 0.0);
  // Now let leaf 1 be the box [0,1]^2 x [-1, 1] (as if it held something tall): it holds the standing
  // triangle's whole area 1 (base 1, height 2, half) at a leaf of cost 80 * 2, over the surface 1 + 1.
  t.nodes[1].box.lo.z = -1.f;
  t.nodes[1].box.hi.z = 1.f;
  const BvhQuality r = tree_quality(t, g, 80.f, 1.f);
  EXPECT_NEAR(r.epo_leaves, 80.0 * 2 * 1.0 / 2.0, 1e-9);
  EXPECT_EQ(r.epo_inner, 0.0);  // the root holds every triangle
  EXPECT_EQ(r.leaves, 2u);
  EXPECT_EQ(r.inner, 1u);
  EXPECT_EQ(r.leaf_prims[1], 1u);
  EXPECT_EQ(r.leaf_prims[2], 1u);
  ASSERT_EQ(r.leaf_depth.size(), 2u);
  EXPECT_EQ(r.leaf_depth[1], 2u);
  // SAH by hand: root 1 + each leaf 80 N S(leaf) / S(root).
  const double root = g.bounds().surface_area();
  EXPECT_NEAR(r.sah_cost,
              1.0 + 80.0 * 2 * double(t.nodes[1].box.surface_area()) / root +
                  80.0 * 1 * double(t.nodes[2].box.surface_area()) / root,
              1e-4);
}

}  // namespace
}  // namespace raystep
