// The uniform grid: resolution rule, agreement with brute force, the mailbox trap, the 3D-DDA's cell
// sequence against an independent enumeration of the cells a ray segment crosses, and the reference budget.
#include <gtest/gtest.h>

#include <algorithm>
#include <random>
#include <string>
#include <tuple>
#include <utility>

#include "raystep/accel/brute_force.h"
#include "raystep/accel/grid.h"
#include "raystep/util/error.h"
#include "ray_battery.h"
#include "test_scenes.h"

namespace raystep {
namespace {

using test::make_soup;

struct CellLog {
  static constexpr bool enabled = true;
  std::vector<GridCellStep> cells;
  int mailbox_hits = 0, deferred = 0, accepted = 0;
  void ray_begin(const Ray&) {}
  void cell(const GridCellStep& c) { cells.push_back(c); }
  void prim_test(uint32_t, bool, float) {}
  void mailbox_hit(uint32_t) { ++mailbox_hits; }
  void hit_deferred(uint32_t, float, float) { ++deferred; }
  void hit_accepted(uint32_t, float, AcceptReason) { ++accepted; }
  void ray_end(const Hit&) {}
};

using test::count_disagreements;

std::vector<Ray> random_rays(const Bounds3& b, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  glm::vec3 c = b.center(), e = 0.75f * b.extent();
  std::uniform_real_distribution<float> u(-1.f, 1.f);
  std::normal_distribution<float> n;
  std::vector<Ray> rays(count);
  for (Ray& r : rays) {
    r.origin = c + e * glm::vec3(u(rng), u(rng), u(rng));
    r.direction = glm::vec3(n(rng), n(rng), n(rng));
  }
  return rays;
}

TEST(Grid, ResolutionFollowsTheLectureRule) {
  // max(nx, ny, nz) = d * cbrt(n), the others in proportion to the extents, at least 1.
  auto n = UniformGrid::resolution_for(Bounds3(glm::vec3(0.f), glm::vec3(2.f, 1.f, 1.f)), 1000, 3.f);
  EXPECT_EQ(n[0], 30);
  EXPECT_EQ(n[1], 15);
  EXPECT_EQ(n[2], 15);
  auto flat = UniformGrid::resolution_for(Bounds3(glm::vec3(0.f), glm::vec3(1.f, 1.f, 0.f)), 8, 2.f);
  EXPECT_EQ(flat[0], 4);
  EXPECT_EQ(flat[2], 1);
}

TEST(Grid, AgreesWithBruteForceOnRandomRays) {
  Geometry g = make_soup(5, 400, 8);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), 100000, 9);
  for (bool exact : {true, false}) {
    GridOptions opt;
    opt.exact_insert = exact;
    UniformGrid grid(opt);
    grid.build(g);
    EXPECT_EQ(count_disagreements(grid, brute, rays), 0) << "exact=" << exact;
  }
}

TEST(Grid, AgreesWithBruteForceAtExplicitResolutions) {
  Geometry g = make_soup(6, 200, 4);
  BruteForce brute;
  brute.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), 5000, 10);
  for (auto res : {std::array<int, 3>{1, 1, 1}, {50, 1, 1}, {1, 1, 64}, {7, 13, 3}, {40, 40, 40}}) {
    GridOptions opt;
    opt.resolution = res;
    UniformGrid grid(opt);
    grid.build(g);
    EXPECT_EQ(count_disagreements(grid, brute, rays), 0) << res[0] << "x" << res[1] << "x" << res[2];
  }
}

