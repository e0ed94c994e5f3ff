// The quiz's questions (question.h): their names and prompts, the answers computed from the recorded walk or
// the build, and the check of a typed prediction. The answers re-derive the kernels' decisions from the
// events in the words of the lecture, with the numbers that decide them (the "Why" text).
#include "raystep/lesson/question.h"

#include "raystep/util/error.h"

namespace raystep {
namespace {

struct KindInfo {
  QuestionKind kind;
  const char* name;
  const char* prompt;
};
constexpr KindInfo kKinds[] = {
    {QuestionKind::next_cell, "next-cell",
     "Which cell does the ray enter next (i,j,k), or does the walk stop?"},
    {QuestionKind::dda_axis, "dda-axis",
     "Along which axis does the 3D-DDA step out of this cell (x, y, z, or none)?"},
    {QuestionKind::first_child, "first-child",
     "Which child does the walk visit first (below or above the plane), and is the far child pushed?"},
    {QuestionKind::next_pop, "next-pop",
     "Which node is popped from the stack next, or does the walk stop here?"},
    {QuestionKind::sah_plane, "sah-plane",
     "Which plane does the SAH choose for this node (axis and position), or a leaf?"},
    {QuestionKind::subdivide, "subdivide",
     "Does adaptive sampling subdivide this pixel (more than its 5 first samples)?"},
};

}  // namespace

const char* question_kind_name(QuestionKind kind) {
  for (const KindInfo& k : kKinds)
    if (k.kind == kind) return k.name;
  return "?";
}

bool parse_question_kind(const std::string& name, QuestionKind* kind) {
  for (const KindInfo& k : kKinds)
    if (name == k.name) {
      *kind = k.kind;
      return true;
    }
  return false;
}

const char* question_prompt(QuestionKind kind) {
  for (const KindInfo& k : kKinds)
    if (k.kind == kind) return k.prompt;
  return "";
}

}  // namespace raystep
