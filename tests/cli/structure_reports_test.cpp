// `raystep compare`, `raystep grid-sweep` and `raystep cost` end to end: every structure agrees with brute
// force on every shipped scene and mesh, the cost formula's bound holds (exactly where it is exact), the
// sweep's rows move the way they must, and bad input exits 2 with one line.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;

using namespace raystep::clitest;

double num(const CsvRow& row, const std::string& key) {
  auto it = row.find(key);
  EXPECT_NE(it, row.end()) << key;
  return it == row.end() ? -1.0 : std::stod(it->second);
}

class StructureReports : public CliTest {
 protected:
  StructureReports() : CliTest("raystep_reports_") {}

  // Nothing but the named entries in the test folder: no DIR.tmp.PID left behind.
  void expect_only(const std::vector<std::string>& names) const {
    std::vector<std::string> found;
    for (const auto& e : fs::directory_iterator(dir_)) found.push_back(e.path().filename().string());
    std::sort(found.begin(), found.end());
    std::vector<std::string> want = names;
    std::sort(want.begin(), want.end());
    EXPECT_EQ(found, want);
  }
};

std::vector<std::string> shipped_inputs() {
  std::vector<std::string> files;
  for (const char* sub : {"/scenes", "/scenes/meshes"})
    for (const auto& e : fs::directory_iterator(std::string(RAYSTEP_SOURCE_DIR) + sub)) {
      std::string ext = e.path().extension().string();
      if (ext == ".json" || ext == ".obj") files.push_back(e.path().string());
    }
  std::sort(files.begin(), files.end());
  return files;
}

TEST_F(StructureReports, CompareFindsNoDisagreementOnAnyShippedSceneOrMesh) {
  std::vector<std::string> inputs = shipped_inputs();
  ASSERT_GE(inputs.size(), 10u);
  for (const std::string& input : inputs) {
    SCOPED_TRACE(input);
    fs::remove_all(path("cmp"));
    Outcome r = run("compare " + input + " --rays 3000 --size 40x30 --reps 1 -o " + path("cmp"));
    ASSERT_EQ(r.code, 0) << "stderr: " << r.err << "\nstdout: " << r.out;
    std::vector<CsvRow> rows = read_csv(path("cmp/report.csv"));
    ASSERT_EQ(rows.size(), 5u);
    const char* names[] = {"brute", "bvol", "grid", "kd", "kd-median"};
    for (size_t i = 0; i < rows.size(); ++i) {
      EXPECT_EQ(rows[i]["structure"], names[i]);
      EXPECT_EQ(num(rows[i], "disagreements"), 0.0) << names[i];
      EXPECT_EQ(num(rows[i], "checked_rays"), 1200.0 + 3000.0) << names[i];  // every ray checked
      EXPECT_GT(num(rows[i], "camera_mrays_per_s"), 0.0) << names[i];
    }
    EXPECT_EQ(num(rows[0], "memory_bytes"), 0.0);
    EXPECT_GT(num(rows[2], "memory_bytes"), 0.0);
    EXPECT_TRUE(fs::exists(path("cmp/report.md")));
    EXPECT_TRUE(fs::exists(path("cmp/speed.gp")));
    EXPECT_NE(r.out.find("| grid |"), std::string::npos);
  }
  expect_only({"cmp"});
}

// A scene with no lights and max_depth 0: each of the m^2 k^2 samples is one ray that brute force tests
// against all n primitives, so the count equals the formula exactly.
TEST_F(StructureReports, CostMeetsTheFormulaExactlyWhereItIsExact) {
  std::ofstream(path("flat.json"))
      << R"({"camera": {"type": "orthographic", "eye": [0, 0, 5], "look_at": [0, 0, 0], "height": 4},
  "lights": [], "materials": {"white": {"diffuse": 1}},
  "objects": [
    {"type": "triangle", "material": "white", "vertices": [[-1, -1, 0], [1, -1, 0], [0, 1, 0]]},
    {"type": "triangle", "material": "white", "vertices": [[-1, -1, 1], [1, -1, 1], [0, 1, 1]]},
    {"type": "quad", "material": "white", "vertices": [[-2, -2, -1], [2, -2, -1], [2, 2, -1], [-2, 2, -1]]}],
  "render": {"size": [10, 8], "aa": "regular:3", "max_depth": 0, "ambient": 1}})";
  Outcome r = run("cost " + path("flat.json") + " -o " + path("cost"));
  ASSERT_EQ(r.code, 0) << r.err;
  const double exact = 10.0 * 8 * 9 * 4;  // m^2 k^2 n: a quad is two triangles
  std::vector<CsvRow> rows = read_csv(path("cost/report.csv"));
  ASSERT_GE(rows.size(), 3u);
  EXPECT_EQ(num(rows[0], "predicted"), exact);
  EXPECT_EQ(num(rows[0], "bound"), exact);
  EXPECT_EQ(num(rows[0], "tests"), exact);  // brute force, no adaptive termination
  EXPECT_EQ(num(rows[1], "tests"), exact);  // with it: nothing to terminate at depth 0
  for (const CsvRow& row : rows) EXPECT_LE(num(row, "tests"), exact) << row.at("render");
  EXPECT_NE(r.out.find("m^2 = 10 x 8 = 80 pixels"), std::string::npos) << r.out;
  EXPECT_TRUE(fs::exists(path("cost/factors.csv")));
  EXPECT_TRUE(fs::exists(path("cost/report.md")));
  EXPECT_EQ(slurp(path("cost/report.txt")), r.out.substr(0, r.out.find("\nwrote ")));
}

