// The BVH builders: the layout's rules (a permutation of the primitive ids, leaves sorted, tight boxes,
// depth-first ids), the binned SAH within 3% of the full sweep's cost on the shipped scenes, the same tree
// for every thread count, pathological input bounded and correct (identical, coplanar, a teapot in a stadium,
// slivers), the listener's replay and the SAH curve, the statistics and Crofton's entry probability.
#include <gtest/gtest.h>

#include <cstring>
#include <filesystem>
#include <random>
#include <set>

#include <tbb/global_control.h>

#include "raystep/accel/brute_force.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_entry_probability.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::count_disagreements;
using test::make_soup;

const BvhBuilder kBuilders[] = {BvhBuilder::binned, BvhBuilder::sweep, BvhBuilder::median};

BvhData build(const Geometry& g, BvhBuilder builder, BvhOptions o = {}) {
  o.builder = builder;
  return build_bvh(g, o);
}

// The layout's rules, checked node by node.
void check_layout(const Geometry& g, const BvhData& d, const BvhOptions& o, const std::string& what) {
  ASSERT_EQ(d.nodes.size(), d.info.size()) << what;
  ASSERT_EQ(d.prim_index.size(), g.size()) << what;
  std::vector<int> seen(g.size(), 0);
  for (uint32_t p : d.prim_index) {
    ASSERT_LT(p, g.size()) << what;
    ++seen[p];
  }
  for (int s : seen) ASSERT_EQ(s, 1) << what << ": prim_index is not a permutation";
  ASSERT_LE(d.nodes.size(), 2 * std::max<size_t>(g.size(), 1) - 1) << what;
  uint32_t next_leaf_prim = 0;
  for (size_t i = 0; i < d.nodes.size(); ++i) {
    const BvhNode& n = d.nodes[i];
    const BvhNodeInfo& info = d.info[i];
    ASSERT_LE(info.depth, o.max_depth) << what;
    if (i == 0) EXPECT_EQ(info.parent, -1) << what;
    if (n.is_leaf()) {
      // Leaves in id order cover prim_index from the start, each sorted by primitive id, with a tight box.
      EXPECT_EQ(n.first_prim(), next_leaf_prim) << what;
      next_leaf_prim += n.prim_count();
      EXPECT_EQ(n.prim_count(), info.prims) << what;
      Bounds3 tight;
      for (uint32_t k = 0; k < n.prim_count(); ++k) {
        if (k > 0) EXPECT_LT(d.prim_index[n.first_prim() + k - 1], d.prim_index[n.first_prim() + k]) << what;
        Bounds3 b = g.prim_bounds(d.prim_index[n.first_prim() + k]);
        tight.extend(b);
      }
      if (g.size() > 0) {
        EXPECT_EQ(tight.lo, n.box.lo) << what << " leaf " << i;
        EXPECT_EQ(tight.hi, n.box.hi) << what << " leaf " << i;
      }
      if (n.prim_count() > uint32_t(o.max_leaf_size)) EXPECT_EQ(info.depth, o.max_depth) << what;
    } else {
      uint32_t l = uint32_t(i) + 1, r = n.second_child();
      ASSERT_GT(r, l) << what;
      ASSERT_LT(r, d.nodes.size()) << what;
      EXPECT_EQ(d.info[l].parent, int32_t(i)) << what;
      EXPECT_EQ(d.info[r].parent, int32_t(i)) << what;
      EXPECT_EQ(d.info[l].depth, info.depth + 1) << what;
      EXPECT_EQ(d.info[l].prims + d.info[r].prims, info.prims) << what;
      EXPECT_GT(d.info[l].prims, 0u) << what;
      EXPECT_GT(d.info[r].prims, 0u) << what;
      Bounds3 both = union_of(d.nodes[l].box, d.nodes[r].box);
      EXPECT_EQ(both.lo, n.box.lo) << what << " node " << i;
      EXPECT_EQ(both.hi, n.box.hi) << what << " node " << i;
    }
  }
  EXPECT_EQ(next_leaf_prim, g.size()) << what;
}

