// kdtree_build.h: the SAH curve on scenes computed by hand (two cubes, clipped triangles, planar sets), the
// inspector's CSV contract (cost = formula, chosen = argmin), the Wald-Havran sweep building the same tree as
// the plain reference, structural invariants on every tree (no primitive lost by a leaf it overlaps, children
// partition their parent, depth limit), bounded work on pathological scenes, and the option checks.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <cmath>
#include <functional>
#include <map>
#include <random>
#include <set>

#include "raystep/accel/kdtree_build.h"
#include "raystep/geometry/icosphere.h"
#include "raystep/scene/triangle_mesh.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

void add_box(Geometry& g, const glm::vec3& lo, const glm::vec3& hi) {
  g.begin_object("box", 0);
  add_mesh(g, make_box(lo, hi), glm::mat4(1.f));
}

// Random small triangles in [-2, 2]^3, a few spheres, optionally axis-aligned boxes on a coarse lattice (their
// faces share planes) and coplanar triangles (in z = 0.5 and x = -1).
Geometry make_scene(uint32_t seed, int triangles, int spheres, int boxes, int coplanar) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.f, 2.f), s(-0.5f, 0.5f);
  std::uniform_int_distribution<int> lattice(-4, 3);
  g.begin_object("soup", 0);
  for (int i = 0; i < triangles; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    g.add_triangle(p, p + glm::vec3(s(rng), s(rng), s(rng)), p + glm::vec3(s(rng), s(rng), s(rng)));
  }
  for (int i = 0; i < coplanar; ++i) {
    glm::vec3 p(u(rng), u(rng), 0.5f);
    glm::vec3 q = p + glm::vec3(s(rng), s(rng), 0.f), r = p + glm::vec3(s(rng), s(rng), 0.f);
    if (i % 2) {  // the other plane
      p = glm::vec3(-1.f, p.x, p.y);
      q = glm::vec3(-1.f, q.x, q.y);
      r = glm::vec3(-1.f, r.x, r.y);
    }
    g.add_triangle(p, q, r);
  }
  for (int i = 0; i < spheres; ++i) g.add_sphere(Sphere{glm::vec3(u(rng), u(rng), u(rng)), 0.25f});
  for (int i = 0; i < boxes; ++i) {
    glm::vec3 lo(0.5f * lattice(rng), 0.5f * lattice(rng), 0.5f * lattice(rng));
    add_box(g, lo, lo + glm::vec3(0.5f * (1 + i % 2), 0.5f, 1.f));
  }
  return g;
}

// Records what a build tells, for every node or for one.
class BuildLog : public BuildListener {
 public:
  struct Split {
    uint32_t n;
    int axis;
    float position, cost, leaf_cost;
  };
  struct Leaf {
    uint32_t n;
    float leaf_cost;
    LeafReason reason;
  };
  explicit BuildLog(int64_t only = -1) : only_(only) {}  // -1: every node; -2: none
  bool wants_candidates(uint32_t node) const override { return only_ == -1 || (only_ >= 0 && node == uint32_t(only_)); }
  void sah_candidate(uint32_t node, const SahCandidate& c) override { candidates[node].push_back(c); }
  void split(uint32_t node, const KdNodeInfo& info, uint32_t n, int axis, float position, float cost,
             float leaf_cost) override {
    EXPECT_EQ(info.cost, cost);
    splits[node] = {n, axis, position, cost, leaf_cost};
    order.push_back(node);
  }
  void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf_cost, LeafReason reason) override {
    EXPECT_EQ(info.cost, leaf_cost);
    leaves[node] = {n, leaf_cost, reason};
    order.push_back(node);
  }
  size_t count(LeafReason r) const {
    return size_t(std::count_if(leaves.begin(), leaves.end(), [&](const auto& l) { return l.second.reason == r; }));
  }

  std::map<uint32_t, std::vector<SahCandidate>> candidates;
  std::map<uint32_t, Split> splits;
  std::map<uint32_t, Leaf> leaves;
  std::vector<uint32_t> order;

 private:
  int64_t only_;
};

KdOptions with_builder(KdBuilder b, KdOptions o = {}) {
  o.builder = b;
  return o;
}

// Margin-free separating axis test in double (Akenine-Moeller's 13 axes) against the box [lo + d, hi - d]:
// tri_box_overlap.h's relative margin of 2^-20, right for inserting into grid cells, is larger than the leaves
// the SAH makes around mesh vertices (a few float ulps wide), so the leak check needs an exact test.
bool triangle_in_open_box(const Geometry& g, uint32_t id, const Bounds3& box) {
  glm::dvec3 lo(box.lo), hi(box.hi);
  for (int a = 0; a < 3; ++a) {
    if (!(box.hi[a] > box.lo[a])) continue;
    double d = (std::fabs(lo[a]) + std::fabs(hi[a])) * std::ldexp(1.0, -40);
    lo[a] += d;
    hi[a] -= d;
  }
  glm::dvec3 c = 0.5 * (lo + hi), h = 0.5 * (hi - lo);
  glm::dvec3 v[3];
  for (int k = 0; k < 3; ++k) v[k] = glm::dvec3(g.vertex(id, k)) - c;
  glm::dvec3 e[3] = {v[1] - v[0], v[2] - v[1], v[0] - v[2]};
  auto separated = [&](const glm::dvec3& axis) {
    double d0 = glm::dot(v[0], axis), d1 = glm::dot(v[1], axis), d2 = glm::dot(v[2], axis);
    double rad = h.x * std::fabs(axis.x) + h.y * std::fabs(axis.y) + h.z * std::fabs(axis.z);
    return std::min({d0, d1, d2}) > rad || std::max({d0, d1, d2}) < -rad;
  };
  for (int a = 0; a < 3; ++a) {
    glm::dvec3 axis(0.0);
    axis[a] = 1.0;
    if (separated(axis)) return false;
  }
  for (int i = 0; i < 3; ++i)
    for (int a = 0; a < 3; ++a) {
      glm::dvec3 unit(0.0);
      unit[a] = 1.0;
      glm::dvec3 axis = glm::cross(unit, e[i]);
      if (glm::dot(axis, axis) > 0.0 && separated(axis)) return false;
    }
  glm::dvec3 n = glm::cross(e[0], e[1]);
  return !(glm::dot(n, n) > 0.0) || !separated(n);
}

