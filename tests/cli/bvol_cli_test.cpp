// `raystep bvol-report` and the bounding-volume kinds on the command line: the report's rows add up (one
// volume test per object per ray, a false-positive rate in [0, 1], no disagreement with brute force), the
// kinds compose with --accel lists, and bad names or options exit 2 with one line.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <vector>

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;
using namespace raystep::clitest;

class BvolCli : public CliTest {
 protected:
  BvolCli() : CliTest("raystep_bvol_cli_") {}
};

double num(const CsvRow& row, const std::string& key) {
  return std::stod(row.at(key));
}

TEST_F(BvolCli, ReportHasEveryKindOnEveryScene) {
  Outcome r = run("bvol-report " + scene("cornell.json") + " " + scene("spheres.json") +
                  " --size 16x12 --reps 1 -o " + path("rep"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<CsvRow> rows = read_csv(path("rep/bvol_report.csv"));
  ASSERT_EQ(rows.size(), 8u);
  const char* kinds[] = {"bvol", "bvol-sphere", "bvol-kdop", "bvol-obb"};
  for (size_t i = 0; i < rows.size(); ++i) {
    const CsvRow& row = rows[i];
    EXPECT_EQ(row.at("scene"), i < 4 ? "cornell.json" : "spheres.json");
    EXPECT_EQ(row.at("kind"), kinds[i % 4]);
    EXPECT_EQ(num(row, "rays"), 16 * 12);
    EXPECT_EQ(num(row, "volume_tests_per_ray"), num(row, "objects"));  // every volume once per ray
    EXPECT_LE(num(row, "entered_per_ray"), num(row, "volume_hits_per_ray"));
    EXPECT_LE(num(row, "false_positives_per_ray"), num(row, "entered_per_ray"));
    EXPECT_GE(num(row, "false_positive_rate"), 0.0);
    EXPECT_LE(num(row, "false_positive_rate"), 1.0);
    EXPECT_GT(num(row, "prim_tests_per_ray"), 0.0);
    EXPECT_EQ(row.at("disagreements"), "0") << row.at("kind");
  }
  const std::string md = slurp(path("rep/bvol_report.md"));
  EXPECT_NE(md.find("| cornell.json | bvol-kdop |"), std::string::npos) << md;
  EXPECT_EQ(r.out.substr(0, md.size()), md);  // the table on stdout too
}

TEST_F(BvolCli, KindsComposeWithAccelLists) {
  Outcome r =
      run("compare " + scene("cornell.json") +
          " --accel bvol,bvol-sphere,bvol-kdop,bvol-obb --rays 200 --size 8x8 --reps 1 -o " + path("cmp"));
  ASSERT_EQ(r.code, 0) << r.err;
  std::vector<CsvRow> rows = read_csv(path("cmp/report.csv"));
  ASSERT_EQ(rows.size(), 4u);
  for (const CsvRow& row : rows) EXPECT_EQ(row.at("disagreements"), "0") << row.at("structure");
  r = run("render " + scene("spheres.json") + " --accel bvol-sphere --size 8x6 -o " + path("s.png"));
  EXPECT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(path("s.png")));
}

TEST_F(BvolCli, BadKindsAndOptionsExit2WithOneLine) {
  expect_error(run("render " + scene("cornell.json") + " --accel bvol-cube -o " + path("x.png")),
               "--accel: unknown accelerator 'bvol-cube'", path("x.png"));
  expect_error(run("bvol-report " + path("missing.json") + " -o " + path("rep")), path("missing.json"),
               path("rep/bvol_report.csv"));
  expect_error(run("bvol-report " + scene("cornell.json") + " --reps 0 -o " + path("rep")),
               "bvol-report: --reps", path("rep/bvol_report.csv"));
  expect_error(run("bvol-report " + scene("cornell.json") + " --size 0x3 -o " + path("rep")), "",
               path("rep/bvol_report.csv"));
  expect_error(run("bvol-report " + scene("cornell.json") + " --bogus"), "");
}

}  // namespace
