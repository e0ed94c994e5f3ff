// Reaching a lesson step's state without a display: load the scene, build the structure, trace the pixel, find
// the event and the node, and answer the step's question, as the presenter does with its windows. Results are
// kept while the state they depend on is unchanged, so a lesson's steps cost one build per structure.
#pragma once

#include <array>
#include <memory>
#include <optional>
#include <string>

#include "raystep/lesson/lesson.h"
#include "raystep/lesson/question.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

struct StepWorld {
  std::shared_ptr<const Scene> scene;
  std::shared_ptr<const Accelerator> accel;
  std::shared_ptr<const Trace> trace;  // null without a pixel
  int width = 0, height = 0;           // the picture's size
  std::string aa;                      // the picture's anti-aliasing spec ("": the scene's)
  std::optional<std::array<int, 2>> pixel;  // the traced pixel
  int ray = 0, step = 0;               // the current ray and event (0 without a trace)
  int node = -1;                       // the selected tree node (tree_nodes.h), -1: none
  std::optional<Answer> answer;        // the step's question answered
  QuestionContext context() const;
};

class LessonRunner {
 public:
  // Throws InputError("", 0, "what") when the state cannot be reached: the scene does not load, the pixel
  // lies outside the picture, the ray or event does not exist, a node option without a tree, the question
  // does not apply.
  StepWorld enter(const LessonState& state, std::optional<QuestionKind> ask = std::nullopt);

 private:
  struct Cache;
  std::shared_ptr<Cache> cache_;
};

// Reaches every step of the lesson in order, answers every question and computes every number; throws
// InputError(lesson path, line of the failing step's setting, heading or number, what) on the first failure,
// a checked number that disagrees with the tool included. Returns the number of questions answered (and in
// `numbers` the numbers computed).
int check_lesson(const Lesson& lesson, int* numbers = nullptr);

// Every number of the lesson computed at its step (the introduction's at the first), in file order.
struct LessonNumberResult {
  const LessonNumber* number = nullptr;
  int step = 0;       // 0-based
  double value = 0;   // computed
  std::string error;  // why it could not be computed ("": it was)
  bool agrees = true;  // a checked number: its literal agrees with the value
};
std::vector<LessonNumberResult> compute_lesson_numbers(const Lesson& lesson);

// The lesson as a reader sees it: every filled number ({{EXPR}}) computed and written in, every checked one
// ({{EXPR = VALUE}}) replaced by its VALUE. Reports are never run (a filled number cannot name one). Throws
// InputError(lesson path, line, what) when a step or a filled number cannot be computed.
Lesson lesson_with_numbers(const Lesson& lesson);

}  // namespace raystep
