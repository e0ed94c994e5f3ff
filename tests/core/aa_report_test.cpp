#include "raystep/report/aa_report.h"

#include <gtest/gtest.h>

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <memory>

#include "raystep/accel/structure_options.h"
#include "raystep/io/image_io.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

struct Built {
  Scene scene;
  std::unique_ptr<Accelerator> accel;
};

Built aliasing() {
  Built b{load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/aliasing.json"),
          make_accelerator("grid", StructureOptions{})};
  b.accel->build(b.scene.geometry);
  return b;
}

AaReportOptions small(std::vector<std::string> methods) {
  AaReportOptions o;
  o.methods = std::move(methods);
  o.reference = "exact";
  o.seeds = 3;
  o.threads = 1;
  return o;
}

TEST(AaReport, LogLogSlopeOfAPowerLaw) {
  std::vector<double> x = {1, 4, 16, 64}, y;
  for (double v : x) y.push_back(3.0 * std::pow(v, -0.75));
  EXPECT_NEAR(loglog_slope(x, y), -0.75, 1e-12);
  EXPECT_TRUE(std::isnan(loglog_slope({4}, {1})));
  EXPECT_TRUE(std::isnan(loglog_slope({4, 4}, {1, 2})));           // no spread in x
  EXPECT_NEAR(loglog_slope({1, 0, 2}, {1, 5, 0.5}), -1.0, 1e-12);  // x = 0 is left out
}

TEST(AaReport, DefaultMethodsParse) {
  const std::vector<std::string> m = default_aa_methods();
  EXPECT_EQ(m.front(), "none");
  EXPECT_EQ(parse_aa_methods(m).size(), m.size());
  int adaptive = 0;
  for (const auto& s : m) adaptive += s.rfind("adaptive:", 0) == 0 && s.substr(s.size() - 2) == ":3";
  EXPECT_GE(adaptive, 3);
}

TEST(AaReport, BadMethodListsNameTheEntry) {
  EXPECT_THROW(parse_aa_methods({}), InputError);
  for (const char* bad : {"jitter:0", "bogus", "regular:", "adaptive:-1", "random:99999"}) {
    try {
      parse_aa_methods({"none", bad});
      ADD_FAILURE() << bad;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("bad method list"), std::string::npos);
      EXPECT_NE(std::string(e.what()).find(bad), std::string::npos) << e.what();
    }
  }
}

TEST(AaReport, BadOptionsThrowBeforeRendering) {
  Built b = aliasing();
  int rows = 0;
  AaReportHooks hooks;
  hooks.row_done = [&](const AaReport&, const AaReportRow&) { ++rows; };
  auto run = [&](AaReportOptions o) { run_aa_report(b.scene, *b.accel, o, hooks); };
  AaReportOptions o = small({"none"});
  o.seeds = 0;
  EXPECT_THROW(run(o), InputError);
  o = small({"none"});
  o.reference = "regular:4";
  EXPECT_THROW(run(o), InputError);
  o.reference = "jitter:0";
  EXPECT_THROW(run(o), InputError);
  o = small({"none"});
  o.width = 10;  // height missing
  EXPECT_THROW(run(o), InputError);
  o = small({"none", "jitter:x"});
  EXPECT_THROW(run(o), InputError);
  EXPECT_EQ(rows, 0);
}

// Each row's figures recomputed from renders made here with the same settings and seeds.
TEST(AaReport, RowsMatchRendersMadeByHand) {
  Built b = aliasing();
  AaReportOptions o = small({"none", "regular:2", "regular:4", "jitter:2", "jitter:4", "random:8"});
  o.width = 32;
  o.height = 24;
  const AaReport r = run_aa_report(b.scene, *b.accel, o);
  EXPECT_EQ(r.reference_kind, "exact");
  EXPECT_EQ(r.reference_rmse, 0.0);
  EXPECT_EQ(r.width, 32);
  ASSERT_EQ(r.rows.size(), 6u);
  const Image exact = render_exact_coverage(b.scene, 32, 24);
  for (const AaReportRow& row : r.rows) {
    const AntiAliasing aa = parse_antialiasing(row.spec);
    const bool random = row.method == "jitter" || row.method == "random";
    EXPECT_EQ(row.seeds, random ? 3 : 1) << row.spec;
    ASSERT_EQ(row.seed_rmse.size(), size_t(row.seeds));
    for (int s = 0; s < row.seeds; ++s) {
      RenderOptions ro;
      ro.aa = aa;
      ro.width = 32;
      ro.height = 24;
      ro.threads = 1;
      ro.seed = random ? uint64_t(s + 1) : 0;
      const RenderResult rr = render_image(b.scene, *b.accel, ro);
      EXPECT_DOUBLE_EQ(row.seed_rmse[s], rmse(rr.image, exact)) << row.spec << " seed " << s + 1;
      EXPECT_EQ(row.rays.primary, rr.rays.primary);  // a fixed count for these methods
    }
    const double expected_spp = row.method == "none" ? 1 : row.method == "random" ? aa.k : aa.k * aa.k;
    EXPECT_DOUBLE_EQ(row.rays_per_pixel, expected_spp) << row.spec;
    EXPECT_LE(row.rmse_min, row.rmse);
    EXPECT_GE(row.rmse_max, row.rmse);
    EXPECT_GT(row.max_error, row.rmse);
    if (random) {
      EXPECT_LT(row.rmse_min, row.rmse_max) << row.spec;  // different seeds, different errors
      EXPECT_GT(row.rmse_stddev, 0.0);
    } else {
      EXPECT_EQ(row.rmse_stddev, 0.0);
    }
    EXPECT_GT(row.seconds, 0.0);
  }
  EXPECT_LT(r.rows[2].rmse, r.rows[0].rmse);  // regular:4 beats one centre sample
  ASSERT_EQ(r.slopes.size(), 2u);             // regular and jitter have two counts each
  EXPECT_EQ(r.slopes[0].first, "regular");
  EXPECT_EQ(r.slopes[1].first, "jitter");
  EXPECT_LT(r.slopes[1].second, -0.3);
}

