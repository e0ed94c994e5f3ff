// BVH traces (format version 3): the recorded walk against the kernel's own answer on hundreds of random
// rays, the events against the rules of the walk (box tests name the current node's children, every push is
// popped or the walk ends, a skip only beyond the nearest hit, a leaf's tests are its primitives), the nodes
// the trace lists (every named node and its parents up to the root), and the JSON round trip.
#include <gtest/gtest.h>

#include <algorithm>
#include <array>
#include <map>
#include <set>
#include <string>

#include "raystep/accel/bvh.h"
#include "raystep/accel/structure_options.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/bvh_trace.h"
#include "raystep/trace/record_trace.h"
#include "test_scenes.h"

namespace raystep {
namespace {

// Random rays through the soup's box, every fourth a shadow ray with a finite tmax, plus rays aimed at
// triangle edges (where neighbouring boxes meet).
std::vector<RayRequest> requests(const Geometry& g, size_t count, uint64_t seed) {
  std::vector<RayRequest> out;
  for (const Ray& r : random_rays(g.bounds(), count, seed)) out.push_back(RayRequest{r, RayKind::primary, 0});
  for (const Ray& r : edge_rays(g, count / 4, seed + 1)) out.push_back(RayRequest{r, RayKind::primary, 0});
  for (size_t i = 0; i < out.size(); i += 4) {
    out[i].kind = RayKind::shadow;
    out[i].ray.tmax = 3.f;
  }
  return out;
}

// A hierarchy as the walk's rules need it: each node's children, primitives and depth.
struct TreeView {
  std::vector<std::vector<int32_t>> children;
  std::vector<std::vector<uint32_t>> prims;  // leaves
  std::vector<int32_t> depth;
  bool leaf(int32_t id) const { return children[size_t(id)].empty(); }
};

TreeView view_of(const Bvh& bvh) {
  const BvhData& d = bvh.data();
  TreeView v;
  for (size_t id = 0; id < d.nodes.size(); ++id) {
    const BvhNode& n = d.nodes[id];
    v.children.push_back(n.is_leaf() ? std::vector<int32_t>{}
                                     : std::vector<int32_t>{int32_t(id) + 1, int32_t(n.second_child())});
    v.prims.emplace_back();
    if (n.is_leaf())
      v.prims.back().assign(d.prim_index.begin() + n.first_prim(),
                            d.prim_index.begin() + n.first_prim() + n.prim_count());
    v.depth.push_back(d.info[id].depth);
  }
  return v;
}

TreeView view_of(const WideBvh& bvh) {
  TreeView v;
  for (const WideBvhView::Node& n : bvh.describe().nodes) {
    v.children.push_back(n.children);
    v.prims.push_back(n.prims);
    v.depth.push_back(n.depth);
  }
  return v;
}

// Checks one recorded ray against the rules of a BVH's walk (binary or wide); counts its skips into *skips.
// A node is entered (node, or for the wide BVH's leaves directly leaf) as the root, as a child just
// box-tested with a hit, or as the entry just popped and not skipped.
void check_walk(const TreeView& v, const TracedRay& tr, const std::string& where, int* skips) {
  SCOPED_TRACE(where);
  const std::vector<Event>& ev = tr.events;
  struct Entry {
    int32_t node;
    float t_near, t_far;
  };
  std::vector<Entry> stack;
  std::map<int32_t, Event> tested;  // the current node's box tests, by child
  int32_t current = -1;             // the node being visited
  int32_t leaf = -1;                // the leaf whose primitives are being tested
  bool entered_any = false;
  std::set<int32_t> prims_tested;
  float nearest = kInfinity;
  bool accepted = false;
  auto enter = [&](const Event& e, size_t i) {
    const bool from_pop = i > 0 && ev[i - 1].type == EventType::pop;
    if (from_pop) {
      EXPECT_EQ(e.node, ev[i - 1].node);
    } else if (!entered_any && e.node == 0 && !tested.count(0)) {
      // The root, entered without a box test (the wide BVH's walk).
    } else {
      ASSERT_TRUE(tested.count(e.node)) << "node " << e.node << " entered without a box test";
      EXPECT_TRUE(tested[e.node].hit);
      EXPECT_EQ(e.t_min_node, tested[e.node].t_min_node);
      EXPECT_EQ(e.t_max_node, tested[e.node].t_max_node);
    }
    EXPECT_EQ(e.depth, v.depth[size_t(e.node)]);
    entered_any = true;
    current = e.node;
    leaf = -1;
    tested.clear();
  };
  for (size_t i = 0; i < ev.size(); ++i) {
    const Event& e = ev[i];
    SCOPED_TRACE("event " + std::to_string(i) + " " + event_type_name(e.type));
    switch (e.type) {
      case EventType::box_test:
        if (e.parent < 0) {  // the root's box, before anything else
          EXPECT_EQ(i, 1u);
          EXPECT_EQ(e.node, 0);
          tested.clear();
          tested[0] = e;
        } else {
          EXPECT_EQ(e.parent, current) << "a box test from another node than the current one";
          const std::vector<int32_t>& children = v.children[size_t(current)];
          EXPECT_NE(std::find(children.begin(), children.end(), e.node), children.end()) << e.node;
          EXPECT_EQ(e.depth, v.depth[size_t(e.node)]);
          tested[e.node] = e;
        }
        if (e.hit) EXPECT_LE(e.t_min_node, e.t_max_node);
        break;
      case EventType::node:
        enter(e, i);
        break;
      case EventType::push:
        // A child of the current node whose box was hit, with that box's interval.
        ASSERT_TRUE(tested.count(e.node)) << "pushed " << e.node << " without a box test";
        EXPECT_TRUE(tested[e.node].hit);
        EXPECT_EQ(e.t_min_node, tested[e.node].t_min_node);
        EXPECT_EQ(e.t_max_node, tested[e.node].t_max_node);
        stack.push_back({e.node, e.t_min_node, e.t_max_node});
        break;
      case EventType::pop:
        ASSERT_FALSE(stack.empty()) << "a pop from an empty stack";
        EXPECT_EQ(e.node, stack.back().node);
        EXPECT_EQ(e.t_min_node, stack.back().t_near);
        stack.pop_back();
        break;
      case EventType::skip:
        // Right after the pop of the same entry, and only when it starts beyond the nearest hit.
        ASSERT_GT(i, 0u);
        EXPECT_EQ(ev[i - 1].type, EventType::pop);
        EXPECT_EQ(e.node, ev[i - 1].node);
        EXPECT_GT(e.t_min_node, nearest);
        ++*skips;
        break;
      case EventType::leaf:
        EXPECT_TRUE(v.leaf(e.node));
        // The binary BVH visits the leaf (node), then reaches it; the wide one enters a leaf directly.
        if (!(i > 0 && ev[i - 1].type == EventType::node && ev[i - 1].node == e.node)) enter(e, i);
        leaf = e.node;
        break;
      case EventType::prim_test: {
        ASSERT_GE(leaf, 0) << "a primitive tested outside a leaf";
        const std::vector<uint32_t>& prims = v.prims[size_t(leaf)];
        EXPECT_NE(std::find(prims.begin(), prims.end(), uint32_t(e.prim)), prims.end()) << e.prim;
        EXPECT_TRUE(prims_tested.insert(e.prim).second) << "primitive " << e.prim << " tested twice";
        if (e.hit) nearest = std::min(nearest, e.t);
        break;
      }
      case EventType::hit_accepted:
        EXPECT_EQ(e.prim, ev.back().prim);
        EXPECT_EQ(e.t, ev.back().t);
        accepted = true;
        if (e.reason == AcceptReason::structure_done)
          EXPECT_TRUE(stack.empty());
        else
          EXPECT_EQ(e.reason, AcceptReason::any_hit);
        break;
      case EventType::ray_begin:
      case EventType::ray_end:
        break;
      default:
        ADD_FAILURE() << "unexpected event";
    }
  }
  // Every push is popped, or the walk ended at a shadow ray's first hit.
  if (!stack.empty()) {
    EXPECT_TRUE(accepted);
    EXPECT_EQ(tr.kind, RayKind::shadow);
  }
  EXPECT_EQ(accepted, ev.back().prim >= 0);
}

// The trace's answers are the kernel's: the same primitive and the same t, bit for bit (shadow rays: occluded
// or not), its box tests and nodes counted as the counting recorder counts them, and its events obey the
// rules. Returns {hits, pushes, skips} over the rays.
std::array<int, 3> check_trace(const Accelerator& accel, const TreeView& v, const Trace& t,
                               const std::vector<RayRequest>& rays, const std::string& name) {
  std::array<int, 3> seen{0, 0, 0};
  EXPECT_EQ(t.rays.size(), rays.size());
  for (size_t r = 0; r < rays.size() && r < t.rays.size(); ++r) {
    const Event& end = t.rays[r].events.back();
    EXPECT_EQ(end.type, EventType::ray_end);
    CountingRecorder counted;
    Hit hit;
    if (rays[r].kind == RayKind::shadow) {
      EXPECT_EQ(end.prim >= 0, accel.occluded(rays[r].ray)) << r;
      accel.occluded_counted(rays[r].ray, counted);
    } else {
      accel.intersect(rays[r].ray, &hit);
      EXPECT_EQ(end.prim, hit.prim) << r;
      if (hit.found()) EXPECT_EQ(end.t, hit.t) << r;
      seen[0] += hit.found();
      accel.intersect_counted(rays[r].ray, &hit, counted);
    }
    size_t box_tests = 0, nodes = 0;
    for (const Event& e : t.rays[r].events) {
      box_tests += e.type == EventType::box_test;
      nodes += e.type == EventType::node;
      seen[1] += e.type == EventType::push;
    }
    EXPECT_EQ(box_tests, counted.box_tests) << r;  // the root's own box test included, hit or missed
    EXPECT_EQ(nodes, counted.nodes) << r;
    check_walk(v, t.rays[r], name + " ray " + std::to_string(r), &seen[2]);
    if (::testing::Test::HasFatalFailure()) break;
  }
  return seen;
}

TEST(BvhTrace, RecordedWalkEqualsTheKernelAndObeysTheRules) {
  const Geometry g = test::make_soup(11, 400, 6);
  const std::vector<RayRequest> rays = requests(g, 400, 5);
  for (BvhBuilder builder : {BvhBuilder::binned, BvhBuilder::median})
    for (BvhOrder order : {BvhOrder::entry_distance, BvhOrder::split_axis}) {
      BvhOptions o;
      o.builder = builder;
      o.leaf_size = builder == BvhBuilder::median ? 3 : 1;
      Bvh bvh(o, order);
      bvh.build(g);
      const std::string name =
          bvh.name() + (order == BvhOrder::split_axis ? " split_axis" : " entry_distance");
      SCOPED_TRACE(name);
      const Trace t = record_trace(g, bvh, rays, "soup", "fnv1a64:0000000000000000");
      EXPECT_EQ(t.structure.kind, bvh.name());
      const std::array<int, 3> seen = check_trace(bvh, view_of(bvh), t, rays, name);
      // The rays exercise what the rules are about.
      EXPECT_GT(seen[0], 50);
      EXPECT_GT(seen[1], 200);
      EXPECT_GT(seen[2], 10);
    }
}

// Every kernel this machine runs (scalar, SSE, AVX2): the recorded walk is the one the tests compare with.
TEST(BvhTrace, RecordedWideWalkEqualsTheKernelAndObeysTheRules) {
  const Geometry g = test::make_soup(12, 600, 6);
  const std::vector<RayRequest> rays = requests(g, 400, 6);
  for (WideSimd level : {WideSimd::scalar, WideSimd::sse, WideSimd::avx2}) {
    if (!WideBvh::force_simd(level)) continue;
    for (int width : {4, 8}) {
      WideBvh wide(width);
      wide.build(g);
      const std::string name = wide.name() + " (" + WideBvh::simd_level() + ")";
      SCOPED_TRACE(name);
      const Trace t = record_trace(g, wide, rays, "soup", "fnv1a64:0000000000000000");
      const std::array<int, 3> seen = check_trace(wide, view_of(wide), t, rays, name);
      EXPECT_GT(seen[0], 50);
      EXPECT_GT(seen[1], 100);
      EXPECT_GT(seen[2], 5);
    }
  }
  WideBvh::force_simd(WideBvh::best_simd());
}

// The wide trace's nodes and parameters, and its JSON round trip.
TEST(BvhTrace, WideTraceListsDescribedNodes) {
  const Geometry g = test::make_soup(12, 600, 6);
  const std::vector<RayRequest> rays = requests(g, 100, 6);
  for (int width : {4, 8}) {
    WideBvh wide(width);
    wide.build(g);
    SCOPED_TRACE(wide.name());
    const Trace t = record_trace(g, wide, rays, "soup", "fnv1a64:0000000000000000");
    EXPECT_EQ(t.structure.kind, wide.name());
    // The nodes: every named one with its parents, as describe() has them; wide nodes have no split axis.
    const WideBvhView view = wide.describe();
    std::set<int32_t> listed;
    for (const TraceNode& n : t.nodes) {
      listed.insert(n.id);
      const WideBvhView::Node& d = view.nodes[size_t(n.id)];
      EXPECT_EQ(n.parent, d.parent);
      EXPECT_EQ(n.children, d.children);
      EXPECT_EQ(n.leaf, d.leaf);
      EXPECT_EQ(n.box.lo, d.box.lo);
      if (!n.leaf) EXPECT_EQ(n.axis, -1);
    }
    for (const TraceNode& n : t.nodes)
      if (n.parent >= 0) EXPECT_TRUE(listed.count(n.parent));
    const std::string once = trace_to_json(t);
    EXPECT_NE(once.find("\"axis\":null,\"children\":["), std::string::npos);
    EXPECT_NE(once.find("\"width\":" + std::to_string(width)), std::string::npos);
    EXPECT_EQ(trace_to_json(parse_trace_json(once, "wide.json")), once);
  }
}

TEST(BvhTrace, ListsEveryNamedNodeWithItsParentsAndRoundTrips) {
  const Geometry g = test::make_soup(4, 200, 2);
  Bvh bvh;
  bvh.build(g);
  const std::vector<RayRequest> rays = requests(g, 40, 9);
  const Trace t = record_bvh_trace(g, bvh, rays, "soup", "fnv1a64:0000000000000000");
  const BvhData& d = bvh.data();
  std::map<std::string, std::string> text;
  std::map<std::string, double> number;
  for (const TraceParam& p : t.structure.params)
    if (p.is_text)
      text[p.key] = p.text;
    else
      number[p.key] = p.number;
  EXPECT_EQ(text["builder"], "binned");
  EXPECT_EQ(text["order"], "entry_distance");
  EXPECT_EQ(number["nodes"], double(d.nodes.size()));
  for (const char* k : {"t_i", "t_t", "bins", "leaf_size", "max_leaf_size", "max_depth", "leaves"})
    EXPECT_TRUE(number.count(k)) << k;
  std::set<int32_t> listed;
  for (const TraceNode& n : t.nodes) {
    EXPECT_TRUE(listed.insert(n.id).second);
    const BvhNode& b = d.nodes[size_t(n.id)];
    EXPECT_EQ(n.parent, d.info[size_t(n.id)].parent);
    EXPECT_EQ(n.depth, d.info[size_t(n.id)].depth);
    EXPECT_EQ(n.box.lo, b.box.lo);
    EXPECT_EQ(n.box.hi, b.box.hi);
    EXPECT_EQ(n.leaf, b.is_leaf());
    if (n.leaf) {
      EXPECT_EQ(n.prims.size(), b.prim_count());
      EXPECT_TRUE(n.children.empty());
    } else {
      EXPECT_EQ(n.children, (std::vector<int32_t>{n.id + 1, int32_t(b.second_child())}));
      EXPECT_EQ(n.axis, b.axis());
    }
  }
  for (const TraceNode& n : t.nodes)
    if (n.parent >= 0) EXPECT_TRUE(listed.count(n.parent)) << "the parent of " << n.id << " is not listed";
  for (const TracedRay& r : t.rays)
    for (const Event& e : r.events) {
      if (e.node >= 0) EXPECT_TRUE(listed.count(e.node)) << e.node;
      if (e.type == EventType::box_test && e.parent >= 0) EXPECT_TRUE(listed.count(e.parent));
    }
  // The trace reads back (the validating reader checks ids, children and parents) and writes the same bytes.
  const std::string once = trace_to_json(t);
  const Trace back = parse_trace_json(once, "bvh.json");
  EXPECT_EQ(trace_to_json(back), once);
  EXPECT_EQ(back.version, kTraceVersion);
  EXPECT_NE(trace_summary(back).find(" box tests, "), std::string::npos);
}

TEST(BvhTrace, RaysThatMissTheRootAndAnEmptySceneRecordOneBoxTest) {
  const Geometry g = test::make_soup(2, 20, 0);
  Bvh bvh;
  bvh.build(g);
  RayRequest away;
  away.ray.origin = glm::vec3(10.f, 10.f, 10.f);
  away.ray.direction = glm::vec3(1.f, 0.f, 0.f);
  RayRequest nan = away;
  nan.ray.direction = glm::vec3(std::nanf(""), 0.f, 1.f);
  const Trace t = record_trace(g, bvh, {away, nan}, "soup", "fnv1a64:0000000000000000");
  for (const TracedRay& r : t.rays) {
    ASSERT_EQ(r.events.size(), 3u);
    EXPECT_EQ(r.events[1].type, EventType::box_test);
    EXPECT_EQ(r.events[1].parent, -1);
    EXPECT_FALSE(r.events[1].hit);
    EXPECT_EQ(r.events[2].prim, -1);
  }
  ASSERT_EQ(t.nodes.size(), 1u);  // the root, which the box test names
  // (A NaN ray has no JSON form: only the other one is written.)
  const Trace miss = record_trace(g, bvh, {away}, "soup", "fnv1a64:0000000000000000");
  EXPECT_EQ(trace_to_json(parse_trace_json(trace_to_json(miss), "miss.json")), trace_to_json(miss));

  Geometry empty;
  Bvh none;
  none.build(empty);
  const Trace e = record_trace(empty, none, {away}, "empty", "fnv1a64:0000000000000000");
  EXPECT_EQ(trace_to_json(parse_trace_json(trace_to_json(e), "empty.json")), trace_to_json(e));
}

TEST(BvhTrace, EveryBvhNameFromTheFactoryRecords) {
  const Geometry g = test::make_soup(3, 60, 1);
  for (const char* name : {"bvh", "bvh-sweep", "bvh-median", "bvh4", "bvh8"}) {
    auto accel = make_accelerator(name, StructureOptions{});
    accel->build(g);
    EXPECT_TRUE(records_events(*accel)) << name;
    const Trace t = record_trace(g, *accel, requests(g, 8, 1), "soup", "fnv1a64:0000000000000000");
    EXPECT_EQ(t.structure.kind, name);
  }
}

}  // namespace
}  // namespace raystep
