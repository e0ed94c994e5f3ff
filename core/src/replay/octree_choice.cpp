#include "raystep/replay/octree_choice.h"

#include <algorithm>
#include <cmath>

#include "raystep/geometry/numerics.h"
#include "raystep/replay/node_crossing.h"

namespace raystep::replay {

bool is_octree_ray(const Trace* trace, const TracedRay& ray) {
  if (trace) return trace->structure.kind == "octree";
  // Without a trace: the octree pushes the cell it is at (its frame), a kd-tree the far child.
  int32_t at = -1;
  for (const Event& e : ray.events) {
    if (e.type == EventType::cell) return false;
    if (e.type == EventType::node) at = e.node;
    if (e.type == EventType::push) return e.node == at;
  }
  return false;
}

std::string octant_name(int octant, int axes) {
  std::string s;
  for (int a = 0; a < axes; ++a) s += std::string(a ? " " : "") + axis_name(a) + ((octant >> a) & 1 ? "+" : "-");
  return s;
}

OctreeChoice octree_choice(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  OctreeChoice c;
  const std::vector<Event>& ev = ray.events;
  if (s.node_event < 0 || ev[size_t(s.node_event)].type != EventType::node) return c;
  const Event& e = ev[size_t(s.node_event)];
  const TraceNode* n = find_node(trace, e.node);
  if (!n || n->leaf || (n->children.size() != 8 && n->children.size() != 4)) return c;
  // A quadtree (a 2D scene's): its cells are cut on x and y only; on z every child spans the cell.
  const int axes = c.axes = n->children.size() == 4 ? 2 : 3;
  const int children = 1 << axes;
  c.node_event = s.node_event;
  c.node = e.node;
  c.depth = e.depth;
  c.t_enter = e.t_min_node;
  c.t_exit = e.t_max_node;
  // The planes' t as the kernel computes them (octree.h): float, by the direction's reciprocal; the cell's
  // centre as the build's 0.5 (lo + hi). In the frame where every direction component is positive (the
  // paper's reflection), t0 is the entry face's t, t1 the exit face's.
  const glm::vec3 o = ray.ray.origin, d = ray.ray.direction;
  for (int a = 0; a < 3; ++a) {
    const float inv = 1.f / d[a];
    const bool neg = std::signbit(d[a]);
    const float mid = 0.5f * (n->box.lo[a] + n->box.hi[a]);
    c.moving[a] = std::isfinite(inv);
    if (c.moving[a]) {
      c.t0[a] = ((neg ? n->box.hi[a] : n->box.lo[a]) - o[a]) * inv;
      c.t1[a] = ((neg ? n->box.lo[a] : n->box.hi[a]) - o[a]) * inv;
      c.t_mid[a] = (mid - o[a]) * inv;
    } else {
      c.t0[a] = -kInfinity;
      c.t1[a] = kInfinity;
      c.t_mid[a] = (o[a] >= mid) != neg ? -kInfinity : kInfinity;
    }
    if (a >= axes) c.t_mid[a] = c.t1[a];  // not cut: no centre plane, the cell's own exit
  }
  const float t_in = std::max({c.t0[0], c.t0[1], c.t0[2]});
  c.entry_axis = c.t0[0] >= c.t0[1] && c.t0[0] >= c.t0[2] ? 0 : (c.t0[1] >= c.t0[2] ? 1 : 2);
  int mask = 0;
  for (int a = 0; a < axes; ++a) mask |= int(std::signbit(d[a])) << a;
  // Revelles' walk in the reflected frame (reflected child r is real child r ^ mask).
  static const int kNext[8][3] = {{1, 2, 4}, {8, 3, 5}, {3, 8, 6}, {8, 8, 7},
                                  {5, 6, 8}, {8, 7, 8}, {7, 8, 8}, {8, 8, 8}};
  int r = 0;
  for (int b = 0; b < axes; ++b)
    if (b != c.entry_axis && c.t_mid[b] < t_in) r |= 1 << b;
  while (r < children && c.path.size() < size_t(children)) {
    OctreeChildStep st;
    st.octant = r ^ mask;
    st.node = n->children[size_t(st.octant)];
    float ct1[3];
    for (int a = 0; a < 3; ++a) ct1[a] = (r >> a) & 1 ? c.t1[a] : c.t_mid[a];
    st.exit_axis = ct1[0] <= ct1[1] && ct1[0] <= ct1[2] ? 0 : (ct1[1] <= ct1[2] ? 1 : 2);
    st.t_exit = ct1[st.exit_axis];
    r = st.exit_axis < axes ? kNext[r][st.exit_axis] : children;  // an uncut axis's face is the parent's
    st.leaves_parent = r >= children;
    c.path.push_back(st);
  }
  // The children the walk visits: the node events one level down between this cell's push and its pop.
  int depth = e.depth;
  for (size_t i = size_t(s.node_event) + 1; i < ev.size(); ++i) {
    const Event& x = ev[i];
    if (x.type == EventType::pop && x.node == e.node) break;
    if (x.type == EventType::hit_accepted || x.type == EventType::ray_end) break;
    if (x.type != EventType::node || x.depth != depth + 1) continue;
    c.visited.push_back(x.node);
    auto it = std::find(n->children.begin(), n->children.end(), x.node);
    c.visited_octants.push_back(it == n->children.end() ? -1 : int(it - n->children.begin()));
    if (int(i) <= s.step) ++c.visited_so_far;
  }
  c.valid = true;
  return c;
}

}  // namespace raystep::replay