std::string str(const Bounds3& b) {
  char buf[200];
  std::snprintf(buf, sizeof buf, "[%.9g %.9g %.9g]-[%.9g %.9g %.9g]", b.lo.x, b.lo.y, b.lo.z, b.hi.x, b.hi.y, b.hi.z);
  return buf;
}

bool overlaps(const Geometry& g, uint32_t id, const Bounds3& box) {
  if (!g.prim_bounds(id).overlaps(box)) return false;
  if (g.type(id) == PrimType::triangle) return triangle_in_open_box(g, id, box);
  // Spheres are placed by their bounding box: check that (the sphere's box inside the open leaf box).
  Bounds3 s = g.prim_bounds(id);
  for (int a = 0; a < 3; ++a)
    if (box.hi[a] > box.lo[a] && (s.hi[a] <= box.lo[a] || s.lo[a] >= box.hi[a])) return false;
  return true;
}

// Structural invariants of any built tree.
void check_invariants(const Geometry& g, const KdTreeData& t, const KdOptions& o) {
  ASSERT_FALSE(t.nodes.empty());
  ASSERT_EQ(t.nodes.size(), t.info.size());
  EXPECT_EQ(t.info[0].parent, -1);
  EXPECT_EQ(t.info[0].depth, 0);
  EXPECT_EQ(t.info[0].box.lo, t.bounds.lo);
  EXPECT_EQ(t.info[0].box.hi, t.bounds.hi);
  EXPECT_EQ(t.bounds.lo, g.bounds().lo);
  EXPECT_EQ(t.bounds.hi, g.bounds().hi);
  const int max_depth = kd_max_depth(o, g.size());
  EXPECT_LE(t.prim_index.size(), kd_reference_budget(o, g.size()));

  // Depth-first preorder: the subtree of node i is [i, end); below = i + 1, above = the stored child.
  size_t leaf_refs = 0;
  std::function<uint32_t(uint32_t)> walk = [&](uint32_t i) -> uint32_t {
    const KdNode& n = t.nodes[i];
    const KdNodeInfo& info = t.info[i];
    EXPECT_LE(info.depth, max_depth);
    if (n.is_leaf()) {
      EXPECT_LE(size_t(n.first_prim) + n.prim_count(), t.prim_index.size());
      leaf_refs += n.prim_count();
      EXPECT_FLOAT_EQ(info.cost, o.t_i * float(n.prim_count()));
      const uint32_t* p = t.prim_index.data() + n.first_prim;
      for (uint32_t k = 1; k < n.prim_count(); ++k) EXPECT_LT(p[k - 1], p[k]) << "leaf " << i;
      // No leaks: every primitive overlapping the leaf's cell is in the leaf.
      std::set<uint32_t> in(p, p + n.prim_count());
      for (uint32_t id = 0; id < g.size(); ++id)
        if (!in.count(id) && overlaps(g, id, info.box)) {
          ADD_FAILURE() << "primitive " << id << " leaks from leaf " << i << " box " << str(info.box) << " prim "
                        << str(g.prim_bounds(id));
        }
      return i + 1;
    }
    int a = n.axis();
    uint32_t below = i + 1, above = n.above_child();
    EXPECT_GT(above, below);
    EXPECT_LT(above, t.nodes.size());
    EXPECT_LT(info.box.lo[a], n.split);
    EXPECT_LT(n.split, info.box.hi[a]);
    for (uint32_t c : {below, above}) {
      EXPECT_EQ(t.info[c].parent, int32_t(i));
      EXPECT_EQ(t.info[c].depth, info.depth + 1);
    }
    // The children partition the parent at the split.
    Bounds3 b = info.box, u = info.box;
    b.hi[a] = n.split;
    u.lo[a] = n.split;
    EXPECT_EQ(t.info[below].box.lo, b.lo);
    EXPECT_EQ(t.info[below].box.hi, b.hi);
    EXPECT_EQ(t.info[above].box.lo, u.lo);
    EXPECT_EQ(t.info[above].box.hi, u.hi);
    EXPECT_EQ(walk(below), above) << "the below subtree ends where the above child starts";
    return walk(above);
  };
  EXPECT_EQ(walk(0), t.nodes.size());
  EXPECT_EQ(leaf_refs, t.prim_index.size());
}

void expect_same_tree(const KdTreeData& a, const KdTreeData& b) {
  ASSERT_EQ(a.nodes.size(), b.nodes.size());
  for (size_t i = 0; i < a.nodes.size(); ++i) {
    EXPECT_EQ(a.nodes[i].bits, b.nodes[i].bits) << "node " << i;
    EXPECT_EQ(a.nodes[i].first_prim, b.nodes[i].first_prim) << "node " << i << " (split or first prim bits)";
    EXPECT_EQ(a.info[i].box.lo, b.info[i].box.lo);
    EXPECT_EQ(a.info[i].box.hi, b.info[i].box.hi);
    EXPECT_EQ(a.info[i].parent, b.info[i].parent);
    EXPECT_EQ(a.info[i].depth, b.info[i].depth);
    EXPECT_EQ(a.info[i].cost, b.info[i].cost) << "node " << i;
  }
  EXPECT_EQ(a.prim_index, b.prim_index);
}

// Cost from the candidate's own fields, as the inspector's CSV reader computes it (empty_bonus 0).
double formula_cost(const SahCandidate& c, const KdOptions& o) {
  return double(o.t_t) + double(o.t_i) * (double(c.area_below) / c.area_node * c.n_below +
                                          double(c.area_above) / c.area_node * c.n_above);
}

