#include "raystep/lesson/lesson_figure.h"

namespace raystep {

LessonFigure lesson_figure(const LessonState& s) {
  if (s.show == "3d") return LessonFigure::view3d;
  if (s.show == "tree") return LessonFigure::tree;
  if (s.show == "chart") return LessonFigure::chart;
  if (s.show == "picture") return LessonFigure::picture;
  if (s.show == "report" || !s.report.empty()) return LessonFigure::report;
  if (s.inspect) return LessonFigure::picture;  // the inspector is about the picture's pixel
  if (!s.pixel) {
    if (s.panel == "sah") return LessonFigure::chart;
    if (s.panel == "kd") return LessonFigure::tree;
    return LessonFigure::picture;
  }
  return LessonFigure::view3d;
}

const char* lesson_figure_name(LessonFigure figure) {
  switch (figure) {
    case LessonFigure::picture: return "the picture";
    case LessonFigure::view3d: return "the 3D view";
    case LessonFigure::tree: return "the tree";
    case LessonFigure::chart: return "the SAH chart";
    case LessonFigure::report: return "the report window";
  }
  return "the debugger";
}

}  // namespace raystep
