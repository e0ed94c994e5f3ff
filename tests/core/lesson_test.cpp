// Tests of lessons (lesson_state.h, lesson.h): every setting and its carry-over from step to step, clearing
// with none/scene, the errors with their file and line, code fences, and the raystep-gui command line of a
// state.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include <unistd.h>

#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

const std::string kSource = RAYSTEP_SOURCE_DIR;
const std::string kLesson = kSource + "/lessons/test.md";  // need not exist: it names the file and its folder
const std::string kCornell =
    (std::filesystem::path(kSource) / "scenes/cornell.json").lexically_normal().string();

// The error a lesson text gives, as "FILE:LINE: what".
std::string error_of(const std::string& text) {
  try {
    parse_lesson_text(text, kLesson);
  } catch (const InputError& e) {
    return e.what();
  }
  return "no error";
}

std::string lesson_with(const std::string& block) {
  return "# T\n\n## S\n\n```raystep\nscene: ../scenes/cornell.json\n" + block + "```\n";
}

TEST(Lesson, ParsesTitleIntroStepsAndNarration) {
  Lesson l = parse_lesson_text(
      "# The title\n\nIntro text.\n\n## First\n\nSome *narration*.\n\n```raystep\n# a comment\nscene: "
      "../scenes/cornell.json\n\naccel: kd\n```\n\nMore.\n\n### A sub-heading\n\n## Second # \n\nText two.\n",
      kLesson);
  EXPECT_EQ(l.title, "The title");
  EXPECT_EQ(l.intro, "Intro text.\n");
  ASSERT_EQ(l.steps.size(), 2u);
  EXPECT_EQ(l.steps[0].title, "First");
  EXPECT_EQ(l.steps[0].line, 5);
  EXPECT_EQ(l.steps[0].narration, "Some *narration*.\n\n\nMore.\n\n### A sub-heading\n");
  ASSERT_EQ(l.steps[0].changes.size(), 2u);
  EXPECT_EQ(l.steps[0].changes[0].key, "scene");
  EXPECT_EQ(l.steps[0].changes[0].line, 11);
  EXPECT_EQ(l.steps[0].changes[1].value, "kd");
  EXPECT_EQ(l.steps[0].changes[1].line, 13);
  EXPECT_EQ(l.steps[0].state.scene, kCornell);
  EXPECT_EQ(l.steps[1].title, "Second");
  EXPECT_EQ(l.steps[1].narration, "Text two.\n");
  EXPECT_EQ(l.steps[1].state.accel, "kd");
  EXPECT_TRUE(l.steps[1].changes.empty());
}

