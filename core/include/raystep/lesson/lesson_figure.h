// The figure a lesson step is about: the view the classroom layout gives the screen to and the handout draws
// for the step. A step names it with `show:`; `show: window` (the default) lets the state decide.
#pragma once

#include <string>

#include "raystep/lesson/lesson_state.h"

namespace raystep {

enum class LessonFigure {
  picture,  // the rendered picture (anti-aliasing, heat maps), with the pixel inspector when it is open
  view3d,   // the 3D view of the walk, beside the state panel that gives its numbers
  tree,     // the tree of nodes (the kd dock's tree, its selected node's SAH text), beside the state panel
  chart,    // the selected node's SAH cost curve
  report,   // the first report window the step opens
};

// `show: 3d | tree | chart | picture | report` as named. `show: window`: a report when the step opens one,
// the tree when a tree panel is open and no pixel is traced, the chart for `panel: sah` without a pixel,
// the 3D view when a pixel is traced, else the picture.
LessonFigure lesson_figure(const LessonState& state);

// "the 3D view", "the tree", ...: a caption's words.
const char* lesson_figure_name(LessonFigure figure);

}  // namespace raystep
