// The figure a lesson step is about when it is not the walk (core's lesson_figure): the rendered picture at
// the step's size and anti-aliasing (or its heat map), the traced pixel framed and, with the pixel inspector
// open, that pixel enlarged with its samples; the SAH cost curve of the selected node; the tree's shape with
// that curve; a report's table. Drawn when the page is written, by the code the debugger runs.
#pragma once

#include <optional>

#include "player_data.h"
#include "raystep/lesson/lesson.h"
#include "raystep/lesson/lesson_runner.h"

namespace raystep::web {

// {"kind": picture | chart | tree | report, "html": the figure, "caption": its words}; nullopt when the step's
// figure is its walk (a traced pixel in the 3D view). Parts that would answer the step's question carry the
// class "answer" (the page hides them until the answer is shown). `width`: the figure's width in pixels.
std::optional<ordered> step_figure_json(const LessonStep& step, const StepWorld& w, int width);

}  // namespace raystep::web
