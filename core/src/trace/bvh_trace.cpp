#include "raystep/trace/bvh_trace.h"

#include <set>

#include "trace_recording.h"

namespace raystep {

namespace {

const char* builder_name(BvhBuilder b) {
  return b == BvhBuilder::sweep ? "sweep" : b == BvhBuilder::median ? "median" : "binned";
}

// The build options every BVH trace states (bvh_build.h's BvhOptions).
void bvh_params(const BvhOptions& o, TraceStructure* s) {
  detail::add_text_param(s, "builder", builder_name(o.builder));
  detail::add_param(s, "t_i", o.t_i);
  detail::add_param(s, "t_t", o.t_t);
  detail::add_param(s, "bins", o.bins);
  detail::add_param(s, "leaf_size", o.leaf_size);
  detail::add_param(s, "max_leaf_size", o.max_leaf_size);
  detail::add_param(s, "max_depth", o.max_depth);
}

}  // namespace

Trace record_bvh_trace(const Geometry& geometry, const Bvh& bvh, const std::vector<RayRequest>& rays,
                       const std::string& scene_path, const std::string& scene_hash) {
  const BvhData& data = bvh.data();
  Trace t = detail::begin_trace(geometry, bvh.name(), scene_path, scene_hash);
  if (!data.nodes.empty()) t.structure.bounds = data.nodes[0].box;
  size_t leaves = 0;
  for (const BvhNode& n : data.nodes) leaves += n.is_leaf();
  bvh_params(bvh.options(), &t.structure);
  detail::add_text_param(&t.structure, "order",
                         bvh.order() == BvhOrder::split_axis ? "split_axis" : "entry_distance");
  detail::add_param(&t.structure, "nodes", double(data.nodes.size()));
  detail::add_param(&t.structure, "leaves", double(leaves));
  detail::sort_params(&t.structure);

  detail::record_traversals(geometry, rays, bvh, &t);
  const std::set<int32_t> ids = detail::with_parent_chains(
      detail::named_nodes(t), [&](int32_t id) { return data.info[size_t(id)].parent; });
  for (int32_t id : ids) {
    const BvhNode& n = data.nodes[size_t(id)];
    const BvhNodeInfo& info = data.info[size_t(id)];
    TraceNode tn = detail::trace_node(id, info.parent, info.depth, n.box, n.is_leaf(), data.prim_index,
                                      n.first_prim(), n.prim_count());
    if (!tn.leaf) {
      tn.axis = n.axis();
      tn.children = {id + 1, int32_t(n.second_child())};  // the first child follows its parent
    }
    t.nodes.push_back(std::move(tn));
  }
  return t;
}

Trace record_wide_bvh_trace(const Geometry& geometry, const WideBvh& bvh, const std::vector<RayRequest>& rays,
                            const std::string& scene_path, const std::string& scene_hash) {
  Trace t = detail::begin_trace(geometry, bvh.name(), scene_path, scene_hash);
  if (bvh.node_count() > 0) t.structure.bounds = bvh.describe_node(0).box;
  bvh_params(bvh.options(), &t.structure);
  detail::add_param(&t.structure, "width", double(bvh.width()));
  detail::add_param(&t.structure, "nodes", double(bvh.node_count()));
  detail::add_param(&t.structure, "leaves", double(bvh.leaf_count()));
  detail::sort_params(&t.structure);

  detail::record_rays(
      geometry, rays,
      [&](const RayRequest& req, EventRecorder& rec) {
        Hit hit;
        bvh.record(req.ray, &hit, req.kind == RayKind::shadow, rec);
      },
      &t);
  // Only the nodes the walks name and their parents, looked up one by one: a few rays through a big tree.
  const std::set<int32_t> ids = detail::with_parent_chains(
      detail::named_nodes(t), [&](int32_t id) { return bvh.describe_node(id).parent; });
  for (int32_t id : ids) {
    const WideBvhView::Node n = bvh.describe_node(id);
    TraceNode tn;
    tn.id = id;
    tn.parent = n.parent;
    tn.depth = n.depth;
    tn.box = n.box;
    tn.leaf = n.leaf;
    tn.axis = -1;  // a wide node's children come from several of the binary tree's splits
    if (n.leaf)
      tn.prims.assign(n.prims.begin(), n.prims.end());
    else
      tn.children = n.children;
    t.nodes.push_back(std::move(tn));
  }
  return t;
}

}  // namespace raystep
