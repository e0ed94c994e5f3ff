// `raystep bvh-stats`, `raystep sah --accel bvh...` and the BVH's options on every --accel command: outputs
// that follow the lecture's formula and brute force, and bad values exiting 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace raystep::clitest;

class BvhCli : public CliTest {
 protected:
  BvhCli() : CliTest("raystep_bvh_cli_") {}
};

std::vector<std::vector<std::string>> rows_of(const std::string& text) {
  std::vector<std::vector<std::string>> rows;
  std::stringstream lines(text);
  for (std::string line; std::getline(lines, line);) {
    std::vector<std::string> cells;
    std::stringstream ss(line);
    for (std::string cell; std::getline(ss, cell, ',');) cells.push_back(cell);
    rows.push_back(cells);
  }
  return rows;
}

const std::string kScene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/torus_knot.json";

TEST_F(BvhCli, StatsPrintTheShapeAndCroftonsPrediction) {
  for (const char* accel : {"bvh", "bvh-sweep", "bvh-median"}) {
    Outcome r = run("bvh-stats " + kScene + " --accel " + accel + " --lines 20000 --csv " + path("n.csv"));
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* key : {"nodes:", "leaves", "depth: max", "primitives per leaf", "SAH cost of the tree",
                            "sibling overlap", "(root)", "predicted"})
      EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
    auto rows = rows_of(slurp(path("n.csv")));
    ASSERT_GT(rows.size(), 10u);
    ASSERT_EQ(rows[0].size(), 8u);
    EXPECT_EQ(rows[1][5], "1");
    EXPECT_EQ(rows[1][6], "1");
    for (size_t i = 2; i < std::min<size_t>(rows.size(), 8); ++i)
      EXPECT_NEAR(std::stod(rows[i][6]), std::stod(rows[i][5]), 0.02) << accel << " node " << rows[i][0];
  }
}

TEST_F(BvhCli, SahCurveFollowsTheFormulaAndMarksTheChoice) {
  Outcome r = run("sah " + kScene + " --accel bvh --bins 8 --node 0 -o " + path("c.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("decision: split"), std::string::npos) << r.out;
  auto rows = rows_of(slurp(path("c.csv")));
  ASSERT_EQ(rows[0].size(), 10u);
  EXPECT_EQ(rows[0][0], "axis");
  EXPECT_EQ(rows[0][9], "chosen");
  ASSERT_EQ(rows.size(), 1u + 3u * 7u);  // a header, then 7 bin boundaries on each axis
  int chosen = 0;
  double best = 1e30, chosen_cost = 0;
  for (size_t i = 1; i < rows.size(); ++i) {
    double n_l = std::stod(rows[i][3]), n_r = std::stod(rows[i][4]);
    double a_l = std::stod(rows[i][5]), a_r = std::stod(rows[i][6]), a = std::stod(rows[i][7]);
    double cost = std::stod(rows[i][8]);
    // C = t_t + (S_l N_l + S_r N_r) t_i / S_node with t_i 80, t_t 1.
    EXPECT_NEAR(cost, 1.0 + 80.0 * (a_l * n_l + a_r * n_r) / a, 1e-3 * cost);
    if (n_l > 0 && n_r > 0) best = std::min(best, cost);
    if (rows[i][9] == "1") {
      ++chosen;
      chosen_cost = cost;
    }
  }
  EXPECT_EQ(chosen, 1);
  EXPECT_EQ(chosen_cost, best);
  // By path, and as JSON.
  Outcome j = run("sah " + kScene + " --accel bvh-sweep --path RL -o " + path("c.json"));
  ASSERT_EQ(j.code, 0) << j.err;
  EXPECT_NE(slurp(path("c.json")).find("\"candidates\""), std::string::npos);
}

TEST_F(BvhCli, CastsLikeBruteForceUnderEveryOption) {
  ASSERT_EQ(run("rays " + kScene + " --kind random --count 4000 --seed 5 -o " + path("r.rays")).code, 0);
  ASSERT_EQ(
      run("cast " + kScene + " --rays " + path("r.rays") + " --hits " + path("b.hits") + " --accel brute")
          .code,
      0);
  for (const char* opts :
       {"--accel bvh", "--accel bvh-sweep", "--accel bvh-median", "--accel bvh --bvh-order axis",
        "--accel bvh --bins 32 --bvh-leaf 4 --bvh-max-leaf 8 --ti 10 --tt 2 --max-depth 12"}) {
    Outcome c =
        run("cast " + kScene + " --rays " + path("r.rays") + " --hits " + path("k.hits") + " " + opts);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_EQ(slurp(path("k.hits")), slurp(path("b.hits"))) << opts;
  }
}

TEST_F(BvhCli, BadOptionsExitTwoWithOneLine) {
  const std::string out = " -o " + path("c.csv");
  expect_error(run("sah " + kScene + " --accel bvh --node 100000" + out), "--node 100000");
  expect_error(run("sah " + kScene + " --accel bvh --path LXR" + out), "--path");
  expect_error(run("sah " + kScene + " --accel bvh --bins 1" + out), "--bins");
  expect_error(run("sah " + kScene + " --accel bvh --bins 300" + out), "--bins");
  expect_error(run("sah " + kScene + " --accel bvh --ti -1" + out), "bvh: t_i");
  expect_error(run("bvh-stats " + kScene + " --bvh-leaf 0"), "--bvh-leaf");
  expect_error(run("bvh-stats " + kScene + " --bvh-leaf 8 --bvh-max-leaf 4"), "--bvh-max-leaf");
  expect_error(run("bvh-stats " + kScene + " --max-depth 65"), "--max-depth");
  expect_error(run("bvh-stats " + kScene + " --lines 0"), "--lines");
  expect_error(run("render " + kScene + " --accel bvh --bvh-order sideways -o " + path("a.png")),
               "--bvh-order");
  EXPECT_FALSE(fs::exists(path("c.csv")));
  EXPECT_FALSE(fs::exists(path("a.png")));
}

}  // namespace
