#include "raystep/trace/kd_trace.h"

#include <set>

#include "trace_recording.h"

namespace raystep {

namespace {
const char* builder_name(KdBuilder b) {
  return b == KdBuilder::median ? "median" : b == KdBuilder::sah ? "sah" : "sah_reference";
}
}  // namespace

Trace record_kd_trace(const Geometry& geometry, const KdTree& tree, const std::vector<RayRequest>& rays,
                      const std::string& scene_path, const std::string& scene_hash) {
  const KdTreeData& data = tree.data();
  const KdOptions& o = tree.options();
  Trace t = detail::begin_trace(geometry, tree.name(), scene_path, scene_hash);
  t.structure.bounds = data.bounds;
  size_t leaves = 0;
  for (const KdNode& n : data.nodes) leaves += n.is_leaf();
  detail::add_text_param(&t.structure, "builder", builder_name(o.builder));
  detail::add_param(&t.structure, "t_i", o.t_i);
  detail::add_param(&t.structure, "t_t", o.t_t);
  detail::add_param(&t.structure, "empty_bonus", o.empty_bonus);
  detail::add_param(&t.structure, "max_depth", kd_max_depth(o, geometry.size()));
  detail::add_param(&t.structure, "leaf_size", o.leaf_size);
  detail::add_text_param(&t.structure, "mailboxes", tree.mailboxes() ? "on" : "off");
  detail::add_param(&t.structure, "nodes", double(data.nodes.size()));
  detail::add_param(&t.structure, "leaves", double(leaves));
  detail::add_param(&t.structure, "references", double(data.prim_index.size()));
  detail::sort_params(&t.structure);

  detail::record_traversals(geometry, rays, tree, &t);
  for (int32_t id : detail::named_nodes(t)) {
    const KdNode& n = data.nodes[size_t(id)];
    const KdNodeInfo& info = data.info[size_t(id)];
    TraceNode tn = detail::trace_node(id, info.parent, info.depth, info.box, n.is_leaf(), data.prim_index,
                                      n.first_prim, n.prim_count());
    if (!tn.leaf) {
      tn.axis = n.axis();
      tn.split = n.split;
    }
    t.nodes.push_back(std::move(tn));
  }
  return t;
}

}  // namespace raystep
