// The general BSP tree on the command line: `--accel bsp` in cast (the same hits as brute force under its
// options), trace (a version 4 trace with planes that trace-info reads back) and compare (nodes and depth
// side by side with the kd-tree, no disagreement on the slanted scenes); bad BSP options exit 2 with one
// line. `raystep sah --accel bsp` writes a node's candidates by orientation, the chosen row the cheapest, the
// plane the one a trace of the same tree names; bad ids exit 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

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

TEST_F(BspCli, SahWritesTheCandidatesByOrientation) {
  Outcome r = run("sah " + kRotated + " --accel bsp --node 0 -o " + path("c.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = slurp(path("c.csv"));
  EXPECT_EQ(
      text.rfind("direction,name,source,prim,normal_x,normal_y,normal_z,offset,cell_min,cell_max,n_below,"
                 "n_above,area_below,area_above,area_node,cost,bounded,chosen\n",
                 0),
      0u);
  std::vector<CsvRow> rows = read_csv(path("c.csv"));
  ASSERT_GT(rows.size(), 13u);
  std::set<int> directions;
  int chosen = -1;
  double min_cost = 1e300;
  for (size_t i = 0; i < rows.size(); ++i) {
    const int d = std::stoi(rows[i]["direction"]);
    directions.insert(d);
    EXPECT_EQ(rows[i]["name"] == "own plane", d == -1);
    EXPECT_EQ(rows[i]["source"] == "primitive", d == -1);
    EXPECT_EQ(rows[i]["prim"] == "-1", d != -1);
    EXPECT_LT(std::stod(rows[i]["cell_min"]), std::stod(rows[i]["offset"]));
    EXPECT_LT(std::stod(rows[i]["offset"]), std::stod(rows[i]["cell_max"]));
    min_cost = std::min(min_cost, std::stod(rows[i]["cost"]));
    if (rows[i]["chosen"] == "1") {
      EXPECT_EQ(chosen, -1) << "two chosen rows";
      chosen = int(i);
    }
  }
  EXPECT_EQ(directions.size(), 14u) << "13 k-DOP directions and the own planes (--bsp-directions both)";
  ASSERT_GE(chosen, 0);
  EXPECT_EQ(std::stod(rows[size_t(chosen)]["cost"]), min_cost) << "the chosen row is the cheapest";
  EXPECT_NE(r.out.find("decision: split by the plane"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("<- chosen"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("x+y+z"), std::string::npos) << r.out;
  // The options reach the build: k-DOP directions alone give no own plane, autopartition only own planes.
  ASSERT_EQ(run("sah " + kRotated + " --accel bsp --bsp-directions kdop -o " + path("k.csv")).code, 0);
  for (CsvRow& row : read_csv(path("k.csv"))) EXPECT_NE(row["direction"], "-1");
  ASSERT_EQ(run("sah " + kRotated + " --accel bsp --bsp-directions autopartition -o " + path("a.csv")).code,
            0);
  for (CsvRow& row : read_csv(path("a.csv"))) EXPECT_EQ(row["direction"], "-1");
}

TEST_F(BspCli, SahNamesTheTracesPlanes) {
  // The planes of the inner nodes a traced ray meets are the chosen planes of `sah` for those ids.
  ASSERT_EQ(run("trace " + kTilted + " --accel bsp --pixel 160,120 -o " + path("t.json")).code, 0);
  nlohmann::json trace = nlohmann::json::parse(slurp(path("t.json")));
  int checked = 0;
  for (const auto& node : trace["geometry"]["nodes"]) {
    if (node["leaf"].get<bool>() || checked == 3) continue;
    const std::string id = std::to_string(node["id"].get<int>());
    Outcome r = run("sah " + kTilted + " --accel bsp --node " + id + " -o " + path("n.json"));
    ASSERT_EQ(r.code, 0) << r.err;
    nlohmann::json curve = nlohmann::json::parse(slurp(path("n.json")));
    ASSERT_EQ(curve["decision"], "split") << id;
    EXPECT_EQ(curve["split"]["normal"], node["normal"]) << id;
    EXPECT_EQ(curve["split"]["offset"], node["offset"]) << id;
    EXPECT_EQ(curve["depth"], node["depth"]) << id;
    int marked = 0;
    for (const auto& c : curve["candidates"]) marked += c["chosen"].get<bool>();
    EXPECT_EQ(marked, 1) << id;
    ++checked;
  }
  EXPECT_EQ(checked, 3);
  // --path L is node 1 (below the root's plane follows its parent).
  ASSERT_EQ(run("sah " + kTilted + " --accel bsp --path L -o " + path("l.csv")).code, 0);
  ASSERT_EQ(run("sah " + kTilted + " --accel bsp --node 1 -o " + path("1.csv")).code, 0);
  EXPECT_EQ(slurp(path("l.csv")), slurp(path("1.csv")));
}

TEST_F(BspCli, SahBadIdsExitTwoWithOneLine) {
  expect_error(run("sah " + kRotated + " --accel bsp --node 100000 -o " + path("c.csv")), "--node 100000",
               path("c.csv"));
  expect_error(run("sah " + kRotated + " --accel bsp --path LXR -o " + path("c.csv")), "--path",
               path("c.csv"));
  expect_error(
      run("sah " + kRotated + " --accel bsp --path " + std::string(70, 'R') + " -o " + path("c.csv")),
      "--path", path("c.csv"));
  expect_error(run("sah " + kRotated + " --accel bsp --bsp-directions sideways -o " + path("c.csv")),
               "--bsp-directions", path("c.csv"));
  expect_error(run("sah " + kRotated + " --accel bsp --node 0 -o " + path("c.txt")), path("c.txt"),
               path("c.txt"));
}

}  // namespace
