// `raystep export-html`: the browser player's page, checked without a browser (tests/web/player_test.mjs
// plays it in Chromium). The page asks the network for nothing; its data, inflated, holds each step's state
// exactly as `raystep replay --step N` writes it, and for a 2D scene the slides' picture at each step; bad
// input (a missing or damaged trace, a 3D scene, a wrong extension, --ray with a trace) exits 2 with one line
// and writes nothing.
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
#include <fstream>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_test_util.h"

namespace {

using namespace raystep::clitest;
using nlohmann::json;

class HtmlCli : public CliTest {
 protected:
  HtmlCli() : CliTest("raystep_html_cli_") {}
};

const std::string kSource = RAYSTEP_SOURCE_DIR;

int count(const std::string& text, const std::string& what) {
  int n = 0;
  for (size_t at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Base64 to bytes, skipping line breaks and padding.
std::string base64_decode(const std::string& text) {
  std::string bytes;
  uint32_t acc = 0;
  int bits = 0;
  for (const char c : text) {
    int v = c >= 'A' && c <= 'Z'   ? c - 'A'
            : c >= 'a' && c <= 'z' ? c - 'a' + 26
            : c >= '0' && c <= '9' ? c - '0' + 52
            : c == '+'             ? 62
            : c == '/'             ? 63
                                   : -1;
    if (v < 0) continue;
    acc = acc << 6 | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes += char((acc >> bits) & 0xff);
    }
  }
  return bytes;
}

// The page's data: the base64 between the data script's tags, gzip-inflated, parsed.
json page_data(const std::string& page) {
  const std::string open = "<script type=\"application/octet-stream\" id=\"raystep-data\">";
  const size_t from = page.find(open);
  EXPECT_NE(from, std::string::npos);
  if (from == std::string::npos) return json();
  const size_t to = page.find("</script>", from);
  std::string bytes = base64_decode(page.substr(from + open.size(), to - from - open.size()));
  z_stream z{};
  EXPECT_EQ(inflateInit2(&z, 15 + 16), Z_OK);
  std::string text;
  char buf[65536];
  z.next_in = reinterpret_cast<Bytef*>(bytes.data());
  z.avail_in = uInt(bytes.size());
  int r = Z_OK;
  while (r == Z_OK) {
    z.next_out = reinterpret_cast<Bytef*>(buf);
    z.avail_out = sizeof buf;
    r = inflate(&z, Z_NO_FLUSH);
    text.append(buf, sizeof buf - z.avail_out);
  }
  inflateEnd(&z);
  EXPECT_EQ(r, Z_STREAM_END);
  return json::parse(text);
}

TEST_F(HtmlCli, ATracesPageHoldsTheReplaysStatesAndAsksTheNetworkForNothing) {
  const std::string trace = path("kd.json");
  ASSERT_EQ(run("trace " + kSource + "/scenes/cornell.json --accel kd --pixel 160,200 -o " + trace).code, 0);
  Outcome r = run("export-html " + trace + " --title 'Cornell <kd>' -o " + path("kd.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_NE(r.out.find("wrote " + path("kd.html")), std::string::npos) << r.out;
  const std::string page = slurp(path("kd.html"));
  EXPECT_EQ(page.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_EQ(count(page, "<title>Cornell &lt;kd&gt;</title>"), 1);  // the title escaped
  // Inlined: no script, style, image or link from anywhere else.
  for (const char* outside : {"src=\"http", "href=\"http", "src=\"//", "<link ", "@import", "url("})
    EXPECT_EQ(page.find(outside), std::string::npos) << outside;
  const json d = page_data(page);
  ASSERT_TRUE(d.is_object());
  EXPECT_EQ(d["format"], "raystep-player");
  const json& ray = d["walks"][0]["rays"][0];
  ASSERT_GT(ray["states"].size(), 8u);
  EXPECT_EQ(ray["lines"].size(), ray["states"].size());
  EXPECT_FALSE(ray.contains("picture"));  // a 3D trace: no 2D picture, its 3D view's walk and scene instead
  ASSERT_TRUE(ray.contains("walk3d"));
  const json& w3 = ray["walk3d"];
  EXPECT_EQ(w3["current"].size(), ray["states"].size());
  EXPECT_EQ(w3["stack"].size(), ray["states"].size());
  const json tj = json::parse(slurp(trace));
  EXPECT_EQ(w3["boxes"].size(), tj["geometry"]["nodes"].size() + tj["geometry"]["cells"].size());
  for (const json& c : w3["current"]) EXPECT_LT(c.get<int>(), int(w3["boxes"].size()));
  ASSERT_TRUE(d.contains("scenes"));
  EXPECT_EQ(d["walks"][0]["scene"], 0);
  EXPECT_GT(d["scenes"][0]["triangles"].size(), 0u);
  EXPECT_EQ(d["scenes"][0]["triangles"].size() % 9, 0u);
  EXPECT_GT(d["scenes"][0]["spheres"].size(), 0u);
  EXPECT_NE(page.find("var raystepView3d="), std::string::npos);  // three.js and the view, bundled in
  for (size_t k : {size_t(0), size_t(5), ray["states"].size() - 1}) {
    Outcome replay = run("replay " + trace + " --step " + std::to_string(k));
    ASSERT_EQ(replay.code, 0) << replay.err;
    const std::string header = ray["header"].get<std::string>() + "\n\n";
    EXPECT_EQ(replay.out, header + ray["states"][k].get<std::string>() + "\n") << k;
  }
}

TEST_F(HtmlCli, A2DScenesPageDrawsTheWalkAtEachStep) {
  Outcome r =
      run("export-html " + kSource + "/scenes/flatland/kd_traversal.json --accel kd -o " + path("flat.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json d = page_data(slurp(path("flat.html")));
  ASSERT_TRUE(d.is_object());
  const json& ray = d["walks"][0]["rays"][0];
  ASSERT_TRUE(ray.contains("picture"));
  const json& p = ray["picture"];
  EXPECT_EQ(p["walk"].size(), ray["states"].size());
  EXPECT_EQ(p["top"].size(), ray["states"].size());
  EXPECT_EQ(count(p["under"].get<std::string>(), "class=\"split\""), 5);  // root, L, LL, LR, R
  EXPECT_EQ(count(p["over"].get<std::string>(), "class=\"shape circle\""), 7);
  // Step 7, as `raystep figure --step 7`: LLL current, LLR and R stacked, the slides' caption.
  const std::string walk7 = p["walk"][7];
  EXPECT_EQ(count(walk7, "class=\"current\""), 1);
  EXPECT_EQ(count(walk7, "class=\"stacked\""), 2);
  EXPECT_EQ(p["caption"][7][1], "Stack: LLR,R   Current: LLL");
  EXPECT_EQ(walk7.find("<?xml"), std::string::npos);       // stacked in the page, not standalone documents
  EXPECT_EQ(walk7.find("background"), std::string::npos);  // transparent over the structure
  EXPECT_LT(slurp(path("flat.html")).size(), 100000u);  // without the 3D view's script (three.js: 0.5 MB)
}

TEST_F(HtmlCli, ALessonsPageHasItsStepsWalksAndQuestions) {
  Outcome r = run("export-html " + kSource + "/lessons/09-3d-dda.md -o " + path("l.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json d = page_data(slurp(path("l.html")));
  ASSERT_TRUE(d.is_object());
  const json& lesson = d["lesson"];
  EXPECT_EQ(lesson["title"], "3D-DDA: tMax and tDelta, one step at a time");
  ASSERT_EQ(lesson["steps"].size(), 6u);
  int questions = 0;
  for (const json& step : lesson["steps"]) {
    EXPECT_NE(step["html"].get<std::string>().find("<p>"), std::string::npos) << step["title"];  // Markdown
    ASSERT_GE(step["walk"].get<int>(), 0) << step["title"];  // every step of this lesson follows a pixel's ray
    const json& walk = d["walks"][step["walk"].get<size_t>()];
    ASSERT_LT(step["step"].get<size_t>(), walk["rays"][step["ray"].get<size_t>()]["states"].size());
    if (!step.contains("question")) continue;
    ++questions;
    int right = 0;
    for (const json& c : step["question"]["choices"]) {
      right += c["right"].get<bool>();
      // A wrong choice says why not, a right one needs no feedback.
      EXPECT_EQ(c["feedback"].get<std::string>().empty(), c["right"].get<bool>()) << c.dump();
    }
    EXPECT_EQ(right, 1) << step["question"].dump();
    EXPECT_FALSE(step["question"]["answer"].get<std::string>().empty());
  }
  EXPECT_EQ(questions, 3);
  // One trace for the steps on one pixel.
  EXPECT_EQ(d["walks"].size(), 1u);
}

// The size in a PNG's header (IHDR: width and height, big-endian, after the 8-byte signature and 8 bytes).
std::pair<int, int> png_size(const std::string& png) {
  EXPECT_EQ(png.substr(1, 3), "PNG");
  auto be = [&](size_t at) {
    return int(uint8_t(png[at])) << 24 | int(uint8_t(png[at + 1])) << 16 | int(uint8_t(png[at + 2])) << 8 |
           int(uint8_t(png[at + 3]));
  };
  return png.size() >= 24 ? std::pair{be(16), be(20)} : std::pair{0, 0};
}

// The first inlined picture's bytes (<img src="data:image/png;base64,...">).
std::string first_png(const std::string& html) {
  const std::string key = "src=\"data:image/png;base64,";
  const size_t at = html.find(key);
  if (at == std::string::npos) return "";
  const size_t from = at + key.size();
  return base64_decode(html.substr(from, html.find('"', from) - from));
}

TEST_F(HtmlCli, ALessonsStepsWithoutAWalkDrawTheirFigure) {
  // A pixel's anti-aliasing with the inspector open, a kd-tree node's cost curve with its question, the
  // tree, a heat map, and a report: what the debugger's figure for each step shows, drawn into the page.
  const std::string lesson = path("figures.md");
  std::ofstream(lesson) << "# Figures\n\nThe figures of a lesson.\n\n"
                           "## The pixel\n\nExact: {{pixel.exact:.4f}}.\n\n```raystep\nscene: "
                        << kSource
                        << "/scenes/aliasing.json\naccel: grid\naa: regular:4\npixel: 32,38\nzoom: 16\n"
                           "inspect: on\nshow: picture\n```\n\n"
                           "## The curve\n\nThe root.\n\n```raystep\nscene: "
                        << kSource
                        << "/scenes/torus_knot.json\naccel: kd\npixel: none\ninspect: off\nnode: 0\npanel: sah\n"
                           "show: chart\nask: sah-plane\n```\n\n"
                           "## The tree\n\nIts shape.\n\n```raystep\nshow: tree\n```\n\n"
                           "## The heat\n\nTests.\n\n```raystep\nheat: tests\nshow: picture\n```\n\n"
                           "## The report\n\nKinds.\n\n```raystep\nscene: "
                        << kSource << "/scenes/cornell.json\nheat: none\nshow: window\nreport: bvol\n```\n";
  Outcome r = run("export-html " + lesson + " -o " + path("f.html"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json d = page_data(slurp(path("f.html")));
  ASSERT_TRUE(d.is_object());
  const json& steps = d["lesson"]["steps"];
  ASSERT_EQ(steps.size(), 5u);
  for (const json& step : steps) ASSERT_TRUE(step.contains("figure")) << step["title"];

  // The picture, zoomed 16 times around the pixel: 560 / 16 = 35 pixels across, 21 down; the pixel framed.
  const std::string picture = steps[0]["figure"]["html"];
  EXPECT_EQ(steps[0]["figure"]["kind"], "picture");
  EXPECT_EQ(png_size(first_png(picture)), (std::pair{35, 21}));
  EXPECT_EQ(count(picture, "class=\"frame\""), 2);  // its two strokes
  // The inspector: the 16 samples, the 3 + 3 dashed strata lines, the value and the exact coverage, which
  // the narration's number (the lesson facts) gives too.
  EXPECT_EQ(count(picture, "<circle class=\"sample"), 16);
  EXPECT_EQ(count(picture, "class=\"strata\""), 1);
  const std::string narration = steps[0]["html"];
  const size_t exact_at = narration.find("Exact: ");
  ASSERT_NE(exact_at, std::string::npos);
  const std::string exact = narration.substr(exact_at + 7, 6);
  EXPECT_NE(picture.find("exact coverage " + exact), std::string::npos) << exact << "\n" << picture.substr(0, 200);
  EXPECT_NE(picture.find("16 samples (regular:4)"), std::string::npos);

  // The curve: the chosen split's words are the question's answer, and they are marked as the answer.
  const json& curve = steps[1]["figure"];
  EXPECT_EQ(curve["kind"], "chart");
  const std::string answer = steps[1]["question"]["answer"];  // "x = 0.11"
  ASSERT_GE(answer.size(), 5u);
  const std::string chart = curve["html"];
  const size_t words = chart.find(">chosen: split " + answer.substr(0, 1) + " at ");
  ASSERT_NE(words, std::string::npos) << answer;
  EXPECT_NE(chart.rfind("<text class=\"answer\"", words), std::string::npos);
  EXPECT_GE(count(chart, "class=\"answer chosen\""), 2);  // its line and its ring
  EXPECT_GT(count(chart, "class=\"candidate-"), 100);
  EXPECT_EQ(curve["caption"].get<std::string>().find("chosen"), std::string::npos);  // the caption tells nothing
  EXPECT_NE(curve["caption"].get<std::string>().find("kd-tree node 0 (the root), depth 0"), std::string::npos);
  // The tree: the kd-tree's shape over the same curve.
  EXPECT_EQ(steps[2]["figure"]["kind"], "tree");
  EXPECT_NE(steps[2]["figure"]["html"].get<std::string>().find("The kd-tree: "), std::string::npos);
  // The heat map: the whole picture (no zoom without a pixel) with its colour bar: wider than the picture.
  const std::pair<int, int> heat = png_size(first_png(steps[3]["figure"]["html"]));
  EXPECT_GT(heat.first, 400);  // the torus knot's picture is 400 x 300
  EXPECT_EQ(heat.second, 300);
  EXPECT_NE(steps[3]["figure"]["caption"].get<std::string>().find("Heat map: "), std::string::npos);
  // The report: a table with a row for each of the four kinds.
  const std::string table = steps[4]["figure"]["html"];
  EXPECT_EQ(steps[4]["figure"]["kind"], "report");
  EXPECT_EQ(count(table, "<tr>"), 5);
  for (const char* kind : {">bvol<", ">bvol-sphere<", ">bvol-kdop<", ">bvol-obb<"})
    EXPECT_NE(table.find(kind), std::string::npos) << kind;
}

TEST_F(HtmlCli, ALessonSiteIsWrittenWholeOrNotAtAll) {
  const std::string lessons = path("lessons");
  std::filesystem::create_directories(lessons);
  std::filesystem::copy_file(kSource + "/lessons/09-3d-dda.md", lessons + "/09-3d-dda.md");
  // The copy's scene is found beside the lessons' folder, as in the repository.
  const std::string scene = "scene: " + kSource + "/scenes/cornell.json";
  std::string text = slurp(lessons + "/09-3d-dda.md");
  text.replace(text.find("scene: ../scenes/cornell.json"), std::string("scene: ../scenes/cornell.json").size(), scene);
  write("lessons/09-3d-dda.md", text);
  Outcome r = run("export-html " + lessons + " --title 'Our course' -o " + path("site"));
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(path("site/09-3d-dda.html")));
  const std::string index = slurp(path("site/index.html"));
  EXPECT_NE(index.find("<title>Our course</title>"), std::string::npos);
  EXPECT_NE(index.find("<a href=\"09-3d-dda.html\">3D-DDA: tMax and tDelta, one step at a time</a>"),
            std::string::npos)
      << index;
  // A lesson whose step cannot be reached: one line naming it, and the old site left as it was.
  write("lessons/10-broken.md", "# Broken\n\n## One\n\n```raystep\nscene: nowhere.json\n```\n");
  Outcome bad = run("export-html " + lessons + " -o " + path("site"));
  EXPECT_EQ(bad.code, 2);
  EXPECT_NE(bad.err.find("10-broken.md"), std::string::npos) << bad.err;
  EXPECT_EQ(count(bad.err, "\n"), 1) << bad.err;
  EXPECT_FALSE(std::filesystem::exists(path("site/10-broken.html")));
  EXPECT_TRUE(std::filesystem::exists(path("site/09-3d-dda.html")));
}

TEST_F(HtmlCli, BadInputIsOneLineAndExitTwo) {
  const std::string damaged =
      write("damaged.json", "{\"format\": \"raystep-trace\", \"version\": 4, \"rays\": [");
  const std::string trace = path("grid.json");
  ASSERT_EQ(run("trace " + kSource + "/scenes/cornell.json --accel grid --pixel 10,10 -o " + trace).code, 0);
  struct Case {
    std::string args, message;
  };
  const Case cases[] = {
      {path("missing.json") + " -o " + path("x.html"), "missing.json"},
      {damaged + " -o " + path("x.html"), "damaged.json"},
      {kSource + "/scenes/cornell.json -o " + path("x.html"), "a 3D scene"},
      {trace + " -o " + path("x.svg"), "written as .html"},
      {trace + " --ray 1,2,3,4 -o " + path("x.html"), "--ray"},
      {kSource + "/scenes/flatland/kd_traversal.json --accel brute -o " + path("x.html"), "brute"},
      {path("nothere.md") + " -o " + path("x.html"), "nothere.md"},
      {kSource + "/lessons/09-3d-dda.md --ray 1,2,3,4 -o " + path("x.html"), "--ray"},
  };
  for (const Case& c : cases) {
    Outcome r = run("export-html " + c.args);
    EXPECT_EQ(r.code, 2) << c.args << ": " << r.err;
    EXPECT_NE(r.err.find(c.message), std::string::npos) << r.err;
    EXPECT_EQ(count(r.err, "\n"), 1) << r.err;
    EXPECT_FALSE(std::filesystem::exists(path("x.html")));
    EXPECT_FALSE(std::filesystem::exists(path("x.svg")));
  }
}

}  // namespace
