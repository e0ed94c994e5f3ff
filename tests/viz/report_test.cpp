// The report windows of raystep-gui (suite Report): the anti-aliasing report's chart gets one point per row
// the report produced, in order and as the rows came; Cancel stops a report and a sweep; the sweep's slider
// rebuilds the main window's grid at the chosen density, as max(nx, ny, nz) = round(d * cbrt(n)) predicts.
// Each runs the real application in scripted mode under Xvfb, on small renders.
#include <cmath>
#include <set>

#include "raystep/io/image_io.h"
#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

const std::string kAliasing = kSourceDir + "/scenes/aliasing.json";
const std::string kCornell = kSourceDir + "/scenes/cornell.json";

json runReport(const std::string& args, const std::string& tag, GuiRun* run = nullptr) {
  const std::string state = kOut + "/" + tag + ".json";
  std::remove(state.c_str());
  GuiRun r = gui(args + " --dump-state '" + state + "' --quit", tag);
  EXPECT_EQ(r.code, 0) << r.err;
  if (run) *run = r;
  return r.code == 0 ? readJson(state) : json::object();
}

int maxOf(const json& res) {
  return std::max({res[0].get<int>(), res[1].get<int>(), res[2].get<int>()});
}

TEST(Report, AaChartHasOnePointPerRowInOrder) {
  const std::string png = kOut + "/report-aa-small.png";
  json s =
      runReport("'" + kAliasing +
                    "' --report aa --report-methods none,regular:2,jitter:2,random:4 --report-size 32x24 "
                    "--report-seeds 2 --screenshot-report '" +
                    png + "'",
                "report-aa-small");
  ASSERT_TRUE(s.contains("aa_report")) << s.dump();
  const json& a = s["aa_report"];
  EXPECT_EQ(a["state"], "done");
  EXPECT_EQ(a["reference"]["kind"], "exact");  // flat polygons seen orthographically
  const json& rows = a["rows"];
  ASSERT_EQ(rows.size(), 4u);
  const char* specs[] = {"none", "regular:2", "jitter:2", "random:4"};
  const char* methods[] = {"none", "regular", "jitter", "random"};
  const json& points = a["points"];
  ASSERT_EQ(points.size(), rows.size());
  for (size_t i = 0; i < rows.size(); ++i) {
    EXPECT_EQ(rows[i]["spec"], specs[i]);
    EXPECT_EQ(rows[i]["method"], methods[i]);
    // The point of row i: its family's series, at (rays per pixel, RMSE).
    EXPECT_EQ(points[i]["series"], methods[i]);
    EXPECT_DOUBLE_EQ(points[i]["x"].get<double>(), rows[i]["rays_per_pixel"].get<double>());
    EXPECT_DOUBLE_EQ(points[i]["y"].get<double>(), rows[i]["rmse"].get<double>());
    EXPECT_GT(rows[i]["rmse"].get<double>(), 0.0);
    // And the series as plotted holds it (float columns).
    bool found = false;
    for (const json& p : a["series"][methods[i]])
      found = found || (std::abs(p[0].get<double>() - points[i]["x"].get<double>()) <=
                            1e-5 * points[i]["x"].get<double>() &&
                        std::abs(p[1].get<double>() - points[i]["y"].get<double>()) <=
                            1e-5 * points[i]["y"].get<double>());
    EXPECT_TRUE(found) << "row " << i << " not in series " << methods[i];
  }
  EXPECT_DOUBLE_EQ(rows[0]["rays_per_pixel"].get<double>(), 1.0);
  EXPECT_DOUBLE_EQ(rows[1]["rays_per_pixel"].get<double>(), 4.0);
  // The chart filled in as the rows came: one more point after each.
  EXPECT_EQ(a["points_after_each_row"], json::parse("[1, 2, 3, 4]"));
  EXPECT_EQ(a["table_rows"], 4);
  EXPECT_EQ(a["log_axes"], json::parse("[true, true]"));
  EXPECT_DOUBLE_EQ(a["progress"].get<double>(), 1.0);
  // The screenshot shows each family's colour (markers and lines), and the theory lines are drawn.
  EXPECT_TRUE(a["series"].contains("theory -1/2"));
  EXPECT_TRUE(a["series"].contains("theory -3/4"));
  Rgb8Image img = read_png_rgb8(png);
  for (const char* f : {"regular", "jitter", "random", "none"})
    EXPECT_GT(countColor(img, a["colors"][f], 0, 0, img.width - 1, img.height - 1, 12), 20) << f;

#ifdef RAYSTEP_CLI_EXE
  // The same report from the command line: the same methods in the same order, the same errors (seeded).
  const std::string dir = kOut + "/report-aa-small-cli";
  const std::string cmd = std::string("'") + RAYSTEP_CLI_EXE + "' aa-report '" + kAliasing +
                          "' --methods none,regular:2,jitter:2,random:4 --size 32x24 --seeds 2 -o '" + dir +
                          "' > /dev/null 2>&1";
  ASSERT_EQ(std::system(cmd.c_str()), 0) << cmd;
  std::istringstream csv(slurp(dir + "/report.csv"));
  std::string line;
  std::getline(csv, line);
  std::vector<std::string> header;
  for (std::stringstream h(line); std::getline(h, line, ',');) header.push_back(line);
  const size_t rmseCol = size_t(std::find(header.begin(), header.end(), "rmse") - header.begin());
  const size_t specCol = size_t(std::find(header.begin(), header.end(), "spec") - header.begin());
  ASSERT_LT(rmseCol, header.size());
  size_t i = 0;
  for (; std::getline(csv, line) && i < rows.size(); ++i) {
    std::vector<std::string> cells;
    for (std::stringstream c(line); std::getline(c, line, ',');) cells.push_back(line);
    ASSERT_GT(cells.size(), rmseCol);
    EXPECT_EQ(cells[specCol], rows[i]["spec"].get<std::string>());
    EXPECT_NEAR(std::stod(cells[rmseCol]), rows[i]["rmse"].get<double>(),
                1e-8 * rows[i]["rmse"].get<double>())
        << rows[i]["spec"];
  }
  EXPECT_EQ(i, rows.size());
#endif
}