TEST(Grid, HardRays) {
  Geometry g = make_soup(7, 300, 0);
  BruteForce brute;
  brute.build(g);
  GridOptions opt;
  opt.resolution = std::array<int, 3>{8, 8, 8};
  UniformGrid grid(opt);
  grid.build(g);
  const Bounds3& b = grid.bounds();
  glm::vec3 cs = grid.cell_size();
  std::vector<Ray> rays;
  std::mt19937 rng(3);
  std::uniform_int_distribution<int> cell(0, 8);
  for (int i = 0; i < 2000; ++i) {
    // Axis-parallel rays with +0 and -0 components, along grid lines (through edges and vertices) and across.
    glm::vec3 p = b.lo + cs * glm::vec3(cell(rng), cell(rng), cell(rng));
    if (i % 2) p += 0.5f * cs;
    for (int axis = 0; axis < 3; ++axis)
      for (float sign : {1.f, -1.f}) {
        Ray r;
        r.origin = p;
        r.origin[axis] = sign > 0 ? b.lo[axis] - 1.f : b.hi[axis] + 1.f;
        r.direction = glm::vec3(i % 4 < 2 ? 0.f : -0.f);
        r.direction[axis] = sign;
        rays.push_back(r);
        r.tmax = 1.f + 0.37f * (b.hi[axis] - b.lo[axis]);  // ends inside the grid
        rays.push_back(r);
      }
    // Diagonals through grid vertices, origins on cell faces, inside and outside.
    Ray d;
    d.origin = p;
    d.direction = glm::vec3(1.f, i % 3 ? 1.f : -1.f, 1.f);
    rays.push_back(d);
    d.origin = b.lo + cs * glm::vec3(cell(rng), 0.5f + cell(rng), 0.25f + cell(rng)) - d.direction;
    rays.push_back(d);
  }
  EXPECT_EQ(count_disagreements(grid, brute, rays), 0);
}

TEST(Grid, NonFiniteRaysMissAndTerminate) {
  Geometry g = make_soup(8, 50, 1);
  UniformGrid grid;
  grid.build(g);
  EXPECT_EQ(test::count_non_finite_hits(grid), 0);
}

// A long thin triangle spanning three cells, hit in the third; a small triangle in the second cell, nearer
// along the ray. The long one is tested first (in cell 1) and its hit must be deferred, not accepted.
TEST(Grid, MailboxTrap) {
  auto build = [](bool with_small) {
    Geometry g;
    g.begin_object("trap", 0);
    // Plane z = 0.5 + 0.2 (x - 2.5): the ray y = z = 0.5 meets it at x = 2.5, in the third cell.
    g.add_triangle(glm::vec3(0.f, -1.f, 0.f), glm::vec3(0.f, 2.f, 0.f), glm::vec3(3.f, 0.5f, 0.6f));
    if (with_small)  // the plane x = 1.5, in the second cell
      g.add_triangle(glm::vec3(1.5f, 0.f, 0.f), glm::vec3(1.5f, 1.f, 0.f), glm::vec3(1.5f, 0.f, 1.f));
    return g;
  };
  Ray ray;
  ray.origin = glm::vec3(-1.f, 0.5f, 0.5f);
  ray.direction = glm::vec3(1.f, 0.f, 0.f);
  GridOptions opt;
  opt.resolution = std::array<int, 3>{3, 1, 1};

  Geometry both = build(true);
  UniformGrid grid(opt);
  grid.build(both);
  CellLog log;
  Hit hit;
  ASSERT_TRUE(grid.traverse(ray, &hit, false, log));
  EXPECT_EQ(hit.prim, 1);  // the small triangle wins
  EXPECT_FLOAT_EQ(hit.t, 2.5f);
  EXPECT_EQ(log.deferred, 1);  // the long triangle's hit was kept, not accepted
  EXPECT_EQ(log.cells.size(), 2u);

  Geometry alone = build(false);
  UniformGrid grid2(opt);
  grid2.build(alone);
  CellLog log2;
  ASSERT_TRUE(grid2.traverse(ray, &hit, false, log2));
  EXPECT_EQ(hit.prim, 0);  // still found, though skipped by the mailbox in cells 2 and 3
  EXPECT_FLOAT_EQ(hit.t, 3.5f);
  EXPECT_EQ(log2.mailbox_hits, 2);
  EXPECT_EQ(log2.cells.size(), 3u);
}

// The reference: every cell whose box the segment crosses with positive length, ordered by entry t.
std::vector<std::tuple<float, int, int, int>> crossed_cells(const UniformGrid& grid, const Ray& ray, float min_len) {
  std::vector<std::tuple<float, int, int, int>> out;
  auto n = grid.resolution();
  for (int k = 0; k < n[2]; ++k)
    for (int j = 0; j < n[1]; ++j)
      for (int i = 0; i < n[0]; ++i) {
        float t0, t1;
        if (intersect_slabs(grid.cell_bounds(i, j, k), ray, &t0, &t1) && t1 - t0 > min_len)
          out.emplace_back(t0, i, j, k);
      }
  std::sort(out.begin(), out.end());
  return out;
}

