// The general BSP tree on the command line: `--accel bsp` in cast (the same hits as brute force under its
// options), trace (a version 4 trace with planes that trace-info reads back) and compare (nodes and depth
// side by side with the kd-tree, no disagreement on the slanted scenes); bad BSP options exit 2 with one
// line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace raystep::clitest;

class BspCli : public CliTest {
 protected:
  BspCli() : CliTest("raystep_bsp_cli_") {}
};

const std::string kRotated = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/rotated_box.json";
const std::string kTilted = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/tilted_plane.json";

TEST_F(BspCli, CastsLikeBruteForceUnderEveryOption) {
  ASSERT_EQ(run("rays " + kRotated + " --kind random --count 4000 --seed 7 -o " + path("r.rays")).code, 0);
  ASSERT_EQ(
      run("cast " + kRotated + " --rays " + path("r.rays") + " --hits " + path("b.hits") + " --accel brute")
          .code,
      0);
  for (const char* opts :
       {"--accel bsp", "--accel bsp --bsp-directions kdop", "--accel bsp --bsp-directions autopartition",
        "--accel bsp --bsp-candidates 4 --ti 10 --tt 2 --max-depth 12 --leaf-size 3 --mailbox off"}) {
    Outcome c =
        run("cast " + kRotated + " --rays " + path("r.rays") + " --hits " + path("k.hits") + " " + opts);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_EQ(slurp(path("k.hits")), slurp(path("b.hits"))) << opts;
  }
}

TEST_F(BspCli, TraceWritesPlanesThatTraceInfoReads) {
  Outcome r = run("trace " + kTilted + " --accel bsp --pixel 160,120 -o " + path("t.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = slurp(path("t.json"));
  EXPECT_EQ(text.rfind("{\n \"format\": \"raystep-trace\",\n \"version\": 4,", 0), 0u);
  EXPECT_NE(text.find("\"kind\":\"bsp\""), std::string::npos);
  EXPECT_NE(text.find("\"directions\":\"both\""), std::string::npos);
  EXPECT_NE(text.find("\"normal\":["), std::string::npos);
  Outcome info = run("trace-info " + path("t.json"));
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("valid raystep trace, version 4"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("structure bsp"), std::string::npos) << info.out;
}

TEST_F(BspCli, CompareShowsKdAndBspSideBySide) {
  for (const std::string& scene : {kRotated, kTilted}) {
    SCOPED_TRACE(scene);
    fs::remove_all(path("cmp"));
    Outcome r =
        run("compare " + scene + " --accel kd,bsp --rays 3000 --size 40x30 --reps 1 -o " + path("cmp"));
    ASSERT_EQ(r.code, 0) << r.err;
    std::vector<CsvRow> rows = read_csv(path("cmp/report.csv"));
    ASSERT_EQ(rows.size(), 2u);
    EXPECT_EQ(rows[1]["structure"], "bsp");
    for (CsvRow& row : rows) {
      EXPECT_EQ(row["disagreements"], "0") << row["structure"];
      EXPECT_EQ(row["steps"], "nodes");
      EXPECT_GT(std::stoi(row["nodes"]), 1);
      EXPECT_GT(std::stoi(row["max_depth"]), 0);
    }
    EXPECT_NE(r.out.find("| bsp |"), std::string::npos) << r.out;
    EXPECT_NE(r.out.find("nodes (depth)"), std::string::npos) << r.out;
  }
}

TEST_F(BspCli, BadOptionsExitTwoWithOneLine) {
  const std::string png = " -o " + path("a.png");
  expect_error(run("render " + kTilted + " --accel bsp --bsp-directions diagonal" + png), "--bsp-directions");
  expect_error(run("render " + kTilted + " --accel bsp --bsp-candidates 0" + png), "--bsp-candidates");
  expect_error(run("render " + kTilted + " --accel bsp --bsp-candidates 5000" + png), "--bsp-candidates");
  expect_error(run("render " + kTilted + " --accel bsp --max-depth 65" + png), "--max-depth");
  expect_error(run("render " + kTilted + " --accel bsp --ti -1" + png), "bsp: t_i");
  expect_error(run("render " + kTilted + " --accel bsp --leaf-size 0" + png), "bsp: leaf_size");
  EXPECT_FALSE(fs::exists(path("a.png")));
}

}  // namespace
