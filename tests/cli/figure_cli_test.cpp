// `raystep figure`: the slides' 2D pictures headless. The SVG is well-formed (xmllint), has one group per
// layer and its caption as text (the kd figure's "Stack: LLR,R   Current: LLL" at that step); the PDF and the
// PNG are what their first bytes say; every structure drawn; bad input (a 3D scene, a step past the end, a
// malformed 2D scene, an unknown extension) exits 2 with one line and writes nothing.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "cli_test_util.h"

namespace {

using namespace raystep::clitest;

class FigureCli : public CliTest {
 protected:
  FigureCli() : CliTest("raystep_figure_cli_") {}
};

const std::string kFlat = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/flatland";

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

TEST_F(FigureCli, TheKdFigureAtLllIsValidSvgWithTheSlidesStack) {
  // The walk of kd_traversal.json: event 7 is the node event of LLL (ray_begin, root, push, L, LL, push,
  // ...).
  Outcome r = run("figure " + kFlat + "/kd_traversal.json --accel kd --step 7 -o " + path("fig.svg"));
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string svg = slurp(path("fig.svg"));
  EXPECT_EQ(std::system(("xmllint --noout " + path("fig.svg") + " 2>" + path("xmllint.txt")).c_str()), 0)
      << slurp(path("xmllint.txt"));
  for (const char* group :
       {"<g id=\"structure\"", "<g id=\"walk\"", "<g id=\"shapes\"", "<g id=\"ray\"", "<g id=\"caption\""})
    EXPECT_EQ(count(svg, group), 1) << group;
  EXPECT_NE(svg.find(">Stack: LLR,R   Current: LLL</text>"), std::string::npos) << svg;
  EXPECT_EQ(count(svg, "class=\"shape circle\""), 7);
  EXPECT_EQ(count(svg, "class=\"stacked\""), 2);  // LLR and R, dashed
  EXPECT_EQ(count(svg, "class=\"current\""), 1);
  EXPECT_EQ(count(svg, "class=\"split\""), 5);  // root, L, LL, LR, R
}

TEST_F(FigureCli, PdfPngAndEveryStructure) {
  ASSERT_EQ(run("figure " + kFlat + "/grid_objects.json --accel grid -o " + path("g.pdf")).code, 0);
  EXPECT_EQ(slurp(path("g.pdf")).substr(0, 5), "%PDF-");
  ASSERT_EQ(run("figure " + kFlat + "/bvh_overlap.json --accel bvh --width 300 -o " + path("b.png")).code, 0);
  EXPECT_EQ(slurp(path("b.png")).substr(1, 3), "PNG");
  for (const char* accel : {"grid", "kd", "kd-median", "octree", "bsp", "bvh", "bvh-sweep", "bvh-median"}) {
    Outcome r = run("figure " + kFlat + "/variations.json --accel " + std::string(accel) +
                    " --ray 0.2,5,1,-0.35 -o " + path(std::string(accel) + ".svg"));
    EXPECT_EQ(r.code, 0) << accel << ": " << r.err;
    // At the end: the final hit, and no current cell or interval (the walk is over).
    const std::string end = slurp(path(std::string(accel) + ".svg"));
    EXPECT_NE(end.find("class=\"hit final\""), std::string::npos) << accel;
    EXPECT_EQ(end.find("class=\"interval\""), std::string::npos) << accel;
    EXPECT_EQ(end.find("class=\"current\""), std::string::npos) << accel;
    // At the first cell or the root (a BVH tests the root's box first): the current one and the ray's
    // interval.
    const std::string step = std::string(accel).rfind("bvh", 0) == 0 ? "2" : "1";
    r = run("figure " + kFlat + "/variations.json --accel " + std::string(accel) + " --step " + step +
            " -o " + path("s.svg"));
    EXPECT_EQ(r.code, 0) << accel << ": " << r.err;
    const std::string first = slurp(path("s.svg"));
    EXPECT_NE(first.find("class=\"interval\""), std::string::npos) << accel;
    EXPECT_NE(first.find("class=\"current\""), std::string::npos) << accel;
  }
}

// `raystep sah` on a 2D scene says that the area columns hold perimeters, and has no z candidate.
TEST_F(FigureCli, SahInThePlaneSaysPerimetersAndCutsXAndYOnly) {
  for (const char* accel : {"kd", "bvh", "bsp"}) {
    Outcome r =
        run("sah " + kFlat + "/kd_traversal.json --accel " + std::string(accel) + " -o " + path("s.csv"));
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.out.find("the area columns hold perimeters"), std::string::npos) << accel << ": " << r.out;
    const std::string csv = slurp(path("s.csv"));
    // kd, bvh: rows start with the axis; bsp: with the direction's number and name (2 is z).
    const std::string z_row = std::string(accel) == "bsp" ? "\n2,z," : "\nz,";
    EXPECT_EQ(csv.find(z_row), std::string::npos) << accel;
    EXPECT_NE(csv.find(std::string(accel) == "bsp" ? "\n0,x," : "\nx,"), std::string::npos) << accel;
  }
  Outcome r =
      run("sah " + std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json --accel kd -o " + path("c.csv"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out.find("perimeters"), std::string::npos);
  EXPECT_NE(slurp(path("c.csv")).find("\nz,"), std::string::npos);  // in space z is cut too
}

// `--aa`: the anti-aliasing figure, three panels (sampled with the samples drawn, exact coverage, error),
// valid SVG; more samples, less error, as the line written says.
TEST_F(FigureCli, AntiAliasingFigureHasThePanelsAndItsError) {
  auto error_of = [&](const std::string& spec) {
    Outcome r = run("figure " + kFlat + "/aliasing_polygon.json --aa " + spec + " -o " + path("aa.svg"));
    EXPECT_EQ(r.code, 0) << r.err;
    const size_t at = r.out.find("error mean ");
    EXPECT_NE(at, std::string::npos) << r.out;
    return at == std::string::npos ? 1.0 : std::stod(r.out.substr(at + 11));
  };
  const double one = error_of("none"), many = error_of("jitter:4");
  EXPECT_LT(many, 0.5 * one);
  EXPECT_EQ(std::system(("xmllint --noout " + path("aa.svg") + " 2>" + path("xmllint.txt")).c_str()), 0)
      << slurp(path("xmllint.txt"));
  const std::string svg = slurp(path("aa.svg"));
  for (const char* group : {"<g id=\"pixels\"", "<g id=\"grid\"", "<g id=\"samples\"", "<g id=\"titles\""})
    EXPECT_EQ(count(svg, group), 1) << group;
  EXPECT_EQ(count(svg, "class=\"sampled\""), 24 * 16);
  EXPECT_EQ(count(svg, "class=\"exact\""), 24 * 16);
  EXPECT_EQ(count(svg, "class=\"sample in\"") + count(svg, "class=\"sample out\""), 24 * 16 * 16);
  EXPECT_NE(svg.find(">exact coverage (pre-filter)</text>"), std::string::npos);
}

TEST_F(FigureCli, BadInputIsOneLineAndExitTwo) {
  const std::string bad = write("bad.json",
                                "{\"dimensions\": 2, \"objects\": [{\"type\": \"circle\",\n"
                                "\"center\": [0, 0], \"radius\": -1}]}");
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json -o " + path("x.svg"), "a 3D scene"},
      {kFlat + "/kd_traversal.json --step 20 -o " + path("x.svg"), "--step 20: the walk has 20 events"},
      {bad + " -o " + path("x.svg"), "bad.json:2"},
      {kFlat + "/kd_traversal.json -o " + path("x.jpg"), "a figure is written as .svg, .pdf or .png"},
      {kFlat + "/kd_traversal.json --accel brute -o " + path("x.svg"), "is not drawn in 2D"},
      {kFlat + "/kd_traversal.json --ray 1,2,3 -o " + path("x.svg"), "--ray"},
      {kFlat + "/aliasing_polygon.json --aa sideways -o " + path("x.svg"), "sideways"},
      {kFlat + "/aliasing_polygon.json --aa none --size 100x100 -o " + path("x.svg"), "at most"},
      {kFlat + "/aliasing_polygon.json --aa none --step 3 -o " + path("x.svg"), "--aa draws the pixels"},
  };
  for (const Case& c : cases) {
    Outcome r = run("figure " + c.args);
    EXPECT_EQ(r.code, 2) << c.args;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("x.svg")));
  }
}

}  // namespace
