// `--accel octree` on the commands that take a structure: cast gives brute force's hits under its options,
// trace records an octree walk that reads back, render and compare accept it, and bad --octree-leaf and
// --max-depth values exit 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace raystep::clitest;

class OctreeCli : public CliTest {
 protected:
  OctreeCli() : CliTest("raystep_octree_cli_") {}
};

const std::string kScene = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/torus_knot.json";

TEST_F(OctreeCli, CastsLikeBruteForceUnderEveryOption) {
  ASSERT_EQ(run("rays " + kScene + " --kind random --count 3000 --seed 5 -o " + path("r.rays")).code, 0);
  ASSERT_EQ(
      run("cast " + kScene + " --rays " + path("r.rays") + " --hits " + path("b.hits") + " --accel brute")
          .code,
      0);
  for (const char* opts :
       {"--accel octree", "--accel octree --octree-leaf 1", "--accel octree --octree-leaf 64",
        "--accel octree --max-depth 3", "--accel octree --octree-leaf 2 --max-depth 20"}) {
    Outcome c =
        run("cast " + kScene + " --rays " + path("r.rays") + " --hits " + path("o.hits") + " " + opts);
    ASSERT_EQ(c.code, 0) << c.err;
    EXPECT_NE(c.out.find("structure: octree"), std::string::npos) << c.out;
    EXPECT_EQ(slurp(path("o.hits")), slurp(path("b.hits"))) << opts;
  }
}

TEST_F(OctreeCli, TraceRecordsTheOctreeWalk) {
  Outcome t = run("trace " + kScene + " --accel octree --pixel 40,30 --secondary -o " + path("t.json"));
  ASSERT_EQ(t.code, 0) << t.err;
  const std::string json = slurp(path("t.json"));
  EXPECT_NE(json.find("\"kind\":\"octree\""), std::string::npos) << json.substr(0, 400);
  EXPECT_NE(json.find("\"children\""), std::string::npos);
  EXPECT_NE(json.find("\"type\":\"leaf\""), std::string::npos);
  // The written trace reads back (trace-info validates it).
  Outcome s = run("trace-info " + path("t.json"));
  EXPECT_EQ(s.code, 0) << s.err;
  EXPECT_NE(s.out.find("octree"), std::string::npos) << s.out;
}

TEST_F(OctreeCli, RenderHeatmapAndCompareAcceptIt) {
  Outcome h = run("render " + kScene + " --accel octree --size 32x24 --heatmap nodes -o " + path("h.png"));
  ASSERT_EQ(h.code, 0) << h.err;
  EXPECT_TRUE(fs::exists(path("h.png")));
  Outcome c =
      run("compare " + kScene + " --accel grid,octree --rays 2000 --size 16x16 --reps 1 -o " + path("cmp"));
  ASSERT_EQ(c.code, 0) << c.err;
  EXPECT_NE(slurp(path("cmp/report.csv")).find("octree"), std::string::npos);
}

TEST_F(OctreeCli, BadOptionsExitTwoWithOneLine) {
  const std::string cast = "cast " + kScene + " --rays " + path("r.rays") + " --hits " + path("o.hits");
  ASSERT_EQ(run("rays " + kScene + " --kind random --count 10 -o " + path("r.rays")).code, 0);
  expect_error(run(cast + " --accel octree --octree-leaf 0"), "--octree-leaf");
  expect_error(run(cast + " --accel octree --octree-leaf -5"), "--octree-leaf");
  expect_error(run(cast + " --accel octree --octree-leaf 99999999"), "--octree-leaf");
  expect_error(run(cast + " --accel octree --max-depth 21"), "--max-depth");
  expect_error(run(cast + " --accel octree --max-depth -1"), "--max-depth");
  expect_error(run("trace " + kScene + " --accel octree --octree-leaf 0 --pixel 1,1 -o " + path("t.json")),
               "--octree-leaf");
  Outcome word = run(cast + " --accel octree --octree-leaf many");
  EXPECT_EQ(word.code, 2) << word.err;
  EXPECT_FALSE(fs::exists(path("o.hits")));
  EXPECT_FALSE(fs::exists(path("t.json")));
}

}  // namespace
