// `raystep hardcases`: exit 0 and a clean table on a shipped mesh, the report file (.csv, .json) written, an
// open mesh said to skip the inside rays, and bad input (a missing or damaged mesh, a bad report name, an
// unknown structure) refused with exit 2 and one line naming the file. Exit 1 (a leak, a disagreement, a
// crash) needs a broken structure: tests/core/hardcases_test.cpp plants them in the same report code.
#include <nlohmann/json.hpp>

#include "cli_test_util.h"

namespace raystep::clitest {
namespace {

class HardCasesCli : public CliTest {
 protected:
  HardCasesCli() : CliTest("raystep_hardcases_cli_") {}
};

std::string mesh(const std::string& name) {
  return scene("meshes/" + name);
}

TEST_F(HardCasesCli, ShippedMeshIsCleanAndTheReportIsWritten) {
  Outcome r =
      run("hardcases " + mesh("octahedron.obj") + " --accel brute,grid,kd,bvh --rays 64 -o " + path("r.csv"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("PASS: 0 leaks, 0 disagreements, 0 crashes"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("grid       inside"), std::string::npos) << r.out;
  std::vector<CsvRow> rows = read_csv(path("r.csv"));
  ASSERT_EQ(rows.size(), 4u * 7u);  // 4 structures x 7 families (the mesh's inside, surface; built-in ones)
  for (const CsvRow& row : rows) {
    EXPECT_EQ(row.at("leaks"), "0");
    EXPECT_EQ(row.at("disagreements"), "0");
    EXPECT_EQ(row.at("crashes"), "0");
    EXPECT_NE(row.at("rays"), "0");
  }
  r = run("hardcases " + mesh("octahedron.obj") + " --accel octree --rays 64 -o " + path("r.json"));
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  nlohmann::json j = nlohmann::json::parse(slurp(path("r.json")));
  EXPECT_EQ(j["clean"], true);
  EXPECT_EQ(j["rows"].size(), 7u);
  EXPECT_EQ(j["mesh"], mesh("octahedron.obj"));
}

TEST_F(HardCasesCli, OpenMeshSkipsTheInsideRaysAndSaysWhy) {
  Outcome r = run("hardcases " + mesh("thin_strips.obj") + " --accel kd --rays 64");
  ASSERT_EQ(r.code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("the mesh is not closed"), std::string::npos) << r.out;
  EXPECT_EQ(r.out.find("kd         inside"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("kd         surface"), std::string::npos) << r.out;
}

TEST_F(HardCasesCli, BadInputExits2NamingTheFile) {
  expect_error(run("hardcases " + path("missing.obj") + " -o " + path("r.csv")), path("missing.obj"),
               path("r.csv"));
  const std::string nan_mesh = write("nan.obj", "v 0 0 0\nv 1 0 0\nv 0 nan 0\nf 1 2 3\n");
  expect_error(run("hardcases " + nan_mesh + " -o " + path("r.csv")), nan_mesh + ":3: v: coordinate 'nan'",
               path("r.csv"));
  expect_error(run("hardcases " + mesh("octahedron.obj") + " -o " + path("r.txt")), path("r.txt"),
               path("r.txt"));
  expect_error(run("hardcases " + mesh("octahedron.obj") + " --accel kd,octree-of-dreams"),
               "unknown accelerator 'octree-of-dreams'");
  expect_error(run("hardcases --rays 100000"), "hardcases: --rays");
}

}  // namespace
}  // namespace raystep::clitest
