// `raystep aa-report` end to end: the folder it writes (CSV, Markdown, PFM images, plots) agrees with itself,
// and bad method lists, scenes, references and sizes exit 2 with one line and leave nothing behind.
#include <gtest/gtest.h>

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <cmath>
#include <csignal>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <map>
#include <sstream>
#include <string>
#include <vector>

#include "raystep/io/image_io.h"
#include "raystep/render/reference.h"

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;

using namespace raystep::clitest;

class AaReportCli : public CliTest {
 protected:
  AaReportCli() : CliTest("raystep_aa_report_") {}

  // `raystep aa-report ARGS`.
  Outcome run(const std::string& args) const { return CliTest::run("aa-report " + args); }

  // Nothing in the test folder but what the test put there: no report, no temporary folder.
  void expect_no_report() const {
    for (const auto& entry : fs::directory_iterator(dir_))
      EXPECT_EQ(entry.path().filename().string().find("report"), std::string::npos) << entry.path();
  }
};

std::vector<std::string> split_images(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ';')) out.push_back(item);
  return out;
}

bool gnuplot_installed() {
  return std::system("gnuplot -e 'exit' >/dev/null 2>&1") == 0;
}

// The acceptance test: each row's RMSE recomputed from the PFM images the report wrote equals the CSV's.
TEST_F(AaReportCli, RmseRecomputedFromTheImagesMatchesTheCsv) {
  const std::string out = path("report");
  const Outcome r =
      run(scene("aliasing.json") +
          " --methods none,regular:2,regular:3,jitter:2,jitter:3,random:4,adaptive:0.1:2 --seeds 3"
          " --size 32x24 --threads 1 -o " +
          out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("reference exact"), std::string::npos) << r.out;
  const raystep::Image reference = raystep::read_pfm(out + "/images/reference.pfm");
  EXPECT_EQ(reference.width, 32);
  const auto rows = read_csv(out + "/report.csv");
  ASSERT_EQ(rows.size(), 7u);
  for (const auto& row : rows) {
    const std::vector<std::string> images = split_images(row.at("images"));
    const int seeds = std::stoi(row.at("seeds"));
    const bool random = row.at("method") == "jitter" || row.at("method") == "random";
    EXPECT_EQ(seeds, random ? 3 : 1) << row.at("spec");
    ASSERT_EQ(images.size(), size_t(seeds)) << row.at("spec");
    double sum = 0.0, lo = INFINITY, hi = 0.0, max_error = 0.0;
    for (const std::string& image : images) {
      const raystep::Image picture = raystep::read_pfm(out + "/" + image);
      const double e = raystep::rmse(picture, reference);
      sum += e;
      lo = std::min(lo, e);
      hi = std::max(hi, e);
      max_error += raystep::max_abs_error(picture, reference);
    }
    const double mean = sum / seeds;
    EXPECT_NEAR(std::stod(row.at("rmse")), mean, 1e-7 * mean) << row.at("spec");
    EXPECT_NEAR(std::stod(row.at("rmse_min")), lo, 1e-7 * lo) << row.at("spec");
    EXPECT_NEAR(std::stod(row.at("rmse_max")), hi, 1e-7 * hi) << row.at("spec");
    EXPECT_NEAR(std::stod(row.at("max_error")), max_error / seeds, 1e-6) << row.at("spec");
    EXPECT_GT(mean, 0.0);
    if (random) EXPECT_LT(lo, hi) << row.at("spec");
    EXPECT_EQ(std::stoull(row.at("rays_total")),
              std::stoull(row.at("rays_primary")));  // no lights, no mirrors
  }
  EXPECT_EQ(rows[1].at("samples_per_pixel"), "4");
  EXPECT_EQ(rows[1].at("rays_primary"), std::to_string(4 * 32 * 24));

  const std::string md = slurp(out + "/report.md");
  EXPECT_NE(md.find("| jitter | jitter:3 |"), std::string::npos);
  EXPECT_NE(md.find("**exact**"), std::string::npos);
  EXPECT_NE(md.find("| regular | "), std::string::npos);  // a slope row
  EXPECT_NE(md.find("Adaptive sampling against jitter:4"), std::string::npos);
  for (const char* plot : {"error_vs_rays", "error_vs_time"}) {
    EXPECT_TRUE(fs::exists(out + "/" + plot + ".gp")) << plot;
    if (gnuplot_installed()) EXPECT_GT(fs::file_size(out + "/" + plot + ".png"), 1000u) << plot;
  }
  // Only the report folder is left: no temporary folder beside it.
  int entries = 0;
  for (const auto& entry : fs::directory_iterator(dir_)) entries += entry.path().filename() != "report";
  EXPECT_EQ(entries, 0);
}

