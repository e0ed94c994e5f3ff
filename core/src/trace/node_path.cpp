#include "raystep/trace/node_path.h"

#include "raystep/accel/bvh_names.h"

namespace raystep {

bool trace_node_path(const Trace& trace, int32_t id, std::string* path) {
  const std::string& kind = trace.structure.kind;
  if (is_wide_bvh_name(kind) || kind == "grid" || kind.empty()) return false;
  auto find = [&](int32_t want) -> const TraceNode* {
    for (const TraceNode& n : trace.nodes)
      if (n.id == want) return &n;
    return nullptr;
  };
  std::string reversed;
  const TraceNode* n = find(id);
  for (size_t guard = 0; n && n->parent >= 0; ++guard) {
    if (guard > trace.nodes.size()) return false;  // a cycle: not a tree
    const TraceNode* parent = find(n->parent);
    if (!parent) return false;
    if (kind == "octree" || kind.rfind("bvh", 0) == 0) {
      size_t i = 0;
      while (i < parent->children.size() && parent->children[i] != n->id) ++i;
      if (i == parent->children.size()) return false;
      if (kind == "octree")
        reversed += char('0' + i);
      else
        reversed += i == 0 ? 'L' : 'R';
    } else {
      reversed += n->id == parent->id + 1 ? 'L' : 'R';  // depth-first order: the child below comes next
    }
    n = parent;
  }
  if (!n) return false;
  *path = std::string(reversed.rbegin(), reversed.rend());
  return true;
}

std::string trace_node_path_text(const Trace& trace, int32_t id) {
  std::string p;
  if (!trace_node_path(trace, id, &p)) return "";
  return p.empty() ? "root" : p;
}

}  // namespace raystep
