// The bounding-volume report window of raystep-gui (suite BvolReport): its bars are the rows core's report
// measured, one per kind in the report's order, and the rows are the command line's `raystep bvol-report`
// (the counts are deterministic: the same camera rays); a lesson step with `report: bvol` opens and runs it,
// the next step without it closes it. Each runs the real application in scripted mode under Xvfb.
#include <cmath>

#include "raystep/io/image_io.h"
#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

const std::string kCornell = kSourceDir + "/scenes/cornell.json";

std::string quote(const std::string& s) {
  return "'" + s + "'";
}

// The series point of kind index k (x = k + 1) of a quantity.
double bar(const json& series, const std::string& key, size_t k) {
  const json& pts = series[key];
  EXPECT_GT(pts.size(), k) << key;
  if (pts.size() <= k) return NAN;
  EXPECT_DOUBLE_EQ(pts[k][0].get<double>(), double(k + 1)) << key;
  return pts[k][1].get<double>();
}

TEST(BvolReport, BarsAreTheReportsRowsForEachKind) {
  const std::string png = kOut + "/bvol-report.png", state = kOut + "/bvol-report.json";
  std::remove(png.c_str());
  std::remove(state.c_str());
  GuiRun r = gui(quote(kCornell) + " --report bvol --screenshot-bvol " + quote(png) + " --dump-state " +
                     quote(state) + " --quit",
                 "bvol-report");
  ASSERT_EQ(r.code, 0) << r.err;
  const json s = readJson(state);
  ASSERT_TRUE(s.contains("bvol_report")) << s.dump();
  const json& b = s["bvol_report"];
  EXPECT_EQ(b["state"], "done");
  EXPECT_EQ(b["visible"], true);
  const json& rows = b["rows"];
  ASSERT_EQ(rows.size(), 4u);
  const char* kinds[] = {"bvol", "bvol-sphere", "bvol-kdop", "bvol-obb"};
  for (size_t k = 0; k < 4; ++k) {
    const json& row = rows[k];
    EXPECT_EQ(row["kind"], kinds[k]);
    EXPECT_EQ(row["objects"], 7);                                      // five walls, the box and the sphere
    EXPECT_DOUBLE_EQ(row["volume_tests_per_ray"].get<double>(), 7.0);  // every volume on every ray
    EXPECT_EQ(row["disagreements"], 0);
    // Each bar is its row's number (float columns).
    const double tol = 1e-5;
    EXPECT_NEAR(bar(b["series"], "entered_per_ray", k), row["entered_per_ray"].get<double>(), tol);
    EXPECT_NEAR(bar(b["series"], "false_positives_per_ray", k), row["false_positives_per_ray"].get<double>(),
                tol);
    EXPECT_NEAR(bar(b["series"], "false_positive_percent", k),
                100.0 * row["false_positive_rate"].get<double>(), 1e-3);
    EXPECT_NEAR(bar(b["series"], "prim_tests_per_ray", k), row["prim_tests_per_ray"].get<double>(), tol);
    EXPECT_NEAR(bar(b["series"], "ns_per_ray", k), row["ns_per_ray"].get<double>(),
                1e-5 * row["ns_per_ray"].get<double>());
  }
  EXPECT_EQ(b["table_rows"], 4);
  // The lecture's point on flat walls: the 14-DOP is entered in vain least, the sphere most.
  EXPECT_LE(rows[2]["false_positive_rate"].get<double>(), rows[0]["false_positive_rate"].get<double>());
  EXPECT_GT(rows[1]["false_positive_rate"].get<double>(), rows[0]["false_positive_rate"].get<double>());
  // The screenshot shows the bars: the blue of "entered" and the vermillion of "in vain".
  Rgb8Image img = read_png_rgb8(png);
  EXPECT_GT(countColor(img, json::array({0, 114, 178}), 0, 0, img.width - 1, img.height - 1, 10), 400);
  EXPECT_GT(countColor(img, json::array({213, 94, 0}), 0, 0, img.width - 1, img.height - 1, 10), 400);

#ifdef RAYSTEP_CLI_EXE
  // The same measurement from the command line: the same counts per kind.
  const std::string dir = kOut + "/bvol-report-cli";
  const std::string cmd = "'" + std::string(RAYSTEP_CLI_EXE) + "' bvol-report " + quote(kCornell) +
                          " --reps 1 -o " + quote(dir) + " > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0);
  const std::string csv = slurp(dir + "/bvol_report.csv");
  for (size_t k = 0; k < 4; ++k) {
    const std::string kind = std::string(",") + kinds[k] + ",";
    const size_t at = csv.find(kind);
    ASSERT_NE(at, std::string::npos) << kinds[k];
    std::string line = csv.substr(at, csv.find('\n', at) - at);
    char entered[32];
    std::snprintf(entered, sizeof entered, "%.4f", rows[k]["entered_per_ray"].get<double>());
    // The CSV prints its numbers with more digits than four; the first four decimals agree.
    EXPECT_NE(line.find(std::string(entered).substr(0, 5)), std::string::npos) << line << " vs " << entered;
  }
#endif
}

TEST(BvolReport, LessonStepOpensAndTheNextClosesIt) {
  const std::string lesson = kOut + "/bvol-lesson.md";
  {
    std::ofstream out(lesson);
    out << "# Kinds\n\n## Report\n\n```raystep\nscene: " << kCornell
        << "\nreport: bvol\nshow: report\n```\n\n## Picture\n\n```raystep\nshow: picture\n```\n";
  }
  const std::string s1 = kOut + "/bvol-lesson-1.json", s2 = kOut + "/bvol-lesson-2.json";
  GuiRun r = gui("--lesson " + quote(lesson) + " --lesson-step 1 --dump-state " + quote(s1) + " --quit",
                 "bvol-lesson-1");
  ASSERT_EQ(r.code, 0) << r.err;
  json a = readJson(s1);
  ASSERT_TRUE(a.contains("bvol_report")) << a.dump();
  EXPECT_EQ(a["bvol_report"]["state"], "done");
  EXPECT_EQ(a["bvol_report"]["visible"], true);
  EXPECT_EQ(a["bvol_report"]["rows"].size(), 4u);
  // The step after: `report` is not carried over, so the window is closed (or never made).
  r = gui("--lesson " + quote(lesson) + " --lesson-walk 1,2 --dump-state " + quote(s2) + " --quit",
          "bvol-lesson-2");
  ASSERT_EQ(r.code, 0) << r.err;
  json b = readJson(s2);
  if (b.contains("bvol_report")) EXPECT_EQ(b["bvol_report"]["visible"], false);
  // The handout's figure of the report step is the report window.
  const std::string handout = kOut + "/bvol-handout";
  r = gui("--lesson " + quote(lesson) + " --export-handout " + quote(handout) + " --quit", "bvol-handout");
  ASSERT_EQ(r.code, 0) << r.err;
  Rgb8Image img = read_png_rgb8(handout + "/step-1.png");
  EXPECT_GT(countColor(img, json::array({213, 94, 0}), 0, 0, img.width - 1, img.height - 1, 10), 400);
  EXPECT_NE(slurp(handout + "/index.html").find("the report window"), std::string::npos);
}

}  // namespace
}  // namespace raystep::viztest
