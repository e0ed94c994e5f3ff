// The quiz: "predict, then step". A question's answer is computed from the recorded walk or the build when the
// step is entered, never stored in the lesson, so it follows the kernels: the next cell and the 3D-DDA's axis
// from the grid's cell events, the first child and the push from the tree's node/push events, the next pop or
// the stop from the walk, the SAH's plane from the built node, the adaptive subdivision from the sampler, the
// bounding volume entered in vain least often from the bounding-volume report on the scene.
#pragma once

#include <array>
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/scene/scene.h"
#include "raystep/trace/trace_file.h"

namespace raystep {

enum class QuestionKind { next_cell, dda_axis, first_child, next_pop, sah_plane, subdivide, bvol_kind };

const char* question_kind_name(QuestionKind kind);  // "next-cell", ...
bool parse_question_kind(const std::string& name, QuestionKind* kind);
// The question as the presenter asks it: "Which cell does the ray enter next?"
const char* question_prompt(QuestionKind kind);
// The same in the words of the structure walked (a trace's structure kind: "octree" asks for a child cell by
// its octant, "bsp" names the slanted plane); other kinds: question_prompt(kind).
const char* question_prompt(QuestionKind kind, const std::string& walk);
// The structure a context's walk goes through (its trace's kind, "" without a trace).
struct QuestionContext;
std::string question_walk(const QuestionContext& context);

// What a question needs: the step's world. Pointers may be null where a kind does not need them.
struct QuestionContext {
  const Scene* scene = nullptr;
  const Accelerator* accel = nullptr;  // the built structure (sah-plane: a KdTree)
  const Trace* trace = nullptr;        // the traced pixel's rays
  int ray = 0, step = 0;               // the current ray of the trace and its current event
  int node = -1;                       // the selected kd-tree node
  std::string aa;                      // subdivide: the picture's anti-aliasing spec ("": the scene's)
  int width = 0, height = 0;           // subdivide: the picture's size
  std::array<int, 2> pixel{0, 0};      // subdivide: the pixel
};

struct Answer {
  QuestionKind kind = QuestionKind::next_cell;
  // next-cell: the cell, or stops = true; dda-axis: axis 0..2, or -1 (the walk ends in this cell)
  std::array<int, 3> cell{0, 0, 0};
  bool stops = false;
  int axis = -1;
  // first-child: the child visited first, whether it is the one below the plane, and the far child if pushed
  int32_t first_child = -1;
  bool first_is_below = true;
  bool far_pushed = false;
  int32_t far_child = -1;
  // next-pop: the node popped next (or stops = true); sah-plane: axis and position (axis -1: the SAH makes a leaf)
  int32_t node = -1;
  // The nodes in the slides' path notation (tree_nodes.h: "LLR", "root"; "" where the tree takes no paths):
  // first-child's first and far child, next-pop's popped node. A prediction may name a node by its path.
  std::string first_child_path, far_child_path, node_path;
  float position = 0.f;
  float extent = 0.f;  // sah-plane: the node's extent along the chosen axis (a typed position's tolerance)
  float lo = 0.f;      // sah-plane: the node's minimum along that axis (the chart's 0)
  // subdivide
  bool subdivided = false;
  uint32_t samples = 0;  // the pixel's samples under the settings
  // bvol-kind: the kinds of bounding volume (bvol, bvol-sphere, bvol-kdop, bvol-obb) entered in vain least
  // often per ray on the scene's camera rays (the bounding-volume report; more than one on a tie)
  std::vector<std::string> volumes;
  // The octree (walk "octree"): next-cell and first-child name a cell, node and first_child its id, octant
  // its place in its parent (bit 0: upper x, bit 1: upper y, bit 2: upper z; -1: unknown).
  std::string walk;  // "octree", "bsp" where the answer is in that structure's terms; else ""
  int octant = -1;
  int axes = 3;  // octree: 2 for a 2D scene's quadtree, whose cells are named by quadrant ("x+y-")
  std::string text;  // the answer in a sentence: "cell (3, 4, 2): the ray steps along y."
  std::string why;   // the reason with its numbers (tMax per axis, t* against [t_min, t_max], costs, contrast)
};

// Throws InputError("", 0, "what") when the question does not apply at this state (e.g. dda-axis at a node
// event, next-pop outside a leaf, sah-plane without a selected inner node).
Answer answer_question(QuestionKind kind, const QuestionContext& context);

// Whether a typed prediction matches the answer. Accepted forms, case and spaces aside:
//   next-cell: "i,j,k" or "stop"; dda-axis: "x", "y", "z" or "none"; first-child: "below" or "above" (or the
//   node id or its path, "LL"), optionally followed by ",push" / ",no push"; next-pop: a node id, its path or
//   "stop"; sah-plane: "x", "y"
//   or "z" then optionally ",POSITION" in world units (within 1e-4 of the node's extent) or ",PERCENT%" across
//   the node as the SAH chart's axis reads (0% the node's minimum, 100% its maximum; within 2%), or "leaf";
//   subdivide: "yes" or
//   "no"; bvol-kind: "box", "sphere", "14-dop" (or "kdop") or "oriented box" (or "obb"). An octree's next-cell and first-child: a node id or an octant "x+y-z+" (next-cell also "stop").
// Throws InputError("", 0, "what") for a form the kind does not accept.
bool prediction_matches(const Answer& answer, const std::string& prediction);

// For a wrong prediction (one prediction_matches accepts as a form but not as the answer): a sentence aimed at
// the misconception it most likely shows, in the lecture's terms ("The stack is last in, first out: ..."),
// without the answer itself (the answer's text and Why follow it). "" for a right prediction.
std::string prediction_feedback(const Answer& answer, const std::string& prediction);

}  // namespace raystep