// Every key set in step 1 carries over to step 2, which changes nothing.
TEST(Lesson, EveryKeyCarriesOver) {
  Lesson l =
      parse_lesson_text(lesson_with("accel: kd-median\ngrid-res: 4,5,6\ngrid-density: 2.5\n"
                                    "grid-insert: bbox\nti: 40\ntt: 2\nempty-bonus: 0.5\nmax-depth: 12\n"
                                    "leaf-size: 3\nmailbox: off\nbins: 8\nbvh-leaf: 2\nbvh-max-leaf: 6\n"
                                    "bvh-order: axis\noctree-leaf: 4\nbsp-directions: kdop\nbsp-candidates: 8\n"
                                    "aa: adaptive:0.1:2\nsize: 64x48\n"
                                    "heat: tests\npixel: 10,20\nsecondary: on\nray: 1\nstep-to: leaf:2\n"
                                    "panel: sah\nnode-path: LR\ninspect: on\nsquare: 2\nfollow: on\n"
                                    "translucent: on\nzoom: 8\nsample-overlay: on\nshow: chart\n"
                                    "crofton-lines: on\nflat-aa: on\n") +
                            "\n## Two\n\nNothing changes.\n",
                        kLesson);
  ASSERT_EQ(l.steps.size(), 2u);
  EXPECT_EQ(l.steps[0].changes.size(), 36u);
  // Every documented key was exercised (ask aside, which is not a setting).
  EXPECT_EQ(lesson_setting_keys().size(), 41u);  // + step, node, sample (below) and report (not carried over)
  const LessonState& s = l.steps[1].state;
  EXPECT_EQ(s.scene, kCornell);
  EXPECT_EQ(s.accel, "kd-median");
  EXPECT_TRUE(s.crofton_lines);  // the 2D view's (a 2D scene's)
  EXPECT_TRUE(s.flat_aa);
  ASSERT_TRUE(s.structure.grid.resolution);
  EXPECT_EQ(*s.structure.grid.resolution, (std::array<int, 3>{4, 5, 6}));
  EXPECT_FLOAT_EQ(s.structure.grid.density, 2.5f);
  EXPECT_FALSE(s.structure.grid.exact_insert);
  EXPECT_FLOAT_EQ(s.structure.kd.t_i, 40.f);
  EXPECT_FLOAT_EQ(s.structure.kd.t_t, 2.f);
  EXPECT_FLOAT_EQ(s.structure.kd.empty_bonus, 0.5f);
  EXPECT_EQ(s.structure.kd.max_depth, 12);
  EXPECT_EQ(s.structure.kd.leaf_size, 3);
  EXPECT_FALSE(s.structure.kd_mailboxes);
  // The BVH takes the kd-tree's t_i, t_t and depth limit (as raystep's --ti, --tt, --max-depth), and its own.
  EXPECT_FLOAT_EQ(s.structure.bvh.t_i, 40.f);
  EXPECT_FLOAT_EQ(s.structure.bvh.t_t, 2.f);
  EXPECT_EQ(s.structure.bvh.max_depth, 12);
  EXPECT_EQ(s.structure.bvh.bins, 8);
  EXPECT_EQ(s.structure.bvh.leaf_size, 2);
  EXPECT_EQ(s.structure.bvh.max_leaf_size, 6);
  EXPECT_EQ(s.structure.bvh_order, BvhOrder::split_axis);
  // The octree's and the BSP tree's own; the BSP tree takes the kd-tree's costs and limits, the octree its
  // depth limit.
  EXPECT_EQ(s.structure.octree.leaf_size, 4);
  EXPECT_EQ(s.structure.octree.max_depth, 12);
  EXPECT_EQ(s.structure.bsp.directions, BspDirections::kdop);
  EXPECT_EQ(s.structure.bsp.candidates, 8);
  EXPECT_FLOAT_EQ(s.structure.bsp.t_i, 40.f);
  EXPECT_FLOAT_EQ(s.structure.bsp.t_t, 2.f);
  EXPECT_EQ(s.structure.bsp.max_depth, 12);
  EXPECT_EQ(s.structure.bsp.leaf_size, 3);
  EXPECT_EQ(s.aa, "adaptive:0.1:2");
  EXPECT_EQ(s.size, (std::array<int, 2>{64, 48}));
  EXPECT_EQ(s.heat, "tests");
  EXPECT_EQ(s.pixel, (std::array<int, 2>{10, 20}));
  EXPECT_TRUE(s.secondary);
  EXPECT_EQ(s.ray, 1);
  EXPECT_EQ(s.event.by, EventSpec::By::nth);
  EXPECT_EQ(s.event.type, EventType::leaf);
  EXPECT_EQ(s.event.k, 2);
  EXPECT_EQ(s.panel, "sah");
  EXPECT_EQ(s.node.by, NodeSpec::By::path);
  EXPECT_EQ(s.node.path, "LR");
  EXPECT_TRUE(s.follow);
  EXPECT_TRUE(s.translucent);
  EXPECT_EQ(s.zoom, 8.0);
  EXPECT_EQ(s.show, "chart");
  EXPECT_TRUE(s.inspect);
  EXPECT_EQ(s.square, 2);
  EXPECT_TRUE(s.sample_overlay);
}

// The octree and the general BSP tree: their names, their own options on the GUI's command line (defaults
// left out), bad values refused.
TEST(Lesson, OctreeAndBspSettings) {
  for (const char* name : {"octree", "bsp"})
    EXPECT_EQ(
        parse_lesson_text(lesson_with(std::string("accel: ") + name + "\n"), kLesson).steps[0].state.accel,
        name);
  Lesson l = parse_lesson_text(lesson_with("accel: bsp\nbsp-directions: autopartition\nbsp-candidates: 32\n"
                                           "octree-leaf: 3\n") +
                                   "## B\n```raystep\naccel: octree\nbsp-directions: both\n```\n",
                               kLesson);
  const std::vector<std::string> a = l.steps[0].state.scripted_args();
  const std::vector<std::string> expected = {"--accel", "bsp", "--octree-leaf", "3", "--bsp-directions",
                                             "autopartition", "--bsp-candidates", "32"};
  EXPECT_EQ(std::vector<std::string>(a.begin() + 1, a.end()), expected);
  const std::vector<std::string> b = l.steps[1].state.scripted_args();
  EXPECT_EQ(std::find(b.begin(), b.end(), "--bsp-directions"), b.end());  // back to the default
  EXPECT_NE(std::find(b.begin(), b.end(), "octree"), b.end());
  for (const char* bad : {"accel: quadtree\n", "octree-leaf: 0\n", "octree-leaf: x\n",
                          "bsp-directions: sideways\n", "bsp-candidates: 0\n", "bsp-candidates: 4097\n"})
    EXPECT_THROW(parse_lesson_text(lesson_with(bad), kLesson), InputError) << bad;
}

