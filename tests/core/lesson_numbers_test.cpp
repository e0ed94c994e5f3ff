// Tests of a lesson's numbers (lesson_numbers.h, lesson_facts.h): the {{...}} forms, literals as written with
// the tolerance their digits state, formats, the errors with their lines, and numbers computed from real steps:
// the adaptive sampler's bound, a grid's references per cell, a kd-tree node's probabilities, and a checked
// number that disagrees failing `check_lesson` at its line.
#include <gtest/gtest.h>

#include <filesystem>

#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_facts.h"
#include "raystep/lesson/lesson_numbers.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

const std::string kSource = RAYSTEP_SOURCE_DIR;
const std::string kLesson = kSource + "/lessons/test.md";  // need not exist: it names the folder

std::vector<LessonNumber> scan(const std::string& line) { return scan_lesson_numbers({line}, {7}); }

std::string scan_error(const std::string& line) {
  try {
    scan(line);
  } catch (const InputError& e) {
    return std::to_string(e.line()) + ": " + e.detail();
  }
  return "no error";
}

TEST(LessonNumbers, FormsAndLiterals) {
  std::vector<LessonNumber> n =
      scan("a {{scene.primitives}}, b {{aa.max_samples / 2:.2f}}, c {{aa.k = 0.4135}}, d {{aa.k=1,024}}");
  ASSERT_EQ(n.size(), 4u);
  EXPECT_EQ(n[0].expr, "scene.primitives");
  EXPECT_FALSE(n[0].checked);
  EXPECT_EQ(n[0].line, 7);
  EXPECT_EQ(n[1].expr, "aa.max_samples / 2");
  EXPECT_EQ(n[1].format, ".2f");
  EXPECT_TRUE(n[2].checked);
  EXPECT_EQ(n[2].written, "0.4135");
  EXPECT_DOUBLE_EQ(n[2].expected, 0.4135);
  EXPECT_NEAR(n[2].tolerance, 0.00005, 1e-12);  // half a unit of the last written digit
  EXPECT_DOUBLE_EQ(n[3].expected, 1024);
  EXPECT_DOUBLE_EQ(n[3].tolerance, 0.5);

  n = scan("{{aa.k = 40%}} {{aa.k = \xE2\x88\x92" "0.75}} {{aa.k = 8.9e-08}} {{aa.k = 2.0 \xC2\xB1 0.1}} "
           "{{aa.k = 200 \xC2\xB1 5%}} {{aa.k == 1 = 1}}");
  ASSERT_EQ(n.size(), 6u);
  EXPECT_DOUBLE_EQ(n[0].expected, 0.40);
  EXPECT_NEAR(n[0].tolerance, 0.005, 1e-12);
  EXPECT_DOUBLE_EQ(n[1].expected, -0.75);
  EXPECT_EQ(n[1].written, "\xE2\x88\x92" "0.75");
  EXPECT_NEAR(n[2].expected, 8.9e-8, 1e-20);
  EXPECT_NEAR(n[2].tolerance, 0.05e-8, 1e-20);
  EXPECT_DOUBLE_EQ(n[3].tolerance, 0.1);
  EXPECT_DOUBLE_EQ(n[4].tolerance, 10);  // 5% of 200
  EXPECT_EQ(n[5].expr, "aa.k == 1");       // == compares; only a lone = separates the literal
  EXPECT_TRUE(lesson_number_agrees(n[3], 2.09));
  EXPECT_FALSE(lesson_number_agrees(n[3], 2.11));
  EXPECT_TRUE(lesson_number_agrees(n[0], 0.4049));
  EXPECT_FALSE(lesson_number_agrees(n[0], 0.4051));
  // A string argument may hold ':' and '=' without starting a format or a literal.
  n = scan("{{aa.rmse(\"adaptive:0.1:2\") = 0.0042}}");
  ASSERT_EQ(n.size(), 1u);
  EXPECT_EQ(n[0].expr, "aa.rmse(\"adaptive:0.1:2\")");
  EXPECT_TRUE(n[0].costly);
}

