#include "raystep/replay/storyboard.h"

#include <cmath>
#include <sstream>

#include <nlohmann/json.hpp>

#include "raystep/replay/bvh_choice.h"
#include "raystep/replay/explain.h"
#include "raystep/replay/node_crossing.h"
#include "raystep/replay/octree_choice.h"
#include "raystep/replay/replayer.h"
#include "raystep/replay/slide_stack.h"
#include "raystep/trace/node_path.h"
#include "raystep/util/error.h"

namespace raystep::replay {

namespace {

using ordered = nlohmann::ordered_json;

// As the trace format: JSON has no infinity, +-inf are the strings "inf" and "-inf"; NaN (a ray in a plane)
// is null.
ordered number(float v) {
  if (std::isnan(v)) return nullptr;
  if (std::isinf(v)) return v > 0 ? "inf" : "-inf";
  return double(v);
}
ordered cell_index(const int* c) {
  return ordered::array({c[0], c[1], c[2]});
}
ordered id_or_null(int32_t id) {
  return id >= 0 ? ordered(id) : ordered(nullptr);
}

const char* prim_state_key(PrimState s) {
  switch (s) {
    case PrimState::pending:
      return "pending";
    case PrimState::testing:
      return "testing";
    case PrimState::hit:
      return "hit";
    case PrimState::missed:
      return "missed";
    case PrimState::skipped:
      return "skipped";
  }
  return "";
}
const char* crossing_key(Crossing c) {
  switch (c) {
    case Crossing::near_only:
      return "near_only";
    case Crossing::far_only:
      return "far_only";
    case Crossing::both:
      return "both";
    case Crossing::in_plane:
      return "in_plane";
  }
  return "";
}

ordered counters_json(const RayCounters& k) {
  return ordered{{"cells", k.cells},
                 {"nodes", k.nodes},
                 {"prim_tests", k.prim_tests},
                 {"prim_hits", k.prim_hits},
                 {"mailbox_hits", k.mailbox_hits},
                 {"pushes", k.pushes},
                 {"pops", k.pops},
                 {"box_tests", k.box_tests}};
}

ordered node_json(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  if (s.node_event < 0) return nullptr;
  const Event& n = ray.events[size_t(s.node_event)];
  ordered j{{"event", s.node_event},           {"id", n.node},
            {"type", event_type_name(n.type)}, {"depth", n.depth},
            {"t_min", number(n.t_min_node)},   {"t_max", number(n.t_max_node)}};
  const std::string path = trace_node_path_text(trace, n.node);
  j["path"] = path.empty() ? ordered(nullptr) : ordered(path);
  if (const TraceNode* tn = find_node(trace, n.node)) j["leaf"] = tn->leaf;
  return j;
}

// The choice at the current inner node: a kd or BSP crossing, a BVH's box tests, an octree's child order.
void choice_json(const Trace& trace, const TracedRay& ray, const ReplayState& s, ordered& j) {
  if (is_bvh_ray(&trace, ray)) {
    const BvhChoice c = bvh_choice(ray, s);
    if (!c.valid) return;
    ordered tests = ordered::array();
    for (const BoxTestMark& m : c.tests) {
      ordered t{{"child", m.child}, {"event", m.event}, {"done", m.done}};
      if (m.done) t["hit"] = m.hit;
      if (m.done && m.hit) t["t_near"] = number(m.t_near), t["t_far"] = number(m.t_far);
      tests.push_back(t);
    }
    j["bvh"] = ordered{{"node", c.node},
                       {"tests", tests},
                       {"decided", c.decided},
                       {"first", c.decided ? id_or_null(c.first) : ordered(nullptr)},
                       {"pushed", c.decided ? ordered(c.pushed) : ordered::array()}};
  } else if (is_octree_ray(&trace, ray)) {
    const OctreeChoice c = octree_choice(trace, ray, s);
    if (!c.valid) return;
    ordered path = ordered::array();
    for (const OctreeChildStep& st : c.path)
      path.push_back(ordered{{"octant", st.octant},
                             {"name", octant_name(st.octant, c.axes)},
                             {"node", id_or_null(st.node)},
                             {"exit_axis", axis_name(st.exit_axis)},
                             {"t_exit", number(st.t_exit)},
                             {"leaves_parent", st.leaves_parent}});
    ordered mids = ordered::array();
    for (int a = 0; a < 3; ++a) mids.push_back(c.moving[a] ? number(c.t_mid[a]) : ordered(nullptr));
    j["octree"] =
        ordered{{"node", c.node},
                {"entry_axis", c.entry_axis >= 0 ? ordered(axis_name(c.entry_axis)) : ordered(nullptr)},
                {"t_enter", number(c.t_enter)},
                {"t_exit", number(c.t_exit)},
                {"t_mid", mids},
                {"path", path},
                {"visited", c.visited},
                {"visited_so_far", c.visited_so_far}};
  } else {
    const NodeCrossing c = node_crossing(trace, ray, s);
    if (!c.valid) return;
    ordered x{{"node", c.node},
              {"t_star", number(c.t_star)},
              {"t_min", number(c.t_min)},
              {"t_max", number(c.t_max)},
              {"near_side", c.near_is_below ? "below" : "above"},
              {"crossing", crossing_key(c.crossing)},
              {"near_child", id_or_null(c.near_child)},
              {"far_child", id_or_null(c.far_child)}};
    if (c.general) {
      x["normal"] = ordered::array({number(c.normal.x), number(c.normal.y), number(c.normal.z)});
      x["offset"] = number(c.offset);
      x["origin_side"] = c.origin_side;
      x["n_dot_dir"] = c.n_dot_dir;
    } else {
      x["axis"] = axis_name(c.axis);
      x["split"] = number(c.split);
    }
    j["crossing"] = x;
  }
}

ordered state_object(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  ordered j;
  if (!s.event) return j;
  const Event& e = *s.event;
  j["step"] = s.step;
  j["type"] = event_type_name(e.type);
  j["line"] = describe_event(e);
  j["interval"] = s.has_interval ? ordered::array({number(s.t_min), number(s.t_max)}) : ordered(nullptr);
  if (s.cell_event >= 0) {
    const Event& c = ray.events[size_t(s.cell_event)];
    j["cell"] =
        ordered{{"event", s.cell_event},
                {"index", cell_index(c.cell)},
                {"t_enter", number(c.t_enter)},
                {"t_exit", number(c.t_exit)},
                {"t_max", ordered::array({number(c.t_max.x), number(c.t_max.y), number(c.t_max.z)})},
                {"t_delta", ordered::array({number(c.t_delta.x), number(c.t_delta.y), number(c.t_delta.z)})},
                {"next_axis", axis_name(c.next_axis)}};
  } else {
    j["cell"] = nullptr;
  }
  ordered visited = ordered::array();
  for (int i : s.visited_cell_events) visited.push_back(cell_index(ray.events[size_t(i)].cell));
  j["visited_cells"] = visited;
  j["node"] = node_json(trace, ray, s);
  ordered stack = ordered::array();
  for (const StackEntry& st : s.stack)
    stack.push_back(ordered{{"node", st.node},
                            {"depth", st.depth},
                            {"t_min", number(st.t_min)},
                            {"t_max", number(st.t_max)},
                            {"push_event", st.push_event}});
  j["stack"] = stack;
  j["visited_nodes"] = s.visited_nodes;
  j["skipped_nodes"] = s.skipped_nodes;
  choice_json(trace, ray, s, j);
  j["block_event"] = s.block_event >= 0 ? ordered(s.block_event) : ordered(nullptr);
  ordered prims = ordered::array();
  for (const PrimMark& p : s.prims) {
    ordered m{{"prim", p.prim}, {"state", prim_state_key(p.state)}};
    if (p.state == PrimState::hit || (p.state == PrimState::testing && p.hit)) m["t"] = number(p.t);
    prims.push_back(m);
  }
  j["prims"] = prims;
  ordered mailbox = ordered::array();
  for (const MailboxEntry& m : s.mailbox) {
    ordered x{{"prim", m.prim}};
    if (m.tested_in_cell_event >= 0)
      x["cell"] = cell_index(m.cell);
    else
      x["leaf"] = id_or_null(m.leaf);
    x["hit"] = m.hit;
    if (m.hit) x["t"] = number(m.t);
    x["skips"] = m.skips;
    mailbox.push_back(x);
  }
  j["mailbox"] = mailbox;
  j["counters"] = counters_json(s.counters);
  if (s.nearest_prim >= 0)
    j["nearest"] = ordered{{"prim", s.nearest_prim},
                           {"t", number(s.nearest_t)},
                           {"status", s.accepted   ? "accepted"
                                      : s.deferred ? "deferred"
                                                   : "candidate"}};
  else
    j["nearest"] = nullptr;
  j["ended"] = s.ended;
  j["why"] = explain_rule(&trace, ray, s);
  return j;
}

template <class Each>
void for_each_ray(const MultiTrace& trace, const StoryboardRequest& r, Each each) {
  if (r.walk >= int(trace.walks.size()))
    throw InputError("", 0,
                     "--walk " + std::to_string(r.walk) + ": the trace has " +
                         std::to_string(trace.walks.size()) + " walk(s), 0.." +
                         std::to_string(int(trace.walks.size()) - 1));
  const size_t rays = trace.walks.empty() ? 0 : trace.walks[0].rays.size();
  if (r.ray >= int(rays))
    throw InputError("", 0,
                     "--ray " + std::to_string(r.ray) + ": the trace has " + std::to_string(rays) +
                         " ray(s), 0.." + std::to_string(int(rays) - 1));
  for (size_t w = 0; w < trace.walks.size(); ++w) {
    if (r.walk >= 0 && int(w) != r.walk) continue;
    const Trace& t = trace.walks[w];
    for (size_t i = 0; i < t.rays.size(); ++i)
      if (r.ray < 0 || int(i) == r.ray) each(w, t, i);
  }
}

ordered ray_header(const Trace& t, size_t i) {
  const TracedRay& ray = t.rays[i];
  ordered j{{"ray", i}, {"kind", ray_kind_name(ray.kind)}, {"depth", ray.depth}};
  j["pixel"] = ray.has_pixel ? ordered::array({ray.pixel[0], ray.pixel[1]}) : ordered(nullptr);
  j["origin"] =
      ordered::array({number(ray.ray.origin.x), number(ray.ray.origin.y), number(ray.ray.origin.z)});
  j["direction"] =
      ordered::array({number(ray.ray.direction.x), number(ray.ray.direction.y), number(ray.ray.direction.z)});
  j["events"] = ray.events.size();
  return j;
}

}  // namespace

std::string state_json(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  return state_object(trace, ray, s).dump();
}

void write_storyboard(std::ostream& out, const MultiTrace& trace, const std::string& source,
                      const StoryboardRequest& request) {
  for_each_ray(trace, request, [](size_t, const Trace&, size_t) {});  // bad --walk or --ray before any output
  out << "{\n \"format\": \"" << kStoryboardFormat << "\",\n \"version\": " << kStoryboardVersion
      << ",\n \"source\": " << ordered(source).dump() << ",\n \"trace_version\": " << trace.version
      << ",\n \"walks\": [";
  int last_walk = -1;
  bool first_ray = true;
  for_each_ray(trace, request, [&](size_t w, const Trace& t, size_t i) {
    if (int(w) != last_walk) {
      if (last_walk >= 0) out << "\n  ]}";
      out << (last_walk >= 0 ? ",\n" : "\n") << "  {\"walk\": " << w
          << ", \"structure\": " << ordered(t.structure.kind).dump() << ", \"rays\": [";
      last_walk = int(w);
      first_ray = true;
    }
    ordered head = ray_header(t, i);
    std::string h = head.dump();
    h.pop_back();  // the states follow inside the ray's object
    out << (first_ray ? "\n   " : ",\n   ") << h << ", \"states\": [";
    first_ray = false;
    const TracedRay& ray = t.rays[i];
    const Replayer replayer(ray);
    const int n = replayer.size();
    const int from = request.step < 0 ? 0 : std::min(request.step, n - 1),
              to = request.step < 0 ? n - 1 : from;
    for (int k = from; k <= to && n > 0; ++k)
      out << (k == from ? "\n    " : ",\n    ") << state_json(t, ray, replayer.at(k));
    out << "\n   ]}";
  });
  if (last_walk >= 0) out << "\n  ]}";
  out << "\n ]\n}\n";
}

std::string state_text(const Trace& trace, const TracedRay& ray, const ReplayState& s) {
  std::ostringstream out;
  out << describe_event(*s.event) << "\n";
  if (s.cell_event >= 0) {
    const Event& c = ray.events[size_t(s.cell_event)];
    out << "  cell (" << c.cell[0] << "," << c.cell[1] << "," << c.cell[2] << ")\n";
    // The 3D-DDA's next boundary on each axis and the step between boundaries (the next axis is the line's).
    out << "  tMax (" << c.t_max.x << ", " << c.t_max.y << ", " << c.t_max.z << "), tDelta (" << c.t_delta.x
        << ", " << c.t_delta.y << ", " << c.t_delta.z << ")\n";
  }
  if (s.node_event >= 0) {
    const Event& nd = ray.events[size_t(s.node_event)];
    const std::string path = trace_node_path_text(trace, nd.node);
    out << "  node " << nd.node << (path.empty() ? "" : " (" + path + ")") << ", depth " << nd.depth
        << "\n";
  }
  if (!s.stack.empty()) {
    out << "  stack (top last):";
    for (const StackEntry& st : s.stack) out << " " << st.node;
    out << "\n";
  }
  const std::string slides = slide_stack_text(trace, ray, s);
  if (!slides.empty()) out << "  as the slides write it: " << slides << "\n";
  if (s.nearest_prim >= 0)
    out << "  nearest: prim " << s.nearest_prim << " at t = " << s.nearest_t
        << (s.accepted   ? " (accepted)"
            : s.deferred ? " (deferred)"
                         : " (candidate)")
        << "\n";
  const RayCounters& c = s.counters;
  out << "  counters: cells " << c.cells << ", nodes " << c.nodes << ", box tests " << c.box_tests
      << ", prim tests " << c.prim_tests << ", hits " << c.prim_hits << ", mailbox hits "
      << c.mailbox_hits << ", pushes " << c.pushes << ", pops " << c.pops << "\n";
  const std::string why = explain_rule(&trace, ray, s);
  if (!why.empty()) {
    std::string indented = "  why: ";
    for (char ch : why) indented += ch == '\n' ? std::string("\n       ") : std::string(1, ch);
    out << indented << "\n";
  }
  return out.str();
}

void write_storyboard_text(std::ostream& out, const MultiTrace& trace, const StoryboardRequest& request) {
  for_each_ray(trace, request, [&](size_t w, const Trace& t, size_t i) {
    const TracedRay& ray = t.rays[i];
    out << "walk " << w << " (" << t.structure.kind << "), ray " << i << " (" << ray_kind_name(ray.kind)
        << "), " << ray.events.size() << " events\n";
    const Replayer replayer(ray);
    const int n = replayer.size();
    const int from = request.step < 0 ? 0 : std::min(request.step, n - 1),
              to = request.step < 0 ? n - 1 : from;
    for (int k = from; k <= to && n > 0; ++k) out << "\n" << state_text(t, ray, replayer.at(k));
    out << "\n";
  });
}

}  // namespace raystep::replay