// The bounding volume hierarchies: every BVH name, its options on the GUI's command line (defaults left out),
// box tests and skips as step kinds, the boxes heat map, and bad values refused.
TEST(Lesson, BvhSettings) {
  for (const char* name : {"bvh", "bvh-sweep", "bvh-median", "bvh4", "bvh8"})
    EXPECT_EQ(
        parse_lesson_text(lesson_with(std::string("accel: ") + name + "\n"), kLesson).steps[0].state.accel,
        name);
  Lesson l =
      parse_lesson_text(lesson_with("accel: bvh\nbins: 32\nbvh-order: axis\nheat: boxes\nmax-depth: 0\n"
                                    "pixel: 1,2\nstep-to: box_test:3\n") +
                            "## B\n```raystep\nstep-to: skip:1\nbvh-order: entry\nbins: 16\n```\n",
                        kLesson);
  const LessonState& a = l.steps[0].state;
  EXPECT_EQ(a.structure.bvh.max_depth, kBvhMaxDepth);  // 0: the BVH's own limit
  EXPECT_EQ(a.event.type, EventType::box_test);
  EXPECT_EQ(a.heat, "boxes");
  const std::vector<std::string> args = a.scripted_args();
  const std::vector<std::string> expected = {"--accel",     "bvh",  "--bins",    "32",
                                             "--bvh-order", "axis", "--heat",    "boxes",
                                             "--pixel",     "1,2",  "--step-to", "box_test:3"};
  EXPECT_EQ(std::vector<std::string>(args.begin() + 1, args.end()), expected);
  EXPECT_EQ(l.steps[1].state.event.type, EventType::skip);
  const std::vector<std::string> b = l.steps[1].state.scripted_args();
  EXPECT_EQ(std::find(b.begin(), b.end(), "--bins"), b.end());  // back to the default
  EXPECT_EQ(std::find(b.begin(), b.end(), "--bvh-order"), b.end());
  for (const char* bad : {"accel: bvh2\n", "bins: 1\n", "bins: 257\n", "bvh-leaf: 0\n", "bvh-max-leaf: x\n",
                          "bvh-order: nearest\n", "heat: box\n", "max-depth: 65\n", "step-to: box:1\n"})
    EXPECT_THROW(parse_lesson_text(lesson_with(bad), kLesson), InputError) << bad;
}

// A sample names a ray of the pixel's trace: it and `ray` replace each other, and a new pixel clears both it
// and the adaptive square.
TEST(Lesson, SampleAndRayReplaceEachOther) {
  Lesson l =
      parse_lesson_text(lesson_with("pixel: 3,4\nray: 2\nsample: 5\nsquare: 3\n") +
                            "## B\n```raystep\nray: 1\n```\n## C\n```raystep\nsample: 2\npixel: 1,1\n```\n",
                        kLesson);
  EXPECT_EQ(l.steps[0].state.ray, 0);
  EXPECT_EQ(l.steps[0].state.sample, 5);
  EXPECT_EQ(l.steps[0].state.square, 3);
  EXPECT_EQ(l.steps[1].state.ray, 1);
  EXPECT_FALSE(l.steps[1].state.sample);
  EXPECT_FALSE(l.steps[2].state.sample);
  EXPECT_FALSE(l.steps[2].state.square);
  const std::vector<std::string> a = l.steps[0].state.scripted_args();
  EXPECT_NE(std::find(a.begin(), a.end(), "--sample"), a.end());
  EXPECT_NE(std::find(a.begin(), a.end(), "--square"), a.end());
  EXPECT_THROW(parse_lesson_text(lesson_with("sample: -1\n"), kLesson), InputError);
  EXPECT_THROW(parse_lesson_text(lesson_with("square: x\n"), kLesson), InputError);
}