// The CSV contract on every node of a build: cost = formula; the split is the first minimum-cost candidate in
// emission order (axis x, y, z, increasing position); a no_cheaper_split leaf has every candidate >= N t_i.
void check_contract(const Geometry& g, const KdOptions& o) {
  const bool sah = o.builder != KdBuilder::median;
  BuildLog log;
  KdTreeData t = build_kdtree(g, o, log);
  EXPECT_EQ(log.order.size(), t.nodes.size());
  for (uint32_t i = 0; i < t.nodes.size(); ++i) EXPECT_EQ(log.order[i], i) << "events in node order";
  for (const auto& [node, cands] : log.candidates) {
    ASSERT_FALSE(cands.empty());
    const Bounds3& box = t.info[node].box;
    for (size_t k = 0; k < cands.size(); ++k) {
      const SahCandidate& c = cands[k];
      EXPECT_NEAR(c.cost, formula_cost(c, o), 1e-5 * formula_cost(c, o)) << "node " << node;
      EXPECT_LT(box.lo[c.axis], c.position);
      EXPECT_LT(c.position, box.hi[c.axis]);
      EXPECT_EQ(c.area_node, box.surface_area());
      if (k > 0 && cands[k - 1].axis == c.axis) EXPECT_LT(cands[k - 1].position, c.position) << "distinct, sorted";
      if (k > 0) EXPECT_LE(cands[k - 1].axis, c.axis);
    }
    auto best = std::min_element(cands.begin(), cands.end(),
                                 [](const SahCandidate& a, const SahCandidate& b) { return a.cost < b.cost; });
    if (log.splits.count(node)) {
      const BuildLog::Split& s = log.splits.at(node);
      EXPECT_EQ(s.axis, best->axis) << "node " << node;
      EXPECT_EQ(s.position, best->position) << "node " << node;
      EXPECT_EQ(s.cost, best->cost);
      if (sah) EXPECT_LT(s.cost, s.leaf_cost);
      // The children hold what the chosen candidate counted.
      const KdNode& n = t.nodes[node];
      auto count_prims = [&](uint32_t c) -> uint32_t {
        return log.leaves.count(c) ? log.leaves.at(c).n : log.splits.at(c).n;
      };
      EXPECT_EQ(count_prims(node + 1), best->n_below);
      EXPECT_EQ(count_prims(n.above_child()), best->n_above);
    } else {
      const BuildLog::Leaf& l = log.leaves.at(node);
      if (l.reason == LeafReason::no_cheaper_split)
        for (const SahCandidate& c : cands) EXPECT_GE(c.cost, l.leaf_cost);
    }
  }
  check_invariants(g, t, o);
}

// ---------------------------------------------------------------------------------------------------------

TEST(KdBuild, OptionsAreChecked) {
  Geometry g = make_scene(1, 20, 0, 0, 0);
  auto bad = [&](auto change) {
    KdOptions o;
    change(o);
    EXPECT_THROW(build_kdtree(g, o), InputError);
  };
  const float nan = std::nanf(""), inf = kInfinity;
  bad([](KdOptions& o) { o.t_i = 0.f; });
  bad([](KdOptions& o) { o.t_i = -1.f; });
  bad([&](KdOptions& o) { o.t_i = nan; });
  bad([&](KdOptions& o) { o.t_i = inf; });
  bad([](KdOptions& o) { o.t_t = -1.f; });
  bad([&](KdOptions& o) { o.t_t = nan; });
  bad([](KdOptions& o) { o.empty_bonus = 1.f; });
  bad([](KdOptions& o) { o.empty_bonus = -0.1f; });
  bad([&](KdOptions& o) { o.empty_bonus = nan; });
  bad([](KdOptions& o) { o.max_depth = -1; });
  bad([](KdOptions& o) { o.max_depth = kKdMaxDepth + 1; });
  bad([](KdOptions& o) { o.leaf_size = 0; });
  bad([](KdOptions& o) { o.reference_budget = 0.5f; });
  bad([&](KdOptions& o) { o.reference_budget = nan; });
  bad([](KdOptions& o) { o.builder = KdBuilder(7); });
  try {
    KdOptions o;
    o.t_i = 0.f;
    build_kdtree(g, o);
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "");
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(e.detail().rfind("kd-tree: ", 0), 0u) << e.detail();
  }
  // Extremes that are allowed.
  KdOptions ok;
  ok.t_t = 0.f;
  ok.empty_bonus = 0.99f;
  ok.max_depth = kKdMaxDepth;
  ok.reference_budget = 1.f;
  EXPECT_NO_THROW(build_kdtree(g, ok));
  // A non-finite primitive is refused.
  Geometry h;
  h.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.f), glm::vec3(0.f, inf, 0.f));
  EXPECT_THROW(build_kdtree(h, KdOptions{}), InputError);
}

TEST(KdBuild, DepthLimitAndBudgetRules) {
  KdOptions o;
  EXPECT_EQ(kd_max_depth(o, 0), 8);
  EXPECT_EQ(kd_max_depth(o, 1), 8);
  EXPECT_EQ(kd_max_depth(o, 64), 8);                         // 1.2 * 6 = 7.2: at least 8
  EXPECT_EQ(kd_max_depth(o, 1024), 12);                      // 1.2 * 10
  EXPECT_EQ(kd_max_depth(o, 69451), 19);                     // 1.2 * 16.08 = 19.3
  EXPECT_EQ(kd_max_depth(o, size_t(1) << 60), kKdMaxDepth);  // 1.2 * 60 = 72
  KdOptions bonus;  // an empty bonus spends levels on empty space: pbrt's 8 + 1.3 log2 N
  bonus.empty_bonus = 0.5f;
  EXPECT_EQ(kd_max_depth(bonus, 1024), 21);   // 8 + 1.3 * 10
  EXPECT_EQ(kd_max_depth(bonus, 69451), 29);  // 8 + 1.3 * 16.08 = 28.9
  o.max_depth = 5;
  EXPECT_EQ(kd_max_depth(o, 69451), 5);
  KdOptions b;
  EXPECT_EQ(kd_reference_budget(b, 1000), 8000u);
  b.reference_budget = 1.f;
  EXPECT_EQ(kd_reference_budget(b, 1000), 1000u);
  EXPECT_EQ(kd_reference_budget(b, 0), 0u);
}

// The automatic depth limit leaves room for what the SAH does with it: with an empty bonus the SAH spends a
// level on every slab of empty space it cuts off, and at 1.2 log2 N (no bonus) those levels would be missing
// (the bunny's leaves held up to 780 triangles), so with a bonus the limit is pbrt's.
TEST(KdBuild, AutomaticDepthLeavesSmallLeavesWithAndWithoutEmptyBonus) {
  Geometry g;
  add_to_geometry(make_icosphere(5), g);  // 20,480 triangles, a closed surface like a scanned mesh
  for (float bonus : {0.f, 0.5f}) {
    KdOptions o;
    o.empty_bonus = bonus;
    KdTreeStats automatic = kd_tree_stats(build_kdtree(g, o), o);
    o.max_depth = std::max(8, int(std::lround(1.2 * std::log2(double(g.size())))));
    KdTreeStats shallow = kd_tree_stats(build_kdtree(g, o), o);
    // Measured: no bonus, depth 17 and at most 12 triangles a leaf either way; bonus 0.5, depth 27 and 8, where
    // depth 17 would leave 70.
    EXPECT_LE(automatic.max_leaf_prims, 16u) << "bonus " << bonus;
    if (bonus > 0.f)
      EXPECT_GT(shallow.max_leaf_prims, 4 * automatic.max_leaf_prims);
    else
      EXPECT_EQ(shallow.max_leaf_prims, automatic.max_leaf_prims);  // the same limit
  }
}

