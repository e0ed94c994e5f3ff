#include "raystep/trace/bsp_trace.h"

#include "trace_recording.h"

namespace raystep {

Trace record_bsp_trace(const Geometry& geometry, const BspTree& tree, const std::vector<RayRequest>& rays,
                       const std::string& scene_path, const std::string& scene_hash) {
  const BspTreeData& data = tree.data();
  const BspOptions& o = tree.options();
  Trace t = detail::begin_trace(geometry, tree.name(), scene_path, scene_hash);
  t.structure.bounds = data.bounds;
  size_t leaves = 0;
  for (const BspNode& n : data.nodes) leaves += n.is_leaf();
  detail::add_text_param(&t.structure, "directions", bsp_directions_name(o.directions));
  detail::add_param(&t.structure, "candidates", o.candidates);
  detail::add_param(&t.structure, "t_i", o.t_i);
  detail::add_param(&t.structure, "t_t", o.t_t);
  detail::add_param(&t.structure, "max_depth", bsp_max_depth(o, geometry.size()));
  detail::add_param(&t.structure, "leaf_size", o.leaf_size);
  detail::add_text_param(&t.structure, "mailboxes", tree.mailboxes() ? "on" : "off");
  detail::add_param(&t.structure, "nodes", double(data.nodes.size()));
  detail::add_param(&t.structure, "leaves", double(leaves));
  detail::add_param(&t.structure, "references", double(data.prim_index.size()));
  // How adaptive the tree is: its inner nodes by where their planes came from.
  const BspTreeStats stats = bsp_tree_stats(data, o);
  detail::add_param(&t.structure, "planes_axis", double(stats.inner_by_source[int(BspPlaneSource::axis)]));
  detail::add_param(&t.structure, "planes_face_diagonal",
                    double(stats.inner_by_source[int(BspPlaneSource::face_diagonal)]));
  detail::add_param(&t.structure, "planes_body_diagonal",
                    double(stats.inner_by_source[int(BspPlaneSource::body_diagonal)]));
  detail::add_param(&t.structure, "planes_primitive",
                    double(stats.inner_by_source[int(BspPlaneSource::primitive)]));
  detail::sort_params(&t.structure);

  detail::record_traversals(geometry, rays, tree, &t);
  for (int32_t id : detail::named_nodes(t)) {
    const BspNode& n = data.nodes[size_t(id)];
    const BspNodeInfo& info = data.info[size_t(id)];
    TraceNode tn = detail::trace_node(id, info.parent, info.depth, info.box, n.is_leaf(), data.prim_index,
                                      n.first_prim(), n.prim_count());
    if (!tn.leaf) {
      tn.has_plane = true;
      tn.normal = n.plane.normal;
      tn.offset = n.plane.offset;
    }
    t.nodes.push_back(std::move(tn));
  }
  return t;
}

}  // namespace raystep
