// The stack and the current node as the slides write them: "Stack: LLR,R   Current: LLL" (the top of the
// stack first, each node by its path from the root), for the kd-tree's and the BSP tree's stack traversal and
// the binary BVH's; a wide BVH's nodes, which take no path, by their ids as its tree view numbers them
// ("Stack: 7   Current: 4").
#pragma once

#include <string>

#include "raystep/replay/replay_state.h"
#include "raystep/trace/trace_file.h"

namespace raystep::replay {

// "" when the state has no current node or a node has no path (an octree: digits, not letters).
std::string slide_stack_text(const Trace& trace, const TracedRay& ray, const ReplayState& state);

}  // namespace raystep::replay