TEST(KdBuild, EmptyGeometryIsOneEmptyLeaf) {
  Geometry g;
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::sah_reference, KdBuilder::median}) {
    BuildLog log;
    KdTreeData t = build_kdtree(g, with_builder(b), log);
    ASSERT_EQ(t.nodes.size(), 1u);
    EXPECT_TRUE(t.nodes[0].is_leaf());
    EXPECT_EQ(t.nodes[0].prim_count(), 0u);
    EXPECT_TRUE(t.prim_index.empty());
    EXPECT_TRUE(t.bounds.empty());
    EXPECT_TRUE(t.info[0].box.empty());
    EXPECT_EQ(log.leaves.at(0).reason, LeafReason::few_primitives);
  }
}

TEST(KdSahCurve, TwoSeparatedCubes) {
  // Unit cubes [0,1]^3 and [3,4]x[0,1]^2, 12 triangles each. Root box [0,4]x[0,1]^2, S = 2(4 + 1 + 4) = 18.
  // On x the candidates inside (0, 4) are the inner faces x = 1 and x = 3 (2 planar triangles each); y and z
  // have none (every triangle spans [0,1] there or lies in a boundary face).
  Geometry g;
  add_box(g, glm::vec3(0.f), glm::vec3(1.f));
  add_box(g, glm::vec3(3.f, 0.f, 0.f), glm::vec3(4.f, 1.f, 1.f));
  KdOptions o;
  BuildLog log;
  KdTreeData t = build_kdtree(g, o, log);
  const std::vector<SahCandidate>& root = log.candidates.at(0);
  ASSERT_EQ(root.size(), 2u);
  // x = 1: N_L = 10 (8 spanning [0,1], 2 in x = 0), N_R = 12, N_P = 2. Below [0,1]^3: S = 6; above S = 14.
  // Planar below: 1 + 80 (6/18 * 12 + 14/18 * 12) = 1067.67; planar above: 1 + 80 (6/18*10 + 14/18*14) = 1138.8.
  const SahCandidate& c1 = root[0];
  EXPECT_EQ(c1.axis, 0);
  EXPECT_EQ(c1.position, 1.f);
  EXPECT_EQ(c1.n_planar, 2u);
  EXPECT_EQ(c1.n_below, 12u);
  EXPECT_EQ(c1.n_above, 12u);
  EXPECT_TRUE(c1.planar_below);
  EXPECT_FLOAT_EQ(c1.area_node, 18.f);
  EXPECT_FLOAT_EQ(c1.area_below, 6.f);
  EXPECT_FLOAT_EQ(c1.area_above, 14.f);
  EXPECT_NEAR(c1.cost, 1.0 + 80.0 * (6.0 / 18 * 12 + 14.0 / 18 * 12), 1e-3);
  // x = 3, the mirror image: planar above is the cheaper side, at exactly the same cost.
  const SahCandidate& c3 = root[1];
  EXPECT_EQ(c3.position, 3.f);
  EXPECT_FALSE(c3.planar_below);
  EXPECT_EQ(c3.n_below, 12u);
  EXPECT_EQ(c3.n_above, 12u);
  EXPECT_EQ(c3.cost, c1.cost);
  // The tie goes to the lower position: the root splits at x = 1.
  EXPECT_EQ(t.nodes[0].axis(), 0);
  EXPECT_EQ(t.nodes[0].split, 1.f);
  EXPECT_EQ(log.splits.at(0).leaf_cost, 24.f * 80.f);
  // The above child [1,4]: only the second cube. At x = 3: N_L = 0, N_P = 2, N_R = 10; planar above leaves the
  // below child empty: 1 + 80 (4/14 * 0 + ... ) with S([1,4]) = 14, S([3,4]) = 6: 1 + 80 * 6/14 * 12 = 412.43.
  uint32_t above = t.nodes[0].above_child();
  const std::vector<SahCandidate>& a = log.candidates.at(above);
  ASSERT_EQ(a.size(), 1u);
  EXPECT_EQ(a[0].n_below, 0u);
  EXPECT_EQ(a[0].n_above, 12u);
  EXPECT_FALSE(a[0].planar_below);
  EXPECT_NEAR(a[0].cost, 1.0 + 80.0 * 6.0 / 14.0 * 12.0, 1e-3);
  check_invariants(g, t, o);

  // With an empty bonus the split with an empty child is cheaper: 1 + (1 - 0.5) 80 (6/14 * 12).
  KdOptions ob;
  ob.empty_bonus = 0.5f;
  BuildLog logb;
  build_kdtree(g, ob, logb);
  EXPECT_NEAR(logb.candidates.at(above)[0].cost, 1.0 + 0.5 * 80.0 * 6.0 / 14.0 * 12.0, 1e-3);
}

TEST(KdSahCurve, FlatSceneOfTwoTriangles) {
  // Two triangles in z = 0: T on x in [0,2], S on x in [6,8]; y in [0,2] for both. The root box is flat
  // ([0,8]x[0,2]x[0,0], S = 2 * 16 = 32); candidates only on x, at 2 and 6, each 1 + 80 (8/32 + 24/32) = 81.
  Geometry g;
  g.add_triangle(glm::vec3(0, 0, 0), glm::vec3(2, 0, 0), glm::vec3(0, 2, 0));
  g.add_triangle(glm::vec3(6, 0, 0), glm::vec3(8, 0, 0), glm::vec3(6, 2, 0));
  BuildLog log;
  KdTreeData t = build_kdtree(g, KdOptions{}, log);
  const auto& c = log.candidates.at(0);
  ASSERT_EQ(c.size(), 2u);
  for (const SahCandidate& k : c) {
    EXPECT_EQ(k.axis, 0);
    EXPECT_EQ(k.n_below, 1u);
    EXPECT_EQ(k.n_above, 1u);
    EXPECT_EQ(k.n_planar, 0u);
    EXPECT_FLOAT_EQ(k.area_node, 32.f);
    EXPECT_FLOAT_EQ(k.cost, 81.f);
  }
  EXPECT_EQ(c[0].position, 2.f);
  EXPECT_EQ(c[1].position, 6.f);
  EXPECT_FLOAT_EQ(c[0].area_below, 8.f);
  EXPECT_FLOAT_EQ(c[0].area_above, 24.f);
  EXPECT_EQ(t.nodes[0].split, 2.f);  // the tie goes to the lower position
  EXPECT_EQ(t.nodes.size(), 3u);
  EXPECT_EQ(log.leaves.at(1).reason, LeafReason::few_primitives);
  check_invariants(g, t, KdOptions{});
}