TEST(LessonNumbers, Formats) {
  EXPECT_EQ(format_lesson_number(49152, ""), "49,152");
  EXPECT_EQ(format_lesson_number(145, ""), "145");
  EXPECT_EQ(format_lesson_number(0.41349, ""), "0.413");
  EXPECT_EQ(format_lesson_number(-0.5, ""), "\xE2\x88\x92" "0.5");
  EXPECT_EQ(format_lesson_number(1234567.4, ","), "1,234,567");
  EXPECT_EQ(format_lesson_number(0.4, "%"), "40%");
  EXPECT_EQ(format_lesson_number(0.4213, ".1%"), "42.1%");
  EXPECT_EQ(format_lesson_number(2.5, ".2f"), "2.50");
  EXPECT_EQ(format_lesson_number(5.914e8, ".3e"), "5.914e+08");
}

TEST(LessonNumbers, ErrorsNameTheLine) {
  EXPECT_EQ(scan_error("x {{scene.primitives"), "7: '{{' without its '}}' in the same paragraph");
  EXPECT_EQ(scan_error("{{scene.primitivs}}"),
            "7: {{scene.primitivs}}: 'scene.primitivs' is no lesson fact (`raystep lesson facts` lists them)");
  EXPECT_NE(scan_error("{{scene.primitives +}}").find("7: {{scene.primitives +}}: "), std::string::npos);
  EXPECT_EQ(scan_error("{{aa.k = about 3}}"),
            "7: {{aa.k = about 3}}: 'about 3' is not a number as written (e.g. 1,024, 0.41, 40%, 8.9e-08)");
  EXPECT_EQ(scan_error("{{}}"), "7: {{}}: no expression");
  // A report's number must be written out: the presenter never runs a report.
  EXPECT_NE(scan_error("{{cost.predicted}}").find("a report's number is written out and checked"),
            std::string::npos);
  EXPECT_NE(scan_error("{{aa.rmse(\"jitter:4\") * 2}}").find("a report's number is written out"),
            std::string::npos);
  EXPECT_EQ(scan_error("{{" + std::string(400, '1') + "}}"),
            "7: a number's expression of 400 characters, more than 300");
}

TEST(LessonNumbers, ANumberMayWrapWithinItsParagraph) {
  std::vector<LessonNumber> n = scan_lesson_numbers({"a {{aa.max_samples", "/ 2}} b {{aa.k}}"}, {3, 4});
  ASSERT_EQ(n.size(), 2u);
  EXPECT_EQ(n[0].line, 3);
  EXPECT_EQ(n[0].expr, "aa.max_samples / 2");
  EXPECT_EQ(n[1].line, 4);
  EXPECT_EQ(fill_lesson_numbers("x\na {{aa.max_samples\n/ 2}} b {{aa.k}}\n\nc\n", {"72.5", "4"}),
            "x\na 72.5 b 4\n\nc\n");
  try {
    scan_lesson_numbers({"a {{aa.k", "", "}}"}, {3, 4, 5});
    FAIL() << "a number across paragraphs";
  } catch (const InputError& e) {
    EXPECT_EQ(e.line(), 3);
  }
}

TEST(LessonNumbers, CodeFencesAreNotScannedNorFilled) {
  const std::vector<std::string> lines = {"{{aa.k}} one", "```", "{{not a number}}", "```", "two {{aa.depth}}"};
  std::vector<LessonNumber> n = scan_lesson_numbers(lines, {1, 2, 3, 4, 5});
  ASSERT_EQ(n.size(), 2u);
  EXPECT_EQ(n[0].line, 1);
  EXPECT_EQ(n[1].line, 5);
  EXPECT_EQ(fill_lesson_numbers("{{aa.k}} one\n```\n{{not a number}}\n```\ntwo {{aa.depth}}\n", {"4", "3"}),
            "4 one\n```\n{{not a number}}\n```\ntwo 3\n");
}

// A lesson on the aliasing scene: numbers from the sampler's settings, the traced pixel, the grid and a
// kd-tree node, each against what the structures themselves report.
const char* kAdaptive =
    "# Numbers\n\nIntro: {{scene.primitives}} primitive.\n\n## Adaptive\n\nBound {{aa.max_samples = 145}}, "
    "{{(2^aa.depth + 1)^2 + 4^aa.depth = 145}}; pixel {{pixel.samples}}.\n\n"
    "```raystep\nscene: ../scenes/aliasing.json\naccel: grid\naa: adaptive:0.1:3\npixel: 32,38\n```\n\n"
    "## Regular\n\nNow {{aa.max_samples}} samples, {{pixel.lit = 7}} of them lit, the pixel {{pixel.value = 0.4375}}"
    " against {{pixel.exact = 0.4135}}.\n\n```raystep\naa: regular:4\n```\n";

