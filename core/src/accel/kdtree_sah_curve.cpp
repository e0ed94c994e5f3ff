#include "raystep/accel/kdtree_sah_curve.h"

#include <nlohmann/json.hpp>

#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "sah_curve_common.h"

namespace raystep {

namespace {

using sah_curve::num;

const char* const kAxisNames[3] = {"x", "y", "z"};

// Wants one node: its candidates, and its decision.
class CurveListener final : public BuildListener {
 public:
  explicit CurveListener(uint32_t node, SahCurve* curve) : node_(node), curve_(curve) {}
  bool wants_candidates(uint32_t node) const override { return node == node_; }
  void sah_candidate(uint32_t node, const SahCandidate& c) override {
    if (node == node_) curve_->candidates.push_back(c);
  }
  void split(uint32_t node, const KdNodeInfo& info, uint32_t n, int axis, float position, float cost,
             float leaf_cost) override {
    if (node != node_) return;
    decided(info, n, leaf_cost);
    curve_->axis = axis;
    curve_->position = position;
    curve_->cost = cost;
  }
  void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf_cost, LeafReason reason) override {
    if (node != node_) return;
    decided(info, n, leaf_cost);
    curve_->leaf = true;
    curve_->leaf_reason = reason;
    curve_->cost = leaf_cost;
  }
  bool found() const { return found_; }

 private:
  // What a split and a leaf both tell of the node.
  void decided(const KdNodeInfo& info, uint32_t n, float leaf_cost) {
    found_ = true;
    curve_->info = info;
    curve_->n_prims = n;
    curve_->leaf_cost = leaf_cost;
  }

  uint32_t node_;
  SahCurve* curve_;
  bool found_ = false;
};

}  // namespace

uint32_t kd_node_by_path(const KdTreeData& tree, const std::string& path) {
  return sah_curve::node_by_path(tree.nodes, path, "L (below) and R (above)",
                                 [](const KdNode& n) { return n.above_child(); });
}

SahCurve record_sah_curve(const Geometry& geometry, const KdOptions& options, uint32_t node) {
  SahCurve curve;
  curve.node = node;
  CurveListener listener(node, &curve);
  KdTreeData tree = build_kdtree(geometry, options, listener);
  if (!listener.found())
    throw InputError("", 0, "--node " + std::to_string(node) + ": the tree has nodes 0.." +
                                std::to_string(tree.nodes.size() - 1));
  if (!curve.leaf)
    for (size_t i = 0; i < curve.candidates.size(); ++i) {
      const SahCandidate& c = curve.candidates[i];
      if (c.axis == curve.axis && c.position == curve.position) {
        curve.chosen = int(i);
        break;
      }
    }
  return curve;
}

void write_sah_csv(const std::string& path, const SahCurve& curve) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "axis,position,n_below,n_above,n_planar,area_below,area_above,area_node,cost,chosen\n";
    for (size_t i = 0; i < curve.candidates.size(); ++i) {
      const SahCandidate& c = curve.candidates[i];
      out << kAxisNames[c.axis] << ',' << num(c.position) << ',' << c.n_below << ',' << c.n_above << ','
          << c.n_planar << ',' << num(c.area_below) << ',' << num(c.area_above) << ',' << num(c.area_node) << ','
          << num(c.cost) << ',' << (int(i) == curve.chosen ? 1 : 0) << '\n';
    }
  });
}

void write_sah_json(const std::string& path, const SahCurve& curve, const KdOptions& options) {
  nlohmann::ordered_json j;
  j["node"] = curve.node;
  j["depth"] = curve.info.depth;
  j["parent"] = curve.info.parent;
  j["min"] = {curve.info.box.lo.x, curve.info.box.lo.y, curve.info.box.lo.z};
  j["max"] = {curve.info.box.hi.x, curve.info.box.hi.y, curve.info.box.hi.z};
  j["primitives"] = curve.n_prims;
  j["t_i"] = options.t_i;
  j["t_t"] = options.t_t;
  j["empty_bonus"] = options.empty_bonus;
  j["leaf_cost"] = curve.leaf_cost;
  if (curve.leaf) {
    j["decision"] = "leaf";
    j["leaf_reason"] = leaf_reason_name(curve.leaf_reason);
  } else {
    j["decision"] = "split";
    j["split"] = {{"axis", kAxisNames[curve.axis]}, {"position", curve.position}, {"cost", curve.cost}};
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (size_t i = 0; i < curve.candidates.size(); ++i) {
    const SahCandidate& c = curve.candidates[i];
    rows.push_back({{"axis", kAxisNames[c.axis]}, {"position", c.position}, {"n_below", c.n_below},
                    {"n_above", c.n_above}, {"n_planar", c.n_planar}, {"area_below", c.area_below},
                    {"area_above", c.area_above}, {"area_node", c.area_node}, {"cost", c.cost},
                    {"planar_side", c.planar_below ? "below" : "above"}, {"chosen", int(i) == curve.chosen}});
  }
  j["candidates"] = rows;
  std::string text = j.dump(1);
  write_file_atomically(path, [&](std::ostream& out) { out << text << "\n"; });
}

}  // namespace raystep