TEST(Report, CancelStopsTheReport) {
  json s = runReport("'" + kAliasing +
                         "' --report aa --report-methods none,jitter:2,jitter:4,jitter:8,random:64 "
                         "--report-size 32x24 --report-seeds 3 --report-cancel-after 1",
                     "report-aa-cancel");
  ASSERT_TRUE(s.contains("aa_report"));
  const json& a = s["aa_report"];
  EXPECT_EQ(a["state"], "cancelled");
  // Cancelled right after the first row: the report stops after the render under way, and leaves the method
  // it cut short out (its seeds would not compare with the others').
  ASSERT_EQ(a["rows"].size(), 1u);
  EXPECT_EQ(a["rows"][0]["spec"], "none");
  EXPECT_EQ(a["points"].size(), a["rows"].size());

  json g =
      runReport("'" + kCornell + "' --report grid-sweep --sweep-densities 0.5,1,2,4 --report-cancel-after 2",
                "report-sweep-cancel");
  ASSERT_TRUE(g.contains("grid_sweep"));
  EXPECT_EQ(g["grid_sweep"]["state"], "cancelled");
  EXPECT_EQ(g["grid_sweep"]["rows"].size(), 2u);  // the sweep stops after the current density
}

TEST(Report, SweepSliderRebuildsTheGridAtTheChosenDensity) {
  // Cornell: n = 23 primitives, cbrt(n) = 2.84; the box is a cube, so nx = ny = nz.
  json s = runReport("'" + kCornell +
                         "' --grid-density 3 --report grid-sweep --sweep-densities 1,2,4 "
                         "--sweep-choose 2 --screenshot-sweep '" +
                         kOut + "/report-sweep.png'",
                     "report-sweep-2");
  ASSERT_TRUE(s.contains("grid_sweep") && s.contains("grid")) << s.dump();
  const json& g = s["grid_sweep"];
  EXPECT_EQ(g["state"], "done");
  ASSERT_EQ(g["rows"].size(), 3u);
  const double n = s["grid"]["primitives"].get<double>();
  EXPECT_FLOAT_EQ(s["grid"]["density"].get<float>(), 2.f);
  EXPECT_FALSE(s["grid"]["explicit_resolution"].get<bool>());
  EXPECT_EQ(maxOf(s["grid"]["resolution"]), int(std::lround(2.0 * std::cbrt(n))));
  EXPECT_EQ(s["grid"]["resolution"], g["rows"][1]["resolution"]);  // the grid the sweep measured at d = 2
  // One point per density in each chart, with the sweep's values.
  ASSERT_EQ(g["series"]["cells_per_ray"].size(), 3u);
  ASSERT_EQ(g["series"]["tests_per_ray"].size(), 3u);
  for (size_t i = 0; i < 3; ++i) {
    EXPECT_DOUBLE_EQ(g["series"]["cells_per_ray"][i][0].get<double>(), g["rows"][i]["density"].get<double>());
    EXPECT_NEAR(g["series"]["cells_per_ray"][i][1].get<double>(), g["rows"][i]["cells_per_ray"].get<double>(),
                1e-5 * g["rows"][i]["cells_per_ray"].get<double>());
    EXPECT_NEAR(g["series"]["tests_per_ray"][i][1].get<double>(), g["rows"][i]["tests_per_ray"].get<double>(),
                1e-5 * g["rows"][i]["tests_per_ray"].get<double>());
  }
  // The walk's trade-off: a finer grid, more cells per ray, fewer tests.
  EXPECT_LT(g["rows"][0]["cells_per_ray"].get<double>(), g["rows"][2]["cells_per_ray"].get<double>());
  EXPECT_GT(g["rows"][0]["tests_per_ray"].get<double>(), g["rows"][2]["tests_per_ray"].get<double>());
  EXPECT_FLOAT_EQ(g["marker_density"].get<float>(), 2.f);
  EXPECT_EQ(g["series"]["marker0"][0][0].get<double>(), 2.0);  // the charts mark d = 2

  // Between measured densities: the slider goes there and the grid follows the rule.
  json t = runReport("'" + kCornell + "' --report grid-sweep --sweep-densities 1,2,4 --sweep-choose 3",
                     "report-sweep-3");
  ASSERT_TRUE(t.contains("grid"));
  EXPECT_FLOAT_EQ(t["grid"]["density"].get<float>(), 3.f);
  const int expected = int(std::lround(3.0 * std::cbrt(n)));
  EXPECT_EQ(maxOf(t["grid"]["resolution"]), expected);
  EXPECT_NE(expected, maxOf(s["grid"]["resolution"]));
  EXPECT_GT(t["grid_sweep"]["slider"]["value"].get<int>(), g["slider"]["value"].get<int>());
}

TEST(Report, BadReportOptionsExit2) {
  GuiRun r = gui("'" + kAliasing + "' --report pie --quit", "report-bad-kind");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("error: --report 'pie'"), std::string::npos) << r.err;
  r = gui("'" + kAliasing + "' --report aa --report-methods regular:2,bogus:3 --quit", "report-bad-methods");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("error: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("bogus"), std::string::npos) << r.err;
  r = gui("'" + kCornell + "' --report aa --report-reference exact --report-size 16x16 --quit",
          "report-bad-reference");  // a pinhole camera: no exact coverage
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("error: --report aa: no exact reference"), std::string::npos) << r.err;
  r = gui("'" + kCornell + "' --sweep-choose 2 --quit", "report-bad-choose");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--sweep-choose"), std::string::npos) << r.err;
}

}  // namespace
}  // namespace raystep::viztest