TEST(Grid, CellSequenceMatchesIndependentEnumeration) {
  Geometry g = make_soup(9, 100, 0);
  GridOptions opt;
  opt.resolution = std::array<int, 3>{9, 6, 4};
  UniformGrid grid(opt);
  grid.build(g);
  std::vector<Ray> rays = random_rays(g.bounds(), 3000, 21);
  for (size_t i = 0; i < rays.size(); i += 3) rays[i].tmax = 2.f;  // some end inside the grid
  int checked = 0;
  for (const Ray& r : rays) {
    CellLog log;
    Hit h;
    grid.traverse(r, &h, false, log);
    if (h.found()) continue;  // a hit ends the walk early; compare only complete walks
    float scale = glm::length(r.direction) * 1e-4f;
    auto strict = crossed_cells(grid, r, scale);
    auto touching = crossed_cells(grid, r, -1.f);
    // Every cell crossed with positive length is visited, in order of entry.
    size_t pos = 0;
    for (const GridCellStep& c : log.cells)
      if (pos < strict.size() && std::get<1>(strict[pos]) == c.i && std::get<2>(strict[pos]) == c.j &&
          std::get<3>(strict[pos]) == c.k)
        ++pos;
    EXPECT_EQ(pos, strict.size());
    // And every visited cell is at least touched by the segment.
    for (const GridCellStep& c : log.cells) {
      bool touched = std::any_of(touching.begin(), touching.end(), [&](const auto& t) {
        return std::get<1>(t) == c.i && std::get<2>(t) == c.j && std::get<3>(t) == c.k;
      });
      EXPECT_TRUE(touched) << c.i << "," << c.j << "," << c.k;
    }
    ++checked;
  }
  EXPECT_GT(checked, 1000);
}

TEST(Grid, ExactInsertionStoresFewerReferencesThanBoxes) {
  // Long diagonal triangles: their boxes cover many cells that the triangles themselves miss.
  Geometry g;
  g.begin_object("diagonals", 0);
  for (int i = 0; i < 20; ++i) {
    float z = 0.1f * i;
    g.add_triangle(glm::vec3(0.f, 0.f, z), glm::vec3(10.f, 10.f, z), glm::vec3(10.f, 10.2f, z + 0.05f));
  }
  GridOptions exact, boxes;
  exact.resolution = boxes.resolution = std::array<int, 3>{20, 20, 4};
  boxes.exact_insert = false;
  UniformGrid ge(exact), gb(boxes);
  ge.build(g);
  gb.build(g);
  EXPECT_LT(ge.reference_count() * 4, gb.reference_count());
}

// 100,000 copies of one triangle: every copy covers the same cells, so the density rule's resolution would
// need ~10^9 references (the old build refused: "more than 268435456 primitive references").
Geometry identical_triangles(glm::vec3 a, glm::vec3 b, glm::vec3 c, int copies) {
  Geometry g;
  g.begin_object("copies", 0);
  for (int i = 0; i < copies; ++i) g.add_triangle(a, b, c);
  return g;
}

// Rays from points above (z > 0) to random points of the box [lo, hi]: no ray grazes the triangles, so every
// structure's answer is a plain hit or a plain miss.
std::vector<Ray> rays_from_above(const Bounds3& b, int count, uint32_t seed) {
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-0.25f, 1.25f);
  std::vector<Ray> rays(count);
  glm::vec3 e = b.extent();
  for (Ray& r : rays) {
    glm::vec3 target = b.lo + e * glm::vec3(u(rng), u(rng), 0.5f);
    r.origin = b.lo + e * glm::vec3(u(rng), u(rng), 0.f) + glm::vec3(0.f, 0.f, 2.f + e.z);
    r.direction = target - r.origin;
  }
  return rays;
}