TEST_F(StructureReports, CostNeverExceedsTheBoundOnTheCornellBox) {
  Outcome r = run("cost " + std::string(RAYSTEP_SOURCE_DIR) +
                  "/scenes/cornell.json --size 20x20 --aa jitter:2 -o " + path("cost"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<CsvRow> rows = read_csv(path("cost/report.csv"));
  // brute twice, fourteen structures (bvol, grid, kd, kd-median, 4 binary BVHs, 4 wide, octree, bsp), adaptive
  ASSERT_EQ(rows.size(), 17u);
  const double bound = num(rows[0], "bound");
  EXPECT_EQ(bound, 20.0 * 20 * 4 * 23 * 63 * 2);  // m^2 k^2 n (2^6 - 1)(1 + 1 light)
  for (const CsvRow& row : rows) EXPECT_LE(num(row, "tests"), bound) << row.at("render");
  // Every structure tests fewer primitives than brute force.
  for (size_t i = 2; i < 16; ++i)
    EXPECT_LT(num(rows[i], "tests"), num(rows[1], "tests")) << rows[i].at("render");
  std::vector<CsvRow> factors = read_csv(path("cost/factors.csv"));
  ASSERT_EQ(factors.size(), 16u);  // 2^d, n for each of the fourteen structures, k^2
  EXPECT_EQ(factors[0]["factor"], "2^d");
  EXPECT_EQ(factors[15]["factor"], "k^2");
  // Without -o: the table on stdout only.
  Outcome plain =
      run("cost " + std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json --size 8x8 --accel grid");
  EXPECT_EQ(plain.code, 0) << plain.err;
  EXPECT_NE(plain.out.find("acceleration: grid"), std::string::npos);
}

TEST_F(StructureReports, GridSweepRowsMoveTheWayTheyMust) {
  Outcome r = run("grid-sweep " + std::string(RAYSTEP_SOURCE_DIR) +
                  "/scenes/meshes/torus_knot.obj --rays 2000 --size 32x24 --reps 1 -o " + path("sweep"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<CsvRow> rows = read_csv(path("sweep/report.csv"));
  ASSERT_EQ(rows.size(), 9u);
  for (size_t i = 1; i < rows.size(); ++i) {
    SCOPED_TRACE(rows[i]["density"]);
    EXPECT_GT(num(rows[i], "density"), num(rows[i - 1], "density"));
    EXPECT_GT(num(rows[i], "cells"), num(rows[i - 1], "cells"));
    EXPECT_GE(num(rows[i], "references_per_prim"), num(rows[i - 1], "references_per_prim"));
    EXPECT_GT(num(rows[i], "cells_per_ray"), num(rows[i - 1], "cells_per_ray"));
    EXPECT_GT(num(rows[i], "bytes"), num(rows[i - 1], "bytes"));
  }
  EXPECT_LT(num(rows.back(), "tests_per_ray"), num(rows.front(), "tests_per_ray"));
  EXPECT_TRUE(fs::exists(path("sweep/report.md")));
  EXPECT_TRUE(fs::exists(path("sweep/sweep.gp")));
  // Chosen densities, in the order given.
  fs::remove_all(path("sweep"));
  r = run("grid-sweep " + std::string(RAYSTEP_SOURCE_DIR) +
          "/scenes/cornell.json --densities 1,3 --rays 100 --size 8x8 --reps 1 -o " + path("sweep"));
  ASSERT_EQ(r.code, 0) << r.err;
  rows = read_csv(path("sweep/report.csv"));
  ASSERT_EQ(rows.size(), 2u);
  EXPECT_EQ(num(rows[1], "density"), 3.0);
  expect_only({"sweep"});
}

TEST_F(StructureReports, AnExistingReportIsReplacedWhole) {
  std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/aliasing.json";
  fs::create_directories(path("out"));
  std::ofstream(path("out/stale.txt")) << "old";
  Outcome r = run("grid-sweep " + scene + " --densities 2 --rays 10 --reps 1 -o " + path("out"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(path("out/stale.txt")));
  EXPECT_TRUE(fs::exists(path("out/report.csv")));
  expect_only({"out"});
}

TEST_F(StructureReports, BadInputExitsTwoWithOneLine) {
  const std::string scene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";
  const std::string out = " -o " + path("r");
  expect_error(run("compare " + scene + " --accel grid,quadtree" + out),
               "--accel: unknown accelerator 'quadtree'");
  expect_error(run("compare " + scene + " --accel grid,,kd" + out), "--accel");
  expect_error(run("compare " + scene + " --accel ''" + out), "--accel");
  expect_error(run("compare " + scene + " --reps 0" + out), "--reps");
  expect_error(run("compare " + scene + " --size 0x3" + out), "--size");
  expect_error(run("compare " + path("missing.json") + out), path("missing.json"));
  expect_error(run("compare " + scene + " -o " + path("no/such/folder")), path("no/such/folder"));
  expect_error(run("grid-sweep " + scene + " --densities 0,1" + out), "--densities");
  expect_error(run("grid-sweep " + scene + " --densities 1,abc" + out), "--densities");
  expect_error(run("grid-sweep " + scene + " --densities 65" + out), "--densities");
  expect_error(run("grid-sweep " + scene + " --densities nan" + out), "--densities");
  expect_error(run("grid-sweep " + scene + " --densities 1," + out), "--densities");
  expect_error(run("cost " + scene + " --accel quadtree" + out), "--accel: unknown accelerator 'quadtree'");
  expect_error(run("cost " + scene + " --aa jitter:0" + out), "");
  expect_error(run("cost " + scene + " --threads -1"), "--threads");
  std::ofstream(path("bad.json")) << "{ \"objects\": 3 }";
  expect_error(run("cost " + path("bad.json")), path("bad.json"));
  expect_error(run("grid-sweep " + path("bad.json") + out), path("bad.json"));
  expect_only({"bad.json"});  // no report folder, no temporary folder
}

}  // namespace
