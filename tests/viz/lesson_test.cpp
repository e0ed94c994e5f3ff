// Lessons in the GUI (presenter mode): entering a step shows exactly what a fresh scripted run of the step's
// equivalent command line (core's LessonState::scripted_args) shows, whether the steps are walked in order,
// backwards or by jumping; the clicker's keys move between steps; a damaged lesson is refused with its file
// and line (exit 2), or in a dialog with the window kept; the handout has one figure per step and the answers
// folded away; the quiz marks predictions. One GUI process walks a whole lesson; each step's scripted
// equivalent is one run, made once and compared with every walk.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <map>
#include <regex>
#include <set>

#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_runner.h"
#include "viz_test_util.h"

namespace {

using namespace raystep::viztest;
namespace fs = std::filesystem;

std::string quote(const std::string& s) {
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

std::string joinArgs(const std::vector<std::string>& args) {
  std::string out;
  for (const std::string& a : args) out += (out.empty() ? "" : " ") + quote(a);
  return out;
}

// Fields that may differ between a step entered in a lesson and its fresh scripted run, and why:
//   window    the lesson pane's width comes on top of the debugger's (the debugger keeps 1280 x 800: the
//             3D view's viewport and every projection are compared);
//   lesson    the pane's own state (a fresh run has no lesson);
//   backdrop  whether the 3D view's scene layer is an image yet depends on how many renders found it
//             unchanged (BackdropImageDrawsLikeTheScene checks the pixels are the same either way);
//   sah/viewport while the kd dock is closed: where the hidden chart was last laid out (a fresh run never
//             laid it out; a walk may have shown the dock at an earlier step);
//   sah/concealed, sah/plots at a sah-plane question: the chart hides the SAH's choice (one plot fewer)
//             until the answer is revealed.
json withoutLessonFields(json j) {
  j.erase("window");
  j.erase("lesson");
  if (j.contains("view")) j["view"].erase("backdrop");
  if (j.contains("sah") && j["sah"].value("visible", true) == false) j["sah"].erase("viewport");
  if (j.contains("sah")) j["sah"].erase("concealed");
  // A report window a step opened (`report:`): a closed one is as good as none (a fresh run never made it),
  // and its times vary from run to run; its counts are compared.
  for (const char* r : {"aa_report", "grid_sweep", "bvol_report"}) {
    if (!j.contains(r)) continue;
    if (j[r].value("visible", true) == false) {
      j.erase(r);
      continue;
    }
    if (std::string(r) == "bvol_report") {
      for (json& row : j[r]["rows"]) row.erase("ns_per_ray");
      j[r]["series"].erase("ns_per_ray");
    }
  }
  return j;
}

// Equal JSON, numbers within a relative 1e-9 (the camera that follows the walk is reached along another
// sequence of float operations); the first difference's path in *where.
bool sameJson(const json& a, const json& b, std::string* where, const std::string& path = "") {
  if (a.is_number() && b.is_number()) {
    double x = a.get<double>(), y = b.get<double>();
    if (std::abs(x - y) <= 1e-9 * std::max({1.0, std::abs(x), std::abs(y)})) return true;
    *where = path + ": " + a.dump() + " vs " + b.dump();
    return false;
  }
  if (a.type() != b.type()) {
    *where = path + ": " + a.dump().substr(0, 200) + " vs " + b.dump().substr(0, 200);
    return false;
  }
  if (a.is_object()) {
    std::set<std::string> keys;
    for (auto it = a.begin(); it != a.end(); ++it) keys.insert(it.key());
    for (auto it = b.begin(); it != b.end(); ++it) keys.insert(it.key());
    for (const std::string& k : keys) {
      if (!a.contains(k) || !b.contains(k)) {
        *where = path + "/" + k + ": only in " + (a.contains(k) ? "the lesson" : "the scripted run");
        return false;
      }
      if (!sameJson(a[k], b[k], where, path + "/" + k)) return false;
    }
    return true;
  }
  if (a.is_array()) {
    if (a.size() != b.size()) {
      *where = path + ": " + std::to_string(a.size()) + " vs " + std::to_string(b.size()) + " entries";
      return false;
    }
    for (size_t i = 0; i < a.size(); ++i)
      if (!sameJson(a[i], b[i], where, path + "/" + std::to_string(i))) return false;
    return true;
  }
  if (a != b) {
    *where = path + ": " + a.dump().substr(0, 300) + " vs " + b.dump().substr(0, 300);
    return false;
  }
  return true;
}

// Pixels whose channels differ by more than 2 (the tolerance: none is expected; a follow camera reached by
// another sequence of float operations could move an edge by a pixel).
size_t differingPixels(const raystep::Rgb8Image& a, const raystep::Rgb8Image& b) {
  if (a.width != b.width || a.height != b.height) return size_t(-1);
  size_t n = 0;
  for (size_t i = 0; i < a.rgb.size(); i += 3)
    n += std::abs(int(a.rgb[i]) - int(b.rgb[i])) > 2 || std::abs(int(a.rgb[i + 1]) - int(b.rgb[i + 1])) > 2 ||
         std::abs(int(a.rgb[i + 2]) - int(b.rgb[i + 2])) > 2;
  return n;
}

std::string tagOf(const std::string& lessonPath) {
  return fs::path(lessonPath).stem().string();
}

// The lessons the equivalence tests walk: the test lessons, the format page's example (read from the page as
// if it were lessons/example.md), and every shipped lesson in lessons/ (globbed now: lessons land on their
// own).
std::string exampleFromFormatPage() {
  std::string page = slurp(kSourceDir + "/docs/lesson-format.md");
  size_t at = page.find("````markdown\n");
  EXPECT_NE(at, std::string::npos) << "docs/lesson-format.md has no example";
  if (at == std::string::npos) return "";
  at += 13;
  size_t end = page.find("\n````", at);
  std::string dir = kOut + "/format_example/lessons";
  fs::create_directories(dir);
  std::error_code ec;
  fs::create_directory_symlink(kSourceDir + "/scenes", kOut + "/format_example/scenes", ec);
  std::string path = dir + "/example.md";
  std::ofstream(path) << page.substr(at, end - at + 1);
  return path;
}

// The shipped lessons (lessons/*.md but its README), or the one RAYSTEP_LESSON names (CTest runs one lesson
// per entry, so that two run side by side and each has its own time limit).
std::vector<std::string> shippedLessons() {
  if (const char* one = std::getenv("RAYSTEP_LESSON"); one && *one) return {one};
  std::vector<std::string> out;
  if (fs::is_directory(kSourceDir + "/lessons"))
    for (const std::string& f : raystep::lesson_files(kSourceDir + "/lessons"))
      if (fs::path(f).filename() != "README.md") out.push_back(f);
  return out;
}

// A walk: one GUI process enters the listed steps (1-based) and dumps each.
std::string walk(const std::string& lesson, const std::vector<int>& steps, const std::string& tag) {
  std::string list;
  for (int n : steps) list += (list.empty() ? "" : ",") + std::to_string(n);
  std::string dir = kOut + "/walk_" + tag;
  fs::remove_all(dir);
  GuiRun r = gui("--lesson " + quote(lesson) + " --window 1280x800 --lesson-walk " + list +
                     " --dump-state-dir " + quote(dir) + " --quit",
                 "walk_" + tag);
  EXPECT_EQ(r.code, 0) << r.err;
  return dir;
}

struct Fresh {
  json state;
  raystep::Rgb8Image view;
};

// The scripted equivalent of each step (1-based), run once per step.
Fresh freshRun(const raystep::Lesson& lesson, int n) {
  static std::map<std::string, Fresh> done;
  std::string key = lesson.path + "#" + std::to_string(n);
  if (auto it = done.find(key); it != done.end()) return it->second;
  std::string tag = "fresh_" + tagOf(lesson.path) + "_" + std::to_string(n);
  std::string st = kOut + "/" + tag + ".json", png = kOut + "/" + tag + ".png";
  GuiRun r =
      gui(joinArgs(lesson.steps[size_t(n - 1)].state.scripted_args()) + " --window 1280x800 --dump-state " +
              quote(st) + " --screenshot-3d " + quote(png) + " --quit",
          tag);
  EXPECT_EQ(r.code, 0) << joinArgs(lesson.steps[size_t(n - 1)].state.scripted_args()) << "\n" << r.err;
  Fresh f;
  if (r.code == 0) {
    f.state = readJson(st);
    f.view = raystep::read_png_rgb8(png);
  }
  return done[key] = f;
}

void checkWalk(const raystep::Lesson& lesson, const std::vector<int>& steps, const std::string& name) {
  std::string dir = walk(lesson.path, steps, tagOf(lesson.path) + "_" + name);
  for (int n : steps) {
    SCOPED_TRACE(lesson.path + ", walk " + name + ", step " + std::to_string(n) + ": " +
                 joinArgs(lesson.steps[size_t(n - 1)].state.scripted_args()));
    Fresh f = freshRun(lesson, n);
    json entered = readJson(dir + "/step-" + std::to_string(n) + ".json");
    ASSERT_TRUE(entered.contains("lesson"));
    EXPECT_EQ(entered["lesson"]["step"], n);
    EXPECT_EQ(entered["lesson"]["away"], false);
    json a = withoutLessonFields(entered), b = withoutLessonFields(f.state);
    // At a question about the walk's next move the Why text, the next axis, the children a node's plane
    // sends the ray to and the events to come wait for
    // Reveal (the quiz test checks that); the rest of the panels is compared.
    const std::string question = entered["lesson"]["pane"]["quiz"].value("question", "");
    if (!question.empty() && question != "sah-plane" && question != "subdivide") {
      for (json* j : {&a, &b}) {
        (*j)["panels"].erase("ruleLabel");
        (*j)["panels"].erase("ddaLabel");
        (*j)["panels"].erase("crossingLabel");
        (*j)["panels"].erase("eventLabel");
      }
    }
    if (entered["sah"].value("concealed", false)) {
      a["sah"].erase("plots");
      b["sah"].erase("plots");
    }
    std::string where;
    EXPECT_TRUE(sameJson(a, b, &where)) << where;
    raystep::Rgb8Image view = raystep::read_png_rgb8(dir + "/step-" + std::to_string(n) + ".png");
    // At a walk question the 3D view outlines an octree cell's children in one colour, not in the order the
    // ray crosses them (the answer): drawn differently from the scripted run by design, the same children.
    const bool concealedChildren = !question.empty() && question != "sah-plane" && question != "subdivide" &&
                                   entered["view"].contains("octree_children_drawn") &&
                                   !entered["view"]["octree_children_drawn"].empty();
    if (concealedChildren)
      EXPECT_EQ(entered["view"]["octree_children_drawn"], f.state["view"]["octree_children_drawn"]);
    else
      EXPECT_EQ(differingPixels(view, f.view), 0u) << "3D view differs from the scripted run's";
  }
}

// In order, in reverse, and by jumps (first, last, middle, back to the second...).
void checkLesson(const std::string& path) {
  raystep::Lesson lesson = raystep::parse_lesson(path);
  const int n = int(lesson.steps.size());
  std::vector<int> forward, backward, jumps;
  for (int i = 1; i <= n; ++i) forward.push_back(i);
  backward.assign(forward.rbegin(), forward.rend());
  // 3, 1, n, 2, n-1, ...: every step once, reached from far away.
  std::vector<int> rest = forward;
  if (n >= 3) {
    jumps.push_back(3);
    rest.erase(rest.begin() + 2);
  }
  for (bool low = true; !rest.empty(); low = !low) {
    jumps.push_back(low ? rest.front() : rest.back());
    if (low)
      rest.erase(rest.begin());
    else
      rest.pop_back();
  }
  checkWalk(lesson, forward, "forward");
  checkWalk(lesson, backward, "backward");
  checkWalk(lesson, jumps, "jumps");
}

TEST(Lesson, StepsEnteredInAnyOrderShowTheScriptedRun) {
  for (const char* f : {"grid-walk.md", "kd-walk.md"}) checkLesson(kSourceDir + "/tests/viz/data/" + f);
  checkLesson(exampleFromFormatPage());
}

TEST(Lesson, ShippedLessonsShowTheScriptedRun) {
  std::vector<std::string> lessons = shippedLessons();
  if (lessons.empty()) GTEST_SKIP() << "no lessons/ yet";
  for (const std::string& f : lessons) checkLesson(f);
}

// The clicker's keys: PageDown and Right forward, PageUp and Left back, Home and End; the walk's own keys are
// Shift+Right/Left (and . ,) in a lesson; F5 full screen.
TEST(Lesson, ClickerKeysMoveBetweenSteps) {
  const std::string lesson = kSourceDir + "/tests/viz/data/grid-walk.md";
  struct Case {
    std::string keys;
    int step;
  };
  for (const Case& c : {Case{"PageDown", 2}, Case{"PageDown,Right,Right", 4}, Case{"End,PageUp", 5},
                        Case{"End,Left,Left,Home,Right", 2}, Case{"PageUp", 1}, Case{"End,PageDown", 6}}) {
    std::string st = kOut + "/keys.json";
    GuiRun r =
        gui("--lesson " + quote(lesson) + " --keys " + c.keys + " --dump-state " + quote(st) + " --quit",
            "lesson_keys");
    ASSERT_EQ(r.code, 0) << r.err;
    json j = readJson(st);
    EXPECT_EQ(j["lesson"]["step"], c.step) << c.keys;
    EXPECT_EQ(j["lesson"]["away"], false) << c.keys;
  }
  // Step 1 is at cell:1 (event 1): Shift+Right steps the walk, the lesson stays at step 1 and says so.
  std::string st = kOut + "/keys_walk.json";
  GuiRun r =
      gui("--lesson " + quote(lesson) + " --keys Shift+Right,Shift+Right,Period,Shift+Left --dump-state " +
              quote(st) + " --quit",
          "lesson_keys_walk");
  ASSERT_EQ(r.code, 0) << r.err;
  json j = readJson(st);
  EXPECT_EQ(j["lesson"]["step"], 1);
  EXPECT_EQ(j["lesson"]["away"], true);
  EXPECT_EQ(j["step"], 3);
  // F5: full screen and back.
  GuiRun f =
      gui("--lesson " + quote(lesson) + " --keys F5 --dump-state " + quote(st) + " --quit", "lesson_f5");
  ASSERT_EQ(f.code, 0) << f.err;
  EXPECT_EQ(readJson(st)["full_screen"], true);
}

void writeFile(const std::string& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A damaged lesson: one line "error: FILE:LINE: what", exit 2, nothing written; through File > Open lesson
// the error goes to a dialog and the window keeps its lesson and step.
TEST(Lesson, DamagedLessonExits2WithFileAndLine) {
  const std::string bad = kOut + "/damaged.md";
  writeFile(
      bad,
      "# Damaged\n\n## One\n\n```raystep\nscene: " + kSourceDir +
          "/scenes/cornell.json\npixel: 160,200\n```\n\n## Two\n\n```raystep\nstep-to: teleport:1\n```\n");
  std::string png = kOut + "/damaged.png";
  fs::remove(png);
  GuiRun r = gui("--lesson " + quote(bad) + " --screenshot " + quote(png) + " --quit", "lesson_damaged");
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("error: " + bad + ":13: "), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("teleport"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(png)) << "nothing is written on error";
  // A step that parses but cannot be reached names its heading's line.
  const std::string far = kOut + "/unreachable.md";
  writeFile(far, "# Unreachable\n\n## One\n\n```raystep\nscene: " + kSourceDir +
                     "/scenes/cornell.json\npixel: 400,1\n```\n");
  GuiRun u = gui("--lesson " + quote(far) + " --quit", "lesson_unreachable");
  EXPECT_EQ(u.code, 2);
  EXPECT_NE(u.err.find("error: " + far + ":3: pixel 400,1: outside the 320x320 image"), std::string::npos)
      << u.err;

  // Through the GUI: the window keeps what it had.
  const std::string good = kSourceDir + "/tests/viz/data/kd-walk.md";
  std::string before = kOut + "/damaged_before.json", after = kOut + "/damaged_after.json";
  ASSERT_EQ(gui("--lesson " + quote(good) + " --lesson-step 3 --dump-state " + quote(before) + " --quit",
                "lesson_damaged_before")
                .code,
            0);
  GuiRun g = gui("--lesson " + quote(good) + " --lesson-step 3 --open-lesson-bad " + quote(bad) +
                     " --dump-state " + quote(after) + " --quit",
                 "lesson_damaged_gui");
  EXPECT_EQ(g.code, 0) << g.err;
  json a = readJson(before), b = readJson(after);
  EXPECT_NE(b["last_error"].get<std::string>().find(bad + ":13:"), std::string::npos) << b["last_error"];
  b.erase("last_error");
  a.erase("last_error");
  std::string where;
  EXPECT_TRUE(sameJson(a, b, &where)) << where;
}

// The handout: index.html with the title, one figure per step (the PNG the step's show names), every question
// with its answer inside <details>; written atomically over an older handout.
TEST(Lesson, HandoutHasAFigurePerStepAndFoldedAnswers) {
  const std::string lesson = kSourceDir + "/tests/viz/data/grid-walk.md";
  raystep::Lesson parsed = raystep::parse_lesson(lesson);
  const std::string dir = kOut + "/handout";
  fs::remove_all(dir);
  fs::create_directories(dir);
  writeFile(dir + "/stale.txt", "from an older handout");
  GuiRun r =
      gui("--lesson " + quote(lesson) + " --export-handout " + quote(dir) + " --quit", "lesson_handout");
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(dir + "/stale.txt")) << "the handout replaces the folder";
  for (const auto& e : fs::directory_iterator(fs::path(dir).parent_path()))
    EXPECT_EQ(e.path().filename().string().find(".handout.tmp-"), std::string::npos) << e.path();
  std::string html = slurp(dir + "/index.html");
  EXPECT_NE(html.find("<h1>Test lesson: the grid walk"), std::string::npos);
  // The interactive page beside it (the browser player's, tests/web), linked from the printable one.
  EXPECT_NE(html.find("<a href=\"interactive.html\">"), std::string::npos);
  const std::string interactive = slurp(dir + "/interactive.html");
  EXPECT_EQ(interactive.rfind("<!DOCTYPE html>", 0), 0u);
  EXPECT_NE(interactive.find("<title>Test lesson: the grid walk"), std::string::npos);
  EXPECT_NE(interactive.find("id=\"raystep-data\""), std::string::npos);
  size_t asks = 0;
  for (size_t i = 0; i < parsed.steps.size(); ++i) {
    const std::string png = "step-" + std::to_string(i + 1) + ".png";
    EXPECT_TRUE(fs::exists(dir + "/" + png)) << png;
    EXPECT_NE(html.find("<img src=\"" + png + "\""), std::string::npos) << png;
    asks += parsed.steps[i].ask.has_value();
  }
  size_t details = 0;
  for (size_t at = html.find("<details>"); at != std::string::npos; at = html.find("<details>", at + 1))
    ++details;
  EXPECT_EQ(details, asks);
  // The figures are what `show:` names (carried over like any setting): the 3D view, the picture (the image
  // panel's canvas, narrower than the 3D view), or for `window` the figure the state names: here a traced
  // pixel's 3D view with the state panel beside it (never the whole window with its buttons).
  const int viewWidth = freshRun(parsed, 1).state["view"]["viewport"][2].get<int>();
  for (size_t i = 0; i < parsed.steps.size(); ++i) {
    raystep::Rgb8Image img = raystep::read_png_rgb8(dir + "/step-" + std::to_string(i + 1) + ".png");
    const std::string& show = parsed.steps[i].state.show;
    if (show == "3d") EXPECT_EQ(img.width, viewWidth) << i + 1;
    if (show == "window") {
      EXPECT_GT(img.width, viewWidth) << i + 1;
      EXPECT_LT(img.width, 1280) << i + 1;
    }
    if (show == "picture") EXPECT_TRUE(img.width != viewWidth && img.width < 1280) << i + 1;
  }
}

// Lesson 12's handout: each figure is the one its step names, never the window. The stack's step draws the
// tree (the current node yellow, the node waiting on the stack pink, the root visited blue) with the state
// panel beside it; the walk's steps show the 3D view with the state panel; the pseudocode stays code.
TEST(Lesson, Lesson12HandoutDrawsTheTreeAndTheWalk) {
  const std::string lesson = kSourceDir + "/lessons/12-kdtree-traversal.md";
  if (!fs::exists(lesson)) GTEST_SKIP() << "no lessons/ yet";
  const raystep::Lesson parsed = raystep::parse_lesson(lesson);
  const std::string dir = kOut + "/handout12";
  fs::remove_all(dir);
  GuiRun r = gui("--lesson " + quote(lesson) + " --export-handout " + quote(dir) + " --quit", "lesson_handout12");
  ASSERT_EQ(r.code, 0) << r.err;
  const std::string html = slurp(dir + "/index.html");
  EXPECT_NE(html.find("<pre><code>Intersect(node, tmin, tmax):\n  if node is a leaf"), std::string::npos)
      << "the pseudocode keeps its lines and indentation";
  int trees = 0;
  for (size_t i = 0; i < parsed.steps.size(); ++i) {
    const std::string n = std::to_string(i + 1);
    const auto at = html.find("<figcaption>Step " + n + ": ");
    ASSERT_NE(at, std::string::npos) << n;
    const std::string caption = html.substr(at, html.find("</figcaption>", at) - at);
    EXPECT_EQ(caption.find("the debugger"), std::string::npos) << caption;
    const raystep::Rgb8Image img = raystep::read_png_rgb8(dir + "/step-" + n + ".png");
    EXPECT_LT(img.width, 3000) << n;
    if (parsed.steps[i].state.show == "tree") {
      ++trees;
      EXPECT_NE(caption.find("the tree and the state panel"), std::string::npos) << caption;
      // The boxes of the tree drawing: at least one current node, one on the stack, one visited.
      const json yellow = {255, 214, 0}, pink = {255, 130, 170}, blue = {90, 140, 255};
      EXPECT_GT(countColor(img, yellow, 0, 0, img.width, img.height, 2), 400) << n;
      EXPECT_GT(countColor(img, pink, 0, 0, img.width, img.height, 2), 400) << n;
      EXPECT_GT(countColor(img, blue, 0, 0, img.width, img.height, 2), 400) << n;
    } else {
      EXPECT_NE(caption.find("the 3D view"), std::string::npos) << caption;
    }
  }
  EXPECT_GE(trees, 1) << "lesson 12 draws the tree where its stack holds nodes";
}

// The classroom layout: lessons 09, 11, 12 and 16 presented at scale 2 on a 1920 x 1080 projector. In every
// step the window fits the screen, the step's figure (the 3D view, the picture, the tree or the chart) takes at
// least half of its width (the tree, below the state panel, the width of the debugger), the text is about
// 28 px a line, nothing is wider than its room (the state panel's right edge), the structure line has the
// height its text wraps to, and a tree walk's stack is in view.
TEST(Lesson, ClassroomLayoutFitsAProjector) {
  int checked = 0;
  for (const char* name : {"09-3d-dda", "11-sah-build", "12-kdtree-traversal", "16-octree"}) {
    const std::string lesson = kSourceDir + "/lessons/" + name + ".md";
    if (!fs::exists(lesson)) continue;
    const raystep::Lesson parsed = raystep::parse_lesson(lesson);
    std::string list;
    for (size_t i = 1; i <= parsed.steps.size(); ++i) list += (list.empty() ? "" : ",") + std::to_string(i);
    const std::string dir = kOut + "/classroom_" + name;
    fs::remove_all(dir);
    GuiRun r = gui("--lesson " + quote(lesson) + " --scale 2 --window 1920x1080 --lesson-walk " + list +
                       " --dump-state-dir " + quote(dir) + " --quit",
                   std::string("classroom_") + name);
    ASSERT_EQ(r.code, 0) << r.err;
    for (size_t i = 1; i <= parsed.steps.size(); ++i) {
      const json st = readJson(dir + "/step-" + std::to_string(i) + ".json");
      const std::string where = std::string(name) + " step " + std::to_string(i);
      ASSERT_TRUE(st.contains("classroom")) << where;
      const json& c = st["classroom"];
      EXPECT_TRUE(c["active"].get<bool>()) << where;
      const int screenW = c["screen"][0].get<int>(), screenH = c["screen"][1].get<int>();
      const int w = st["window"][0].get<int>(), h = st["window"][1].get<int>();
      EXPECT_LE(w, screenW) << where;
      EXPECT_LE(h, screenH) << where;
      EXPECT_GE(c["font_px"].get<int>(), 28) << where;
      const json& parts = c["parts"];
      for (const auto& [part, rect] : parts.items()) {
        EXPECT_GE(rect[0].get<int>(), 0) << where << " " << part;
        EXPECT_LE(rect[0].get<int>() + rect[2].get<int>(), w) << where << " " << part << " goes off the window";
        EXPECT_LE(rect[1].get<int>() + rect[3].get<int>(), h) << where << " " << part << " goes off the window";
      }
      const std::string figure = c["figure"].get<std::string>();
      const char* key = figure == "the 3D view"     ? "3d"
                        : figure == "the picture"   ? "picture"
                        : figure == "the SAH chart" ? "chart"
                        : figure == "the tree"      ? "tree"
                                                    : nullptr;
      ASSERT_NE(key, nullptr) << where << ": " << figure;
      ASSERT_TRUE(parts.contains(key)) << where << ": " << figure << " not shown: " << parts.dump();
      EXPECT_GE(2 * parts[key][2].get<int>(), w) << where << ": " << figure << " narrower than half the window";
      EXPECT_TRUE(parts.contains("lesson")) << where;
      if (c.contains("state_need")) {
        EXPECT_LE(c["state_need"][0].get<int>(), c["state_room"][0].get<int>())
            << where << ": the state panel is cut off on the right";
      }
      if (c.contains("structure_clipped")) EXPECT_FALSE(c["structure_clipped"].get<bool>()) << where;
      if (c.contains("stack_in_view")) EXPECT_TRUE(c["stack_in_view"].get<bool>()) << where;
      ++checked;
    }
  }
  EXPECT_GT(checked, 20) << "the four lessons' steps";
}

// The quiz: a prediction typed for the step's question is marked by core's prediction_matches against the
// answer core computes (here computed again headless by LessonRunner), the answer and why are shown, the walk
// steps to what was asked, and the score counts. Predict mode does the same for the next cell of any ray.
TEST(Lesson, QuizMarksRightAndWrongPredictions) {
  const std::string path = kSourceDir + "/tests/viz/data/grid-walk.md";
  raystep::Lesson lesson = raystep::parse_lesson(path);
  raystep::LessonRunner runner;
  // Step 2 asks next-cell, step 5 dda-axis.
  raystep::StepWorld w2 = runner.enter(lesson.steps[1].state, lesson.steps[1].ask);
  raystep::StepWorld w5 = runner.enter(lesson.steps[4].state, lesson.steps[4].ask);
  ASSERT_TRUE(w2.answer && w5.answer);
  const raystep::Answer& cell = *w2.answer;
  std::string right = cell.stops ? "stop"
                                 : std::to_string(cell.cell[0]) + "," + std::to_string(cell.cell[1]) + "," +
                                       std::to_string(cell.cell[2]);
  std::string wrong = cell.stops ? "0,0,0" : "stop";
  struct Case {
    int step;
    std::string prediction;
    bool right;
  };
  const std::string axis = std::string(w5.answer->axis < 0 ? "none" : std::string(1, "xyz"[w5.answer->axis]));
  for (const Case& c : {Case{2, right, true}, Case{2, wrong, false}, Case{5, axis, true},
                        Case{5, axis == "x" ? "y" : "x", false}}) {
    SCOPED_TRACE("step " + std::to_string(c.step) + " predicting " + c.prediction);
    std::string st = kOut + "/quiz.json";
    GuiRun r = gui("--lesson " + quote(path) + " --lesson-step " + std::to_string(c.step) + " --predict " +
                       quote(c.prediction) + " --dump-state " + quote(st) + " --quit",
                   "lesson_quiz");
    ASSERT_EQ(r.code, 0) << r.err;
    json j = readJson(st);
    const json& quiz = j["lesson"]["pane"]["quiz"];
    EXPECT_EQ(quiz["right"], c.right) << quiz.dump(1);
    EXPECT_EQ(j["lesson"]["right"], c.right ? 1 : 0);
    EXPECT_EQ(j["lesson"]["asked"], 1);
    const raystep::Answer& answer = c.step == 2 ? cell : *w5.answer;
    EXPECT_NE(quiz["result"].get<std::string>().find(answer.text.substr(0, 12)), std::string::npos)
        << quiz["result"];
    EXPECT_NE(quiz["result"].get<std::string>().find("Debugger, at the walk's next step:"), std::string::npos)
        << quiz["result"];
    // A wrong prediction is answered with the feedback aimed at its misconception first.
    const std::string feedback = raystep::prediction_feedback(answer, c.prediction);
    EXPECT_EQ(feedback.empty(), c.right);
    if (!c.right)
      EXPECT_NE(quiz["result"].get<std::string>().find(feedback.substr(0, 30)), std::string::npos) << quiz["result"];
    EXPECT_EQ(j["panels"]["ruleLabel"].get<std::string>().find("Shown with the answer"), std::string::npos)
        << "revealed: the Why text is back";
    EXPECT_EQ(j["lesson"]["away"], true) << "the walk stepped to what was asked";
    if (c.step == 2 && !cell.stops) {  // ... to the cell the answer names
      EXPECT_EQ(j["event_type"], "cell");
      EXPECT_EQ(j["view"]["current_cell"]["cell"], json({cell.cell[0], cell.cell[1], cell.cell[2]}));
    }
  }
  // Before Reveal the Why text and the next axis say nothing of the answer.
  {
    std::string st = kOut + "/quiz_concealed.json";
    GuiRun r = gui("--lesson " + quote(path) + " --lesson-step 5 --dump-state " + quote(st) + " --quit",
                   "lesson_quiz_concealed");
    ASSERT_EQ(r.code, 0) << r.err;
    json j = readJson(st);
    EXPECT_NE(j["panels"]["ruleLabel"].get<std::string>().find("Shown with the answer"), std::string::npos) << j["panels"];
    EXPECT_NE(j["panels"]["ddaLabel"].get<std::string>().find("next axis: <i>?"), std::string::npos)
        << j["panels"];
  }

  // sah-plane (the kd lesson's step 2): the chart hides the SAH's choice until the answer is revealed.
  const std::string kdPath = kSourceDir + "/tests/viz/data/kd-walk.md";
  raystep::Lesson kd = raystep::parse_lesson(kdPath);
  raystep::StepWorld root = runner.enter(kd.steps[1].state, kd.steps[1].ask);
  ASSERT_TRUE(root.answer && root.answer->axis >= 0);
  char buf[64];
  std::snprintf(buf, sizeof buf, "%c,%.9g", "xyz"[root.answer->axis], double(root.answer->position));
  for (bool reveal : {false, true}) {
    std::string st = kOut + "/quiz_sah.json";
    GuiRun r = gui("--lesson " + quote(kdPath) + " --lesson-step 2" +
                       (reveal ? " --predict " + quote(buf) : "") + " --dump-state " + quote(st) + " --quit",
                   "lesson_quiz_sah");
    ASSERT_EQ(r.code, 0) << r.err;
    json j = readJson(st);
    EXPECT_EQ(j["sah"]["concealed"], !reveal);
    EXPECT_EQ(j["sah"]["node"], 0);
    if (reveal) EXPECT_EQ(j["lesson"]["pane"]["quiz"]["right"], true) << j["lesson"]["pane"]["quiz"].dump(1);
  }

  // Predict mode on step 1's ray (at its first cell): the next cell is step 2's (cell:2), then a wrong guess.
  const json next = freshRun(lesson, 2).state["view"]["current_cell"]["cell"];
  std::string second = std::to_string(next[0].get<int>()) + "," + std::to_string(next[1].get<int>()) + "," +
                       std::to_string(next[2].get<int>());
  std::string st = kOut + "/quiz_predict.json";
  GuiRun r = gui("--lesson " + quote(path) + " --lesson-step 1 --predict-next " + quote(second + ";stop") +
                     " --dump-state " + quote(st) + " --quit",
                 "lesson_quiz_predict");
  ASSERT_EQ(r.code, 0) << r.err;
  json j = readJson(st);
  EXPECT_EQ(j["lesson"]["right"], 1);
  EXPECT_EQ(j["lesson"]["asked"], 2);
  EXPECT_EQ(j["lesson"]["pane"]["quiz"]["right"], false);
  EXPECT_EQ(j["lesson"]["pane"]["quiz"]["score"], "Score: 1 / 2");
}

}  // namespace
