// The numbers a lesson's text may compute (docs/lesson-format.md, "Numbers"): facts of the step's world by
// name, such as `scene.primitives`, `grid.per_cell` or `node.p_above`, and a few functions of a text, such
// as `ray.events("prim_test")` or `aa.rmse("jitter:4")`. Cheap facts read the scene, the built structure and
// the traced pixel the step already has; costly ones run a report (`raystep cost`, `raystep aa-report`) on
// the step's scene, once per scene, size and structure for the whole process.
#pragma once

#include <memory>
#include <string>
#include <vector>

#include "raystep/lesson/lesson_runner.h"
#include "raystep/lesson/lesson_state.h"

namespace raystep {

struct LessonFactInfo {
  std::string name;  // "scene.primitives"; a function's name is followed by ("TEXT")
  bool function = false;
  bool costly = false;  // runs a report: allowed only where the text states the value (`{{expr = 12}}`)
  std::string help;
};
// Every fact and function, in the documented order.
const std::vector<LessonFactInfo>& lesson_fact_list();
const LessonFactInfo* find_lesson_fact(const std::string& name);

// The facts of one entered step. Values are computed on first use and kept.
class LessonFacts {
 public:
  LessonFacts(const StepWorld& world, const LessonState& state);
  ~LessonFacts();
  // A named fact (no argument) or a function of `arg`. Throws InputError("", 0, "what") when the fact does
  // not apply at this step (e.g. node.cost without a kd-tree node, pixel.exact on a scene without an exact
  // reference), or for an argument the function does not know.
  double value(const std::string& name);
  double call(const std::string& name, const std::string& arg);

  struct Impl;  // lesson_facts.cpp's

 private:
  std::unique_ptr<Impl> impl_;
};

}  // namespace raystep