TEST(KdSahCurve, CandidatesComeFromClippedTriangles) {
  // T1 = (0,0,0) (4,0,0) (0,4,0) covers x + y <= 4; T2 = a small triangle in the corner [3.5,4]^2. The root
  // splits at x = 3.5 (1 + 80 (28/32 * 1 + 4/32 * 2) = 91; y = 3.5 ties and loses). In the above child
  // [3.5,4] x [0,4], T1 clipped to x >= 3.5 only reaches y = 0.5: that is a candidate (a perfect split), where
  // the unclipped bounds would give none between T1 and T2.
  Geometry g;
  g.add_triangle(glm::vec3(0, 0, 0), glm::vec3(4, 0, 0), glm::vec3(0, 4, 0));
  g.add_triangle(glm::vec3(3.5f, 3.5f, 0), glm::vec3(4, 3.5f, 0), glm::vec3(4, 4, 0));
  BuildLog log;
  KdTreeData t = build_kdtree(g, KdOptions{}, log);
  EXPECT_EQ(t.nodes[0].axis(), 0);
  EXPECT_EQ(t.nodes[0].split, 3.5f);
  EXPECT_NEAR(log.splits.at(0).cost, 91.0, 1e-3);
  uint32_t above = t.nodes[0].above_child();
  const auto& c = log.candidates.at(above);
  ASSERT_EQ(c.size(), 2u);
  // y = 0.5 exactly (the clip's arithmetic is exact here): N_b = 1, N_a = 1, S = 4, S_b = 0.5, S_a = 3.5.
  EXPECT_EQ(c[0].axis, 1);
  EXPECT_EQ(c[0].position, 0.5f);
  EXPECT_EQ(c[0].n_below, 1u);
  EXPECT_EQ(c[0].n_above, 1u);
  EXPECT_NEAR(c[0].area_below, 0.5f, 1e-5);
  EXPECT_NEAR(c[0].cost, 81.0, 1e-3);
  EXPECT_EQ(c[1].position, 3.5f);
  EXPECT_EQ(t.nodes[above].axis(), 1);
  EXPECT_EQ(t.nodes[above].split, c[0].position);
  check_invariants(g, t, KdOptions{});
}

TEST(KdSahCurve, PlanarPrimitivesGoToTheCheaperSide) {
  // A unit quad in the plane x = 1.5 (2 triangles), A spanning x in [0,0.5], B spanning [1.75,2]; all span
  // y, z in [0,1]. Root [0,2]x[0,1]^2, S = 10. At x = 1.5: N_L = 1, N_R = 1, N_P = 2; S_b = 8, S_a = 4.
  // Planar below: 1 + 80 (0.8 * 3 + 0.4 * 1) = 225; planar above: 1 + 80 (0.8 * 1 + 0.4 * 3) = 161.
  Geometry g;
  g.begin_object("quad", 0);
  add_mesh(g, make_quad(glm::vec3(1.5f, 0, 0), glm::vec3(1.5f, 1, 0), glm::vec3(1.5f, 1, 1), glm::vec3(1.5f, 0, 1)),
           glm::mat4(1.f));
  g.add_triangle(glm::vec3(0, 0, 0), glm::vec3(0.5f, 0, 0), glm::vec3(0, 1, 1));      // A, id 2
  g.add_triangle(glm::vec3(1.75f, 0, 0), glm::vec3(2, 0, 0), glm::vec3(2, 1, 1));     // B, id 3
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::sah_reference}) {
    BuildLog log;
    KdTreeData t = build_kdtree(g, with_builder(b), log);
    const auto& c = log.candidates.at(0);
    ASSERT_EQ(c.size(), 3u);  // x = 0.5, 1.5, 1.75
    EXPECT_EQ(c[1].position, 1.5f);
    EXPECT_EQ(c[1].n_planar, 2u);
    EXPECT_FALSE(c[1].planar_below);
    EXPECT_EQ(c[1].n_below, 1u);
    EXPECT_EQ(c[1].n_above, 3u);
    EXPECT_NEAR(c[1].cost, 161.0, 1e-3);
    EXPECT_NEAR(c[0].cost, 1.0 + 80.0 * (0.4 * 1 + 0.8 * 3), 1e-3);   // x = 0.5: 225
    EXPECT_NEAR(c[2].cost, 1.0 + 80.0 * (0.9 * 3 + 0.3 * 1), 1e-3);   // x = 1.75: 241
    // The split puts the quad above: below holds A alone.
    EXPECT_EQ(t.nodes[0].split, 1.5f);
    ASSERT_TRUE(t.nodes[1].is_leaf());
    ASSERT_EQ(t.nodes[1].prim_count(), 1u);
    EXPECT_EQ(t.prim_index[t.nodes[1].first_prim], 2u);
    check_invariants(g, t, KdOptions{});
  }
}

TEST(KdSahContract, CostIsTheFormulaAndTheSplitIsTheMinimum) {
  for (uint32_t seed : {1u, 2u, 3u}) check_contract(make_scene(seed, 150, 4, 6, 20), KdOptions{});
  Geometry ico;
  add_to_geometry(make_icosphere(3), ico);
  check_contract(ico, KdOptions{});
  KdOptions cheap;
  cheap.t_i = 2.f;  // more leaves decided by cost
  check_contract(make_scene(4, 200, 0, 0, 0), cheap);
  check_contract(make_scene(5, 100, 0, 4, 10), with_builder(KdBuilder::median));
}