TEST(Lesson, StepAndNodeAreOneSettingEach) {
  Lesson l = parse_lesson_text(lesson_with("step-to: cell:3\nstep: 7\nnode-path: L\nnode: 5\n") +
                                   "## B\n```raystep\nstep-to: hit:1\nnode-path: RR\n```\n",
                               kLesson);
  EXPECT_EQ(l.steps[0].state.event.by, EventSpec::By::index);
  EXPECT_EQ(l.steps[0].state.event.index, 7);
  EXPECT_EQ(l.steps[0].state.node.by, NodeSpec::By::id);
  EXPECT_EQ(l.steps[0].state.node.id, 5);
  EXPECT_EQ(l.steps[1].state.event.by, EventSpec::By::nth);
  EXPECT_EQ(l.steps[1].state.event.type, EventType::hit_accepted);
  EXPECT_EQ(l.steps[1].state.node.by, NodeSpec::By::path);
}

TEST(Lesson, NoneAndSceneClear) {
  Lesson l =
      parse_lesson_text(lesson_with("grid-res: 2,2,2\naa: jitter:2\nsize: 10x10\nheat: cells\npixel: 1,1\n"
                                    "panel: kd\nnode: 3\n") +
                            "## B\n```raystep\ngrid-res: none\naa: scene\nsize: scene\nheat: none\n"
                            "pixel: none\npanel: none\nnode: none\n```\n",
                        kLesson);
  const LessonState& a = l.steps[0].state;
  EXPECT_TRUE(a.structure.grid.resolution && a.size && a.pixel);
  EXPECT_EQ(a.aa, "jitter:2");
  const LessonState& s = l.steps[1].state;
  EXPECT_FALSE(s.structure.grid.resolution);
  EXPECT_EQ(s.aa, "");
  EXPECT_FALSE(s.size);
  EXPECT_EQ(s.heat, "");
  EXPECT_FALSE(s.pixel);
  EXPECT_EQ(s.panel, "");
  EXPECT_EQ(s.node.by, NodeSpec::By::none);
  // aa: none is the no-anti-aliasing spec, not the scene's.
  EXPECT_EQ(parse_lesson_text(lesson_with("aa: none\n"), kLesson).steps[0].state.aa, "none");
}

TEST(Lesson, PixelAndRayResetTheEvent) {
  Lesson l =
      parse_lesson_text(lesson_with("pixel: 1,2\nray: 2\nstep: 9\n") + "## B\n```raystep\npixel: 3,4\n```\n" +
                            "## C\n```raystep\nray: 1\nstep: 4\n```\n## D\n```raystep\nray: 3\n```\n",
                        kLesson);
  EXPECT_EQ(l.steps[0].state.event.index, 9);
  EXPECT_EQ(l.steps[1].state.event.by, EventSpec::By::start);
  EXPECT_EQ(l.steps[1].state.ray, 0);  // a new pixel is a new trace, from its primary ray
  EXPECT_EQ(l.steps[2].state.event.index, 4);
  EXPECT_EQ(l.steps[3].state.event.by, EventSpec::By::start);
  EXPECT_EQ(l.steps[3].state.ray, 3);
}

TEST(Lesson, AskIsNotCarriedOver) {
  Lesson l = parse_lesson_text(lesson_with("pixel: 1,1\nask: dda-axis\n") + "## B\ntext\n", kLesson);
  ASSERT_TRUE(l.steps[0].ask);
  EXPECT_EQ(*l.steps[0].ask, QuestionKind::dda_axis);
  EXPECT_EQ(l.steps[0].ask_line, 8);
  EXPECT_EQ(l.steps[0].changes.size(), 2u);  // scene, pixel: ask is not a change of state
  EXPECT_FALSE(l.steps[1].ask);
}

TEST(Lesson, HeadingsAndBlocksInsideOtherFencesAreNarration) {
  Lesson l = parse_lesson_text(
      "# T\n## S\n```raystep\nscene: ../scenes/cornell.json\n```\n\n````markdown\n# Not a title\n## Not a "
      "step\n"
      "```raystep\nscene: nowhere.json\n```\n````\n\n~~~\n## still not\n~~~\n```cpp\n# include\n```\n",
      kLesson);
  ASSERT_EQ(l.steps.size(), 1u);
  EXPECT_EQ(l.title, "T");
  EXPECT_NE(l.steps[0].narration.find("## Not a step"), std::string::npos);
  EXPECT_NE(l.steps[0].narration.find("~~~\n## still not\n~~~"), std::string::npos);
}

