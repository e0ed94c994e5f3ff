// The general BSP tree's construction: the cell polytopes (exact areas of known cuts, the SAH's area shortcut
// equal to the built parts, parts on their sides of the plane), the exact plane-side predicate against GMP,
// the classification guarantee (every vertex of a primitive reaches a leaf that lists it), and bounded trees
// on pathological input (identical, coplanar, sliver triangles).
#include <gtest/gtest.h>

#include <random>

#include <glm/geometric.hpp>

#include "exact_reference.h"
#include "raystep/accel/bsp.h"
#include "raystep/accel/bsp_cell.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

TEST(BspCell, BoxAndKnownCuts) {
  ConvexCell cube = ConvexCell::box(Bounds3(glm::vec3(0.f), glm::vec3(1.f)));
  EXPECT_EQ(cube.face_count(), 6u);
  EXPECT_NEAR(cube.area(), 6.0, 1e-12);
  // An axis cut at x = 0.25: a 0.25 x 1 x 1 box below.
  ConvexCell below, above;
  cube.split(glm::dvec3(1, 0, 0), 0.25, &below, &above);
  EXPECT_NEAR(below.area(), 2.0 * (0.25 + 0.25 + 1.0), 1e-12);
  EXPECT_NEAR(above.area(), 2.0 * (0.75 + 0.75 + 1.0), 1e-12);
  // The diagonal x + y = 1: two triangular prisms, each two half squares, two unit squares and a sqrt(2) x 1
  // cap.
  const double s = std::sqrt(0.5);
  cube.split(glm::dvec3(s, s, 0), s, &below, &above);
  EXPECT_EQ(below.face_count(), 5u);
  EXPECT_NEAR(below.area(), 3.0 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(above.area(), 3.0 + std::sqrt(2.0), 1e-12);
  double ab, aa;
  cube.split_areas(glm::dvec3(s, s, 0), s, &ab, &aa);
  EXPECT_NEAR(ab, 3.0 + std::sqrt(2.0), 1e-12);
  EXPECT_NEAR(aa, 3.0 + std::sqrt(2.0), 1e-12);
  // A plane that misses the cell, or only touches a face, leaves it whole on one side.
  cube.split(glm::dvec3(0, 0, 1), 2.0, &below, &above);
  EXPECT_NEAR(below.area(), 6.0, 1e-12);
  EXPECT_TRUE(above.empty());
  cube.split(glm::dvec3(0, 0, 1), 0.0, &below, &above);
  EXPECT_TRUE(below.empty());
  EXPECT_NEAR(above.area(), 6.0, 1e-12);
}

TEST(BspCell, RandomCutsStayValid) {
  // Chains of 40 random cuts, keeping a random side: the area shortcut equals the built parts' areas, each
  // part lies on its side of the plane, a cut part is smaller than its parent, and Crofton's sum holds
  // (S_below + S_above = S + 2 S_cap > S).
  std::mt19937 rng(21);
  std::normal_distribution<double> g;
  std::uniform_real_distribution<double> u(0.0, 1.0);
  int cuts = 0;
  for (int chain = 0; chain < 50; ++chain) {
    ConvexCell cell = ConvexCell::box(Bounds3(glm::vec3(-3.f, -1.f, 2.f), glm::vec3(5.f, 4.f, 2.5f)));
    const double root_area = cell.area();
    // Down to cells a millionth of the root's size, where the 2^-40 side tolerance is still far away.
    for (int step = 0; step < 40 && !cell.empty() && cell.area() > 1e-12 * root_area; ++step) {
      glm::dvec3 n = glm::normalize(glm::dvec3(g(rng), g(rng), g(rng)));
      double lo, hi;
      cell.extent(n, &lo, &hi);
      double d = lo + (hi - lo) * u(rng);
      ConvexCell below, above;
      cell.split(n, d, &below, &above);
      double ab, aa;
      cell.split_areas(n, d, &ab, &aa);
      const double area = cell.area();
      ASSERT_NEAR(ab, below.area(), 1e-9 * area);
      ASSERT_NEAR(aa, above.area(), 1e-9 * area);
      if (!below.empty() && !above.empty()) {
        ++cuts;
        EXPECT_LT(below.area(), area * (1 + 1e-12));
        EXPECT_LT(above.area(), area * (1 + 1e-12));
        EXPECT_GT(ab + aa, area * (1 - 1e-12));
        for (const ConvexCell* part : {&below, &above}) {
          const double sign = part == &below ? 1.0 : -1.0;
          for (size_t f = 0; f < part->face_count(); ++f) {
            EXPECT_GE(part->face_size(f), 3u);
            for (size_t k = 0; k < part->face_size(f); ++k)
              EXPECT_LE(sign * (glm::dot(n, part->face(f)[k]) - d), 1e-9);
          }
        }
      }
      cell = u(rng) < 0.5 ? below : above;
    }
  }
  EXPECT_GT(cuts, 300);
}

TEST(BspPlaneSide, AgreesWithExactRationals) {
  // Points on, and within an ulp of, planes of every k-DOP and random direction: the filter must hand the
  // close ones to exact arithmetic and get every sign right.
  std::mt19937 rng(22);
  std::uniform_real_distribution<float> u(-100.f, 100.f);
  std::normal_distribution<float> g;
  int zeros = 0;
  for (int i = 0; i < 20000; ++i) {
    BspPlane plane;
    plane.normal =
        glm::normalize(i % 2 ? glm::vec3(g(rng), g(rng), g(rng)) : glm::vec3(1.f, 1.f, float(i % 3) - 1.f));
    glm::vec3 p(u(rng), u(rng), u(rng));
    plane.offset = float(glm::dot(glm::dvec3(plane.normal), glm::dvec3(p)));
    if (i % 4 == 1) plane.offset = std::nextafter(plane.offset, kInfinity);
    if (i % 4 == 2) p.x = std::nextafter(p.x, -kInfinity);
    if (i % 8 == 3) {  // exactly on an axis plane
      plane.normal = glm::vec3(0.f, 1.f, 0.f);
      plane.offset = p.y;
    }
    test::Q s = test::Q(double(plane.normal.x)) * test::Q(double(p.x)) +
                test::Q(double(plane.normal.y)) * test::Q(double(p.y)) +
                test::Q(double(plane.normal.z)) * test::Q(double(p.z)) - test::Q(double(plane.offset));
    ASSERT_EQ(bsp_plane_side(plane, p), sgn(s)) << i;
    zeros += sgn(s) == 0;
  }
  EXPECT_GT(zeros, 1000);
}

// True if point p of primitive `prim` lies in the closed cell of a leaf that lists the primitive: descend by
// the exact side, both ways where p lies on the plane.
bool reaches_listing_leaf(const BspTreeData& t, uint32_t node, const glm::vec3& p, uint32_t prim) {
  const BspNode& n = t.nodes[node];
  if (n.is_leaf()) {
    const uint32_t* b = t.prim_index.data() + n.first_prim();
    return std::binary_search(b, b + n.prim_count(), prim);
  }
  int s = bsp_plane_side(n.plane, p);
  return (s <= 0 && reaches_listing_leaf(t, node + 1, p, prim)) ||
         (s >= 0 && reaches_listing_leaf(t, n.above_child(), p, prim));
}

// The tree's shape: children after their parent, depths, parents, sorted leaves, unit normals.
void check_shape(const BspTreeData& t, const BspOptions& o, size_t prims) {
  ASSERT_EQ(t.nodes.size(), t.info.size());
  for (size_t i = 0; i < t.nodes.size(); ++i) {
    const BspNode& n = t.nodes[i];
    EXPECT_LE(t.info[i].depth, bsp_max_depth(o, prims));
    if (n.is_leaf()) {
      const uint32_t* b = t.prim_index.data() + n.first_prim();
      ASSERT_LE(size_t(n.first_prim()) + n.prim_count(), t.prim_index.size());
      EXPECT_TRUE(std::is_sorted(b, b + n.prim_count()));
      continue;
    }
    EXPECT_NEAR(glm::length(n.plane.normal), 1.f, 1e-5f);
    ASSERT_GT(n.above_child(), i + 1);
    ASSERT_LT(n.above_child(), t.nodes.size());
    EXPECT_EQ(t.info[i + 1].parent, int32_t(i));
    EXPECT_EQ(t.info[n.above_child()].parent, int32_t(i));
    EXPECT_EQ(t.info[i + 1].depth, t.info[i].depth + 1);
    // A child's cell is part of its parent's.
    EXPECT_LE(t.info[i + 1].area, t.info[i].area * 1.0001f);
    EXPECT_LE(t.info[n.above_child()].area, t.info[i].area * 1.0001f);
  }
}

void check_covers(const Geometry& g, const BspTreeData& t) {
  int lost = 0;
  for (uint32_t id = 0; id < g.size(); ++id) {
    if (g.type(id) == PrimType::triangle) {
      for (int k = 0; k < 3; ++k) lost += !reaches_listing_leaf(t, 0, g.vertex(id, k), id);
    } else {
      Bounds3 b = g.prim_bounds(id);
      lost += !reaches_listing_leaf(t, 0, b.lo, id) + !reaches_listing_leaf(t, 0, b.hi, id);
    }
  }
  EXPECT_EQ(lost, 0);
}

TEST(BspBuild, EveryPrimitiveVertexReachesALeafListingIt) {
  Geometry soup = test::make_soup(31, 500, 6);
  for (BspDirections dirs : {BspDirections::both, BspDirections::kdop, BspDirections::autopartition}) {
    BspOptions o;
    o.directions = dirs;
    BspTreeData t = build_bsp(soup, o);
    check_shape(t, o, soup.size());
    check_covers(soup, t);
    BspTreeStats s = bsp_tree_stats(t, o);
    EXPECT_GT(s.leaves, 20u) << bsp_directions_name(dirs);
    if (dirs == BspDirections::autopartition) {
      EXPECT_EQ(s.inner_by_source[int(BspPlaneSource::axis)], 0u);
      EXPECT_GT(s.inner_by_source[int(BspPlaneSource::primitive)], 0u);
    }
    if (dirs == BspDirections::kdop) EXPECT_EQ(s.inner_by_source[int(BspPlaneSource::primitive)], 0u);
    // The SAH cost of the tree is far below brute force's N t_i.
    EXPECT_LT(s.sah_cost, 0.2 * o.t_i * double(soup.size()));
  }
}

Geometry slanted_slab(int n, float tilt_degrees) {
  // n thin triangles in one tilted plane: the kd-tree's worst case, an autopartition's best.
  Geometry g;
  g.begin_object("tilted", 0);
  const float a = glm::radians(tilt_degrees);
  glm::vec3 u(std::cos(a), 0.f, std::sin(a)), v(0.f, 1.f, 0.f);
  for (int i = 0; i < n; ++i) {
    float x = float(i % 40) * 0.25f, y = float(i / 40) * 0.25f;
    g.add_triangle(x * u + y * v, (x + 0.24f) * u + y * v, (x + 0.12f) * u + (y + 0.2f) * v);
  }
  return g;
}

TEST(BspBuild, PathologicalInputStaysBounded) {
  struct Case {
    const char* name;
    Geometry g;
  };
  std::vector<Case> cases;
  {
    Geometry g;
    g.begin_object("identical", 0);
    for (int i = 0; i < 100000; ++i)
      g.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.2f), glm::vec3(0.f, 1.f, 0.4f));
    cases.push_back({"100000 identical", std::move(g)});
  }
  {
    Geometry g;
    g.begin_object("coplanar", 0);
    std::mt19937 rng(23);
    std::uniform_real_distribution<float> u(0.f, 10.f);
    for (int i = 0; i < 10000; ++i) {
      glm::vec3 p(u(rng), u(rng), 0.5f);
      g.add_triangle(p, p + glm::vec3(0.3f, 0.f, 0.f), p + glm::vec3(0.f, 0.3f, 0.f));
    }
    cases.push_back({"10000 coplanar", std::move(g)});
  }
  {
    Geometry g;
    g.begin_object("slivers", 0);
    std::mt19937 rng(24);
    std::uniform_real_distribution<float> u(-1.f, 1.f);
    for (int i = 0; i < 3000; ++i) {  // long thin needles across the whole scene, every direction
      glm::vec3 a(u(rng), u(rng), u(rng)), b(u(rng), u(rng), u(rng));
      g.add_triangle(10.f * a, -10.f * a, 10.f * a + 1e-3f * b);
    }
    cases.push_back({"3000 slivers", std::move(g)});
  }
  cases.push_back({"tilted plane", slanted_slab(2000, 27.f)});
  for (Case& c : cases) {
    BspOptions o;
    BspTreeData t = build_bsp(c.g, o);
    check_shape(t, o, c.g.size());
    check_covers(c.g, t);
    // Memory: the reference budget caps the leaves' references, so the nodes are bounded too.
    EXPECT_LE(t.prim_index.size(), size_t(o.reference_budget * float(c.g.size())) + 1) << c.name;
    // Every inner node has a non-empty child, so empty leaves hang off chains no longer than the depth limit.
    EXPECT_LE(t.nodes.size(), 2 * size_t(bsp_max_depth(o, c.g.size())) * (t.prim_index.size() + 1)) << c.name;
  }
}