TEST(LessonNumbers, ComputedFromTheStep) {
  const Lesson lesson = parse_lesson_text(kAdaptive, kLesson);
  ASSERT_EQ(lesson.intro_numbers.size(), 1u);
  ASSERT_EQ(lesson.steps[0].numbers.size(), 3u);
  EXPECT_EQ(lesson.steps[0].numbers[0].line, 7);
  int numbers = 0;
  EXPECT_EQ(check_lesson(lesson, &numbers), 0);
  EXPECT_EQ(numbers, 8);
  const Lesson shown = lesson_with_numbers(lesson);
  EXPECT_EQ(shown.intro, "Intro: 1 primitive.\n");
  const std::vector<LessonNumberResult> r = compute_lesson_numbers(lesson);
  ASSERT_EQ(r.size(), 8u);
  EXPECT_EQ(r[1].value, 145);  // the adaptive sampler's own bound: (2^D + 1)^2 + 4^D for D = 3
  const double samples = r[3].value;
  EXPECT_GT(samples, 5);
  EXPECT_LE(samples, 145);
  EXPECT_EQ(shown.steps[0].narration, "Bound 145, 145; pixel " + format_lesson_number(samples, "") + ".\n");
  EXPECT_EQ(shown.steps[1].narration, "Now 16 samples, 7 of them lit, the pixel 0.4375 against 0.4135.\n");
}

TEST(LessonNumbers, ADisagreeingNumberFailsTheCheckAtItsLine) {
  std::string text = kAdaptive;
  text.replace(text.find("= 145}}"), 7, "= 81}}");  // the old lesson's (2^D + 1)^2
  const Lesson lesson = parse_lesson_text(text, kLesson);
  try {
    check_lesson(lesson);
    FAIL() << "check_lesson accepted 81 for the adaptive bound";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()), kLesson + ":7: step 'Adaptive': {{aa.max_samples = 81}}: the text says 81, "
                                               "the tool computes 145 (agreement asked: within 0.5)");
  }
  // A fact that does not apply at its step fails at the number's line.
  text = kAdaptive;
  text.replace(text.find("{{pixel.samples}}"), 17, "{{node.p_above}}");
  try {
    check_lesson(parse_lesson_text(text, kLesson));
    FAIL() << "node.p_above without a kd-tree";
  } catch (const InputError& e) {
    EXPECT_EQ(std::string(e.what()),
              kLesson + ":7: step 'Adaptive': {{node.p_above}}: the structure is not a kd-tree or a binary BVH "
                        "(accel: kd or bvh)");
  }
}

TEST(LessonNumbers, TreeAndGridFactsAreTheStructures) {
  const Lesson lesson = parse_lesson_text(
      "# T\n\n## Grid\n\n{{grid.references / grid.cells}} {{grid.per_cell}} {{grid.nx * grid.ny * grid.nz}} "
      "{{grid.cells}}\n\n```raystep\nscene: ../scenes/cornell.json\naccel: grid\n```\n\n## Kd\n\n"
      "{{node.p_above}} {{node.p_below}} {{kd.t_t + node.p_above * node.n_above * kd.t_i + node.p_below * "
      "node.n_below * kd.t_i}} {{node.cost}} {{node.fraction}}\n\n```raystep\naccel: kd\nnode: 0\n```\n",
      kLesson);
  const std::vector<LessonNumberResult> r = compute_lesson_numbers(lesson);
  ASSERT_EQ(r.size(), 9u);
  for (const LessonNumberResult& x : r) EXPECT_EQ(x.error, "") << x.number->token;
  EXPECT_DOUBLE_EQ(r[0].value, r[1].value);
  EXPECT_EQ(r[2].value, r[3].value);
  EXPECT_GT(r[1].value, 0);
  // The SAH formula from its parts gives the builder's cost (floats: to their precision).
  EXPECT_NEAR(r[6].value, r[7].value, 1e-4 * r[7].value);
  EXPECT_GT(r[4].value, 0);
  EXPECT_LT(r[4].value, 1);
  EXPECT_GT(r[5].value, 0);
  EXPECT_LT(r[5].value, 1);
  EXPECT_GT(r[8].value, 0);
  EXPECT_LT(r[8].value, 1);
}

}  // namespace
}  // namespace raystep