TEST(Lesson, ErrorsNameFileAndLine) {
  const std::string f = kLesson + ":";
  EXPECT_EQ(error_of("# T\n\n## S\n\nno state\n"),
            f + "3: step 'S' has no scene: the first step must name one (scene: FILE)");
  EXPECT_EQ(error_of(lesson_with("foo: 1\n"))
                .rfind(f + "7: unknown setting 'foo' (known: scene, accel, grid-res,", 0),
            0u);
  EXPECT_EQ(error_of(lesson_with("pixel: 3,x\n")),
            f + "7: pixel '3,x': expected X,Y whole numbers >= 0, or none");
  EXPECT_EQ(error_of(lesson_with("pixel: -1,2\n")),
            f + "7: pixel '-1,2': expected X,Y whole numbers >= 0, or none");
  EXPECT_EQ(error_of(lesson_with("accel: bvh2\n")),
            f + "7: accel 'bvh2': expected grid, kd, kd-median, bvh, bvh-sweep, bvh-median, bvh-sbvh, bvh4, bvh8, "
                "bvh4-sbvh, bvh8-sbvh, octree or bsp");
  EXPECT_EQ(error_of(lesson_with("grid-res: 1,2\n")),
            f + "7: grid-res '1,2': expected NX,NY,NZ, each a whole number 1..4096, or none");
  EXPECT_EQ(error_of(lesson_with("grid-res: 1,2,4097\n")).rfind(f + "7: grid-res '1,2,4097'", 0), 0u);
  EXPECT_EQ(error_of(lesson_with("grid-density: 0\n")),
            f + "7: grid-density '0': expected a number in (0, 64]");
  EXPECT_EQ(error_of(lesson_with("grid-density: 64.5\n")),
            f + "7: grid-density '64.5': expected a number in (0, 64]");
  EXPECT_EQ(error_of(lesson_with("grid-insert: fast\n")),
            f + "7: grid-insert 'fast': expected exact or bbox");
  EXPECT_EQ(error_of(lesson_with("ti: 0\n")), f + "7: ti '0': expected a number in (0, 10000]");
  EXPECT_EQ(error_of(lesson_with("ti: nan\n")), f + "7: ti 'nan': expected a number in (0, 10000]");
  EXPECT_EQ(error_of(lesson_with("tt: -1\n")), f + "7: tt '-1': expected a number in [0, 10000]");
  EXPECT_EQ(error_of(lesson_with("empty-bonus: 1\n")), f + "7: empty-bonus '1': expected a number in [0, 1)");
  EXPECT_EQ(error_of(lesson_with("max-depth: 65\n")),
            f + "7: max-depth '65': expected a whole number 0..64 (0: by the rule)");
  EXPECT_EQ(error_of(lesson_with("leaf-size: 0\n")), f + "7: leaf-size '0': expected a whole number >= 1");
  EXPECT_EQ(error_of(lesson_with("mailbox: yes\n")), f + "7: mailbox 'yes': expected on or off");
  EXPECT_EQ(error_of(lesson_with("aa: adaptive:2\n")),
            f + "7: aa 'adaptive:2': expected none, regular:K, jitter:K, random:N, adaptive:T[:D] or scene");
  EXPECT_EQ(error_of(lesson_with("size: 0x10\n")),
            f + "7: size '0x10': expected WxH with 1 <= W, H <= 16384, or scene");
  EXPECT_EQ(error_of(lesson_with("heat: nodes\n")),
            f + "7: heat 'nodes': expected cells, tests, mailbox, boxes, samples, error or none");
  EXPECT_EQ(error_of(lesson_with("ray: -1\n")), f + "7: ray '-1': expected a whole number >= 0");
  EXPECT_EQ(error_of(lesson_with("step: 1.5\n")),
            f + "7: step '1.5': expected an event index, a whole number >= 0");
  EXPECT_EQ(error_of(lesson_with("step-to: cell:0\n")).rfind(f + "7: step-to 'cell:0': expected", 0), 0u);
  EXPECT_EQ(error_of(lesson_with("step-to: sah_candidate:1\n"))
                .rfind(f + "7: step-to 'sah_candidate:1': expected", 0),
            0u);
  EXPECT_EQ(error_of(lesson_with("panel: tree\n")), f + "7: panel 'tree': expected sah, kd or none");
  EXPECT_EQ(error_of(lesson_with("node: x\n")),
            f + "7: node 'x': expected a node id, a whole number >= 0, or none");
  EXPECT_EQ(error_of(lesson_with("node-path: LX\n")).rfind(f + "7: node-path 'LX': expected", 0), 0u);
  EXPECT_EQ(error_of(lesson_with("follow: 1\n")), f + "7: follow '1': expected on or off");
  EXPECT_EQ(error_of(lesson_with("translucent: \n")), f + "7: translucent '': expected on or off");
  EXPECT_EQ(error_of(lesson_with("zoom: 65\n")), f + "7: zoom '65': expected a number in [0, 64] (0: fit)");
  EXPECT_EQ(error_of(lesson_with("show: movie\n")),
            f + "7: show 'movie': expected window, 3d, tree, chart, picture or report");
  EXPECT_EQ(
      error_of(lesson_with("ask: guess\n")),
      f + "7: ask 'guess': expected one of next-cell, dda-axis, first-child, next-pop, sah-plane, subdivide, bvol-kind");
  EXPECT_EQ(error_of(lesson_with("ask: dda-axis\nask: next-cell\n")), f + "8: a second ask in step 'S'");
  EXPECT_EQ(error_of(lesson_with("just words\n")), f + "7: 'just words': expected key: value");
  EXPECT_EQ(error_of("# T\n## S\n```raystep\nscene: ../scenes/nowhere.json\n```\n"),
            f + "4: scene '../scenes/nowhere.json': no such file (" +
                (std::filesystem::path(kSource) / "scenes/nowhere.json").lexically_normal().string() + ")");
}

