// A lesson: one Markdown file of steps, each with narration and the debugger state it shows
// (docs/lesson-format.md). Parsed in full before anything is shown, so that a bad file is reported at once
// with its file and line and never half-presented.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "raystep/lesson/lesson_numbers.h"
#include "raystep/lesson/lesson_state.h"
#include "raystep/lesson/question.h"

namespace raystep {

struct LessonSetting {
  std::string key, value;
  int line = 0;
};

struct LessonStep {
  std::string title;      // the level-2 heading's text
  int line = 0;           // the heading's line
  std::string narration;  // Markdown: the step's text without its heading and state block
  std::vector<LessonSetting> changes;  // the state block's settings, in file order (ask excluded)
  LessonState state;                   // the whole state: the previous step's with the changes applied
  std::optional<QuestionKind> ask;
  int ask_line = 0;
  std::vector<LessonNumber> numbers;  // the narration's {{...}} numbers, in order (lesson_numbers.h)
};

struct Lesson {
  std::string path;   // as given
  std::string title;  // the level-1 heading
  std::string intro;  // Markdown before the first step ("" if none)
  std::vector<LessonNumber> intro_numbers;  // the introduction's numbers, computed at the first step
  std::vector<LessonStep> steps;
};

// Throws InputError(path, line, what) for an unreadable file, a missing or second title, no steps, a step
// without a scene so far, an unknown key, a bad value, an unclosed state block or a second one in a step.
Lesson parse_lesson(const std::string& path);
// The same from text; `path` names the file in messages and its folder resolves relative scene paths.
Lesson parse_lesson_text(const std::string& text, const std::string& path);

// The lesson files a `raystep lesson check` argument names: a file itself, or a folder's *.md but README.md, in name order.
std::vector<std::string> lesson_files(const std::string& file_or_folder);

}  // namespace raystep