// The slopes the theory predicts at edges, on the exact-coverage scenes at their own size: jittered N^-3/4;
// a regular grid N^-1 on slanted edges (aliasing.json) but N^-1/2 on edges along the grid (grid_edges.json).
TEST(AaReport, FittedSlopesFollowTheTheory) {
  auto slopes = [](const std::string& name, const std::vector<std::string>& methods) {
    Built b{load_scene(std::string(RAYSTEP_SOURCE_DIR) + "/scenes/" + name),
            make_accelerator("grid", StructureOptions{})};
    b.accel->build(b.scene.geometry);
    AaReportOptions o = small(methods);
    o.seeds = 5;
    std::map<std::string, double> out;
    for (const auto& [method, slope] : run_aa_report(b.scene, *b.accel, o).slopes) out[method] = slope;
    return out;
  };
  std::vector<std::string> methods;
  for (int k = 2; k <= 8; ++k) methods.push_back("regular:" + std::to_string(k));
  for (int k = 2; k <= 8; ++k) methods.push_back("jitter:" + std::to_string(k));
  auto slanted = slopes("aliasing.json", methods);
  EXPECT_NEAR(slanted.at("regular"), -1.0, 0.1);
  EXPECT_NEAR(slanted.at("jitter"), -0.75, 0.1);
  auto along = slopes("grid_edges.json", {"regular:2", "regular:3", "regular:4", "regular:5", "regular:6",
                                          "regular:7", "regular:8"});
  EXPECT_NEAR(along.at("regular"), -0.5, 0.1);
}

TEST(AaReport, HooksProgressRowsAndImages) {
  Built b = aliasing();
  const std::string dir = ::testing::TempDir() + "aa_report_" + std::to_string(::getpid());
  std::filesystem::create_directories(dir);
  AaReportOptions o = small({"none", "jitter:2", "adaptive:0.1:2"});
  o.reference = "jitter:3";
  o.seeds = 2;
  AaReportHooks hooks;
  std::vector<std::string> seen;
  double last = -1.0;
  hooks.row_done = [&](const AaReport& so_far, const AaReportRow& row) {
    EXPECT_EQ(&so_far.rows.back(), &row);
    seen.push_back(row.spec);
  };
  hooks.progress = [&](double f) {
    EXPECT_GE(f, last);
    EXPECT_LE(f, 1.0);
    last = f;
  };
  hooks.image_dir = dir;
  const AaReport r = run_aa_report(b.scene, *b.accel, o, hooks);
  EXPECT_EQ(seen, (std::vector<std::string>{"none", "jitter:2", "adaptive:0.1:2"}));
  EXPECT_EQ(last, 1.0);
  EXPECT_EQ(r.reference_kind, "jitter:3");
  EXPECT_GT(r.reference_rmse, 0.0);
  const Image reference = read_pfm(dir + "/reference.pfm");
  for (const AaReportRow& row : r.rows) {
    ASSERT_EQ(row.images.size(), size_t(row.seeds));
    for (size_t s = 0; s < row.images.size(); ++s)
      EXPECT_DOUBLE_EQ(rmse(read_pfm(dir + "/" + row.images[s]), reference), row.seed_rmse[s]);
  }
  EXPECT_EQ(r.rows[1].images[1], "jitter-2-seed2.pfm");
  std::filesystem::remove_all(dir);
}

TEST(AaReport, CancelStopsAfterTheCurrentRender) {
  Built b = aliasing();
  std::atomic<bool> cancel{false};
  AaReportHooks hooks;
  hooks.cancel = &cancel;
  hooks.row_done = [&](const AaReport&, const AaReportRow&) { cancel = true; };
  const AaReport r = run_aa_report(b.scene, *b.accel, small({"none", "regular:2", "jitter:2"}), hooks);
  EXPECT_EQ(r.rows.size(), 1u);
  EXPECT_TRUE(r.slopes.empty());
}

}  // namespace
}  // namespace raystep
