#include "raystep/replay/slide_stack.h"

#include "raystep/accel/bvh_names.h"
#include "raystep/trace/node_path.h"

namespace raystep::replay {

std::string slide_stack_text(const Trace& trace, const TracedRay& ray, const ReplayState& state) {
  if (state.node_event < 0 || trace.structure.kind == "octree") return "";
  const bool wide = is_wide_bvh_name(trace.structure.kind);
  auto name = [&](int32_t id, std::string* out) {
    if (wide) {  // no paths: the ids its tree view writes in the nodes
      *out = id == 0 ? "root" : std::to_string(id);
      return true;
    }
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