TEST(BvhBuild, LayoutRulesForEveryBuilderAndOption) {
  Geometry g = make_soup(3, 600, 5);
  std::vector<BvhOptions> variants(5);
  variants[1].leaf_size = 4;
  variants[1].max_leaf_size = 8;
  variants[2].max_depth = 4;
  variants[3].bins = 32;
  variants[4].t_i = 1.f;
  variants[4].t_t = 10.f;  // leaves are cheap: no_cheaper_split, bounded by max_leaf_size
  for (size_t v = 0; v < variants.size(); ++v)
    for (BvhBuilder b : kBuilders)
      check_layout(g, build(g, b, variants[v]), variants[v],
                   "variant " + std::to_string(v) + " builder " + std::to_string(int(b)));
  // The median builder halves by count: a balanced tree of single-primitive leaves.
  BvhOptions single;
  single.leaf_size = 1;
  BvhData median = build(g, BvhBuilder::median, single);
  EXPECT_EQ(median.nodes.size(), 2 * g.size() - 1);
  EXPECT_LE(bvh_stats(median, {}).max_depth, 11);
}

TEST(BvhBuild, BadOptionsAndNonFinitePrimitivesThrow) {
  Geometry g = make_soup(1, 10, 0);
  auto bad = [&](auto change) {
    BvhOptions o;
    change(o);
    EXPECT_THROW(build_bvh(g, o), InputError);
  };
  bad([](BvhOptions& o) { o.bins = 1; });
  bad([](BvhOptions& o) { o.bins = 257; });
  bad([](BvhOptions& o) { o.t_i = 0.f; });
  bad([](BvhOptions& o) { o.t_i = std::nanf(""); });
  bad([](BvhOptions& o) { o.t_t = -1.f; });
  bad([](BvhOptions& o) { o.leaf_size = 0; });
  bad([](BvhOptions& o) { o.max_leaf_size = 0; });
  bad([](BvhOptions& o) { o.max_depth = 0; });
  bad([](BvhOptions& o) { o.max_depth = kBvhMaxDepth + 1; });
  bad([](BvhOptions& o) { o.threads = -1; });
  Geometry inf;
  inf.begin_object("bad", 0);
  inf.add_triangle(glm::vec3(0.f), glm::vec3(kInfinity, 0.f, 0.f), glm::vec3(0.f, 1.f, 0.f));
  EXPECT_THROW(build_bvh(inf, BvhOptions{}), InputError);
}

// The SAH cost of the binned build is within 3% of the full sweep's on every scene the tests can load (the
// shipped scenes and meshes; the shared bunny when present).
TEST(BvhBuild, BinnedCostWithinThreePercentOfTheSweep) {
  std::vector<std::string> paths;
  for (const auto& e : std::filesystem::directory_iterator(std::string(RAYSTEP_SOURCE_DIR) + "/scenes"))
    if (e.path().extension() == ".json") paths.push_back(e.path().string());
  for (const auto& e :
       std::filesystem::directory_iterator(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/meshes"))
    if (e.path().extension() == ".obj") paths.push_back(e.path().string());
  std::string bunny = std::string(RAYSTEP_SOURCE_DIR) + "/../shared/meshes/stanford-bunny.obj";
  if (std::filesystem::exists(bunny)) paths.push_back(bunny);
  int compared = 0;
  for (const std::string& path : paths) {
    Scene scene;
    try {
      scene = load_scene(path);
    } catch (const InputError&) {
      continue;  // scenes that exist to show an error
    }
    if (scene.geometry.size() < 2) continue;
    // The searches compared at every node: leaves of one primitive unless the SAH stops earlier (with the
    // default leaf size 4 a tiny scene, the Cornell box, is mostly forced leaves and the bins matter more).
    BvhOptions o;
    o.leaf_size = 1;
    double binned = bvh_stats(build(scene.geometry, BvhBuilder::binned, o), o).sah_cost;
    double sweep = bvh_stats(build(scene.geometry, BvhBuilder::sweep, o), o).sah_cost;
    double median = bvh_stats(build(scene.geometry, BvhBuilder::median, o), o).sah_cost;
    EXPECT_LE(binned, 1.03 * sweep) << path << ": binned " << binned << ", sweep " << sweep;
    EXPECT_GT(binned, 0.0) << path;
    // The median builder ignores the cost; on these scenes it is never the cheaper one by much.
    EXPECT_GE(median, 0.97 * sweep) << path;
    ++compared;
  }
  EXPECT_GE(compared, 5);
}

// The same tree, bit for bit, whatever the number of threads (the parallel paths start at 4096 primitives).
TEST(BvhBuild, DeterministicAcrossThreadCounts) {
  Geometry g = make_soup(11, 30000, 0);
  for (BvhBuilder b : kBuilders) {
    std::vector<BvhData> trees;
    for (int threads : {1, 2, 4}) {
      tbb::global_control limit(tbb::global_control::max_allowed_parallelism, size_t(threads));
      BvhOptions o;
      o.threads = threads;
      trees.push_back(build(g, b, o));
    }
    for (size_t t = 1; t < trees.size(); ++t) {
      ASSERT_EQ(trees[t].nodes.size(), trees[0].nodes.size()) << int(b);
      EXPECT_EQ(
          std::memcmp(trees[t].nodes.data(), trees[0].nodes.data(), trees[0].nodes.size() * sizeof(BvhNode)),
          0)
          << int(b);
      EXPECT_EQ(
          std::memcmp(trees[t].info.data(), trees[0].info.data(), trees[0].info.size() * sizeof(BvhNodeInfo)),
          0)
          << int(b);
      EXPECT_EQ(trees[t].prim_index, trees[0].prim_index) << int(b);
    }
  }
}

void check_pathological(const Geometry& g, const std::string& what, size_t ray_count) {
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), ray_count, 21);
  for (BvhBuilder b : kBuilders) {
    BvhOptions o;
    o.builder = b;
    Bvh bvh(o);
    bvh.build(g);
    const BvhData& d = bvh.data();
    check_layout(g, d, o, what + " builder " + std::to_string(int(b)));
    BvhStats st = bvh_stats(d, o);
    EXPECT_LE(st.max_depth, kBvhMaxDepth) << what;
    EXPECT_LE(st.max_leaf_prims, size_t(o.max_leaf_size)) << what << " builder " << int(b);
    EXPECT_EQ(count_disagreements(bvh, brute, rays), 0) << what << " builder " << int(b);
  }
}

