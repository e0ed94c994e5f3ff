// Grazing and degenerate cases for every structure (accelerator_names(), the variants too): rays tangent to
// spheres, rays in the plane of a triangle, collinear, repeated-vertex and zero-area triangles, duplicated
// faces, directions of length 1e-30 and 1e30, huge finite coordinates, and what the OBJ reader does with NaN
// and infinite vertices. The kernels' own cases are in triangle_test.cpp and sphere_test.cpp; here each case
// goes through every structure's build and walk, which is where a box, a cell or a split plane can lose it.
// The ray leaving a grid through a cell edge at a mesh vertex is the regression case of the grid's fix.
#include <gtest/gtest.h>

#include <cmath>

#include <glm/geometric.hpp>

#include "raystep/accel/accelerator.h"
#include "raystep/accel/brute_force.h"
#include "raystep/io/obj.h"
#include "raystep/report/hardcase_battery.h"
#include "raystep/report/hardcase_reference.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

// Every structure gives brute force's answer on every ray: hit or miss, the same t, and the same primitive or
// (ties: coincident faces, a shared edge) another one at the same t that brute force also hits there.
// With may_refuse, a structure may refuse the geometry with an InputError (never crash).
void expect_brute_force_answers(const Geometry& g, const std::vector<Ray>& rays, const std::string& what,
                                bool may_refuse = false) {
  BruteForce brute;
  brute.build(g);
  for (const std::string& name : accelerator_names()) {
    auto acc = make_accelerator(name);
    if (may_refuse) {
      try {
        acc->build(g);
      } catch (const InputError& e) {
        EXPECT_NE(std::string(e.what()).find("overflows"), std::string::npos) << name << ": " << e.what();
        continue;
      }
    } else {
      acc->build(g);
    }
    int differ = 0;
    for (const Ray& r : rays) {
      Hit a, b;
      const bool ha = brute.intersect(r, &a), hb = acc->intersect(r, &b);
      bool same = ha == hb && a.t == b.t && (a.prim == b.prim || !ha);
      if (!same && ha && hb && a.t == b.t) {  // a tie: b's primitive must be hit at that t too
        Hit c;
        WatertightRay w(r);
        same = g.intersect(uint32_t(b.prim), r, w, kInfinity, &c) && c.t == a.t;
      }
      same = same && brute.occluded(r) == acc->occluded(r);
      differ += !same;
    }
    EXPECT_EQ(differ, 0) << name << ": " << what;
  }
}

// Tangent rays: lines at distance r from the centre (exactly, in float, along an axis), just inside and just
// outside, through the sphere's bounding box faces, at scales 1e-3 .. 1e3 and far from the origin.
TEST(Degenerate, RaysTangentToSpheresAgreeWithBruteForce) {
  for (float s : {1e-3f, 1.f, 1e3f})
    for (float far : {0.f, 1e4f}) {
      Geometry g;
      g.begin_object("spheres", 0);
      const glm::vec3 c0 = far * s * glm::vec3(1.f, -0.5f, 0.25f);
      for (int i = 0; i < 8; ++i) g.add_sphere(Sphere{c0 + s * glm::vec3(float(3 * i), 0.f, 0.f), s});
      std::vector<Ray> rays;
      for (int i = 0; i < 8; ++i) {
        const glm::vec3 c = g.sphere(uint32_t(i)).center;
        for (float y : {s, next_float_down(s), next_float_up(s), -s, 0.5f * s})
          for (int a = 0; a < 3; ++a) {
            glm::vec3 o = c, d(0.f);
            o[a] -= 5.f * s;
            d[a] = 1.f;
            o[(a + 1) % 3] += y;
            rays.push_back(Ray{o, d});
            d[(a + 2) % 3] = -0.f;
            rays.push_back(Ray{o, d});
            o[(a + 2) % 3] += y;  // through the box's edge: tangent nowhere, it misses
            rays.push_back(Ray{o, d});
          }
      }
      // Along the row of spheres, tangent to every one of them.
      rays.push_back(Ray{c0 + glm::vec3(-5.f * s, s, 0.f), glm::vec3(1.f, 0.f, 0.f)});
      rays.push_back(Ray{c0 + glm::vec3(-5.f * s, 0.f, -s), glm::vec3(1.f, -0.f, 0.f)});
      expect_brute_force_answers(g, rays, "tangent rays, scale " + std::to_string(s));
    }
}

