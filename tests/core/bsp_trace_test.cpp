// BSP traces (format version 4): the recorded walk against the kernel's own answer on hundreds of random rays
// through a slanted scene, every inner node named with the tree's plane, the JSON round trip (same planes,
// bit for bit, same bytes), the reader's checks of the new keys, and version 3 documents still read.
#include <gtest/gtest.h>

#include <random>

#include "raystep/accel/bsp.h"
#include "raystep/accel/kdtree.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

Geometry slanted_scene() {
  Geometry g = test::make_soup(61, 150, 2);
  g.begin_object("tilted", 0);
  for (int i = 0; i < 100; ++i) {  // a tilted strip of thin triangles
    glm::vec3 p(-2.f + 0.04f * float(i), -1.f + 0.03f * float(i), 0.5f * (-2.f + 0.04f * float(i)));
    g.add_triangle(p, p + glm::vec3(0.03f, 0.8f, 0.015f), p + glm::vec3(0.035f, 0.f, 0.0175f));
  }
  return g;
}

std::vector<RayRequest> requests(const Geometry& g, size_t n) {
  std::vector<RayRequest> out;
  for (const Ray& r : random_rays(g.bounds(), n, 62)) {
    RayRequest q;
    q.ray = r;
    out.push_back(q);
  }
  return out;
}

TEST(BspTrace, RecordedWalksMatchTheKernelAndNameTheirPlanes) {
  Geometry g = slanted_scene();
  BspTree tree;
  tree.build(g);
  std::vector<RayRequest> rays = requests(g, 400);
  Trace t = record_trace(g, tree, rays, "slanted", "fnv1a64:0000000000000000");
  EXPECT_EQ(t.structure.kind, "bsp");
  ASSERT_EQ(t.rays.size(), rays.size());
  int hits = 0;
  for (size_t i = 0; i < rays.size(); ++i) {
    Hit h;
    tree.intersect(rays[i].ray, &h);
    EXPECT_EQ(t.rays[i].events.back().prim, h.prim) << i;
    hits += h.found();
  }
  EXPECT_GT(hits, 15);
  const BspTreeData& d = tree.data();
  int planes = 0;
  for (const TraceNode& n : t.nodes) {
    const BspNode& node = d.nodes[size_t(n.id)];
    EXPECT_EQ(n.leaf, node.is_leaf());
    EXPECT_EQ(n.has_plane, !node.is_leaf());
    if (n.has_plane) {
      EXPECT_EQ(n.normal, node.plane.normal);
      EXPECT_EQ(n.offset, node.plane.offset);
      ++planes;
    }
  }
  EXPECT_GT(planes, 20);
  // The plane counts by source add up to the tree's inner nodes.
  double inner = 0, nodes = 0, leaves = 0;
  for (const TraceParam& p : t.structure.params) {
    if (p.key.rfind("planes_", 0) == 0) inner += p.number;
    if (p.key == "nodes") nodes = p.number;
    if (p.key == "leaves") leaves = p.number;
  }
  EXPECT_EQ(inner, nodes - leaves);
  EXPECT_GT(inner, 0);
}

TEST(BspTrace, RoundTripsWithTheSamePlanes) {
  Geometry g = slanted_scene();
  BspTree tree;
  tree.build(g);
  Trace t = record_trace(g, tree, requests(g, 40), "slanted", "fnv1a64:0000000000000000");
  const std::string text = trace_to_json(t);
  EXPECT_EQ(text.rfind("{\n \"format\": \"raystep-trace\",\n \"version\": 4,", 0), 0u);
  Trace back = parse_trace_json(text, "bsp.json");
  EXPECT_EQ(back.version, 4);
  ASSERT_EQ(back.nodes.size(), t.nodes.size());
  for (size_t i = 0; i < t.nodes.size(); ++i) {
    EXPECT_EQ(back.nodes[i].has_plane, t.nodes[i].has_plane);
    EXPECT_EQ(back.nodes[i].normal, t.nodes[i].normal);  // bit for bit
    EXPECT_EQ(back.nodes[i].offset, t.nodes[i].offset);
  }
  EXPECT_EQ(trace_to_json(back), text);
}

void expect_rejected(const std::string& text, const std::string& from, const std::string& to,
                     const std::string& message_part) {
  std::string bad = text;
  size_t at = bad.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  bad.replace(at, from.size(), to);
  try {
    parse_trace_json(bad, "bad.json");
    ADD_FAILURE() << "accepted a trace with " << to;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
  }
}

TEST(BspTrace, ReaderChecksThePlanes) {
  Geometry g = slanted_scene();
  BspTree tree;
  tree.build(g);
  const std::string text =
      trace_to_json(record_trace(g, tree, requests(g, 10), "s", "fnv1a64:0000000000000000"));
  expect_rejected(text, "\"normal\":[", "\"normal\":[0,0,0],\"x\":[", "expected a finite unit normal");
  expect_rejected(text, "\"normal\":[", "\"normal\":[3,0,0],\"x\":[", "expected a finite unit normal");
  expect_rejected(text, "\"normal\":[", "\"normal\":[\"inf\",0,0],\"x\":[", "normal");
  expect_rejected(text, "\"offset\":", "\"offset\":null,\"x\":", "offset");
  expect_rejected(text, "\"normal\":[", "\"axis\":\"x\",\"nothing\":[", "normal");
  // A BSP structure did not exist before version 4.
  expect_rejected(text, "\"version\": 4", "\"version\": 3", "axis");
}

TEST(BspTrace, Version3DocumentsStillRead) {
  // A kd-tree's trace written now, labelled version 3 (its content is the same in both versions).
  Geometry g = slanted_scene();
  KdTree kd;
  kd.build(g);
  std::string text = trace_to_json(record_trace(g, kd, requests(g, 20), "s", "fnv1a64:0000000000000000"));
  const std::string v4 = text;
  text.replace(text.find("\"version\": 4"), 12, "\"version\": 3");
  Trace t = parse_trace_json(text, "v3.json");
  EXPECT_EQ(t.version, 3);
  for (const TraceNode& n : t.nodes) EXPECT_FALSE(n.has_plane);
  EXPECT_EQ(trace_to_json(t), v4);  // written back as version 4, otherwise the same bytes
}

}  // namespace
}  // namespace raystep