TEST(BvhBuild, PathologicalInputIsBoundedAndCorrect) {
  {
    // 100,000 identical triangles: every centroid the same point, so the id range is halved down to 16.
    Geometry g;
    g.begin_object("identical", 0);
    for (int i = 0; i < 100000; ++i)
      g.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.2f), glm::vec3(0.f, 1.f, 0.4f));
    g.add_triangle(glm::vec3(-1.f, -1.f, 1.f), glm::vec3(2.f, -1.f, 1.f), glm::vec3(-1.f, 2.f, 1.f));
    check_pathological(g, "identical", 20);
  }
  {
    // 10,000 coplanar triangles, and a box through their plane.
    Geometry g;
    g.begin_object("coplanar", 0);
    std::mt19937 rng(4);
    std::uniform_real_distribution<float> u(0.f, 10.f), s(0.05f, 0.5f);
    for (int i = 0; i < 10000; ++i) {
      glm::vec3 p(u(rng), u(rng), 0.5f);
      g.add_triangle(p, p + glm::vec3(s(rng), 0.f, 0.f), p + glm::vec3(0.f, s(rng), 0.f));
    }
    add_mesh(g, make_box(glm::vec3(2.f, 2.f, -1.f), glm::vec3(3.f, 3.f, 2.f)), glm::mat4(1.f));
    check_pathological(g, "coplanar", 500);
  }
  {
    // A teapot in a stadium: a fine sphere of 20,480 triangles, 1 across, inside a box 1e4 across. (Smaller,
    // its triangles would be finer than the floats around a ray origin 100 away can resolve: the triangle
    // test's t then strays outside the triangle's own box, which no box-pruning structure can follow.)
    Geometry g;
    add_to_geometry(make_icosphere(5, glm::vec3(3.f, 2.f, 1.f), 0.5f), g);
    g.begin_object("stadium", 0);
    add_mesh(g, make_box(glm::vec3(-5e3f), glm::vec3(5e3f)), glm::mat4(1.f));
    check_pathological(g, "teapot in a stadium", 300);
    // Rays aimed at the teapot find it.
    BruteForce brute;
    brute.build(g);
    Bvh bvh;
    bvh.build(g);
    std::vector<Ray> rays;
    std::mt19937 rng(2);
    std::normal_distribution<float> n;
    for (int i = 0; i < 1000; ++i) {
      Ray r;
      r.origin = glm::vec3(3.f, 2.f, 1.f) + 100.f * glm::vec3(n(rng), n(rng), n(rng));
      r.direction = glm::vec3(3.f, 2.f, 1.f) + 0.3f * glm::vec3(n(rng), n(rng), n(rng)) - r.origin;
      rays.push_back(r);
    }
    EXPECT_EQ(count_disagreements(bvh, brute, rays), 0);
  }
  {
    // Long slivers: 5,000 triangles 100 long and 1e-3 wide, criss-crossing.
    Geometry g;
    g.begin_object("slivers", 0);
    std::mt19937 rng(6);
    std::uniform_real_distribution<float> u(-50.f, 50.f);
    std::normal_distribution<float> n;
    for (int i = 0; i < 5000; ++i) {
      glm::vec3 a(u(rng), u(rng), u(rng)), d(n(rng), n(rng), n(rng));
      glm::vec3 b = a + 100.f * glm::normalize(d);
      g.add_triangle(a, b, a + glm::vec3(1e-3f, 2e-3f, -1e-3f));
    }
    check_pathological(g, "slivers", 600);
  }
}

