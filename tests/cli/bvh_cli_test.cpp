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
  ASSERT_EQ(rows[0].size(), 11u);
  EXPECT_EQ(rows[0][0], "axis");
  EXPECT_EQ(rows[0][9], "chosen");
  EXPECT_EQ(rows[0][10], "kind");
  for (size_t i = 1; i < rows.size(); ++i) EXPECT_EQ(rows[i][10], "object");
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

namespace raystep_sbvh_cli {

using namespace raystep::clitest;

class SbvhCli : public CliTest {
 protected:
  SbvhCli() : CliTest("raystep_sbvh_cli_") {}
};

const std::string kCornell = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";

// The SBVH's curve lists spatial rows; a node split spatially has its chosen row among them, with more
// references on its two sides than the node holds (Cornell's node 5: the two triangles of one face of the
// tall box, whose boxes are the same).
TEST_F(SbvhCli, SahCurveListsSpatialCandidates) {
  Outcome r = run("sah " + kCornell + " --accel bvh-sbvh --node 5 -o " + path("c.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("spatial split"), std::string::npos) << r.out;
  std::vector<CsvRow> rows = read_csv(path("c.csv"));
  int spatial = 0, chosen = 0;
  for (CsvRow& row : rows) {
    spatial += row["kind"] == "spatial";
    if (row["chosen"] == "1") {
      ++chosen;
      EXPECT_EQ(row["kind"], "spatial");
      EXPECT_GT(std::stoi(row["n_left"]) + std::stoi(row["n_right"]), 2);
    }
  }
  EXPECT_EQ(chosen, 1);
  EXPECT_GT(spatial, 10);
}

// bvh-stats gives the quality metrics in text and as a CSV row: EPO, the histograms that count every leaf,
// the measured cost per ray; the SBVH has more references than primitives and a lower SAH cost.
TEST_F(SbvhCli, StatsGiveTheQualityMetrics) {
  std::map<std::string, CsvRow> q;
  for (const char* accel : {"bvh", "bvh-sbvh"}) {
    Outcome r = run("bvh-stats " + kCornell + " --accel " + accel + " --lines 2000 --rays 4096 --quality-csv " +
                    path(std::string(accel) + ".csv"));
    ASSERT_EQ(r.code, 0) << r.err;
    for (const char* key : {"EPO (end-point overlap", "leaves by primitive count:", "leaves by depth:",
                            "measured, ", "the SAH predicts"})
      EXPECT_NE(r.out.find(key), std::string::npos) << key << "\n" << r.out;
    std::vector<CsvRow> rows = read_csv(path(std::string(accel) + ".csv"));
    ASSERT_EQ(rows.size(), 1u);
    q[accel] = rows[0];
    CsvRow& row = rows[0];
    EXPECT_EQ(row["structure"], accel);
    uint64_t leaves = 0, by_depth = 0;
    std::stringstream a(row["leaf_prims"]), b(row["leaf_depth"]);
    for (std::string c; std::getline(a, c, ';');) leaves += std::stoull(c);
    for (std::string c; std::getline(b, c, ';');) by_depth += std::stoull(c);
    EXPECT_EQ(leaves, std::stoull(row["leaves"]));
    EXPECT_EQ(by_depth, std::stoull(row["leaves"]));
    EXPECT_GE(std::stod(row["epo"]), 0.0);
    EXPECT_NEAR(std::stod(row["epo"]), std::stod(row["epo_inner"]) + std::stod(row["epo_leaves"]), 1e-3);
    EXPECT_GT(std::stod(row["camera_tests_per_ray"]), 0.0);
    EXPECT_NEAR(std::stod(row["random_cost_per_ray"]),
                std::stod(row["random_nodes_per_ray"]) + 80.0 * std::stod(row["random_tests_per_ray"]),
                1e-3 * std::stod(row["random_cost_per_ray"]));
  }
  EXPECT_EQ(q["bvh"]["references"], q["bvh"]["primitives"]);
  EXPECT_GT(std::stoull(q["bvh-sbvh"]["references"]), std::stoull(q["bvh-sbvh"]["primitives"]));
  EXPECT_LT(std::stod(q["bvh-sbvh"]["sah_cost"]), std::stod(q["bvh"]["sah_cost"]));
}

// compare gives each BVH's SAH cost and EPO beside its measured cost per ray, and plots one against the other.
TEST_F(SbvhCli, CompareSetsPredictedBesideMeasured) {
  Outcome r = run("compare " + kCornell + " --accel kd,bvh,bvh-sbvh,bvh8,bvh8-sbvh --rays 2000 --size 32x32 "
                  "--reps 1 -o " + path("cmp"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<CsvRow> rows = read_csv(path("cmp/report.csv"));
  ASSERT_EQ(rows.size(), 5u);
  EXPECT_EQ(rows[0]["sah_cost"], "nan");  // the kd-tree: no BVH metrics
  for (size_t i = 1; i < rows.size(); ++i) {
    EXPECT_GT(std::stod(rows[i]["sah_cost"]), 0.0) << rows[i]["structure"];
    EXPECT_GE(std::stod(rows[i]["epo"]), 0.0) << rows[i]["structure"];
    EXPECT_EQ(rows[i]["disagreements"], "0") << rows[i]["structure"];
    EXPECT_GT(std::stod(rows[i]["random_cost_per_ray"]), 0.0);
  }
  EXPECT_NE(slurp(path("cmp/report.md")).find("SAH cost (predicted)"), std::string::npos);
  EXPECT_TRUE(fs::exists(path("cmp/predicted_vs_measured.gp")));
}

}  // namespace raystep_sbvh_cli