TEST(Grid, ReferenceBudgetFormula) {
  // max(2^22, 32 n), never above 2^28.
  EXPECT_EQ(UniformGrid::reference_budget(0), size_t(1) << 22);
  EXPECT_EQ(UniformGrid::reference_budget(100000), size_t(1) << 22);
  EXPECT_EQ(UniformGrid::reference_budget(size_t(1) << 20), size_t(32) << 20);
  EXPECT_EQ(UniformGrid::reference_budget(size_t(1) << 30), size_t(1) << 28);
}

TEST(Grid, IdenticalTrianglesCoarsenToTheReferenceBudget) {
  const size_t budget = UniformGrid::reference_budget(100000);
  struct Case {
    const char* name;
    glm::vec3 a, b, c;
  };
  for (const Case& k : {Case{"flat", {0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 0.f}},
                        Case{"tilted", {0.f, 0.f, 0.f}, {1.f, 0.2f, 0.1f}, {0.3f, 1.f, 1.f}}}) {
    Geometry g = identical_triangles(k.a, k.b, k.c, 100000);
    BruteForce brute;
    brute.build(g);
    for (bool exact : {true, false}) {
      GridOptions opt;
      opt.exact_insert = exact;
      UniformGrid grid(opt);
      grid.build(g);
      SCOPED_TRACE(std::string(k.name) + (exact ? " exact" : " bbox"));
      EXPECT_TRUE(grid.coarsened());
      EXPECT_EQ(grid.coarsening(), GridCoarsening::reference_budget);
      EXPECT_EQ(grid.requested_resolution(),
                UniformGrid::resolution_for(grid.bounds(), g.size(), opt.density));
      std::array<int, 3> n = grid.resolution(), r = grid.requested_resolution();
      for (int a = 0; a < 3; ++a) EXPECT_LE(n[a], r[a]);
      EXPECT_LT(size_t(n[0]) * n[1] * n[2], size_t(r[0]) * r[1] * r[2]);
      EXPECT_LE(grid.reference_count(), budget);
      EXPECT_GE(grid.reference_count(), g.size());  // every copy is stored somewhere
      // Ties go to the lowest id: every hit is copy 0, at brute force's t.
      EXPECT_EQ(count_disagreements(grid, brute, rays_from_above(g.bounds(), 60, 11)), 0);
    }
  }
}

TEST(Grid, OrdinaryScenesAreNotCoarsened) {
  // The budget binds only on pathological input: soups of small triangles keep the density rule's resolution.
  for (auto [triangles, density] : {std::pair<int, float>{400, 3.f}, {400, 8.f}, {20000, 3.f}}) {
    Geometry g = make_soup(12, triangles, 8);
    GridOptions opt;
    opt.density = density;
    UniformGrid grid(opt);
    grid.build(g);
    EXPECT_FALSE(grid.coarsened()) << triangles << " triangles, d = " << density;
    EXPECT_EQ(grid.coarsening(), GridCoarsening::none);
    EXPECT_EQ(grid.resolution(), UniformGrid::resolution_for(g.bounds(), g.size(), density));
    EXPECT_EQ(grid.resolution(), grid.requested_resolution());
  }
}

TEST(Grid, ExplicitResolutionPastTheBudgetIsRefused) {
  // Who names the cells wants those cells: refused before any reference is stored, not coarsened.
  Geometry g = identical_triangles({0.f, 0.f, 0.f}, {1.f, 0.f, 0.f}, {0.f, 1.f, 1.f}, 1000);
  GridOptions opt;
  opt.resolution = std::array<int, 3>{100, 100, 100};
  UniformGrid grid(opt);
  try {
    grid.build(g);
    FAIL() << "built";
  } catch (const InputError& e) {
    EXPECT_NE(e.detail().find("100x100x100"), std::string::npos) << e.detail();
    EXPECT_NE(e.detail().find("budget of 16777216 for 1000 primitives"), std::string::npos) << e.detail();
  }
  EXPECT_TRUE(grid.empty());
  EXPECT_EQ(grid.reference_count(), 0u);
  // Within the budget the explicit resolution is kept.
  opt.resolution = std::array<int, 3>{10, 10, 10};
  UniformGrid fits(opt);
  fits.build(g);
  EXPECT_FALSE(fits.coarsened());
  EXPECT_EQ(fits.resolution(), (std::array<int, 3>{10, 10, 10}));
}

}  // namespace
}  // namespace raystep