TEST(KdSahContract, OneNodeListenerSeesThatNodeOnly) {
  Geometry g = make_scene(6, 120, 2, 4, 10);
  BuildLog all;
  KdTreeData t = build_kdtree(g, KdOptions{}, all);
  for (uint32_t node : {0u, 1u, t.nodes[0].above_child(), uint32_t(t.nodes.size() / 2)}) {
    BuildLog one(node);
    build_kdtree(g, KdOptions{}, one);
    EXPECT_LE(one.candidates.size(), 1u);
    if (!all.candidates.count(node)) {
      EXPECT_TRUE(one.candidates.empty());
      continue;
    }
    const auto& a = all.candidates.at(node);
    const auto& b = one.candidates.at(node);
    ASSERT_EQ(a.size(), b.size());
    for (size_t k = 0; k < a.size(); ++k) {
      EXPECT_EQ(a[k].position, b[k].position);
      EXPECT_EQ(a[k].cost, b[k].cost);
    }
  }
}

TEST(KdSweep, BuildsTheSameTreeAsTheReference) {
  struct Case {
    uint32_t seed;
    int triangles, spheres, boxes, coplanar;
  };
  for (Case c : {Case{11, 30, 0, 0, 0}, Case{12, 120, 0, 0, 0}, Case{13, 60, 5, 8, 0}, Case{14, 0, 0, 20, 0},
                 Case{15, 40, 0, 0, 60}, Case{16, 200, 3, 10, 40}, Case{17, 0, 0, 0, 100}}) {
    Geometry g = make_scene(c.seed, c.triangles, c.spheres, c.boxes, c.coplanar);
    for (KdOptions o : {KdOptions{}, [] { KdOptions k; k.empty_bonus = 0.5f; k.leaf_size = 3; return k; }(),
                        [] { KdOptions k; k.t_i = 3.f; k.max_depth = 6; return k; }(),
                        [] { KdOptions k; k.t_t = 0.f; k.empty_bonus = 0.9f; return k; }()}) {
      SCOPED_TRACE("seed " + std::to_string(c.seed));
      BuildLog fast_log, ref_log;
      KdTreeData fast = build_kdtree(g, with_builder(KdBuilder::sah, o), fast_log);
      KdTreeData ref = build_kdtree(g, with_builder(KdBuilder::sah_reference, o), ref_log);
      expect_same_tree(fast, ref);
      // Without a listener the sweep skips the exact cost of candidates that cannot be cheaper (a lower
      // bound): still the same tree.
      expect_same_tree(build_kdtree(g, with_builder(KdBuilder::sah, o)), ref);
      // The same curve at every node.
      ASSERT_EQ(fast_log.candidates.size(), ref_log.candidates.size());
      for (const auto& [node, cands] : fast_log.candidates) {
        const auto& rc = ref_log.candidates.at(node);
        ASSERT_EQ(cands.size(), rc.size()) << "node " << node;
        for (size_t k = 0; k < cands.size(); ++k) {
          EXPECT_EQ(cands[k].axis, rc[k].axis);
          EXPECT_EQ(cands[k].position, rc[k].position);
          EXPECT_EQ(cands[k].n_below, rc[k].n_below);
          EXPECT_EQ(cands[k].n_above, rc[k].n_above);
          EXPECT_EQ(cands[k].n_planar, rc[k].n_planar);
          EXPECT_EQ(cands[k].cost, rc[k].cost);
        }
      }
      for (const auto& [node, leaf] : fast_log.leaves) EXPECT_EQ(leaf.reason, ref_log.leaves.at(node).reason);
      check_invariants(g, fast, o);
    }
  }
  Geometry ico;
  add_to_geometry(make_icosphere(2), ico);
  expect_same_tree(build_kdtree(ico, KdOptions{}), build_kdtree(ico, with_builder(KdBuilder::sah_reference)));
}

// Scenes scaled far up and far down: the sweep's cheap lower bound (areas times counts over the node's area)
// would overflow to infinity and skip every candidate; where it cannot be trusted, candidates are evaluated
// exactly, and the tree is still the reference's.
TEST(KdSweep, HugeAndTinyScenesBuildTheReferenceTree) {
  for (float scale : {3e17f, 1e-21f}) {
    SCOPED_TRACE("scale " + std::to_string(scale));
    std::mt19937 rng(21);
    std::uniform_real_distribution<float> u(-2.f, 2.f), s(-0.3f, 0.3f);
    Geometry g;
    g.begin_object("soup", 0);
    for (int i = 0; i < 150; ++i) {
      glm::vec3 c(u(rng), u(rng), u(rng));
      g.add_triangle(scale * (c + glm::vec3(s(rng), s(rng), s(rng))), scale * (c + glm::vec3(s(rng), s(rng), s(rng))),
                     scale * (c + glm::vec3(s(rng), s(rng), s(rng))));
    }
    KdTreeData ref = build_kdtree(g, with_builder(KdBuilder::sah_reference, KdOptions{}));
    ASSERT_GT(ref.nodes.size(), 20u);  // a real tree, not one leaf
    expect_same_tree(build_kdtree(g, KdOptions{}), ref);
  }
}

TEST(KdSweep, BoxesOnALatticeSplitOnExactPlanes) {
  // Clipping box faces at lattice planes is exact arithmetic: no plane one ulp off a face, no sliver nodes.
  Geometry g = make_scene(14, 0, 0, 30, 0);
  KdTreeData t = build_kdtree(g, KdOptions{});
  size_t inner = 0;
  for (const KdNode& n : t.nodes) {
    if (n.is_leaf()) continue;
    ++inner;
    EXPECT_EQ(std::fmod(n.split * 256.f, 1.f), 0.f) << n.split;
  }
  EXPECT_GT(inner, 20u);
}

TEST(KdSweep, RecorderDoesNotChangeTheTree) {
  Geometry g = make_scene(21, 300, 5, 5, 30);
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::median}) {
    BuildLog log;
    expect_same_tree(build_kdtree(g, with_builder(b)), build_kdtree(g, with_builder(b), log));
  }
}

