#include "raystep/replay/slide_stack.h"

#include "raystep/trace/node_path.h"

namespace raystep::replay {

std::string slide_stack_text(const Trace& trace, const TracedRay& ray, const ReplayState& state) {
  if (state.node_event < 0 || trace.structure.kind == "octree") return "";
  auto name = [&](int32_t id, std::string* out) {
    std::string path;
    if (!trace_node_path(trace, id, &path)) return false;
    *out = path.empty() ? "root" : path;
    return true;
  };
  std::string current, stack;
  if (!name(ray.events[size_t(state.node_event)].node, &current)) return "";
  for (size_t i = state.stack.size(); i-- > 0;) {
    std::string path;
    if (!name(state.stack[i].node, &path)) return "";
    stack += (stack.empty() ? "" : ",") + path;
  }
  return "Stack: " + (stack.empty() ? std::string("(empty)") : stack) + "   Current: " + current;
}

}  // namespace raystep::replay
