// The replay's words: one line per event for the event list, and the Why text of the current step in the
// lecture's terms (the 3D-DDA's axis, t* and the children, the mailbox, the stopping rules). Every sentence
// the debugger, the lessons and `raystep replay` show about a step is written here, once.
#pragma once

#include <string>

#include "raystep/replay/replay_state.h"

namespace raystep::replay {

// One line describing an event, for the event list: "12  prim_test  prim 7: miss".
std::string describe_event(const Event& e);
// Why the walk does what the current event shows, with its numbers: the 3D-DDA's axis, the tree's t* and
// children, the mailbox, and the stopping rule (grid: "tmin(cell) > tmax(ray)"; tree: the next node on the
// stack starts beyond the hit). `trace` gives the nodes' split planes (null: t* is not shown) and the
// primitives' vertices (null: a triangle's test is not compared with Möller–Trumbore).
std::string explain_rule(const Trace* trace, const TracedRay& ray, const ReplayState& s);
inline std::string explain_rule(const TracedRay& ray, const ReplayState& s) {
  return explain_rule(nullptr, ray, s);
}

// One line for a triangle's test (empty for another primitive): what the watertight test decides for this ray
// and triangle alone (up to the ray's own tmax) and how (float alone, the double-precision filter or exact
// rational arithmetic, by exact_counters()), and what Möller–Trumbore says, with the barycentric that rejects
// a miss: "... watertight hit (settled by exact rational arithmetic); Möller–Trumbore miss (v = -3e-08 < 0)."
std::string compare_triangle_tests(const TracedRay& ray, const TracePrimitive& prim);

}  // namespace raystep::replay
