#include "raystep/accel/bvh_sah_curve.h"

#include <nlohmann/json.hpp>

#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "sah_curve_common.h"

namespace raystep {

namespace {

using sah_curve::num;

const char* const kAxisNames[3] = {"x", "y", "z"};

// Wants one node: its candidates, and its decision.
class CurveListener final : public BvhBuildListener {
 public:
  CurveListener(uint32_t node, BvhSahCurve* curve) : node_(node), curve_(curve) {}
  bool wants_candidates(uint32_t node) const override { return node == node_; }
  void candidate(uint32_t node, const BvhCandidate& c) override {
    if (node == node_) curve_->candidates.push_back(c);
  }
  void split(uint32_t node, const BvhNode& n, const BvhNodeInfo& info, const BvhCandidate&,
             float leaf_cost) override {
    if (node == node_) decided(n, info, leaf_cost);
  }
  void leaf_made(uint32_t node, const BvhNode& n, const BvhNodeInfo& info, float leaf_cost,
                 BvhLeafReason reason) override {
    if (node != node_) return;
    decided(n, info, leaf_cost);
    curve_->leaf = true;
    curve_->leaf_reason = reason;
  }
  bool found() const { return found_; }

 private:
  void decided(const BvhNode& n, const BvhNodeInfo& info, float leaf_cost) {
    found_ = true;
    curve_->bvh_node = n;
    curve_->info = info;
    curve_->leaf_cost = leaf_cost;
  }
  uint32_t node_;
  BvhSahCurve* curve_;
  bool found_ = false;
};

}  // namespace

uint32_t bvh_node_by_path(const BvhData& bvh, const std::string& path) {
  return sah_curve::node_by_path(bvh.nodes, path, "L (first child) and R (second)",
                                 [](const BvhNode& n) { return n.second_child(); });
}

BvhSahCurve record_bvh_sah_curve(const Geometry& geometry, const BvhOptions& options, uint32_t node) {
  BvhSahCurve curve;
  curve.node = node;
  CurveListener listener(node, &curve);
  BvhData bvh = build_bvh(geometry, options, listener);
  if (!listener.found())
    throw InputError(
        "", 0,
        "--node " + std::to_string(node) + ": the tree has nodes 0.." + std::to_string(bvh.nodes.size() - 1));
  for (size_t i = 0; i < curve.candidates.size(); ++i)
    if (curve.candidates[i].chosen) curve.chosen = int(i);
  return curve;
}

std::vector<BvhCandidate> bvh_sah_curve(const Geometry& geometry, const BvhOptions& options, uint32_t node) {
  return record_bvh_sah_curve(geometry, options, node).candidates;
}

SahCurve as_kd_curve(const BvhSahCurve& b, bool spatial) {
  SahCurve c;
  c.node = b.node;
  c.info.box = b.bvh_node.box;
  c.info.parent = b.info.parent;
  c.info.depth = b.info.depth;
  c.info.cost = b.info.cost;
  c.n_prims = b.info.prims;
  c.leaf_cost = b.leaf_cost;
  c.leaf = b.leaf;
  switch (b.leaf_reason) {
    case BvhLeafReason::few_primitives:
      c.leaf_reason = LeafReason::few_primitives;
      break;
    case BvhLeafReason::max_depth:
      c.leaf_reason = LeafReason::max_depth;
      break;
    case BvhLeafReason::no_cheaper_split:
      c.leaf_reason = LeafReason::no_cheaper_split;
      break;
    case BvhLeafReason::no_candidate:
      c.leaf_reason = LeafReason::no_candidate;
      break;
  }
  for (size_t i = 0; i < b.candidates.size(); ++i) {
    const BvhCandidate& k = b.candidates[i];
    if (k.spatial && !spatial) continue;
    if (int(i) == b.chosen) c.chosen = int(c.candidates.size());
    SahCandidate s;
    s.axis = k.axis;
    s.position = k.position;
    s.n_below = k.n_left;
    s.n_above = k.n_right;
    s.area_below = k.area_left;
    s.area_above = k.area_right;
    s.area_node = k.area_node;
    s.cost = k.cost;
    c.candidates.push_back(s);
  }
  if (!b.leaf && b.chosen >= 0 && size_t(b.chosen) < b.candidates.size()) {
    const BvhCandidate& k = b.candidates[size_t(b.chosen)];
    c.axis = k.axis;
    c.position = k.position;
    c.cost = k.cost;
  }
  return c;
}

void write_bvh_sah_csv(const std::string& path, const BvhSahCurve& curve) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "axis,bin,position,n_left,n_right,area_left,area_right,area_node,cost,chosen,kind\n";
    for (const BvhCandidate& c : curve.candidates)
      out << kAxisNames[c.axis] << ',' << c.bin << ',' << num(c.position) << ',' << c.n_left << ','
          << c.n_right << ',' << num(c.area_left) << ',' << num(c.area_right) << ',' << num(c.area_node)
          << ',' << num(c.cost) << ',' << (c.chosen ? 1 : 0) << ',' << (c.spatial ? "spatial" : "object")
          << '\n';
  });
}

void write_bvh_sah_json(const std::string& path, const BvhSahCurve& curve, const BvhOptions& options) {
  nlohmann::ordered_json j;
  const Bounds3& box = curve.bvh_node.box;
  j["node"] = curve.node;
  j["depth"] = curve.info.depth;
  j["parent"] = curve.info.parent;
  j["min"] = {box.lo.x, box.lo.y, box.lo.z};
  j["max"] = {box.hi.x, box.hi.y, box.hi.z};
  j["primitives"] = curve.info.prims;
  j["t_i"] = options.t_i;
  j["t_t"] = options.t_t;
  j["bins"] = options.bins;
  j["leaf_cost"] = curve.leaf_cost;
  if (curve.leaf) {
    j["decision"] = "leaf";
    j["leaf_reason"] = bvh_leaf_reason_name(curve.leaf_reason);
  } else if (curve.chosen >= 0) {
    const BvhCandidate& c = curve.candidates[size_t(curve.chosen)];
    j["decision"] = "split";
    j["split"] = {{"axis", kAxisNames[c.axis]},
                  {"bin", c.bin},
                  {"position", c.position},
                  {"cost", c.cost},
                  {"kind", c.spatial ? "spatial" : "object"}};
  }
  nlohmann::ordered_json rows = nlohmann::ordered_json::array();
  for (const BvhCandidate& c : curve.candidates)
    rows.push_back({{"axis", kAxisNames[c.axis]},
                    {"bin", c.bin},
                    {"position", c.position},
                    {"n_left", c.n_left},
                    {"n_right", c.n_right},
                    {"area_left", c.area_left},
                    {"area_right", c.area_right},
                    {"area_node", c.area_node},
                    {"cost", c.cost},
                    {"chosen", c.chosen},
                    {"kind", c.spatial ? "spatial" : "object"}});
  j["candidates"] = rows;
  std::string text = j.dump(1);
  write_file_atomically(path, [&](std::ostream& out) { out << text << "\n"; });
}

}  // namespace raystep
