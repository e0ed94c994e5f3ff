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
  auto param = [&](const char* key, double number) {
    t.structure.params.push_back({key, false, number, ""});
  };
  auto text = [&](const char* key, const char* value) {
    t.structure.params.push_back({key, true, 0.0, value});
  };
  text("directions", bsp_directions_name(o.directions));
  param("candidates", o.candidates);
  param("t_i", o.t_i);
  param("t_t", o.t_t);
  param("max_depth", bsp_max_depth(o, geometry.size()));
  param("leaf_size", o.leaf_size);
  text("mailboxes", tree.mailboxes() ? "on" : "off");
  param("nodes", double(data.nodes.size()));
  param("leaves", double(leaves));
  param("references", double(data.prim_index.size()));
  // How adaptive the tree is: its inner nodes by where their planes came from.
  const BspTreeStats stats = bsp_tree_stats(data, o);
  param("planes_axis", double(stats.inner_by_source[int(BspPlaneSource::axis)]));
  param("planes_face_diagonal", double(stats.inner_by_source[int(BspPlaneSource::face_diagonal)]));
  param("planes_body_diagonal", double(stats.inner_by_source[int(BspPlaneSource::body_diagonal)]));
  param("planes_primitive", double(stats.inner_by_source[int(BspPlaneSource::primitive)]));
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