TEST_F(AaReportCli, ReplacesAnExistingFolderWhole) {
  const std::string out = path("report");
  fs::create_directories(out + "/images");
  std::ofstream(out + "/stale.txt") << "old";
  const Outcome r = run(scene("coverage.json") + " --methods none,jitter:2 --seeds 2 --size 16x12 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(out + "/stale.txt"));
  EXPECT_TRUE(fs::exists(out + "/report.csv"));
  EXPECT_TRUE(fs::exists(out + "/images/jitter-2-seed2.pfm"));
}

// A scene without an exact reference: auto falls back to jitter:16 and states its own error.
TEST_F(AaReportCli, StratifiedReferenceStatesItsOwnError) {
  const std::string out = path("report");
  const Outcome r = run(scene("spheres.json") + " --methods none,jitter:2 --seeds 2 --size 16x12 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string md = slurp(out + "/report.md");
  EXPECT_NE(md.find("**jitter:16**"), std::string::npos) << md;
  EXPECT_NE(md.find("own RMSE is estimated at"), std::string::npos);
  EXPECT_NE(r.out.find("its own RMSE about"), std::string::npos) << r.out;
}

TEST_F(AaReportCli, BadInputExitsTwoWithOneLine) {
  const std::string a = scene("aliasing.json"), out = " -o " + path("report");
  expect_error(run(a + " --methods jitter:0" + out), "--methods: bad anti-aliasing 'jitter:0'");
  expect_error(run(a + " --methods none,,jitter:2" + out), "--methods: bad anti-aliasing ''");
  expect_error(run(a + " --methods none,bogus" + out), "--methods: bad anti-aliasing 'bogus'");
  expect_error(run(a + " --methods random:99999" + out), "--methods: ");
  expect_error(run(a + " --reference bogus" + out), "--reference 'bogus'");
  expect_error(run(a + " --reference jitter:0" + out), "--reference 'jitter:0'");
  expect_error(run(scene("cornell.json") + " --reference exact" + out),
               "--reference exact: the camera is a pinhole");
  expect_error(run(a + " --size 0x4" + out), "--size '0x4'");
  expect_error(run(a + " --size big" + out), "--size 'big'");
  expect_error(run(a + " --seeds 0" + out), "--seeds");
  expect_error(run(a + " --threads -1" + out), "--threads");
  expect_error(run(path("missing.json") + out), path("missing.json"));
  std::ofstream(path("broken.json")) << "{ \"objects\": [ }";
  expect_error(run(path("broken.json") + out), path("broken.json"));
  expect_error(run(a + " -o " + path("no/such/folder/report")), path("no/such/folder/report"));
  expect_no_report();
}

}  // namespace

namespace raystep::clitest {
namespace {

// Starts `raystep ARGS...` with no stdin, stdout or stderr, waits until `temp_prefix` names an entry of the
// folder (its temporary output folder), lets it work a moment, sends Ctrl-C's SIGINT and returns the wait
// status.
int interrupt_when_started(const fs::path& dir, const std::string& temp_prefix, std::vector<std::string> args) {
  std::vector<char*> argv;
  argv.push_back(const_cast<char*>(RAYSTEP_EXE));
  for (std::string& a : args) argv.push_back(a.data());
  argv.push_back(nullptr);
  const pid_t child = ::fork();
  if (child == 0) {
    const int null = ::open("/dev/null", O_RDWR);
    ::dup2(null, 0);
    ::dup2(null, 1);
    ::dup2(null, 2);
    ::execv(RAYSTEP_EXE, argv.data());
    ::_exit(127);
  }
  bool started = false;
  for (int i = 0; i < 3000 && !started; ++i) {  // up to 30 s on a slow machine
    for (const auto& e : fs::directory_iterator(dir))
      started = started || e.path().filename().string().rfind(temp_prefix, 0) == 0;
    if (!started) ::usleep(10000);
  }
  EXPECT_TRUE(started) << "no " << temp_prefix << "* appeared";
  ::usleep(300000);
  ::kill(child, SIGINT);
  int status = 0;
  EXPECT_EQ(::waitpid(child, &status, 0), child);
  return status;
}

// Ctrl-C in the middle of a report: the process ends by the signal (a shell says 130), and neither the report
// folder nor its temporary folder (with the images and plot files written so far) is left behind.
TEST_F(AaReportCli, CtrlCLeavesNoTemporaryFolder) {
  struct Case {
    std::string output;
    std::vector<std::string> args;
  };
  const std::vector<Case> cases = {
      {"aa", {"aa-report", scene("cornell.json"), "--size", "320x240", "--methods", "jitter:16", "-o",
              path("aa")}},
      {"cmp", {"compare", scene("cornell.json"), "--accel", "grid,kd,bvh,brute", "--rays", "4000000", "--reps",
               "3", "-o", path("cmp")}}};
  for (const Case& c : cases) {
    SCOPED_TRACE(c.output);
    const int status = interrupt_when_started(dir_, c.output + ".tmp.", c.args);
    ASSERT_TRUE(WIFSIGNALED(status)) << "status " << status;
    EXPECT_EQ(WTERMSIG(status), SIGINT);
    EXPECT_EQ(128 + WTERMSIG(status), 130);  // what the shell reports
    for (const auto& e : fs::directory_iterator(dir_)) {
      const std::string name = e.path().filename().string();
      EXPECT_EQ(name.find(".tmp."), std::string::npos) << name;
      EXPECT_NE(name, c.output);
    }
  }
}

}  // namespace
}  // namespace raystep::clitest
