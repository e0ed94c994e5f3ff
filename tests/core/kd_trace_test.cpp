// kd-tree traces: the recorded walk with the nodes it names (boxes, split planes, leaves' primitives), the build
// events streamed by BuildEventWriter, the JSON round trip (write -> read -> write is identical), and the
// validating reader's refusals for tree-specific damage.
#include <gtest/gtest.h>

#include <random>
#include <set>
#include <sstream>

#include "raystep/scene/ray_sets.h"
#include "raystep/trace/build_event_writer.h"
#include "raystep/trace/kd_trace.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

struct KdScene {
  Geometry g = test::make_soup(3, 150, 1);
  KdTree tree;
  BuildEventCollector build;
  Trace trace() {
    tree.build(g, build);
    std::vector<RayRequest> rays;
    for (const Ray& r : random_rays(g.bounds(), 12, 4)) rays.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
    rays[1].kind = RayKind::shadow;
    rays[2].has_pixel = true;
    rays[2].pixel[0] = 7;
    Trace t = record_trace(g, tree, rays, "soup", "fnv1a64:0000000000000000");
    t.build = build.events;
    return t;
  }
};

TEST(KdTrace, NamesEveryNodeItsEventsVisit) {
  KdScene s;
  Trace t = s.trace();
  EXPECT_EQ(t.structure.kind, "kd");
  std::set<std::string> keys;
  for (const TraceParam& p : t.structure.params) keys.insert(p.key);
  for (const char* k : {"builder", "t_i", "t_t", "empty_bonus", "max_depth", "leaf_size", "mailboxes", "nodes"})
    EXPECT_TRUE(keys.count(k)) << k;
  std::set<int32_t> listed;
  for (const TraceNode& n : t.nodes) {
    listed.insert(n.id);
    const KdNodeInfo& info = s.tree.data().info[size_t(n.id)];
    EXPECT_EQ(n.box.lo, info.box.lo);
    EXPECT_EQ(n.depth, info.depth);
    EXPECT_EQ(n.leaf, s.tree.data().nodes[size_t(n.id)].is_leaf());
    if (!n.leaf) EXPECT_EQ(n.split, s.tree.data().nodes[size_t(n.id)].split);
  }
  size_t tree_events = 0;
  for (const TracedRay& r : t.rays)
    for (const Event& e : r.events)
      if (e.type == EventType::node || e.type == EventType::push || e.type == EventType::pop ||
          e.type == EventType::leaf) {
        EXPECT_TRUE(listed.count(e.node)) << e.node;
        ++tree_events;
      }
  EXPECT_GT(tree_events, 20u);
  // The shadow ray stops at its first hit, or misses.
  const Event& last = t.rays[1].events[t.rays[1].events.size() - 2];
  if (t.rays[1].events.back().prim >= 0) EXPECT_EQ(last.reason, AcceptReason::any_hit);
}

TEST(KdTrace, JsonRoundTripIsIdenticalWithNodesAndBuildEvents) {
  KdScene s;
  Trace t = s.trace();
  ASSERT_GT(t.build.size(), 10u);
  std::string once = trace_to_json(t);
  Trace back = parse_trace_json(once, "kd.json");
  EXPECT_EQ(trace_to_json(back), once);
  EXPECT_EQ(back.nodes.size(), t.nodes.size());
  EXPECT_EQ(back.build.size(), t.build.size());
  EXPECT_NE(once.find("\"type\":\"leaf_made\""), std::string::npos);
}

// The streamed log and a collected one agree, event for event, with the builder's own decisions.
TEST(KdTrace, StreamedBuildEventsAreTheSameAsCollectedOnes) {
  KdScene s;
  Trace t = s.trace();
  std::ostringstream streamed;
  BuildEventWriter writer(streamed);
  KdTree again;
  again.build(s.g, writer);
  std::string collected;
  for (size_t i = 0; i < t.build.size(); ++i) collected += (i ? ",\n  " : "\n  ") + build_event_json(t.build[i], i);
  EXPECT_EQ(writer.count(), t.build.size());
  EXPECT_EQ(streamed.str(), collected);
  // One decision per node, matching the tree: splits where the tree has inner nodes, at their planes.
  const KdTreeData& d = s.tree.data();
  std::vector<int> decisions(d.nodes.size(), 0);
  for (const TraceBuildEvent& b : t.build) {
    if (b.type == EventType::sah_candidate) continue;
    ASSERT_LT(b.node, d.nodes.size());
    ++decisions[b.node];
    const KdNode& n = d.nodes[b.node];
    EXPECT_EQ(b.type == EventType::leaf_made, n.is_leaf()) << b.node;
    if (!n.is_leaf()) {
      EXPECT_EQ(b.axis, n.axis());
      EXPECT_EQ(b.position, n.split);
    } else {
      EXPECT_EQ(b.prims, n.prim_count());
    }
    EXPECT_EQ(b.box.lo, d.info[b.node].box.lo);
  }
  for (size_t i = 0; i < decisions.size(); ++i) EXPECT_EQ(decisions[i], 1) << "node " << i;
}

TEST(KdTrace, DamagedTreeTracesAreRefused) {
  KdScene s;
  std::string text = trace_to_json(s.trace());
  auto expect_refused = [&](const std::string& from, const std::string& to, const std::string& what) {
    size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    std::string bad = text.substr(0, at) + to + text.substr(at + from.size());
    try {
      parse_trace_json(bad, "bad.json");
      ADD_FAILURE() << "accepted: " << what;
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find(what), std::string::npos) << e.what();
      EXPECT_EQ(e.file(), "bad.json");
      EXPECT_GT(e.line(), 0);
    }
  };
  expect_refused("\"type\":\"split\"", "\"type\":\"cell\"", "unknown build event type");
  expect_refused("\"reason\":\"", "\"reason\":\"tired", "unknown leaf reason");
  expect_refused("\"nodes\": [\n   {\"id\":", "\"nodes\": [\n   {\"id\":99999999,\"was\":", "out of range");
  expect_refused("\"leaf\":false,\"axis\":\"", "\"leaf\":false,\"axis\":\"w", "expected \"x\"");
}

}  // namespace
}  // namespace raystep