// A ray in a triangle's plane sees no area: it misses that triangle (edge-on), with every structure, also
// when the ray runs along the triangle's edge or through its vertex; the triangle beyond is hit.
TEST(Degenerate, RaysInThePlaneOfATriangleMissIt) {
  for (bool tilted : {false, true}) {
    Geometry g;
    g.begin_object("edge-on", 0);
    auto place = [tilted](glm::vec3 p) {
      return tilted ? glm::vec3(p.x + 0.5f * p.z, p.y, p.z - 0.5f * p.x) : p;  // exact in float for these p
    };
    g.add_triangle(place({0, 0, 0}), place({2, 0, 0}), place({0, 2, 0}));
    g.add_triangle(place({5, -3, -3}), place({5, 3, -3}), place({5, 0, 3}));  // a wall beyond
    for (int k = 0; k < 20; ++k)
      g.add_triangle(place({-9.f + float(k), 7, 1}), place({-8.f + float(k), 7, 1}),
                     place({-9.f + float(k), 8, 2}));
    std::vector<Ray> rays = {
        Ray{place({-3, 0.5f, 0}), place({1, 0, 0})},     // through the interior, in its plane
        Ray{place({-3, 0, 0}), place({1, 0, 0})},        // along its edge
        Ray{place({-3, -3, 0}), place({1, 1, 0})},       // through its vertex (0, 0, 0)
        Ray{place({-3, 1, 0}), place({1, -0.f, -0.f})},  // -0 components
    };
    for (const Ray& r : rays)
      for (const std::string& name : accelerator_names()) {
        auto acc = make_accelerator(name);
        acc->build(g);
        Hit h;
        const bool found = acc->intersect(r, &h);
        EXPECT_TRUE(!found || h.prim != 0) << name << (tilted ? " tilted" : "");
      }
    expect_brute_force_answers(g, rays, tilted ? "edge-on, tilted" : "edge-on");
  }
}

// Collinear, repeated-vertex and zero-area triangles: every structure builds over them and never reports one,
// also for rays aimed exactly at their points; a scene of nothing else is a scene of misses.
TEST(Degenerate, ZeroAreaTrianglesAreNeverHit) {
  for (bool only_degenerate : {false, true}) {
    Geometry g;
    g.begin_object("degenerate", 0);
    std::vector<glm::vec3> points;
    for (int k = 0; k < 16; ++k) {
      const glm::vec3 a(float(k % 7) - 3.f, float(k % 5) - 2.f, float(k % 3) - 1.f);
      const glm::vec3 b = a + glm::vec3(1.f, 0.5f, 0.25f), mid = a + glm::vec3(0.5f, 0.25f, 0.125f);
      switch (k % 4) {
        case 0:
          g.add_triangle(a, mid, b);
          break;  // collinear (exactly: mid is the midpoint in float)
        case 1:
          g.add_triangle(a, a, b);
          break;  // a repeated vertex
        case 2:
          g.add_triangle(a, a, a);
          break;  // a point
        case 3:
          g.add_triangle(a, b, a + 2.f * (b - a));
          break;  // collinear, exact
      }
      points.push_back(a);
      points.push_back(mid);
    }
    if (!only_degenerate) {
      g.add_triangle({-9, -9, 5}, {9, -9, 5}, {0, 9, 5});
      g.add_triangle({-9, -9, -5}, {0, 9, -5}, {9, -9, -5});
    }
    std::vector<Ray> rays;
    for (const glm::vec3& p : points)
      for (glm::vec3 d :
           {glm::vec3(0, 0, 1), glm::vec3(0.3f, -0.2f, 1), glm::vec3(1, 0.5f, 0.25f), glm::vec3(-1, 2, -0.f)})
        rays.push_back(Ray{p - d, d});
    const uint32_t first_real = 16;
    for (const std::string& name : accelerator_names()) {
      auto acc = make_accelerator(name);
      acc->build(g);
      int bad = 0;
      for (const Ray& r : rays) {
        Hit h;
        const bool found = acc->intersect(r, &h);
        bad += found && uint32_t(h.prim) < first_real;
        bad += only_degenerate && (found || acc->occluded(r));
      }
      EXPECT_EQ(bad, 0) << name << (only_degenerate ? " (degenerate only)" : "");
    }
    expect_brute_force_answers(g, rays, only_degenerate ? "degenerate only" : "degenerate");
  }
}

