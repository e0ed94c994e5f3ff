// A traced node's path from the root in the slides' notation (kd-tree and BSP tree L below / R above, binary
// BVH L / R its first / second child, octree a digit per level), from the trace's nodes alone: the name the
// lessons, the Why texts and the debugger give a node.
#pragma once

#include <cstdint>
#include <string>

#include "raystep/trace/trace_file.h"

namespace raystep {

// The path of node `id` from the root, in the slides' notation (kd-tree and
// BSP tree L below / R above, binary BVH L / R its first / second child, octree a digit per level; "" the
// root). False when the trace's nodes do not chain up to the root or the tree takes no paths (a wide BVH).
bool trace_node_path(const Trace& trace, int32_t id, std::string* path);
// "LLR", or "root"; "" when unknown: for texts that name a node.
std::string trace_node_path_text(const Trace& trace, int32_t id);

}  // namespace raystep
