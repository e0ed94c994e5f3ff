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

namespace raystep {
namespace {

Geometry make_soup(uint32_t seed, int triangles) {
  Geometry g;
  std::mt19937 rng(seed);
  std::uniform_real_distribution<float> u(-2.f, 2.f), s(-0.4f, 0.4f);
  g.begin_object("soup", 0);
  for (int i = 0; i < triangles; ++i) {
    glm::vec3 p(u(rng), u(rng), u(rng));
    g.add_triangle(p, p + glm::vec3(s(rng), s(rng), s(rng)), p + glm::vec3(s(rng), s(rng), s(rng)));
  }
  g.add_sphere(Sphere{glm::vec3(0.5f), 0.4f});
  return g;
}

// Keeps every build event in memory, as the trace reader would read them back.
class CollectBuild final : public BuildListener {
 public:
  std::vector<TraceBuildEvent> events;
  bool wants_candidates(uint32_t) const override { return true; }
  void sah_candidate(uint32_t node, const SahCandidate& c) override {
    TraceBuildEvent b;
    b.type = EventType::sah_candidate;
    b.node = node;
    b.candidate = c;
    events.push_back(b);
  }
  void split(uint32_t node, const KdNodeInfo& info, uint32_t n, int axis, float pos, float cost, float leaf) override {
    TraceBuildEvent b = base(EventType::split, node, info, n, leaf);
    b.axis = axis;
    b.position = pos;
    b.cost = cost;
    events.push_back(b);
  }
  void leaf_made(uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf, LeafReason reason) override {
    TraceBuildEvent b = base(EventType::leaf_made, node, info, n, leaf);
    b.reason = reason;
    events.push_back(b);
  }

 private:
  static TraceBuildEvent base(EventType type, uint32_t node, const KdNodeInfo& info, uint32_t n, float leaf) {
    TraceBuildEvent b;
    b.type = type;
    b.node = node;
    b.depth = info.depth;
    b.box = info.box;
    b.prims = n;
    b.leaf_cost = leaf;
    return b;
  }
};

struct KdScene {
  Geometry g = make_soup(3, 150);
  KdTree tree;
  CollectBuild build;
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