// Duplicated faces (the same vertices, reversed, rotated): every structure reports one of them at the same t
// as brute force, through the interior, the edges and the vertices.
TEST(Degenerate, DuplicatedFacesGiveOneOfThemAtTheSameDistance) {
  Geometry g;
  g.begin_object("duplicates", 0);
  const glm::vec3 a(0.1f, 0.2f, 1.f), b(2.3f, 0.4f, 1.5f), c(0.7f, 1.9f, 0.8f);
  for (int k = 0; k < 30; ++k)
    g.add_triangle(glm::vec3(float(k), 5, 0), glm::vec3(float(k) + 1, 5, 0), glm::vec3(float(k), 6, 1));
  g.add_triangle(a, b, c);
  g.add_triangle(a, b, c);
  g.add_triangle(a, c, b);
  g.add_triangle(c, a, b);
  std::vector<Ray> rays;
  const glm::vec3 targets[] = {(a + b + c) / 3.f,  a, b, c, 0.5f * (a + b), a + 0.25f * (c - a),
                               b + 0.75f * (c - b)};
  for (const glm::vec3& t : targets)
    for (glm::vec3 o : {glm::vec3(0.5f, 0.5f, -3.f), glm::vec3(1.f, 1.f, 4.f), glm::vec3(-2.f, 0.3f, 1.1f)})
      rays.push_back(Ray{o, t - o});
  expect_brute_force_answers(g, rays, "duplicated faces");
  for (const std::string& name : accelerator_names()) {
    auto acc = make_accelerator(name);
    acc->build(g);
    Hit h;
    ASSERT_TRUE(acc->intersect(rays[0], &h)) << name;  // the centre, from below
    EXPECT_GE(h.prim, 30) << name;
  }
}

// Directions of length 1e-30 and 1e30: the same primitive as the unit direction, at t scaled by 1e30 and
// 1e-30 (within rounding), with every structure; the same for the built-in hard-case octahedron's inside
// rays.
TEST(Degenerate, TinyAndHugeDirectionsHitTheSamePrimitiveAtScaledDistances) {
  HardCaseSet set = inside_rays_set(
      [] {
        TriangleMesh m;
        m.positions = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
        m.triangles = {{0, 2, 4}, {2, 1, 4}, {1, 3, 4}, {3, 0, 4},
                       {2, 0, 5}, {1, 2, 5}, {3, 1, 5}, {0, 3, 5}};
        return m;
      }(),
      "octahedron", HardCaseFamily::nonfinite, 256, 3);
  ASSERT_GE(set.rays.size(), 200u);
  for (const std::string& name : accelerator_names()) {
    auto acc = make_accelerator(name);
    acc->build(set.geometry);
    int bad = 0;
    for (const Ray& unit : set.rays) {
      Hit h1;
      ASSERT_TRUE(acc->intersect(unit, &h1)) << name;

      for (float scale : {1e-30f, 1e30f}) {
        Ray r = unit;
        r.direction *= scale;
        Hit h;
        const bool found = acc->intersect(r, &h);
        // Rays aimed at an edge or a vertex hit several triangles at one distance, and scaling rounds each
        // component of d, which moves the line by an ulp: any of the scaled ray's own ties will do.
        const ReferenceHit ties = reference_nearest(set.geometry, r);
        const double t_unit = double(h.t) * double(scale);
        bad += !found || !agrees_with_reference(ties, h) ||
               std::fabs(t_unit - double(h1.t)) > 1e-5 * double(h1.t);
        bad += !acc->occluded(r);
      }
    }
    EXPECT_EQ(bad, 0) << name;
  }
}