TEST(Lesson, StructuralErrors) {
  const std::string f = kLesson + ":";
  EXPECT_EQ(error_of(lesson_with("") + "\n```raystep\npixel: 1,1\n```\n"),
            f + "9: a second raystep block in step 'S' (the first is on line 5)");
  EXPECT_EQ(error_of(lesson_with("") + "```cpp\nint x;\n"),
            f + "8: unclosed code fence ```cpp (no closing ```)");
  EXPECT_EQ(error_of("# T\n## S\n```raystep\nscene: ../scenes/cornell.json\n"),
            f + "3: unclosed code fence ```raystep (no closing ```)");
  EXPECT_EQ(error_of(lesson_with("") + "# Again\n"),
            f + "8: a second title (# heading); the first is on line 1");
  EXPECT_EQ(error_of("Some text\n"), f + "1: no title: a lesson starts with a # heading");
  EXPECT_EQ(error_of("# T\n\ntext\n"), f + "1: no steps: every ## heading starts a step");
  EXPECT_EQ(error_of("## S\n"), f + "1: a step before the title: the lesson starts with a # heading");
  EXPECT_EQ(error_of("# T\n```raystep\nscene: x\n```\n"),
            f + "2: a raystep block before the first step (## heading)");
  std::string many = lesson_with("");
  for (int i = 0; i < 200; ++i) many += "## S" + std::to_string(i) + "\n";
  EXPECT_EQ(error_of(many), f + "207: more than 200 steps");
  EXPECT_EQ(error_of(std::string((1 << 20) + 1, 'x')).rfind(kLesson + ": the lesson has 1048577 bytes", 0),
            0u);
}