TEST(BvhBuild, EmptyAndSinglePrimitive) {
  Geometry empty;
  BvhData d = build_bvh(empty, BvhOptions{});
  ASSERT_EQ(d.nodes.size(), 1u);
  EXPECT_TRUE(d.nodes[0].is_leaf());
  EXPECT_EQ(d.nodes[0].prim_count(), 0u);
  EXPECT_TRUE(d.nodes[0].box.empty());
  Geometry one = make_soup(2, 1, 0);
  for (BvhBuilder b : kBuilders) {
    BvhData t = build(one, b);
    ASSERT_EQ(t.nodes.size(), 1u);
    EXPECT_EQ(t.nodes[0].prim_count(), 1u);
  }
}

// Records the listener's calls.
class Recorder final : public BvhBuildListener {
 public:
  explicit Recorder(uint32_t wanted) : wanted_(wanted) {}
  bool wants_candidates(uint32_t node) const override { return node == wanted_; }
  void candidate(uint32_t node, const BvhCandidate& c) override {
    EXPECT_EQ(node, wanted_);
    candidates.push_back(c);
  }
  void split(uint32_t node, const BvhNode& n, const BvhNodeInfo&, const BvhCandidate& chosen,
             float leaf_cost) override {
    EXPECT_EQ(node, next++);
    EXPECT_FALSE(n.is_leaf());
    EXPECT_EQ(chosen.axis, n.axis());
    splits.push_back({node, chosen});
    leaf_costs.push_back(leaf_cost);
  }
  void leaf_made(uint32_t node, const BvhNode& n, const BvhNodeInfo&, float, BvhLeafReason reason) override {
    EXPECT_EQ(node, next++);
    EXPECT_TRUE(n.is_leaf());
    reasons.push_back(reason);
  }
  uint32_t wanted_, next = 0;
  std::vector<BvhCandidate> candidates;
  std::vector<std::pair<uint32_t, BvhCandidate>> splits;
  std::vector<float> leaf_costs;
  std::vector<BvhLeafReason> reasons;
};