TEST(KdInvariants, HoldOnEveryBuilder) {
  Geometry ico;
  add_to_geometry(make_icosphere(3), ico);  // 1280 triangles, a closed surface like a scanned mesh
  Geometry mixed = make_scene(31, 400, 10, 10, 40);
  for (const Geometry* g : {&ico, &mixed})
    for (KdBuilder b : {KdBuilder::sah, KdBuilder::median}) {
      KdOptions o = with_builder(b);
      KdTreeData t = build_kdtree(*g, o);
      check_invariants(*g, t, o);
      KdTreeStats s = kd_tree_stats(t, o);
      EXPECT_GT(s.leaves, 1u);
      EXPECT_EQ(s.references, t.prim_index.size());
      EXPECT_LT(s.sah_cost, o.t_i * double(g->size()));  // better than one leaf
    }
}

TEST(KdMedian, SplitsTheLongestAxisInTheMiddle) {
  Geometry g = make_scene(41, 100, 0, 0, 0);
  BuildLog log;
  KdTreeData t = build_kdtree(g, with_builder(KdBuilder::median), log);
  for (const auto& [node, s] : log.splits) {
    const Bounds3& box = t.info[node].box;
    EXPECT_EQ(s.axis, box.max_axis());
    EXPECT_EQ(s.position, box.center()[s.axis]);
    ASSERT_EQ(log.candidates.at(node).size(), 1u);
  }
  EXPECT_GT(log.splits.size(), 10u);
  check_invariants(g, t, with_builder(KdBuilder::median));
}

// ---------------------------------------------------------------------------------------------------------
// Pathological scenes: the build ends, with node and reference counts bounded.

TEST(KdPathological, IdenticalTriangles) {
  Geometry g;
  for (int i = 0; i < 100000; ++i) g.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 0, 0), glm::vec3(0, 1, 0.5f));
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::median}) {
    BuildLog log(-2);  // no candidates wanted
    KdTreeData t = build_kdtree(g, with_builder(b), log);
    EXPECT_LE(t.nodes.size(), 2u * kd_max_depth(KdOptions{}, g.size()) + 1);
    EXPECT_LE(t.prim_index.size(), kd_reference_budget(KdOptions{}, g.size()));
  }
  // SAH: no plane strictly inside the common bounds: one leaf.
  BuildLog log(-2);
  KdTreeData t = build_kdtree(g, KdOptions{}, log);
  EXPECT_EQ(t.nodes.size(), 1u);
  EXPECT_EQ(log.leaves.at(0).reason, LeafReason::no_candidate);
  EXPECT_EQ(t.prim_index.size(), g.size());
}

TEST(KdPathological, CoplanarTriangles) {
  Geometry g;
  std::mt19937 rng(51);
  std::uniform_real_distribution<float> u(0.f, 10.f), s(-0.3f, 0.3f);
  for (int i = 0; i < 10000; ++i) {
    glm::vec3 p(u(rng), u(rng), 2.f);
    g.add_triangle(p, p + glm::vec3(s(rng), s(rng), 0.f), p + glm::vec3(s(rng), s(rng), 0.f));
  }
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::median}) {
    KdOptions o = with_builder(b);
    KdTreeData t = build_kdtree(g, o);
    EXPECT_LE(t.prim_index.size(), kd_reference_budget(o, g.size()));
    EXPECT_LE(t.nodes.size(), 2 * t.prim_index.size() * size_t(kd_max_depth(o, g.size())));
    KdTreeStats st = kd_tree_stats(t, o);
    EXPECT_EQ(t.info[0].box.extent().z, 0.f);
    // In a flat scene S_b + S_a = S: cutting costs no area, so the SAH cuts the overlapping triangles into the
    // cells of their arrangement, down to the depth limit or the budget.
    EXPECT_GT(st.leaves, 1000u);
  }
}

TEST(KdPathological, TeapotInAStadium) {
  // One huge triangle over 10,000 tiny ones: the huge one straddles every plane near it.
  Geometry g;
  g.add_triangle(glm::vec3(-1000, -1000, 0), glm::vec3(1000, -1000, 0), glm::vec3(0, 1000, 0.5f));
  std::mt19937 rng(61);
  std::uniform_real_distribution<float> u(-1.f, 1.f), s(-0.01f, 0.01f);
  for (int i = 0; i < 10000; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    g.add_triangle(p, p + glm::vec3(s(rng), s(rng), s(rng)), p + glm::vec3(s(rng), s(rng), s(rng)));
  }
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::median}) {
    KdOptions o = with_builder(b);
    KdTreeData t = build_kdtree(g, o);
    EXPECT_LE(t.prim_index.size(), kd_reference_budget(o, g.size()));
    EXPECT_LE(t.nodes.size(), 2 * t.prim_index.size() * size_t(kd_max_depth(o, g.size())));
    // The huge triangle is in the leaves around the teapot.
    size_t huge = size_t(std::count(t.prim_index.begin(), t.prim_index.end(), 0u));
    EXPECT_GT(huge, 1u);
  }
}

// Long thin triangles along x, y and z through the same region: every split duplicates a third of them.
Geometry make_slivers(int count, uint32_t seed) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  for (int i = 0; i < count; ++i) {
    int a = i % 3;
    glm::vec3 p(u(rng), u(rng), u(rng)), q = p;
    p[a] = -1.f;
    q[a] = 1.f;
    glm::vec3 r = q;
    r[(a + 1) % 3] += 0.01f;
    g.add_triangle(p, q, r);
  }
  return g;
}

TEST(KdPathological, BudgetLeavesAreTheSameInBothSahBuilders) {
  Geometry g = make_slivers(240, 72);
  for (float budget : {1.f, 1.25f, 2.f}) {
    KdOptions o;
    o.reference_budget = budget;
    BuildLog a(-2), b(-2);
    KdTreeData fast = build_kdtree(g, o, a);
    KdTreeData ref = build_kdtree(g, with_builder(KdBuilder::sah_reference, o), b);
    expect_same_tree(fast, ref);
    EXPECT_GT(a.count(LeafReason::budget), 0u);
    EXPECT_EQ(a.count(LeafReason::budget), b.count(LeafReason::budget));
  }
}

TEST(KdPathological, BudgetStopsDuplication) {
  Geometry g = make_slivers(3000, 71);
  for (float budget : {1.f, 1.5f}) {
    KdOptions o;
    o.reference_budget = budget;
    BuildLog log(-2);
    KdTreeData t = build_kdtree(g, o, log);
    EXPECT_LE(t.prim_index.size(), size_t(budget * g.size()));
    EXPECT_GT(log.count(LeafReason::budget), 0u);
    check_invariants(g, t, o);
    KdTreeData r = build_kdtree(g, with_builder(KdBuilder::median, o));
    EXPECT_LE(r.prim_index.size(), size_t(budget * g.size()));
  }
}

