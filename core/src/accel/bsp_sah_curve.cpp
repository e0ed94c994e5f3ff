#include "raystep/accel/bsp_sah_curve.h"

#include <nlohmann/json.hpp>

#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "sah_curve_common.h"

namespace raystep {

namespace {

using sah_curve::num;

// Wants one node: its candidates and its decision; then the build may stop.
class CurveListener final : public BspBuildListener {
 public:
  CurveListener(uint32_t node, BspSahCurve* curve) : node_(node), curve_(curve) {}
  bool wants_candidates(uint32_t node) const override { return node == node_; }
  void candidate(uint32_t node, const BspCandidate& c) override {
    if (node == node_) curve_->candidates.push_back(c);
  }
  void split(uint32_t node, const BspNodeInfo& info, uint32_t n_prims, const BspCandidate& chosen,
             uint32_t n_below, uint32_t n_above, float leaf_cost) override {
    if (node != node_) return;
    decided(info, n_prims, leaf_cost);
    curve_->split = chosen;
    curve_->n_below = n_below;
    curve_->n_above = n_above;
  }
  void leaf_made(uint32_t node, const BspNodeInfo& info, uint32_t n_prims, float leaf_cost,
                 BspLeafReason reason) override {
    if (node != node_) return;
    decided(info, n_prims, leaf_cost);
    curve_->leaf = true;
    curve_->leaf_reason = reason;
  }
  bool done() const override { return found_; }
  bool found() const { return found_; }

 private:
  void decided(const BspNodeInfo& info, uint32_t n_prims, float leaf_cost) {
    found_ = true;
    curve_->info = info;
    curve_->n_prims = n_prims;
    curve_->leaf_cost = leaf_cost;
  }
  uint32_t node_;
  BspSahCurve* curve_;
  bool found_ = false;
};

long long prim_column(const BspCandidate& c) {
  return c.direction < 0 ? (long long)c.prim : -1;
}

}  // namespace

uint32_t bsp_node_by_path(const BspTreeData& tree, const std::string& path) {
  return sah_curve::node_by_path(tree.nodes, path, "L (below the plane) and R (above)",
                                 [](const BspNode& n) { return n.above_child(); });
}

BspSahCurve record_bsp_sah_curve(const Geometry& geometry, const BspOptions& options, uint32_t node) {
  BspSahCurve curve;
  curve.node = node;
  CurveListener listener(node, &curve);
  BspTreeData tree = build_bsp(geometry, options, listener);
  if (!listener.found())  // the build ran to its end: the tree is whole
    throw InputError("", 0,
                     "--node " + std::to_string(node) + ": the tree has nodes 0.." +
                         std::to_string(tree.nodes.size() - 1));
  for (size_t i = 0; i < curve.candidates.size(); ++i)
    if (curve.candidates[i].chosen) curve.chosen = int(i);
  return curve;
}

void write_bsp_sah_csv(const std::string& path, const BspSahCurve& curve) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "direction,name,source,prim,normal_x,normal_y,normal_z,offset,cell_min,cell_max,n_below,n_above,"
           "area_below,area_above,area_node,cost,bounded,chosen\n";
    for (const BspCandidate& c : curve.candidates)
      out << c.direction << ',' << bsp_direction_name(c.direction) << ',' << bsp_plane_source_name(c.source)
          << ',' << prim_column(c) << ',' << num(c.plane.normal.x) << ',' << num(c.plane.normal.y) << ','
          << num(c.plane.normal.z) << ',' << num(c.plane.offset) << ',' << num(c.cell_min) << ','
          << num(c.cell_max) << ',' << c.n_below << ',' << c.n_above << ',' << num(c.area_below) << ','
          << num(c.area_above) << ',' << num(c.area_node) << ',' << num(c.cost) << ',' << (c.bounded ? 1 : 0)
          << ',' << (c.chosen ? 1 : 0) << '\n';
  });
}

void write_bsp_sah_json(const std::string& path, const BspSahCurve& curve, const BspOptions& options) {
  nlohmann::ordered_json j;
  const Bounds3& box = curve.info.box;
  j["node"] = curve.node;
  j["depth"] = curve.info.depth;
  j["parent"] = curve.info.parent;
  j["min"] = {box.lo.x, box.lo.y, box.lo.z};
  j["max"] = {box.hi.x, box.hi.y, box.hi.z};
  j["cell_area"] = curve.info.area;
  j["primitives"] = curve.n_prims;
  j["t_i"] = options.t_i;
  j["t_t"] = options.t_t;
  j["directions"] = bsp_directions_name(options.directions);
  j["candidates_per_direction"] = options.candidates;
  j["leaf_cost"] = curve.leaf_cost;
  if (curve.leaf) {
    j["decision"] = "leaf";
    j["leaf_reason"] = bsp_leaf_reason_name(curve.leaf_reason);
  } else {
    const BspCandidate& c = curve.split;
    j["decision"] = "split";
    j["split"] = {{"direction", c.direction},
                  {"name", bsp_direction_name(c.direction)},
                  {"source", bsp_plane_source_name(c.source)},
                  {"normal", {c.plane.normal.x, c.plane.normal.y, c.plane.normal.z}},
                  {"offset", c.plane.offset},
                  {"cost", c.cost},
                  {"n_below", curve.n_below},
                  {"n_above", curve.n_above}};
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const BspCandidate& c : curve.candidates)
    rows.push_back({{"direction", c.direction},
                    {"name", bsp_direction_name(c.direction)},
                    {"source", bsp_plane_source_name(c.source)},
                    {"prim", prim_column(c)},
                    {"normal", {c.plane.normal.x, c.plane.normal.y, c.plane.normal.z}},
                    {"offset", c.plane.offset},
                    {"cell_min", c.cell_min},
                    {"cell_max", c.cell_max},
                    {"n_below", c.n_below},
                    {"n_above", c.n_above},
                    {"area_below", c.area_below},
                    {"area_above", c.area_above},
                    {"area_node", c.area_node},
                    {"cost", c.cost},
                    {"bounded", c.bounded},
                    {"chosen", c.chosen}});
  j["candidates"] = rows;
  std::string text = j.dump(1);
  write_file_atomically(path, [&](std::ostream& out) { out << text << "\n"; });
}

}  // namespace raystep
