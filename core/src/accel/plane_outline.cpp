#include "raystep/accel/plane_outline.h"

#include <algorithm>
#include <functional>

#include "raystep/accel/bsp.h"
#include "raystep/accel/bvh.h"
#include "raystep/accel/grid.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/octree.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

std::vector<glm::vec2> box_polygon(const Bounds3& b) {
  return {{b.lo.x, b.lo.y}, {b.hi.x, b.lo.y}, {b.hi.x, b.hi.y}, {b.lo.x, b.hi.y}};
}

// The deepest depth d whose nodes of depth <= d number at most max_nodes (at least the root's).
int depth_limit(const std::vector<int32_t>& depths, size_t max_nodes) {
  std::vector<size_t> per_depth;
  for (int32_t d : depths) {
    if (size_t(d) >= per_depth.size()) per_depth.resize(size_t(d) + 1, 0);
    ++per_depth[size_t(d)];
  }
  size_t sum = 0;
  int limit = 0;
  for (size_t d = 0; d < per_depth.size(); ++d) {
    sum += per_depth[d];
    if (sum > max_nodes && d > 0) break;
    limit = int(d);
  }
  return limit;
}

void set_root(PlaneOutline* out, const Bounds3& b) {
  out->lo = {b.lo.x, b.lo.y};
  out->hi = {b.hi.x, b.hi.y};
}

void grid_outline(const UniformGrid& g, size_t, PlaneOutline* out) {
  set_root(out, g.bounds());
  const auto n = g.resolution();
  out->grid[0] = n[0];
  out->grid[1] = n[1];
  const float x0 = g.bounds().lo.x, x1 = g.bounds().hi.x, y0 = g.bounds().lo.y, y1 = g.bounds().hi.y;
  for (int i = 0; i <= n[0]; ++i) out->lines.push_back({{g.boundary(0, i), y0}, {g.boundary(0, i), y1}});
  for (int j = 0; j <= n[1]; ++j) out->lines.push_back({{x0, g.boundary(1, j)}, {x1, g.boundary(1, j)}});
}

void kd_outline(const KdTree& kd, size_t max_nodes, PlaneOutline* out) {
  const KdTreeData& t = kd.data();
  out->total_nodes = t.nodes.size();
  set_root(out, t.bounds);
  std::vector<int32_t> depths;
  for (const KdNodeInfo& i : t.info) depths.push_back(i.depth);
  const int limit = depth_limit(depths, max_nodes);
  std::vector<std::string> paths(t.nodes.size());
  for (size_t id = 0; id < t.nodes.size(); ++id) {
    const KdNodeInfo& info = t.info[id];
    const KdNode& n = t.nodes[id];
    if (!n.is_leaf()) {
      paths[id + 1] = paths[id] + "L";
      paths[n.above_child()] = paths[id] + "R";
    }
    if (info.depth > limit) continue;
    out->regions.push_back({int32_t(id), info.depth, n.is_leaf(), box_polygon(info.box), paths[id]});
    if (n.is_leaf() || n.axis() == 2) continue;
    const Bounds3& b = info.box;
    if (n.axis() == 0)
      out->lines.push_back({{n.split, b.lo.y}, {n.split, b.hi.y}, int32_t(id), info.depth});
    else
      out->lines.push_back({{b.lo.x, n.split}, {b.hi.x, n.split}, int32_t(id), info.depth});
  }
}

void octree_outline(const Octree& o, size_t max_nodes, PlaneOutline* out) {
  const OctreeData& t = o.data();
  out->total_nodes = t.nodes.size();
  set_root(out, t.bounds);
  std::vector<int32_t> depths;
  for (const OctreeNodeInfo& i : t.info) depths.push_back(i.depth);
  const int limit = depth_limit(depths, max_nodes);
  std::vector<std::string> paths(t.nodes.size());
  for (size_t id = 0; id < t.nodes.size(); ++id) {
    const OctreeNodeInfo& info = t.info[id];
    if (!t.nodes[id].is_leaf())
      for (int c = 0; c < 1 << t.axes; ++c) paths[t.nodes[id].child(c)] = paths[id] + char('0' + c);
    if (info.depth > limit) continue;
    out->regions.push_back(
        {int32_t(id), info.depth, t.nodes[id].is_leaf(), box_polygon(info.box), paths[id]});
    if (t.nodes[id].is_leaf()) continue;
    const Bounds3& b = info.box;
    const glm::vec3 c = b.center();
    out->lines.push_back({{c.x, b.lo.y}, {c.x, b.hi.y}, int32_t(id), info.depth});
    out->lines.push_back({{b.lo.x, c.y}, {b.hi.x, c.y}, int32_t(id), info.depth});
  }
}

void bvh_outline(const Bvh& bvh, size_t max_nodes, PlaneOutline* out) {
  const BvhData& t = bvh.data();
  out->total_nodes = t.nodes.size();
  if (t.nodes.empty()) return;
  set_root(out, t.nodes[0].box);
  out->boxes = true;
  std::vector<int32_t> depths;
  for (const BvhNodeInfo& i : t.info) depths.push_back(i.depth);
  const int limit = depth_limit(depths, max_nodes);
  std::vector<std::string> paths(t.nodes.size());
  for (size_t id = 0; id < t.nodes.size(); ++id) {
    if (!t.nodes[id].is_leaf()) {
      paths[id + 1] = paths[id] + "L";
      paths[t.nodes[id].second_child()] = paths[id] + "R";
    }
    if (t.info[id].depth <= limit)
      out->regions.push_back(
          {int32_t(id), t.info[id].depth, t.nodes[id].is_leaf(), box_polygon(t.nodes[id].box), paths[id]});
  }
}