TEST(BspBuild, OptionsAreChecked) {
  Geometry g = test::make_soup(1, 10, 0);
  auto bad = [&](auto edit) {
    BspOptions o;
    edit(o);
    EXPECT_THROW(build_bsp(g, o), InputError);
  };
  bad([](BspOptions& o) { o.candidates = 0; });
  bad([](BspOptions& o) { o.candidates = 5000; });
  bad([](BspOptions& o) { o.t_i = -1.f; });
  bad([](BspOptions& o) { o.t_t = std::nanf(""); });
  bad([](BspOptions& o) { o.max_depth = kBspMaxDepth + 1; });
  bad([](BspOptions& o) { o.leaf_size = 0; });
  bad([](BspOptions& o) { o.reference_budget = 0.5f; });
  BspDirections d;
  EXPECT_TRUE(parse_bsp_directions("kdop", &d));
  EXPECT_EQ(d, BspDirections::kdop);
  EXPECT_FALSE(parse_bsp_directions("diagonal", &d));
  // Empty geometry: one empty leaf.
  Geometry empty;
  BspTreeData t = build_bsp(empty, BspOptions{});
  ASSERT_EQ(t.nodes.size(), 1u);
  EXPECT_TRUE(t.nodes[0].is_leaf());
  EXPECT_EQ(t.nodes[0].prim_count(), 0u);
}

}  // namespace
}  // namespace raystep
