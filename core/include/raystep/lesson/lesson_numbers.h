// A lesson's numbers (docs/lesson-format.md, "Numbers"): in narration, `{{EXPR}}` is filled in from the step's
// world (lesson_facts.h), `{{EXPR:FORMAT}}` the same with a format, and `{{EXPR = 0.41}}` shows 0.41 as written
// while `raystep lesson check` computes EXPR and fails unless it agrees within half a unit of the last written
// digit (or `{{EXPR = 0.41 ± 0.02}}`). So no number the tool can compute is typed in by hand unchecked.
// Expressions are muparser's (+ - * / ^, sqrt, cbrt, log2, min, max, ...) over fact names.
#pragma once

#include <string>
#include <vector>

namespace raystep {

class LessonFacts;  // lesson_facts.h

struct LessonNumber {
  int line = 0;            // the lesson file's line
  std::string token;       // "{{...}}" as written
  std::string expr;        // the expression
  std::string format;      // filled: "" (default), ".3f", ".2g", ".1e", "," (thousands), "%", ".1%"
  bool checked = false;    // "EXPR = LITERAL": shown as written, checked by lesson check
  std::string written;     // checked: the literal as written
  double expected = 0.0;   // checked: the literal's value (a percentage divided by 100)
  double tolerance = 0.0;  // checked: the agreement asked for
  bool costly = false;     // the expression runs a report (allowed only checked)
};

// The numbers of Markdown lines (`at` their file lines), outside code fences, in order. Throws
// InputError("", line, "what") for an unclosed {{, a bad expression, an unknown fact or function, a bad
// literal or format, or a costly fact in a filled (unchecked) number.
std::vector<LessonNumber> scan_lesson_numbers(const std::vector<std::string>& lines, const std::vector<int>& at);

// The expression's value at the step. Throws InputError("", 0, "what") when a fact does not apply.
double evaluate_lesson_number(const LessonNumber& number, LessonFacts& facts);
// Whether a checked number's literal agrees with the value.
bool lesson_number_agrees(const LessonNumber& number, double value);
// The value in the number's format: integers with thousands separators, others with 3 significant digits.
std::string format_lesson_number(double value, const std::string& format);
// The text a reader sees: a checked number's literal, a filled one's formatted value.
std::string shown_lesson_number(const LessonNumber& number, double value);

// `markdown` with its numbers (outside code fences, in order) replaced by `shown`, one per number.
std::string fill_lesson_numbers(const std::string& markdown, const std::vector<std::string>& shown);

}  // namespace raystep
