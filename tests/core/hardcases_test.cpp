// The hard-case battery and report (report/hardcase_battery.h, hardcase_reference.h, hardcases.h): every
// structure has 0 leaks, 0 disagreements and 0 crashes on the built-in battery and on the shipped meshes; the
// generator makes the rays it claims (aimed within rounding of edges and vertices, +0 and -0 components, NaN,
// infinite, tiny and huge rays; every "must hit" ray really hits); and planted bugs (a leaky structure, one
// that hits NaN rays, one that crashes, one that hangs) are caught, so the checker can fail.
#include <gtest/gtest.h>

#include <cmath>
#include <csignal>
#include <filesystem>

#include <glm/geometric.hpp>

#include "raystep/accel/accelerator.h"
#include "raystep/io/obj.h"
#include "raystep/report/hardcase_battery.h"
#include "raystep/report/hardcase_reference.h"
#include "raystep/report/hardcases.h"
#include "test_budget.h"

namespace raystep {
namespace {

const char* kMeshes[] = {"octahedron", "subdivided_box", "leak_octahedron", "thin_strips", "torus_knot"};

std::string mesh_path(const std::string& name) {
  return std::string(RAYSTEP_SOURCE_DIR) + "/scenes/meshes/" + name + ".obj";
}

const HardCaseRow* find_row(const HardCaseReport& r, const std::string& structure, HardCaseFamily f) {
  for (const HardCaseRow& row : r.rows)
    if (row.structure == structure && row.family == f) return &row;
  return nullptr;
}

// Every structure, the variants too, in child processes: the built-in battery is clean.
TEST(HardCases, BuiltInBatteryIsCleanForEveryStructure) {
  HardCaseOptions options;
  options.mesh_rays = size_t(test::budget(256));
  std::string note;
  std::vector<HardCaseSet> battery = hardcase_battery(nullptr, options, &note);
  EXPECT_EQ(note, "");
  HardCaseRunOptions run;
  run.structures = accelerator_names();
  HardCaseReport report = run_hardcases(battery, run);
  EXPECT_TRUE(report.clean()) << hardcases_table(report);
  // Every structure ran every family present (inside, axis, plane, overlap, sliver, nonfinite).
  EXPECT_EQ(report.rows.size(), run.structures.size() * 6);
  for (const HardCaseRow& row : report.rows) EXPECT_GT(row.rays, 0u) << row.structure;
}

// The shipped meshes: the inside family on the closed ones (four scales), the surface and nonfinite families
// on all of them; thin_strips is open, and says so.
TEST(HardCases, ShippedMeshesAreCleanForEveryStructure) {
  for (const char* name : kMeshes) {
    TriangleMesh mesh = load_obj(mesh_path(name));
    HardCaseOptions options;
    options.mesh_rays = size_t(test::budget(256));
    options.built_in_families = false;
    std::string note;
    std::vector<HardCaseSet> battery = hardcase_battery(&mesh, options, &note);
    const bool closed = mesh_closure(mesh).closed();
    EXPECT_EQ(closed, std::string(name) != "thin_strips") << name;
    EXPECT_EQ(note.empty(), closed) << name << ": " << note;
    HardCaseRunOptions run;
    run.structures = accelerator_names();
    HardCaseReport report = run_hardcases(battery, run);
    EXPECT_TRUE(report.clean()) << name << "\n" << hardcases_table(report);
    const HardCaseRow* inside = find_row(report, "bsp", HardCaseFamily::inside);
    if (closed) {
      ASSERT_NE(inside, nullptr) << name;
      // Most of the 4 x mesh_rays rays found an inside point.
      EXPECT_GE(inside->rays, 4u * uint32_t(test::budget(200))) << name;
    } else {
      EXPECT_EQ(inside, nullptr) << name;
    }
  }
}

double max_abs(const glm::vec3& v) {
  return std::max({std::fabs(v.x), std::fabs(v.y), std::fabs(v.z)});
}

// Aimed rays pass within rounding of their target, and each target is a vertex or lies within rounding of an
// edge of the set's geometry; every ray the generator says must hit is hit by the reference.
TEST(HardCases, GeneratedRaysAreWhatTheyClaim) {
  HardCaseOptions options;
  options.mesh_rays = size_t(test::budget(128));
  TriangleMesh knot = load_obj(mesh_path("torus_knot"));
  std::vector<HardCaseSet> battery = hardcase_battery(nullptr, options, nullptr);
  std::vector<HardCaseSet> mine = hardcase_battery(&knot, options, nullptr);
  battery.insert(battery.end(), mine.begin(), mine.end());
  size_t aimed = 0, on_vertex = 0, on_edge = 0, must = 0;
  for (const HardCaseSet& set : battery) {
    ASSERT_EQ(set.rays.size(), set.must_hit.size()) << set.name;
    ASSERT_EQ(set.rays.size(), set.targets.size()) << set.name;
    for (size_t i = 0; i < set.rays.size(); ++i) {
      const Ray& r = set.rays[i];
      if (set.must_hit[i]) {
        ++must;
        EXPECT_TRUE(reference_nearest(set.geometry, r).hit) << set.name << " ray " << i;
      }
      const glm::vec3 target = set.targets[i];
      if (std::isnan(target.x)) continue;
      ++aimed;
      // The line o + t d passes within rounding of the target: |(target - o) x d| / |d|, in double.
      const glm::dvec3 w = glm::dvec3(target) - glm::dvec3(r.origin), d(r.direction);
      const double miss = glm::length(glm::cross(w, d)) / glm::length(d);
      const double scale = std::max(max_abs(target), max_abs(r.origin));
      EXPECT_LE(miss, 8 * 0x1p-24 * scale) << set.name << " ray " << i;
      // The target is a vertex of a triangle, or within rounding of one of its edges.
      bool vertex = false, edge = false;
      for (uint32_t id = 0; id < set.geometry.size() && !vertex; ++id)
        for (int k = 0; k < 3; ++k) {
          const glm::vec3 a = set.geometry.vertex(id, k), b = set.geometry.vertex(id, (k + 1) % 3);
          if (a == target) vertex = true;
          const glm::dvec3 ab = glm::dvec3(b) - glm::dvec3(a), at = glm::dvec3(target) - glm::dvec3(a);
          const double len2 = glm::dot(ab, ab);
          if (len2 == 0.0) continue;
          const double f = glm::dot(at, ab) / len2;
          const double dist = glm::length(at - f * ab);
          if (f > 0.0 && f < 1.0 && dist <= 4 * 0x1p-24 * std::max(max_abs(a), max_abs(b))) edge = true;
        }
      on_vertex += vertex;
      on_edge += !vertex && edge;
      EXPECT_TRUE(vertex || edge) << set.name << " ray " << i;
    }
  }
  EXPECT_GT(aimed, 10000u);
  EXPECT_GT(on_vertex, 2000u);
  EXPECT_GT(on_edge, 2000u);
  EXPECT_GT(must, 20000u);
}

TEST(HardCases, FamiliesHoldTheirSpecialRays) {
  std::vector<HardCaseSet> battery = hardcase_battery(nullptr, HardCaseOptions{}, nullptr);
  int plus_zero = 0, minus_zero = 0, nan_origin = 0, inf_direction = 0, tiny = 0, huge = 0, nan_bound = 0;
  for (const HardCaseSet& set : battery)
    for (const Ray& r : set.rays) {
      for (int a = 0; a < 3; ++a) {
        if (set.family == HardCaseFamily::axis && r.direction[a] == 0.f)
          (std::signbit(r.direction[a]) ? minus_zero : plus_zero)++;
        if (set.family == HardCaseFamily::nonfinite) {
          nan_origin += std::isnan(r.origin[a]);
          inf_direction += std::isinf(r.direction[a]);
        }
      }
      if (set.family == HardCaseFamily::nonfinite) {
        const double len = glm::length(glm::dvec3(r.direction));
        tiny += len > 1e-31 && len < 1e-29;
        huge += len > 1e29 && len < 1e31;
        nan_bound += std::isnan(r.tmin) || std::isnan(r.tmax);
      }
    }
  EXPECT_GT(plus_zero, 1000);
  EXPECT_GT(minus_zero, 1000);
  EXPECT_GT(nan_origin, 10);
  EXPECT_GT(inf_direction, 10);
  EXPECT_GT(tiny, 10);
  EXPECT_GT(huge, 10);
  EXPECT_GT(nan_bound, 10);
}

TEST(HardCases, ClosedMeansEveryEdgeSharedAnEvenNumberOfTimes) {
  EXPECT_TRUE(mesh_closure(load_obj(mesh_path("octahedron"))).closed());
  EXPECT_TRUE(mesh_closure(load_obj(mesh_path("torus_knot"))).closed());
  MeshClosure strips = mesh_closure(load_obj(mesh_path("thin_strips")));
  EXPECT_FALSE(strips.closed());
  EXPECT_GT(strips.odd_edges, 0u);
  // A face removed leaves its three edges odd.
  TriangleMesh oct = load_obj(mesh_path("octahedron"));
  oct.triangles.pop_back();
  EXPECT_EQ(mesh_closure(oct).odd_edges, 3u);
  // The same octahedron with its vertices repeated per face (no shared indices) is still closed by position.
  TriangleMesh soup;
  for (const glm::uvec3& t : load_obj(mesh_path("octahedron")).triangles) {
    const uint32_t base = uint32_t(soup.positions.size());
    for (int k = 0; k < 3; ++k) soup.positions.push_back(load_obj(mesh_path("octahedron")).positions[t[k]]);
    soup.triangles.push_back({base, base + 1, base + 2});
  }
  EXPECT_TRUE(mesh_closure(soup).closed());
}

// Ties: coincident triangles and triangles sharing the edge a ray passes through are all nearest.
TEST(HardCases, ReferenceKeepsCoincidentAndEdgeSharingTrianglesAsTies) {
  Geometry g;
  g.begin_object("ties", 0);
  const glm::vec3 a(-1, -1, 2), b(1, -1, 2), c(-1, 1, 2), d(1, 1, 2);
  g.add_triangle(a, b, c);
  g.add_triangle(b, d, c);  // shares the diagonal b-c
  g.add_triangle(a, c, b);  // coincident with the first, reversed
  g.add_triangle(glm::vec3(-3, -3, 2.5f), glm::vec3(3, -3, 2.5f), glm::vec3(0, 3, 2.5f));  // behind
  Ray r;
  r.direction = glm::vec3(0, 0, 1);  // through the middle of b-c
  ReferenceHit ref = reference_nearest(g, r);
  ASSERT_TRUE(ref.hit);
  EXPECT_EQ(ref.t, 2.0);
  EXPECT_EQ(ref.tied, (std::vector<int32_t>{0, 1, 2}));
  Hit h;
  h.prim = 1;
  EXPECT_TRUE(agrees_with_reference(ref, h));
  h.prim = 3;
  EXPECT_FALSE(agrees_with_reference(ref, h));
  h.prim = -1;
  EXPECT_FALSE(agrees_with_reference(ref, h));
  // Edge-on (the ray in the triangles' plane) and NaN: misses.
  r.origin = glm::vec3(-3, 0, 2);
  r.direction = glm::vec3(1, 0, 0);
  EXPECT_FALSE(reference_nearest(g, r).hit);
  r.origin = glm::vec3(std::nanf(""), 0, 0);
  r.direction = glm::vec3(0, 0, 1);
  EXPECT_FALSE(reference_nearest(g, r).hit);
}

// ---- Planted bugs: the checker must be able to fail ----

// Wraps a real structure and breaks it in one way.
class Planted : public Accelerator {
 public:
  enum class Bug { leaky, nan_hit, crash_on_nan, hang_on_nan, throws_on_build };
  Planted(Bug bug) : bug_(bug), inner_(make_accelerator("bvh")) {}
  std::string name() const override { return "planted"; }
  void build(const Geometry& g) override {
    if (bug_ == Bug::throws_on_build && g.size() == 48) throw std::runtime_error("planted");  // the axis cube
    inner_->build(g);
  }
  bool intersect(const Ray& ray, Hit* hit) const override {
    const bool nan = std::isnan(ray.origin.x) || std::isnan(ray.direction.x) || std::isnan(ray.direction.y);
    if (nan && bug_ == Bug::crash_on_nan) {
      // The default action, so that the child dies of the signal under AddressSanitizer too (its handler
      // would report the fault and exit with code 1).
      std::signal(SIGSEGV, SIG_DFL);
      std::raise(SIGSEGV);
    }
    if (nan && bug_ == Bug::hang_on_nan)
      for (volatile unsigned spin = 0;; spin = spin + 1u) {  // unsigned: wraps, no overflow for UBSan to stop
      }
    if (nan && bug_ == Bug::nan_hit) {
      *hit = Hit{};
      hit->prim = 0;
      hit->t = 1.f;
      return true;
    }
    const bool found = inner_->intersect(ray, hit);
    // Leaky: drops every hit on primitive 0 (one triangle of each geometry has a hole).
    if (bug_ == Bug::leaky && found && hit->prim == 0) {
      *hit = Hit{};
      return false;
    }
    return found;
  }
  bool occluded(const Ray& ray) const override {
    Hit h;
    return intersect(ray, &h);
  }
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder&) const override {
    return intersect(ray, hit);
  }