TEST(Lesson, ReadsFilesAndFolders) {
  namespace fs = std::filesystem;
  fs::path dir = fs::temp_directory_path() / ("raystep_lesson_test_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ofstream(dir / "b.md") << "# B\n## S\n```raystep\nscene: " << kCornell << "\n```\n";
  std::ofstream(dir / "a.md") << "# A\n## S\n```raystep\nscene: " << kCornell << "\n```\n";
  std::ofstream(dir / "notes.txt") << "not a lesson\n";
  std::vector<std::string> files = lesson_files(dir.string());
  ASSERT_EQ(files.size(), 2u);
  EXPECT_EQ(fs::path(files[0]).filename(), "a.md");
  EXPECT_EQ(fs::path(files[1]).filename(), "b.md");
  EXPECT_EQ(lesson_files(files[1]), std::vector<std::string>{files[1]});
  EXPECT_EQ(parse_lesson(files[0]).title, "A");
  EXPECT_THROW(lesson_files((dir / "none.md").string()), InputError);
  EXPECT_THROW(parse_lesson((dir / "none.md").string()), InputError);
  EXPECT_THROW(parse_lesson(dir.string()), InputError);
  fs::remove_all(dir);
}

// The command line of a state: the exact arguments, and reading them back gives the same command line.
std::vector<std::string> round_trip(const std::vector<std::string>& args) {
  LessonState s;
  for (size_t i = 0; i < args.size(); ++i) {
    if (args[i].rfind("--", 0) != 0) {
      apply_setting(s, "scene", args[i], "");
      continue;
    }
    std::string key = args[i].substr(2);
    bool flag = key == "secondary" || key == "follow" || key == "translucent";
    apply_setting(s, key, flag ? "on" : args[++i], "");
  }
  return s.scripted_args();
}

TEST(LessonState, ScriptedArgs) {
  Lesson l = parse_lesson_text(
      lesson_with(
          "accel: kd\nti: 80\npixel: 160,200\nstep-to: cell:3\npanel: sah\nnode-path: LR\nfollow: on\n"
          "translucent: on\nzoom: 8\n") +
          "## B\n```raystep\naccel: grid\ngrid-res: 4,5,6\ngrid-density: 0.1\ngrid-insert: bbox\nti: "
          "20\ntt: 0\n"
          "empty-bonus: 0.3\nmax-depth: 20\nleaf-size: 2\nmailbox: off\naa: adaptive:0.05:2\nsize: 64x48\n"
          "heat: mailbox\npixel: 3,4\nsecondary: on\nray: 2\nstep: 17\npanel: none\nnode: 12\nfollow: off\n"
          "translucent: off\nzoom: 0.3\n```\n## C\n```raystep\nstep-to: hit:1\nnode: none\n```\n",
      kLesson);
  using V = std::vector<std::string>;
  EXPECT_EQ(l.steps[0].state.scripted_args(),
            (V{kCornell, "--accel", "kd", "--pixel", "160,200", "--step-to", "cell:3", "--panel", "sah",
               "--node-path", "LR", "--follow", "--translucent", "--zoom", "8"}));
  // Step C changes only the event and the node: the rest carries over from B.
  const V carried = {kCornell,
                     "--grid-res",
                     "4,5,6",
                     "--grid-density",
                     "0.1",
                     "--grid-insert",
                     "bbox",
                     "--ti",
                     "20",
                     "--tt",
                     "0",
                     "--empty-bonus",
                     "0.3",
                     "--max-depth",
                     "20",
                     "--leaf-size",
                     "2",
                     "--mailbox",
                     "off",
                     "--aa",
                     "adaptive:0.05:2",
                     "--size",
                     "64x48",
                     "--heat",
                     "mailbox",
                     "--pixel",
                     "3,4",
                     "--secondary",
                     "--ray",
                     "2"};
  auto with = [&](const V& tail) {
    V all = carried;
    all.insert(all.end(), tail.begin(), tail.end());
    return all;
  };
  EXPECT_EQ(l.steps[1].state.scripted_args(), with({"--step", "17", "--node", "12", "--zoom", "0.3"}));
  EXPECT_EQ(l.steps[2].state.scripted_args(), with({"--step-to", "hit:1", "--zoom", "0.3"}));
  for (const LessonStep& step : l.steps)
    EXPECT_EQ(round_trip(step.state.scripted_args()), step.state.scripted_args());
  // A fresh state reads back field by field, too.
  LessonState s;
  apply_setting(s, "scene", kCornell, "");
  for (const auto& [key, value] :
       std::vector<std::pair<std::string, std::string>>{{"ti", "0.1"},
                                                        {"grid-density", "2.7182817"},
                                                        {"zoom", "1.0000001"},
                                                        {"pixel", "5,6"},
                                                        {"step", "3"}})
    apply_setting(s, key, value, "");
  LessonState back;
  std::vector<std::string> args = s.scripted_args();
  for (size_t i = 1; i < args.size(); i += 2) apply_setting(back, args[i].substr(2), args[i + 1], "");
  EXPECT_EQ(back.structure.kd.t_i, s.structure.kd.t_i);
  EXPECT_EQ(back.structure.grid.density, s.structure.grid.density);
  EXPECT_EQ(back.zoom, s.zoom);
  EXPECT_EQ(back.pixel, s.pixel);
  EXPECT_EQ(back.event.index, 3);
}

TEST(LessonState, ApplySettingRejectsAskAndUnknownKeys) {
  LessonState s;
  EXPECT_THROW(apply_setting(s, "ask", "dda-axis", ""), InputError);
  try {
    apply_setting(s, "foo", "1", "");
    FAIL();
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "");
    EXPECT_EQ(e.line(), 0);
    EXPECT_EQ(
        std::string(e.what()).rfind("unknown setting 'foo' (known: scene, accel, grid-res, grid-density,", 0),
        0u);
  }
}

