// `raystep lesson ...`: lessons checked headless (every step entered, every question answered, as the
// presenter would), a step printed as the equivalent raystep-gui command line, and the computed answers for
// the writers.
#include <cstdio>

#include "commands.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_facts.h"
#include "raystep/lesson/lesson_numbers.h"
#include "raystep/lesson/lesson_runner.h"
#include "raystep/util/error.h"

namespace raystep::cli {
namespace {

std::string plural(size_t n, const char* one, const char* many) {
  return std::to_string(n) + " " + (n == 1 ? one : many);
}

// POSIX shell quoting: plain words as they are, anything else in single quotes.
std::string shell_quote(const std::string& s) {
  bool plain = !s.empty();
  for (char c : s)
    plain = plain && ((c >= 'a' && c <= 'z') || (c >= 'A' && c <= 'Z') || (c >= '0' && c <= '9') ||
                      std::string("_-./:=,@%+").find(c) != std::string::npos);
  if (plain) return s;
  std::string q = "'";
  for (char c : s) q += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return q + "'";
}

}  // namespace

int run_lesson_check(const LessonCheckArgs& args) {
  std::vector<std::string> paths = args.paths;
  if (paths.empty()) paths.push_back("lessons");
  for (const std::string& p : paths)
    for (const std::string& file : lesson_files(p)) {
      const Lesson lesson = parse_lesson(file);
      int numbers = 0;
      const int questions = check_lesson(lesson, &numbers);
      std::printf("%s: %s, %s, %s: ok\n", file.c_str(), plural(lesson.steps.size(), "step", "steps").c_str(),
                  plural(size_t(questions), "question", "questions").c_str(),
                  plural(size_t(numbers), "number", "numbers").c_str());
      std::fflush(stdout);
    }
  return 0;
}

int run_lesson_command(const LessonCommandArgs& args) {
  const Lesson lesson = parse_lesson(args.file);
  const int n = int(lesson.steps.size());
  if (args.step < 1 || args.step > n)
    throw InputError(args.file, 0,
                     "step " + std::to_string(args.step) + ": the lesson has " +
                         plural(size_t(n), "step", "steps") + " (1.." + std::to_string(n) + ")");
  std::string line = "raystep-gui";
  for (const std::string& a : lesson.steps[size_t(args.step - 1)].state.scripted_args())
    line += " " + shell_quote(a);
  std::printf("%s\n", line.c_str());
  return 0;
}

int run_lesson_answers(const LessonAnswersArgs& args) {
  const Lesson lesson = parse_lesson(args.file);
  check_lesson(lesson);  // a failing step is reported with its line before anything is printed
  LessonRunner runner;
  for (size_t i = 0; i < lesson.steps.size(); ++i) {
    const LessonStep& step = lesson.steps[i];
    StepWorld w = runner.enter(step.state, step.ask);
    if (!w.answer) continue;
    std::printf("step %zu '%s' (%s, line %d): %s\n  %s\n", i + 1, step.title.c_str(),
                question_kind_name(*step.ask), step.ask_line, w.answer->text.c_str(), w.answer->why.c_str());
  }
  return 0;
}

int run_lesson_numbers(const LessonAnswersArgs& args) {
  const Lesson lesson = parse_lesson(args.file);
  int failures = 0;
  for (const LessonNumberResult& r : compute_lesson_numbers(lesson)) {
    const LessonNumber& n = *r.number;
    const std::string value = r.error.empty() ? format_lesson_number(r.value, ".6g") : "-";
    const char* verdict = !r.error.empty() ? "cannot compute" : !n.checked ? "filled" : r.agrees ? "agrees" : "DISAGREES";
    std::printf("%s:%d: step %d: %s  value %s  shown %s  %s%s%s\n", args.file.c_str(), n.line, r.step + 1,
                n.token.c_str(), value.c_str(), r.error.empty() ? shown_lesson_number(n, r.value).c_str() : "-",
                verdict, r.error.empty() ? "" : ": ", r.error.c_str());
    failures += !r.error.empty() || !r.agrees;
  }
  std::fflush(stdout);
  if (failures)
    throw InputError(args.file, 0, std::to_string(failures) + " of its numbers disagree or cannot be computed");
  return 0;
}

int run_lesson_facts() {
  for (const LessonFactInfo& f : lesson_fact_list())
    std::printf("%-26s %s%s\n", (f.name + (f.function ? "(\"...\")" : "")).c_str(), f.help.c_str(),
                f.costly ? " [runs a report: checked numbers only]" : "");
  return 0;
}

}  // namespace raystep::cli
