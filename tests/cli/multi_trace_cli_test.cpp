// `raystep trace --accel A,B,...`: one multi-walk trace (version 5) whose walks equal the single traces,
// trace-info's table of each walk's cost along t, the CSV with its walk column, the single form unchanged,
// and bad lists (unknown, twice, a structure that records no events, more than six) exit 2 with one line.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

#include "cli_test_util.h"

namespace {

using namespace raystep::clitest;
using nlohmann::json;

class MultiTraceCli : public CliTest {
 protected:
  MultiTraceCli() : CliTest("raystep_multi_trace_cli_") {}
};

const std::string kScene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/torus_knot.json";
const char* const kFive[] = {"grid", "kd", "bvh", "octree", "bsp"};

TEST_F(MultiTraceCli, OneFileWhoseWalksAreTheSingleTraces) {
  Outcome m = run("trace " + kScene + " --accel grid,kd,bvh,octree,bsp --pixel 40,30 -o " + path("m.json"));
  ASSERT_EQ(m.code, 0) << m.err;
  const json doc = json::parse(slurp(path("m.json")));
  EXPECT_EQ(doc["version"], 5);
  ASSERT_EQ(doc["walks"].size(), 5u);
  for (int i = 0; i < 5; ++i) {
    Outcome s = run("trace " + kScene + " --accel " + kFive[i] + " --pixel 40,30 -o " + path("s.json"));
    ASSERT_EQ(s.code, 0) << s.err;
    const json single = json::parse(slurp(path("s.json")));
    EXPECT_EQ(single["version"], 4);
    EXPECT_EQ(single["scene"], doc["scene"]);
    for (const char* key : {"structure", "rays", "geometry"})
      EXPECT_EQ(single[key], doc["walks"][i][key]) << kFive[i] << " " << key;
  }
  // trace-info validates it and prints the table: a row per structure with its cost at the hit.
  Outcome info = run("trace-info " + path("m.json"));
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("version 5 (5 walks)"), std::string::npos) << info.out;
  for (const char* name : kFive)
    EXPECT_NE(info.out.find("\n  " + std::string(name) + " "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("t="), std::string::npos) << info.out;
  EXPECT_NE(info.out.find('*'), std::string::npos) << info.out;  // the cheapest is marked
}

TEST_F(MultiTraceCli, CsvHasAWalkColumnAndTheSingleFormIsUnchanged) {
  Outcome m =
      run("trace " + kScene + " --accel kd,octree --ray 0,0,-8,0.05,0.02,1 --format csv -o " + path("m.csv"));
  ASSERT_EQ(m.code, 0) << m.err;
  const std::vector<CsvRow> rows = read_csv(path("m.csv"));
  ASSERT_FALSE(rows.empty());
  size_t walk1 = 0;
  for (const CsvRow& r : rows) walk1 += r.at("walk") == "1";
  Outcome s =
      run("trace " + kScene + " --accel octree --ray 0,0,-8,0.05,0.02,1 --format csv -o " + path("s.csv"));
  ASSERT_EQ(s.code, 0) << s.err;
  const std::vector<CsvRow> single = read_csv(path("s.csv"));
  EXPECT_EQ(walk1, single.size());
  EXPECT_EQ(slurp(path("s.csv")).rfind("ray,seq,type,", 0), 0u);
  // A single structure's trace is still version 4 and trace-info prints it as before.
  ASSERT_EQ(run("trace " + kScene + " --accel kd --pixel 3,4 -o " + path("k.json")).code, 0);
  EXPECT_NE(slurp(path("k.json")).find("\"version\": 4"), std::string::npos);
  Outcome info = run("trace-info " + path("k.json"));
  EXPECT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("valid raystep trace, version 4\ntrace: 1 ray(s), structure kd"), std::string::npos)
      << info.out;
}

TEST_F(MultiTraceCli, BadListsExit2WithOneLine) {
  const std::string tail = " --pixel 1,1 -o " + path("m.json");
  expect_error(run("trace " + kScene + " --accel grid,kdd" + tail),
               "trace: --accel 'grid,kdd': unknown structure 'kdd'");
  expect_error(run("trace " + kScene + " --accel grid,kd,grid" + tail),
               "trace: --accel 'grid,kd,grid': grid is listed twice");
  expect_error(run("trace " + kScene + " --accel grid,brute" + tail),
               "trace: --accel 'grid,brute': brute records no events");
  expect_error(run("trace " + kScene + " --accel kd,bvol-sphere" + tail),
               "trace: --accel 'kd,bvol-sphere': bvol-sphere records no events");
  expect_error(run("trace " + kScene + " --accel grid,kd,kd-median,bvh,bvh4,bvh8,octree" + tail),
               "trace: --accel 'grid,kd,kd-median,bvh,bvh4,bvh8,octree': 7 structures, at most 6");
  expect_error(run("trace " + kScene + " --accel grid," + tail), "trace: --accel 'grid,': an empty name");
  expect_error(run("trace " + kScene + " --accel grid,kd --aa 2x2" + tail),
               "trace: --aa records one structure");
  EXPECT_FALSE(std::filesystem::exists(path("m.json")));
  // A damaged multi-walk file: one line naming the path.
  ASSERT_EQ(run("trace " + kScene + " --accel grid,kd" + tail).code, 0);
  json doc = json::parse(slurp(path("m.json")));
  doc["walks"][1]["rays"][0]["events"][0]["type"] = "teleport";
  {
    std::ofstream out(path("bad.json"));
    out << doc.dump(1);
  }
  expect_error(run("trace-info " + path("bad.json")), path("bad.json"));
  EXPECT_NE(run("trace-info " + path("bad.json")).err.find("walks[1].rays[0].events[0].type"),
            std::string::npos);
}

}  // namespace