 private:
  Bug bug_;
  std::unique_ptr<Accelerator> inner_;
};

HardCaseReport run_planted(Planted::Bug bug, double time_limit = 60.0) {
  HardCaseOptions options;
  options.mesh_rays = 128;
  std::vector<HardCaseSet> all = hardcase_battery(nullptr, options, nullptr), battery;
  for (HardCaseSet& set : all)  // the first geometry of each family is enough to catch these bugs
    if (battery.empty() || battery.back().family != set.family) battery.push_back(std::move(set));
  HardCaseRunOptions run;
  run.structures = {"bvh", "planted"};
  run.time_limit_seconds = time_limit;
  run.factory = [bug](const std::string& name) -> std::unique_ptr<Accelerator> {
    if (name == "planted") return std::make_unique<Planted>(bug);
    return make_accelerator(name);
  };
  return run_hardcases(battery, run);
}

TEST(HardCases, PlantedLeakIsCaught) {
  HardCaseReport r = run_planted(Planted::Bug::leaky);
  EXPECT_FALSE(r.clean());
  const HardCaseRow* inside = find_row(r, "planted", HardCaseFamily::inside);
  ASSERT_NE(inside, nullptr);
  EXPECT_GT(inside->leaks, 0u);
  EXPECT_NE(inside->first_issue.find("leak"), std::string::npos) << inside->first_issue;
  EXPECT_EQ(find_row(r, "bvh", HardCaseFamily::inside)->leaks, 0u);
  EXPECT_EQ(r.crashes(), 0u);
}

TEST(HardCases, PlantedNaNHitIsADisagreement) {
  HardCaseReport r = run_planted(Planted::Bug::nan_hit);
  const HardCaseRow* nonfinite = find_row(r, "planted", HardCaseFamily::nonfinite);
  ASSERT_NE(nonfinite, nullptr);
  EXPECT_GT(nonfinite->disagreements, 0u);
  EXPECT_EQ(r.leaks(), 0u);
  EXPECT_EQ(find_row(r, "planted", HardCaseFamily::inside)->disagreements, 0u);
  EXPECT_NE(hardcases_verdict(r).find("FAIL"), std::string::npos);
}

// A crash ends its family only: the families after it still run, in a new child.
TEST(HardCases, PlantedCrashIsCountedWithItsFamily) {
  HardCaseReport r = run_planted(Planted::Bug::crash_on_nan);
  EXPECT_EQ(r.crashes(), 1u);
  const HardCaseRow* nonfinite = find_row(r, "planted", HardCaseFamily::nonfinite);
  ASSERT_NE(nonfinite, nullptr);
  EXPECT_EQ(nonfinite->crashes, 1u);
  EXPECT_NE(nonfinite->first_issue.find("signal 11"), std::string::npos) << nonfinite->first_issue;

  HardCaseReport thrown = run_planted(Planted::Bug::throws_on_build);
  const HardCaseRow* axis = find_row(thrown, "planted", HardCaseFamily::axis);
  ASSERT_NE(axis, nullptr);
  EXPECT_EQ(axis->crashes, 1u);
  const HardCaseRow* after = find_row(thrown, "planted", HardCaseFamily::plane);
  ASSERT_NE(after, nullptr);  // the next family ran
  EXPECT_EQ(after->crashes, 0u);
  EXPECT_GT(after->rays, 0u);
}

TEST(HardCases, PlantedHangHitsTheTimeLimit) {
  HardCaseReport r = run_planted(Planted::Bug::hang_on_nan, 2.0);
  const HardCaseRow* nonfinite = find_row(r, "planted", HardCaseFamily::nonfinite);
  ASSERT_NE(nonfinite, nullptr);
  EXPECT_EQ(nonfinite->crashes, 1u);
  EXPECT_NE(nonfinite->first_issue.find("time limit"), std::string::npos) << nonfinite->first_issue;
}

TEST(HardCases, ReportFormats) {
  HardCaseReport r = run_planted(Planted::Bug::nan_hit);
  const std::string csv = hardcases_csv(r), json = hardcases_json(r), table = hardcases_table(r);
  EXPECT_EQ(csv.rfind("structure,family,rays,leaks,disagreements,crashes,ms,first_issue\n", 0), 0u);
  EXPECT_NE(csv.find("planted,nonfinite,"), std::string::npos);
  EXPECT_NE(json.find("\"clean\": false"), std::string::npos);
  EXPECT_NE(table.find("first issue of each failing row"), std::string::npos);
}

}  // namespace
}  // namespace raystep