TEST(BvhBuild, ListenerReplaysEveryNodeAndTheCurveShowsTheChoice) {
  Geometry g = make_soup(7, 500, 3);
  for (BvhBuilder b : kBuilders) {
    BvhOptions o;
    o.builder = b;
    Recorder rec(0);
    BvhData d = build_bvh(g, o, rec);
    EXPECT_EQ(rec.next, d.nodes.size());
    EXPECT_EQ(rec.splits.size() + rec.reasons.size(), d.nodes.size());
    // Each split's left count is its first child's primitives; the chosen candidate is the cheapest valid
    // one.
    for (const auto& [node, c] : rec.splits) {
      EXPECT_EQ(c.n_left, d.info[node + 1].prims);
      EXPECT_EQ(c.n_right, d.info[d.nodes[node].second_child()].prims);
      EXPECT_TRUE(c.chosen);
    }
    // The root's candidates: binned, every bin boundary on each axis; sweep, every boundary; median, one.
    size_t expected = b == BvhBuilder::binned  ? 3 * size_t(o.bins - 1)
                      : b == BvhBuilder::sweep ? 3 * (g.size() - 1)
                                               : 1;
    EXPECT_EQ(rec.candidates.size(), expected) << int(b);
    int chosen = 0;
    float best = kInfinity;
    for (const BvhCandidate& c : rec.candidates) {
      chosen += c.chosen;
      if (c.n_left > 0 && c.n_right > 0) best = std::min(best, c.cost);
    }
    EXPECT_EQ(chosen, 1);
    EXPECT_EQ(rec.splits[0].second.cost, best);
    // The SAH curve call gives the same rows.
    std::vector<BvhCandidate> curve = bvh_sah_curve(g, o, 0);
    ASSERT_EQ(curve.size(), rec.candidates.size());
    for (size_t i = 0; i < curve.size(); ++i) {
      EXPECT_EQ(curve[i].cost, rec.candidates[i].cost);
      EXPECT_EQ(curve[i].chosen, rec.candidates[i].chosen);
    }
  }
  EXPECT_THROW(bvh_sah_curve(g, BvhOptions{}, 1u << 20), InputError);
  BvhData d = build_bvh(g, BvhOptions{});
  EXPECT_EQ(bvh_node_by_path(d, ""), 0u);
  EXPECT_EQ(bvh_node_by_path(d, "L"), 1u);
  EXPECT_EQ(bvh_node_by_path(d, "R"), d.nodes[0].second_child());
  EXPECT_THROW(bvh_node_by_path(d, "X"), InputError);
}

TEST(BvhBuild, StatisticsOfAKnownTree) {
  // Two unit cubes far apart: a root and two leaves; no overlap. Then two overlapping ones.
  for (float gap : {3.f, -0.5f}) {
    Geometry g;
    g.begin_object("two", 0);
    add_mesh(g, make_box(glm::vec3(0.f), glm::vec3(1.f)), glm::mat4(1.f));
    add_mesh(g, make_box(glm::vec3(1.f + gap, 0.f, 0.f), glm::vec3(2.f + gap, 1.f, 1.f)), glm::mat4(1.f));
    BvhOptions o;
    o.leaf_size = 12;  // each cube's 12 triangles a leaf without a search; the root's 24 are split
    o.max_leaf_size = 12;
    BvhData d = build_bvh(g, o);
    BvhStats s = bvh_stats(d, o);
    double root = d.nodes[0].box.surface_area();
    ASSERT_FALSE(d.nodes[0].is_leaf());
    if (gap > 0.f) {
      // The split between the cubes: two leaves of 12, each of area 6.
      ASSERT_EQ(d.nodes.size(), 3u);
      EXPECT_EQ(s.leaves, 2u);
      EXPECT_NEAR(s.sah_cost, o.t_t + o.t_i * 12.0 * 2.0 * 6.0 / root, 1e-3);
      EXPECT_EQ(s.overlap, 0.0);
      EXPECT_EQ(s.max_depth, 1);
    } else {
      EXPECT_GT(s.overlap, 0.0);  // the cubes overlap, so do their leaves' boxes
    }
    EXPECT_EQ(s.mean_leaf_prims, double(g.size()) / double(s.leaves));
  }
}

// Crofton: the fraction of random lines through the root that cross a node's box is near S_node / S_root; the
// rays, which stop at the first hit, enter no more often than the lines cross.
TEST(BvhEntryProbability, LinesFollowCrofton) {
  Geometry g = make_soup(12, 300, 0);
  Bvh bvh;
  bvh.build(g);
  size_t cast = 0;
  std::vector<BvhNodeEntry> e = measure_bvh_entry_probability(bvh, 40000, 3, &cast);
  ASSERT_EQ(e.size(), bvh.data().nodes.size());
  EXPECT_EQ(cast, 40000u);
  EXPECT_EQ(e[0].predicted, 1.0);
  EXPECT_EQ(e[0].lines, 1.0);
  for (size_t i = 0; i < e.size(); ++i) {
    EXPECT_NEAR(e[i].lines, e[i].predicted, 0.015) << i;
    EXPECT_LE(e[i].rays, e[i].lines + 1e-12) << i;
  }
}

}  // namespace
}  // namespace raystep
