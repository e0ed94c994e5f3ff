// The lecture's 2D picture of one walk: a 2D scene's shapes, a structure's cells as the slides draw them
// (accel/plane_outline.h), and a ray's walk after step N of its replay (the cells or nodes visited, the
// current one, the stack's nodes, the ray with its current interval [t_min, t_max] and the nearest hit), with
// a caption: the step, its event, and for a tree the stack as the slides write it.
#pragma once

#include "raystep/accel/plane_outline.h"
#include "raystep/figure/figure.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

struct FlatFigureInput {
  const Scene* scene = nullptr;           // a 2D scene (scene->flat)
  const PlaneOutline* outline = nullptr;  // the structure's, or null for the shapes and the ray alone
  const Trace* trace = nullptr;           // one ray's walk through that structure, or null
  int step = -1;                          // the event after which the walk is drawn (-1: its end)
};

// Throws InputError("", 0, ...) for a 3D scene or a step past the walk's end.
Figure flat_figure(const FlatFigureInput& input);

// The same in two parts, for a view that redraws the walk as the ray moves: the still part (the frame, the
// structure, the leaves' names, the shapes; the frame also holds *origin when given), made once, and the
// walk's layers over it (the cells or nodes of the walk under the shapes; over them the marks: the mailbox's
// shapes, the shape tested, a grid's tMax ticks; the ray; the caption), made at every move.
// built_up_to >= 0: the build so far, only the splits (a BVH: the boxes) of nodes 0 .. built_up_to (the
// builders make nodes in id order) and no leaf names; -1: the whole structure.
Figure flat_figure_still(const Scene& scene, const PlaneOutline* outline, const glm::vec2* origin,
                         int32_t built_up_to = -1);
struct FlatWalkLayers {
  FigureLayer walk, marks, ray;
  std::vector<std::string> caption;
};
FlatWalkLayers flat_figure_walk(const FlatFigureInput& input, const Figure& still);

}  // namespace raystep
