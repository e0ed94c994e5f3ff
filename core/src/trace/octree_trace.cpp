#include "raystep/trace/octree_trace.h"

#include <set>

#include "trace_recording.h"

namespace raystep {

Trace record_octree_trace(const Geometry& geometry, const Octree& tree, const std::vector<RayRequest>& rays,
                          const std::string& scene_path, const std::string& scene_hash) {
  const OctreeData& data = tree.data();
  Trace t = detail::begin_trace(geometry, tree.name(), scene_path, scene_hash);
  t.structure.bounds = data.bounds;
  const OctreeStats& st = tree.stats();
  detail::add_param(&t.structure, "leaf_size", tree.options().leaf_size);
  detail::add_param(&t.structure, "axes", data.axes);  // 2: a 2D scene's quadtree
  detail::add_param(&t.structure, "max_depth", octree_max_depth(tree.options(), geometry.size()));
  detail::add_param(&t.structure, "nodes", double(st.nodes));
  detail::add_param(&t.structure, "leaves", double(st.leaves));
  detail::add_param(&t.structure, "references", double(st.references));
  detail::add_text_param(&t.structure, "mailboxes", "on");
  detail::sort_params(&t.structure);

  detail::record_traversals(geometry, rays, tree, &t);
  // The named nodes and their parents up to the root, so that a reader sees each cell's place in the tree.
  const std::set<int32_t> ids = detail::with_parent_chains(
      detail::named_nodes(t), [&](int32_t id) { return data.info[size_t(id)].parent; });
  for (int32_t id : ids) {
    const OctreeNode& n = data.nodes[size_t(id)];
    const OctreeNodeInfo& info = data.info[size_t(id)];
    TraceNode tn = detail::trace_node(id, info.parent, info.depth, info.box, n.is_leaf(), data.prim_index,
                                      n.first, n.prim_count());
    tn.axis = -1;
    if (!tn.leaf)
      for (int c = 0; c < 1 << data.axes; ++c) tn.children.push_back(int32_t(n.child(c)));  // 8, or 4
    t.nodes.push_back(std::move(tn));
  }
  return t;
}

}  // namespace raystep