// The budget is shared out depth first: what the below subtree leaves unused goes to the above subtree, so
// duplication on one side of the scene is not cut off while the other side's share lies idle. Tiny triangles
// below x = 0 (about one reference each) and slivers above it (every split duplicates a third of them): the
// median builder's root splits at x = 0, and the slivers' side ends up with more references than its
// proportional share of the root's budget, while the whole tree stays within that budget.
TEST(KdPathological, BudgetTheBelowSideLeavesGoesToTheAboveSide) {
  Geometry g = make_slivers(1000, 73);  // in [-1, 1]^3
  for (uint32_t i = 0; i < g.size(); ++i)
    for (int k = 0; k < 3; ++k) ASSERT_GE(g.vertex(i, k).x, -1.f);
  std::mt19937 rng(74);
  std::uniform_real_distribution<float> u(0.f, 1.f);
  const int tiny = 1000;
  for (int i = 0; i < tiny; ++i) {  // x in [-3.1, -1.2]: the root box's x range is [-3.1, about 1.01]
    glm::vec3 p(i == 0 ? -3.1f : -3.f + 1.79f * u(rng), -1.f + 1.99f * u(rng), -1.f + 1.99f * u(rng));
    g.add_triangle(p, p + glm::vec3(0.001f, 0.f, 0.f), p + glm::vec3(0.f, 0.001f, 0.f));
  }
  KdOptions o = with_builder(KdBuilder::median);
  o.reference_budget = 1.5f;
  BuildLog log(-2);
  KdTreeData t = build_kdtree(g, o, log);
  const size_t budget = kd_reference_budget(o, g.size());  // 3,000
  ASSERT_FALSE(t.nodes[0].is_leaf());
  ASSERT_EQ(t.nodes[0].axis(), 0);
  ASSERT_GT(t.nodes[0].split, -1.2f);  // the middle of x: between the tiny triangles and the slivers
  ASSERT_LT(t.nodes[0].split, -1.f);
  // References held by the leaves of the above subtree (node ids from the above child on).
  size_t above_refs = 0;
  for (uint32_t id = t.nodes[0].above_child(); id < t.nodes.size(); ++id)
    if (t.nodes[id].is_leaf()) above_refs += t.nodes[id].prim_count();
  const size_t proportional = budget - budget * tiny / g.size();  // 1,500
  EXPECT_GT(above_refs, proportional);
  EXPECT_LE(t.prim_index.size(), budget);
  EXPECT_GT(log.count(LeafReason::budget), 0u);  // the slivers still run into it
  check_invariants(g, t, o);
}

// A sphere resting on the floor: its box starts at the floor's plane y = 0 exactly (rounded outwards only
// where rounding happened), so the SAH has no zero-width slab [-1.4e-45, 0] to cut off below every node on
// the floor.
TEST(KdDegenerate, SphereOnTheFloorLeavesNoZeroWidthSlab) {
  Geometry g;
  g.add_triangle(glm::vec3(-1, 0, -1), glm::vec3(1, 0, -1), glm::vec3(1, 0, 1));
  g.add_triangle(glm::vec3(-1, 0, -1), glm::vec3(1, 0, 1), glm::vec3(-1, 0, 1));
  g.add_sphere(Sphere{glm::vec3(0.3f, 0.5f, -0.2f), 0.5f});
  add_box(g, glm::vec3(-0.8f, 0.f, 0.2f), glm::vec3(-0.3f, 1.2f, 0.7f));
  EXPECT_EQ(g.prim_bounds(2).lo.y, 0.f);
  EXPECT_EQ(g.bounds().lo.y, 0.f);
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::sah_reference}) {
    KdTreeData t = build_kdtree(g, with_builder(b));
    for (size_t i = 0; i < t.nodes.size(); ++i)
      EXPECT_GT(t.info[i].box.hi.y - t.info[i].box.lo.y, 1e-6f) << "node " << i;
  }
}

TEST(KdDegenerate, ZeroAreaTrianglesAndSpheres) {
  Geometry g;
  g.add_triangle(glm::vec3(0, 0, 0), glm::vec3(1, 1, 1), glm::vec3(2, 2, 2));  // collinear
  g.add_triangle(glm::vec3(3, 0, 0), glm::vec3(3, 0, 0), glm::vec3(3, 0, 0));  // a point
  g.add_triangle(glm::vec3(-1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(-1, 2, 0));
  g.add_sphere(Sphere{glm::vec3(1, 1, 1), 0.5f});
  g.add_sphere(Sphere{glm::vec3(-2, 2, 1), 0.25f});
  for (int i = 0; i < 20; ++i) g.add_triangle(glm::vec3(i * 0.1f, 0, 0), glm::vec3(i * 0.1f + 0.05f, 0, 0), glm::vec3(i * 0.1f, 0.05f, 0));
  for (KdBuilder b : {KdBuilder::sah, KdBuilder::sah_reference, KdBuilder::median}) {
    KdTreeData t = build_kdtree(g, with_builder(b));
    check_invariants(g, t, with_builder(b));
  }
  expect_same_tree(build_kdtree(g, KdOptions{}), build_kdtree(g, with_builder(KdBuilder::sah_reference)));
  // All on one point: no candidate.
  Geometry p;
  for (int i = 0; i < 5; ++i) p.add_triangle(glm::vec3(1.f), glm::vec3(1.f), glm::vec3(1.f));
  BuildLog log;
  KdTreeData t = build_kdtree(p, KdOptions{}, log);
  EXPECT_EQ(t.nodes.size(), 1u);
  EXPECT_EQ(log.leaves.at(0).reason, LeafReason::no_candidate);
}

TEST(KdBuild, LeafReasonNames) {
  EXPECT_STREQ(leaf_reason_name(LeafReason::few_primitives), "few_primitives");
  EXPECT_STREQ(leaf_reason_name(LeafReason::max_depth), "max_depth");
  EXPECT_STREQ(leaf_reason_name(LeafReason::no_cheaper_split), "no_cheaper_split");
  EXPECT_STREQ(leaf_reason_name(LeafReason::no_candidate), "no_candidate");
  EXPECT_STREQ(leaf_reason_name(LeafReason::budget), "budget");
}

}  // namespace
}  // namespace raystep
