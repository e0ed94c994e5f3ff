// `raystep export-html`: the browser player's page, checked without a browser (tests/web/player_test.mjs
// plays it in Chromium). The page asks the network for nothing; its data, inflated, holds each step's state
// exactly as `raystep replay --step N` writes it, and for a 2D scene the slides' picture at each step; bad
// input (a missing or damaged trace, a 3D scene, a wrong extension, --ray with a trace) exits 2 with one line
// and writes nothing.
#include <gtest/gtest.h>
#include <zlib.h>

#include <filesystem>
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

// The page's data: the base64 between the data script's tags, gzip-inflated, parsed.
json page_data(const std::string& page) {
  const std::string open = "<script type=\"application/octet-stream\" id=\"raystep-data\">";
  const size_t from = page.find(open);
  EXPECT_NE(from, std::string::npos);
  if (from == std::string::npos) return json();
  const size_t to = page.find("</script>", from);
  std::string bytes;
  uint32_t acc = 0;
  int bits = 0;
  for (size_t i = from + open.size(); i < to; ++i) {
    const char c = page[i];
    int v = c >= 'A' && c <= 'Z'   ? c - 'A'
            : c >= 'a' && c <= 'z' ? c - 'a' + 26
            : c >= '0' && c <= '9' ? c - '0' + 52
            : c == '+'             ? 62
            : c == '/'             ? 63
                                   : -1;
    if (v < 0) continue;  // line breaks, padding
    acc = acc << 6 | uint32_t(v);
    bits += 6;
    if (bits >= 8) {
      bits -= 8;
      bytes += char((acc >> bits) & 0xff);
    }
  }
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