// Huge finite coordinates and tiny ones (near the smallest normal float): every structure builds without a
// crash and agrees with brute force. At 1e37 the scene's extent overflows float (the OBJ reader accepts such
// coordinates): a structure may then refuse the scene with an InputError saying so (the grid does: its cells
// would have infinite size; it once refused with "grid resolution must be 1..4096"), but never crash.
TEST(Degenerate, CoordinatesNearTheEndsOfTheFloatRange) {
  for (float s : {1e37f, 1e35f, 1e-37f}) {
    Geometry g;
    g.begin_object("extreme", 0);
    for (int k = 0; k < 30; ++k) {
      const float x = (float(k) - 15.f) / 8.f;
      g.add_triangle(s * glm::vec3(x, -1, 2), s * glm::vec3(x + 0.1f, 1, 2), s * glm::vec3(x, 1, 2.5f));
    }
    g.add_triangle(s * glm::vec3(-30, -30, 3), s * glm::vec3(30, -30, 3), s * glm::vec3(0, 30, 3));
    std::vector<Ray> rays;
    for (int k = 0; k < 60; ++k) {
      const glm::vec3 target = s * glm::vec3((float(k) - 30.f) / 16.f, 0.125f * float(k % 7) - 0.4f, 2.2f);
      rays.push_back(Ray{glm::vec3(0.f), target});
      rays.push_back(Ray{s * glm::vec3(0.3f, -0.2f, -1.f), target - s * glm::vec3(0.3f, -0.2f, -1.f)});
    }
    expect_brute_force_answers(g, rays, "coordinates x" + std::to_string(s), s > 1e36f);
  }
}

// The grid once lost a ray that leaves it through a cell edge at a mesh vertex: the 3D-DDA's tMax, summed
// step by step, put the exit across x before the crossing of the z boundary that lies a few ulps before it,
// so the last cell, holding the face the ray crosses, was never visited. The two rays `raystep hardcases`
// found on subdivided_box.obj at x1e6 and x1e-6 (both from inside the box, so a miss is a leak).
TEST(Degenerate, GridRayLeavingThroughACellEdgeAtAVertexIsHit) {
  const TriangleMesh box = load_obj(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/meshes/subdivided_box.obj");
  struct Case {
    int scale;
    glm::vec3 o, d;
  };
  const Case cases[] = {
      {2, {-444444.656f, 472222.344f, -497053.719f}, {944444.625f, -888889.375f, 330386.719f}},
      {0,
       {-2.77777673e-07f, 2.77777673e-07f, 4.97053747e-07f},
       {-2.22222326e-07f, -6.9444468e-07f, -9.13720783e-07f}},
  };
  for (const Case& c : cases) {
    Geometry g;
    g.begin_object("box", 0);
    const std::vector<glm::vec3> p = hardcase_scaled(box.positions, c.scale);
    for (const glm::uvec3& t : box.triangles) g.add_triangle(p[t[0]], p[t[1]], p[t[2]]);
    const Ray r = Ray{c.o, c.d};
    const ReferenceHit ref = reference_nearest(g, r);
    ASSERT_TRUE(ref.hit);
    for (const std::string& name : accelerator_names()) {
      auto acc = make_accelerator(name);
      acc->build(g);
      Hit h;
      EXPECT_TRUE(acc->intersect(r, &h)) << name << " " << hardcase_scale_name(c.scale);
      EXPECT_TRUE(agrees_with_reference(ref, h)) << name << " " << hardcase_scale_name(c.scale);
    }
  }
}

// NaN and infinite vertices in an OBJ file are refused with the line (not skipped): a NaN vertex would poison
// every bound it enters (a grid's cell size, a tree's split), and skipping one would renumber or drop the
// faces that use it, silently changing the primitive ids every structure reports. Even a vertex no face uses
// is refused, so that a damaged file never half-loads. Huge finite ones load.
TEST(Degenerate, ObjNonFiniteVerticesAreRefusedWithTheirLine) {
  const char* bad[] = {"v 0 0 0\nv 1 0 0\nv 0 1 0\nv nan 0 0\nf 1 2 3\n",
                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 0 inf 0\n",
                       "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\nv 0 0 -1e39\n"};
  const int line[] = {4, 5, 5};
  for (int i = 0; i < 3; ++i) {
    try {
      parse_obj(bad[i], "m.obj");
      ADD_FAILURE() << "accepted:\n" << bad[i];
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "m.obj");
      EXPECT_EQ(e.line(), line[i]) << e.what();
      EXPECT_NE(e.detail().find("not a finite number"), std::string::npos) << e.what();
    }
  }
  const TriangleMesh huge = parse_obj("v 0 0 0\nv 3e38 0 0\nv 0 -3e38 0\nf 1 2 3\n", "m.obj");
  EXPECT_EQ(huge.triangles.size(), 1u);
}

}  // namespace
}  // namespace raystep