// Damaged lessons (characters dropped, duplicated or replaced, lines swapped) are refused with an InputError
// or read; they never crash, and a lesson that reads is checked the same way.
TEST(Lesson, DamagedLessonsGiveInputErrors) {
  const std::string good =
      "# T\n\nIntro.\n\n## A\n\n```raystep\nscene: ../scenes/cornell.json\naccel: kd\npixel: 160,200\n"
      "step-to: node:2\nask: first-child\n```\n\n## B\n\n````md\n## x\n```raystep\n````\n\n```raystep\n"
      "step-to: leaf:1\nask: next-pop\npanel: sah\n```\n## C\n```raystep\nask: sah-plane\nnode-path: "
      "LR\n```\n";
  check_lesson(parse_lesson_text(good, kLesson));
  std::mt19937 rng(5);
  const std::string alphabet = "#`~:, \nLR0123456789-abcxyz";
  int read = 0, refused = 0;
  for (int n = 0; n < 600; ++n) {
    std::string text = good;
    for (int k = 0, edits = 1 + int(rng() % 3); k < edits; ++k) {
      size_t at = rng() % text.size();
      switch (rng() % 3) {
        case 0:
          text.erase(at, 1 + rng() % 4);
          break;
        case 1:
          text.insert(at, 1, alphabet[rng() % alphabet.size()]);
          break;
        default:
          text[at] = alphabet[rng() % alphabet.size()];
          break;
      }
    }
    try {
      check_lesson(parse_lesson_text(text, kLesson));
      ++read;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), kLesson);
      EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
      ++refused;
    }
  }
  EXPECT_GT(read, 50);
  EXPECT_GT(refused, 50);
}

}  // namespace
}  // namespace raystep

namespace raystep {
namespace {

// lessons/README.md's table: every lesson listed, with the number of questions it asks (the last column's
// leading number) and every scene file it uses named in its scene column.
TEST(Lesson, ReadmeTableMatchesTheLessons) {
  std::ifstream in(kSource + "/lessons/README.md");
  ASSERT_TRUE(in) << "lessons/README.md";
  std::map<std::string, std::pair<std::string, std::string>> rows;  // file -> (scene column, questions column)
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind("| [", 0) != 0) continue;
    std::vector<std::string> cells;
    std::stringstream ss(line.substr(1));
    std::string cell;
    while (std::getline(ss, cell, '|')) cells.push_back(cell);
    ASSERT_GE(cells.size(), 4u) << line;
    const std::string file = cells[0].substr(cells[0].find('[') + 1, cells[0].find(']') - cells[0].find('[') - 1);
    rows[file] = {cells[cells.size() - 2], cells.back()};
  }
  const std::vector<std::string> files = lesson_files(kSource + "/lessons");
  EXPECT_EQ(rows.size(), files.size());
  for (const std::string& path : files) {
    const std::string name = std::filesystem::path(path).filename().string();
    auto it = rows.find(name);
    ASSERT_NE(it, rows.end()) << name << " is not in lessons/README.md";
    const Lesson lesson = parse_lesson(path);
    int asks = 0;
    for (const LessonStep& s : lesson.steps) {
      asks += s.ask.has_value();
      const std::string scene = std::filesystem::path(s.state.scene).filename().string();
      EXPECT_NE(it->second.first.find(scene), std::string::npos) << name << " uses " << scene;
    }
    // "1 first-child, 2 next-cell": the counts of the kinds, summed.
    int listed = 0;
    std::stringstream kinds(it->second.second);
    std::string kind;
    while (std::getline(kinds, kind, ',')) listed += std::atoi(kind.c_str());
    EXPECT_EQ(listed, asks) << name << ": " << it->second.second;
  }
}

}  // namespace
}  // namespace raystep
