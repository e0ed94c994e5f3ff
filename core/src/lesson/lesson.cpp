// The lesson parser (docs/lesson-format.md): a Markdown file read line by line into a title, an introduction
// and steps, each step's state block applied on top of the step before. Code fences are tracked as CommonMark
// does (a fence closes only with the same character, at least as long), so a lesson can show Markdown, even a
// ```raystep block, as narration inside a longer fence without it being read.
#include "raystep/lesson/lesson.h"

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>

#include "raystep/lesson/markdown_fence.h"
#include "raystep/lesson/lesson_numbers.h"
#include "raystep/util/error.h"

namespace raystep {
namespace {

constexpr size_t kMaxLessonBytes = 1u << 20;  // a lesson is a few pages; anything larger is not one
constexpr size_t kMaxSteps = 200;

std::string trim(const std::string& s) {
  size_t b = s.find_first_not_of(" \t");
  if (b == std::string::npos) return "";
  size_t e = s.find_last_not_of(" \t");
  return s.substr(b, e - b + 1);
}

// An ATX heading outside fences: its level (1..6) and text, or 0.
int heading_of(const std::string& line, std::string* text) {
  size_t i = 0;
  while (i < line.size() && i < 3 && line[i] == ' ') ++i;
  size_t n = 0;
  while (i + n < line.size() && line[i + n] == '#') ++n;
  if (n == 0 || n > 6) return 0;
  if (i + n < line.size() && line[i + n] != ' ' && line[i + n] != '\t') return 0;
  std::string t = trim(line.substr(i + n));
  // A closing sequence of #s is not part of the text.
  size_t end = t.find_last_not_of('#');
  if (end == std::string::npos)
    t.clear();
  else if (end + 1 < t.size() && (t[end] == ' ' || t[end] == '\t'))
    t = trim(t.substr(0, end + 1));
  *text = t;
  return int(n);
}

// Drops leading and trailing blank lines.
std::string join_trimmed(const std::vector<std::string>& lines) {
  size_t b = 0, e = lines.size();
  while (b < e && trim(lines[b]).empty()) ++b;
  while (e > b && trim(lines[e - 1]).empty()) --e;
  std::string out;
  for (size_t i = b; i < e; ++i) out += lines[i] + "\n";
  return out;
}

std::string question_kinds_list() {
  std::string s;
  for (QuestionKind k : {QuestionKind::next_cell, QuestionKind::dda_axis, QuestionKind::first_child,
                         QuestionKind::next_pop, QuestionKind::sah_plane, QuestionKind::subdivide, QuestionKind::bvol_kind})
    s += (s.empty() ? "" : ", ") + std::string(question_kind_name(k));
  return s;
}

}  // namespace

Lesson parse_lesson_text(const std::string& text, const std::string& path) {
  auto fail = [&](int line, const std::string& what) -> void { throw InputError(path, line, what); };
  if (text.size() > kMaxLessonBytes)
    fail(0, "the lesson has " + std::to_string(text.size()) + " bytes, more than the limit of " +
                std::to_string(kMaxLessonBytes));
  const std::string base_dir = std::filesystem::path(path).parent_path().string();

  std::vector<std::string> lines;
  {
    std::istringstream in(text);
    std::string line;
    while (std::getline(in, line)) {
      if (!line.empty() && line.back() == '\r') line.pop_back();
      lines.push_back(line);
    }
  }

  Lesson lesson;
  lesson.path = path;
  int title_line = 0;
  std::vector<std::string> intro, narration;  // the text of the part being read
  std::vector<int> intro_at, narration_at;    // their lines' numbers in the file
  int state_line = 0;                         // the current step's state block (0: none yet)
  auto numbers = [&](const std::vector<std::string>& text, const std::vector<int>& at) {
    try {
      return scan_lesson_numbers(text, at);
    } catch (const InputError& e) {
      throw InputError(path, e.line(), e.detail());
    }
  };
  auto finish_step = [&] {
    if (!lesson.steps.empty()) {
      lesson.steps.back().narration = join_trimmed(narration);
      lesson.steps.back().numbers = numbers(narration, narration_at);
    }
    narration.clear();
    narration_at.clear();
  };

  for (size_t i = 0; i < lines.size(); ++i) {
    const int line_no = int(i) + 1;
    const std::string& line = lines[i];
    std::vector<std::string>& part = lesson.steps.empty() ? intro : narration;
    std::vector<int>& part_at = lesson.steps.empty() ? intro_at : narration_at;
    Fence fence;
    if (fence_of(line, &fence)) {
      // Find the closing fence first: an unclosed fence would swallow the rest of the lesson unseen.
      size_t close = i + 1;
      while (close < lines.size() && !fence_closes(fence, lines[close])) ++close;
      if (close == lines.size())
        fail(line_no, "unclosed code fence " + std::string(fence.length, fence.ch) + fence.info +
                          " (no closing " + std::string(fence.length, fence.ch) + ")");
      if (fence.info != "raystep") {  // narration, shown as code; headings inside are not headings
        for (size_t j = i; j <= close; ++j) {
          part.push_back(lines[j]);
          part_at.push_back(int(j) + 1);
        }
        i = close;
        continue;
      }
      if (lesson.steps.empty()) fail(line_no, "a raystep block before the first step (## heading)");
      LessonStep& step = lesson.steps.back();
      if (state_line)
        fail(line_no, "a second raystep block in step '" + step.title + "' (the first is on line " +
                          std::to_string(state_line) + ")");
      state_line = line_no;
      for (size_t j = i + 1; j < close; ++j) {
        const int at = int(j) + 1;
        std::string s = trim(lines[j]);
        if (s.empty() || s[0] == '#') continue;
        size_t colon = s.find(':');
        if (colon == std::string::npos) fail(at, "'" + s + "': expected key: value");
        std::string key = trim(s.substr(0, colon)), value = trim(s.substr(colon + 1));
        if (key == "ask") {
          if (step.ask) fail(at, "a second ask in step '" + step.title + "'");
          QuestionKind kind;
          if (!parse_question_kind(value, &kind))
            fail(at, "ask '" + value + "': expected one of " + question_kinds_list());
          step.ask = kind;
          step.ask_line = at;
          continue;
        }
        try {
          apply_setting(step.state, key, value, base_dir);
        } catch (const InputError& e) {
          fail(at, e.detail());
        }
        step.changes.push_back(LessonSetting{key, value, at});
      }
      i = close;
      continue;
    }

    std::string heading;
    int level = heading_of(line, &heading);
    if (level == 1) {
      if (title_line)
        fail(line_no, "a second title (# heading); the first is on line " + std::to_string(title_line));
      if (!lesson.steps.empty()) fail(line_no, "the title (# heading) must come before the first step");
      if (heading.empty()) fail(line_no, "an empty title");
      title_line = line_no;
      lesson.title = heading;
      intro.clear();  // anything before the title is not the introduction
      intro_at.clear();
      continue;
    }
    if (level == 2) {
      if (!title_line) fail(line_no, "a step before the title: the lesson starts with a # heading");
      if (lesson.steps.size() == kMaxSteps)
        fail(line_no, "more than " + std::to_string(kMaxSteps) + " steps");
      if (heading.empty()) fail(line_no, "a step without a title");
      // The previous step must have had a scene by its end.
      if (!lesson.steps.empty() && lesson.steps.back().state.scene.empty())
        fail(lesson.steps.back().line, "step '" + lesson.steps.back().title +
                                           "' has no scene: the first step must name one (scene: FILE)");
      finish_step();
      LessonStep step;
      step.title = heading;
      step.line = line_no;
      if (!lesson.steps.empty()) step.state = lesson.steps.back().state;  // carry over; ask and report do not
      step.state.report.clear();
      lesson.steps.push_back(std::move(step));
      state_line = 0;
      continue;
    }
    part.push_back(line);
    part_at.push_back(line_no);
  }

  if (!title_line) fail(lines.empty() ? 0 : 1, "no title: a lesson starts with a # heading");
  if (lesson.steps.empty()) fail(title_line, "no steps: every ## heading starts a step");
  if (lesson.steps.back().state.scene.empty())
    fail(lesson.steps.back().line,
         "step '" + lesson.steps.back().title + "' has no scene: the first step must name one (scene: FILE)");
  finish_step();
  lesson.intro = join_trimmed(intro);
  lesson.intro_numbers = numbers(intro, intro_at);
  return lesson;
}

Lesson parse_lesson(const std::string& path) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(path, ec)) throw InputError(path, 0, "a folder, not a lesson file");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw InputError(path, 0, "cannot read the lesson file");
  // Read at most one byte beyond the limit: a huge file is refused without being loaded.
  std::string text(kMaxLessonBytes + 1, '\0');
  in.read(&text[0], std::streamsize(text.size()));
  text.resize(size_t(in.gcount()));
  if (in.bad()) throw InputError(path, 0, "cannot read the lesson file");
  if (text.size() > kMaxLessonBytes)
    throw InputError(path, 0, "the lesson is larger than " + std::to_string(kMaxLessonBytes) + " bytes");
  return parse_lesson_text(text, path);
}

std::vector<std::string> lesson_files(const std::string& file_or_folder) {
  namespace fs = std::filesystem;
  std::error_code ec;
  if (fs::is_directory(file_or_folder, ec)) {
    std::vector<std::string> files;
    for (const fs::directory_entry& e : fs::directory_iterator(file_or_folder, ec))
      // The folder's README.md is its index, not a lesson.
      if (e.path().extension() == ".md" && e.path().filename() != "README.md" && e.is_regular_file(ec))
        files.push_back(e.path().string());
    if (ec) throw InputError(file_or_folder, 0, "cannot list the folder: " + ec.message());
    if (files.empty()) throw InputError(file_or_folder, 0, "no lessons (*.md) in this folder");
    std::sort(files.begin(), files.end());
    return files;
  }
  if (!fs::exists(file_or_folder, ec)) throw InputError(file_or_folder, 0, "no such lesson file or folder");
  return {file_or_folder};
}

}  // namespace raystep