// A wide BVH as traces see it (WideBvh::describe): every child slot a node, ids in depth-first preorder. Its
// nodes take no path (a trace names none), so its regions have none either.
void wide_bvh_outline(const WideBvh& bvh, size_t max_nodes, PlaneOutline* out) {
  const WideBvhView view = bvh.describe();
  out->total_nodes = view.nodes.size();
  if (view.nodes.empty()) return;
  set_root(out, view.nodes[0].box);
  out->boxes = true;
  std::vector<int32_t> depths;
  for (const WideBvhView::Node& n : view.nodes) depths.push_back(n.depth);
  const int limit = depth_limit(depths, max_nodes);
  for (size_t id = 0; id < view.nodes.size(); ++id) {
    const WideBvhView::Node& n = view.nodes[id];
    if (n.depth <= limit) out->regions.push_back({int32_t(id), n.depth, n.leaf, box_polygon(n.box), ""});
  }
}

// A convex polygon cut by the line n . p = d: the part with n . p <= d (below) or >= d, and the chord.
std::vector<glm::dvec2> clip(const std::vector<glm::dvec2>& poly, const glm::dvec2& n, double d, bool below) {
  std::vector<glm::dvec2> out;
  const size_t m = poly.size();
  for (size_t i = 0; i < m; ++i) {
    const glm::dvec2 &a = poly[i], &b = poly[(i + 1) % m];
    const double sa = (below ? 1.0 : -1.0) * (glm::dot(n, a) - d),
                 sb = (below ? 1.0 : -1.0) * (glm::dot(n, b) - d);
    if (sa <= 0.0) out.push_back(a);
    if ((sa < 0.0 && sb > 0.0) || (sa > 0.0 && sb < 0.0)) out.push_back(a + (b - a) * (sa / (sa - sb)));
  }
  return out;
}

void bsp_outline(const BspTree& bsp, size_t max_nodes, PlaneOutline* out) {
  const BspTreeData& t = bsp.data();
  out->total_nodes = t.nodes.size();
  set_root(out, t.bounds);
  if (t.nodes.empty()) return;
  std::vector<int32_t> depths;
  for (const BspNodeInfo& i : t.info) depths.push_back(i.depth);
  const int limit = depth_limit(depths, max_nodes);
  const Bounds3& r = t.bounds;
  std::vector<std::vector<glm::dvec2>> cells(t.nodes.size());
  std::vector<std::string> paths(t.nodes.size());
  cells[0] = {{r.lo.x, r.lo.y}, {r.hi.x, r.lo.y}, {r.hi.x, r.hi.y}, {r.lo.x, r.hi.y}};
  for (size_t id = 0; id < t.nodes.size(); ++id) {  // parents come before their children
    const BspNode& n = t.nodes[id];
    const BspNodeInfo& info = t.info[id];
    if (info.depth <= limit) {
      OutlineRegion region{int32_t(id), info.depth, n.is_leaf(), {}, paths[id]};
      for (const glm::dvec2& p : cells[id]) region.polygon.push_back(glm::vec2(p));
      out->regions.push_back(std::move(region));
    }
    if (n.is_leaf()) continue;
    const glm::dvec2 normal(n.plane.normal.x, n.plane.normal.y);
    const double d = n.plane.offset;
    paths[id + 1] = paths[id] + "L";
    paths[n.above_child()] = paths[id] + "R";
    cells[id + 1] = clip(cells[id], normal, d, true);
    cells[n.above_child()] = clip(cells[id], normal, d, false);
    // The chord: the points of the cell's polygon on the line, in the below part's boundary.
    if (info.depth <= limit && n.plane.normal.z == 0.f) {
      std::vector<glm::dvec2> on;
      for (const glm::dvec2& p : cells[id + 1])
        if (std::fabs(glm::dot(normal, p) - d) <= 1e-9 * (1.0 + std::fabs(d) + glm::length(p)))
          on.push_back(p);
      if (on.size() >= 2)
        out->lines.push_back({glm::vec2(on.front()), glm::vec2(on.back()), int32_t(id), info.depth});
    }
    cells[id] = {};
  }
}

struct Row {
  std::function<bool(const Accelerator&)> is;
  std::function<void(const Accelerator&, size_t, PlaneOutline*)> fill;
};
template <class T>
Row row(void (*fill)(const T&, size_t, PlaneOutline*)) {
  return {[](const Accelerator& a) { return dynamic_cast<const T*>(&a) != nullptr; },
          [fill](const Accelerator& a, size_t m, PlaneOutline* o) { fill(dynamic_cast<const T&>(a), m, o); }};
}
const std::vector<Row>& rows() {
  static const std::vector<Row> table = {row<UniformGrid>(grid_outline), row<KdTree>(kd_outline),
                                         row<Octree>(octree_outline),    row<Bvh>(bvh_outline),
                                         row<WideBvh>(wide_bvh_outline), row<BspTree>(bsp_outline)};
  return table;
}

}  // namespace

bool has_plane_outline(const Accelerator& accel) {
  for (const Row& r : rows())
    if (r.is(accel)) return true;
  return false;
}

PlaneOutline plane_outline(const Accelerator& accel, size_t max_nodes) {
  for (const Row& r : rows())
    if (r.is(accel)) {
      PlaneOutline out;
      out.kind = accel.name();
      r.fill(accel, max_nodes, &out);
      return out;
    }
  throw InputError(
      "", 0,
      "a 2D outline of " + accel.name() + " is not drawn (use " + recorded_structure_list() + ")");
}

}  // namespace raystep
