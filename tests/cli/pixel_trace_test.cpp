// `raystep trace --pixel X,Y --aa SPEC` end to end: an anti-aliased pixel's samples and every sample's rays
// in a version 2 trace, `trace-info` summarising the pixel section, and bad options refused with one line,
// exit 2.
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "raystep/trace/trace_file.h"

#include "cli_test_util.h"

namespace {

namespace fs = std::filesystem;

using namespace raystep::clitest;

class PixelTraceCli : public CliTest {
 protected:
  PixelTraceCli() : CliTest("raystep_pixel_trace_") {}
};

size_t count(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

// Pixel (30, 38) of the aliasing scene lies on the triangle's lower edge.
TEST_F(PixelTraceCli, AdaptivePixelWithItsSquaresAndEverySamplesRays) {
  const std::string out = path("t.json");
  Outcome r = run("trace " + scene("aliasing.json") + " --pixel 30,38 --aa adaptive:0.1:2 -o " + out);
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string text = slurp(out);
  EXPECT_EQ(text.rfind("{\n \"format\": \"raystep-trace\",\n \"version\": 4,", 0), 0u) << text.substr(0, 80);
  EXPECT_NE(
      text.find(
          " \"pixel\": {\"x\":30,\"y\":38,\"width\":64,\"height\":48,\"seed\":0,\"aa\":\"adaptive:0.1:2\""),
      std::string::npos)
      << text.substr(0, 600);
  EXPECT_NE(text.find("\"outcome\":\"subdivided\""), std::string::npos);
  // One primary ray per sample, numbered in order.
  const size_t samples = count(text, "\"lattice\":[");
  EXPECT_GT(samples, 5u);
  EXPECT_EQ(count(text, "\"kind\":\"primary\""), samples);
  EXPECT_NE(text.find("\"sample\":" + std::to_string(samples - 1) + ","), std::string::npos);
  EXPECT_NE(r.out.find("pixel 30,38 of 64x48: aa adaptive:0.1:2"), std::string::npos) << r.out;

  Outcome info = run("trace-info " + out);
  ASSERT_EQ(info.code, 0) << info.err;
  EXPECT_NE(info.out.find("valid raystep trace, version 4"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find(std::to_string(samples) + " sample(s)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("adaptive: "), std::string::npos) << info.out;
  EXPECT_NE(info.out.find(" squares, depth 2 reached (limit 2)"), std::string::npos) << info.out;
  EXPECT_NE(info.out.find("\nvalue ("), std::string::npos) << info.out;
}

TEST_F(PixelTraceCli, SecondaryRaysSeedsAndTheScenesSetting) {
  // spheres.json: mirror and glass, so secondary rays descend from the samples.
  const std::string a = path("a.json"), b = path("b.json"), c = path("c.json");
  ASSERT_EQ(run("trace " + scene("spheres.json") + " --pixel 170,120 --aa jitter:2 --secondary -o " + a).code,
            0);
  ASSERT_EQ(run("trace " + scene("spheres.json") + " --pixel 170,120 --aa jitter:2 --seed 9 -o " + b).code,
            0);
  const std::string ta = slurp(a), tb = slurp(b);
  EXPECT_EQ(count(ta, "\"stratum\":["), 4u);
  EXPECT_EQ(count(ta, "\"kind\":\"primary\""), 4u);
  EXPECT_GT(count(ta, "\"kind\":\"shadow\""), 0u);
  EXPECT_EQ(count(tb, "\"kind\":\"shadow\""), 0u);  // without --secondary, the primary rays only
  EXPECT_NE(tb.find("\"seed\":9,"), std::string::npos);
  // Another seed, other jittered positions.
  auto first_px = [](const std::string& t) { return t.substr(t.find("\"px\":"), 30); };
  EXPECT_NE(first_px(ta), first_px(tb));
  // --aa scene: the scene's own setting (aliasing.json renders with none: one sample at the centre).
  ASSERT_EQ(run("trace " + scene("aliasing.json") + " --pixel 3,4 --aa scene -o " + c).code, 0);
  const std::string tc = slurp(c);
  EXPECT_NE(tc.find("\"aa\":\"none\""), std::string::npos);
  EXPECT_NE(tc.find("{\"px\":3.5,\"py\":4.5,"), std::string::npos) << tc.substr(0, 800);
}

TEST_F(PixelTraceCli, WithoutAaTheCentreRayAndNoPixelSection) {
  const std::string out = path("t.json");
  ASSERT_EQ(run("trace " + scene("aliasing.json") + " --pixel 30,38 -o " + out).code, 0);
  const std::string text = slurp(out);
  EXPECT_EQ(text.find("\"pixel\": {"), std::string::npos);
  EXPECT_EQ(text.find("\"sample\":"), std::string::npos);
  EXPECT_EQ(count(text, "\"kind\":\"primary\""), 1u);
  EXPECT_NE(text.find("\"origin\":[30.5,9.5"), std::string::npos) << text.substr(0, 800);  // the centre
}

TEST_F(PixelTraceCli, CsvCarriesTheSampleColumn) {
  const std::string out = path("t.csv");
  ASSERT_EQ(
      run("trace " + scene("aliasing.json") + " --pixel 30,38 --aa regular:2 --format csv -o " + out).code,
      0);
  std::istringstream csv(slurp(out));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line.substr(line.size() - 21), ",reason,sample,parent");  // parent: version 3, box_test's
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("0,0,ray_begin,", 0), 0u) << line;
  EXPECT_EQ(line.substr(line.size() - 2), "0,");  // sample 0; no parent
}

TEST_F(PixelTraceCli, BadOptionsExitTwoWithOneLine) {
  const std::string out = path("t.json"), s = scene("aliasing.json");
  for (const char* bad : {"jitter:0", "bogus", "adaptive:2", "regular:65", "random:", "adaptive:0.1:9", ""})
    expect_error(run("trace " + s + " --pixel 1,1 --aa '" + std::string(bad) + "' -o " + out),
                 "bad anti-aliasing", out);
  expect_error(run("trace " + s + " --ray 0,0,10,0,0,-1 --aa jitter:2 -o " + out),
               "trace: --aa goes with --pixel", out);
  expect_error(run("trace " + s + " --pixel 1,1 --seed 3 -o " + out), "trace: --seed goes with --aa", out);
  expect_error(run("trace " + s + " --pixel 64,1 --aa jitter:2 -o " + out), "--pixel", out);
  expect_error(run("trace " + s + " --pixel 1,1 --aa jitter:2 --accel bvol -o " + out), "trace: --accel bvol",
               out);
}

}  // namespace

// The exact pre-filtered value travels with the pixel where the scene has one (flat triangles seen
// orthographically): the covered fraction of pixel (30, 38), from the triangle's vertices by the shoelace
// formula; a pinhole scene has none.
TEST_F(PixelTraceCli, TheExactValueWhereTheSceneHasOne) {
  const std::string flat = path("flat.json"), lit = path("lit.json");
  ASSERT_EQ(run("trace " + scene("aliasing.json") + " --pixel 30,38 --aa jitter:2 -o " + flat).code, 0);
  const raystep::Trace t = raystep::read_trace_json(flat);
  ASSERT_TRUE(t.pixel.has_value());
  ASSERT_TRUE(t.pixel->exact.has_value());
  // Pixel (30, 38) is the square [30, 31] x [9, 10] of the plane; the edge from (6, 5) to (58, 14) crosses it
  // at y = 5 + 9 (x - 6) / 52, so the covered part above the edge has area 10 - 5 - 9 (30.5 - 6) / 52.
  const double covered = 10.0 - 5.0 - 9.0 * (30.5 - 6.0) / 52.0;
  EXPECT_NEAR(t.pixel->exact->x, covered, 1e-6);
  EXPECT_NE(run("trace-info " + flat).out.find(", exact ("), std::string::npos);

  ASSERT_EQ(run("trace " + scene("cornell.json") + " --pixel 100,100 --aa jitter:2 -o " + lit).code, 0);
  const raystep::Trace u = raystep::read_trace_json(lit);
  ASSERT_TRUE(u.pixel.has_value());
  EXPECT_FALSE(u.pixel->exact.has_value());
}
