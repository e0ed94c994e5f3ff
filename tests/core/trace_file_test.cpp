// Trace files: the recorded events of the mailbox trap, the JSON round trip (write -> read -> write is
// identical), CSV, and every malformed case rejected with the file, the line and the JSON path.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <map>
#include <random>
#include <sstream>

#include "raystep/accel/kdtree.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/trace/build_event_writer.h"
#include "raystep/trace/grid_trace.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "test_budget.h"
#include "test_scenes.h"

namespace raystep {
namespace {

// The mailbox trap of grid_test.cpp: a long triangle hit in the third cell, a small one in the second.
struct TrapScene {
  Geometry g;
  UniformGrid grid;
  TrapScene() : grid(options()) {
    g.begin_object("trap", 0);
    g.add_triangle(glm::vec3(0.f, -1.f, 0.f), glm::vec3(0.f, 2.f, 0.f), glm::vec3(3.f, 0.5f, 0.6f));
    g.add_triangle(glm::vec3(1.5f, 0.f, 0.f), glm::vec3(1.5f, 1.f, 0.f), glm::vec3(1.5f, 0.f, 1.f));
    g.add_sphere(Sphere{glm::vec3(2.5f, 1.5f, 0.3f), 0.2f});
    grid.build(g);
  }
  static GridOptions options() {
    GridOptions o;
    o.resolution = std::array<int, 3>{3, 1, 1};
    return o;
  }
  Trace trace() const {
    RayRequest primary;
    primary.ray.origin = glm::vec3(-1.f, 0.5f, 0.5f);
    primary.ray.direction = glm::vec3(1.f, 0.f, 0.f);
    primary.has_pixel = true;
    primary.pixel[0] = 12;
    primary.pixel[1] = 7;
    RayRequest shadow;
    shadow.kind = RayKind::shadow;
    shadow.depth = 1;
    shadow.ray.origin = glm::vec3(2.5f, 1.5f, 2.f);
    shadow.ray.direction = glm::vec3(0.f, -0.f, -1.f);
    shadow.ray.tmax = 10.f;
    return record_grid_trace(g, grid, {primary, shadow}, "trap.json", "fnv1a64:0123456789abcdef");
  }
};

std::vector<EventType> types(const TracedRay& r) {
  std::vector<EventType> out;
  for (const Event& e : r.events) out.push_back(e.type);
  return out;
}

TEST(TraceFile, CoarsenedGridSaysSoInParamsAndSummary) {
  // 20,000 copies of one triangle: the reference budget coarsens the density rule's grid; the trace keeps the
  // resolution asked for and the reason, through the JSON round trip.
  Geometry g;
  g.begin_object("copies", 0);
  for (int i = 0; i < 20000; ++i)
    g.add_triangle(glm::vec3(0.f), glm::vec3(1.f, 0.f, 0.f), glm::vec3(0.f, 1.f, 0.f));
  UniformGrid grid;
  grid.build(g);
  ASSERT_TRUE(grid.coarsened());
  RayRequest down;
  down.ray.origin = glm::vec3(0.25f, 0.25f, 1.f);
  down.ray.direction = glm::vec3(0.f, 0.f, -1.f);
  Trace t =
      parse_trace_json(trace_to_json(record_grid_trace(g, grid, {down}, "copies.obj", "fnv1a64:0")), "t");
  std::array<int, 3> r = grid.requested_resolution();
  std::string from = std::to_string(r[0]) + "x" + std::to_string(r[1]) + "x" + std::to_string(r[2]);
  std::map<std::string, std::string> text;
  for (const TraceParam& p : t.structure.params)
    if (p.is_text) text[p.key] = p.text;
  EXPECT_EQ(text["coarsened_from"], from);
  EXPECT_EQ(text["coarsening"], "reference budget");
  EXPECT_EQ(t.structure.resolution, grid.resolution());
  EXPECT_NE(trace_summary(t).find("(coarsened from " + from + ": reference budget)"), std::string::npos)
      << trace_summary(t);
}

TEST(TraceFile, RecordsTheMailboxTrapStepByStep) {
  TrapScene s;
  Trace t = s.trace();
  ASSERT_EQ(t.rays.size(), 2u);
  using E = EventType;
  std::vector<E> expected = {E::ray_begin,   E::cell,      E::prim_test,    E::hit_deferred, E::cell,
                             E::mailbox_hit, E::prim_test, E::hit_accepted, E::ray_end};
  EXPECT_EQ(types(t.rays[0]), expected);
  const Event& deferred = t.rays[0].events[3];
  EXPECT_EQ(deferred.prim, 0);
  EXPECT_FLOAT_EQ(deferred.t, 3.5f);
  EXPECT_FLOAT_EQ(deferred.t_exit, 2.f);
  const Event& accepted = t.rays[0].events[7];
  EXPECT_EQ(accepted.prim, 1);
  EXPECT_EQ(accepted.reason, AcceptReason::inside_cell);
  const Event& first_cell = t.rays[0].events[1];
  EXPECT_EQ(first_cell.cell[0], 0);
  // The grid's entry comes from the slab test, which moves it outward by at most 2 gamma(3) of the distance
  // (Ize's factor, bounds.h): at most the exact 1, never after it.
  EXPECT_LE(first_cell.t_enter, 1.f);
  EXPECT_GE(first_cell.t_enter, 1.f - gamma(10));
  EXPECT_FLOAT_EQ(first_cell.t_exit, 2.f);
  EXPECT_EQ(first_cell.next_axis, 0);
  EXPECT_EQ(first_cell.t_max.y, kInfinity);  // the ray does not move on y or z
  // The shadow ray stops at the first hit: any_hit.
  EXPECT_EQ(t.rays[1].events[t.rays[1].events.size() - 2].reason, AcceptReason::any_hit);
  // The geometry section: every visited cell's box and every named primitive.
  EXPECT_EQ(t.cells.size(), 2u + 0u + (t.rays[1].events.size() > 0 ? 1u : 0u) - 0u);
  EXPECT_EQ(t.primitives.size(), 3u);
}

TEST(TraceFile, JsonRoundTripIsIdentical) {
  TrapScene s;
  Trace t = s.trace();
  std::string once = trace_to_json(t);
  Trace back = parse_trace_json(once, "mem.json");
  std::string twice = trace_to_json(back);
  EXPECT_EQ(once, twice);
  EXPECT_NE(once.find("\"format\": \"raystep-trace\""), std::string::npos);
  // One event per line.
  EXPECT_NE(once.find("\n    {\"seq\":1,\"type\":\"cell\",\"cell\":[0,0,0],"), std::string::npos) << once;
  EXPECT_NE(once.find("\"tmax\":\"inf\""), std::string::npos);
  ASSERT_EQ(back.rays.size(), 2u);
  EXPECT_EQ(back.rays[0].events.size(), t.rays[0].events.size());
  EXPECT_EQ(back.rays[0].ray.tmax, kInfinity);
  EXPECT_EQ(back.structure.resolution[0], 3);
}

TEST(TraceFile, FilesAreWrittenAtomicallyAndCsvHasOneRowPerEvent) {
  TrapScene s;
  Trace t = s.trace();
  std::string dir = ::testing::TempDir();
  std::string json_path = dir + "/trap_trace.json", csv_path = dir + "/trap_trace.csv";
  write_trace_json(json_path, t);
  write_trace_csv(csv_path, t);
  Trace back = read_trace_json(json_path);
  EXPECT_EQ(trace_to_json(back), trace_to_json(t));
  std::ifstream csv(csv_path);
  std::string line;
  int rows = 0;
  std::getline(csv, line);
  EXPECT_EQ(line.rfind("ray,seq,type,i,j,k,", 0), 0u);
  size_t columns = std::count(line.begin(), line.end(), ',');
  while (std::getline(csv, line)) {
    EXPECT_EQ(size_t(std::count(line.begin(), line.end(), ',')), columns) << line;
    ++rows;
  }
  EXPECT_EQ(rows, int(t.rays[0].events.size() + t.rays[1].events.size()));
  for (const auto& e : std::filesystem::directory_iterator(dir))
    EXPECT_EQ(e.path().string().find(".tmp."), std::string::npos);
}

// Replace the first occurrence of `from` in the trace text and expect a rejection naming line and path.
void expect_rejected(const std::string& text, const std::string& from, const std::string& to,
                     const std::string& message_part, int expected_line = -1) {
  std::string bad = text;
  size_t at = bad.find(from);
  ASSERT_NE(at, std::string::npos) << from;
  bad.replace(at, from.size(), to);
  try {
    parse_trace_json(bad, "bad.json");
    ADD_FAILURE() << "accepted a trace with " << to;
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_GT(e.line(), 0) << e.what();
    if (expected_line > 0) EXPECT_EQ(e.line(), expected_line) << e.what();
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
  }
}

int line_of(const std::string& text, const std::string& needle) {
  size_t at = text.find(needle);
  return 1 + int(std::count(text.begin(), text.begin() + at, '\n'));
}

TEST(TraceFile, MalformedTracesAreRejectedWithFileLineAndPath) {
  TrapScene s;
  std::string text = trace_to_json(s.trace());
  expect_rejected(text, "\"raystep-trace\"", "\"other-trace\"", "not a raystep trace");
  expect_rejected(text, "\"version\": 4", "\"version\": 7", "unsupported trace version 7");
  expect_rejected(text, "\"version\": 4", "\"version\": 0", "unsupported trace version 0");
  expect_rejected(text, "\"type\":\"mailbox_hit\"", "\"type\":\"teleport\"",
                  "unknown event type \"teleport\"", line_of(text, "\"type\":\"mailbox_hit\""));
  expect_rejected(text, "\"prim\":1", "\"prim\":99", "rays[0].events[6].prim: value 99 out of range 0..2");
  expect_rejected(text, "\"cell\":[0,0,0]", "\"cell\":[5,0,0]", "out of range 0..2");
  expect_rejected(text, "\"t_enter\":2.0", "\"t_enter\":null", "t_enter: expected a number, found null");
  expect_rejected(text, "\"seq\":2", "\"seq\":5", "expected 2");
  expect_rejected(text, "\"kind\":\"primary\"", "\"kind\":\"sideways\"", "unknown ray kind");
  // A number too large for a double: nlohmann's overflow, as an InputError on the literal's line.
  expect_rejected(text, "\"t_enter\":2.0", "\"t_enter\":1e400", "number overflow parsing '1e400'",
                  line_of(text, "\"t_enter\":2.0"));
  // Truncation anywhere.
  for (size_t cut : {size_t(10), text.size() / 2, text.size() - 3}) {
    try {
      parse_trace_json(text.substr(0, cut), "cut.json");
      ADD_FAILURE() << "accepted a truncated trace";
    } catch (const InputError& e) {
      EXPECT_NE(std::string(e.what()).find("truncated"), std::string::npos) << e.what();
      EXPECT_GT(e.line(), 0);
    }
  }
  EXPECT_THROW(read_trace_json(::testing::TempDir() + "/no_such_trace.json"), InputError);
}

// ---- version 3: a bounding volume hierarchy's trace ----

// A two-leaf BVH's trace made by hand (bvh_trace_test.cpp records real ones): the root's children are two
// leaves with a triangle each, at x = 2 and x = 3. The first ray tests the root's box (parent -1), then both
// children's, enters the nearer leaf, hits triangle 0, pops the other leaf and skips it; the second misses
// leaf 1's box and ends in a miss.
Trace bvh_trace_by_hand() {
  Trace t;
  t.scene_path = "two.obj";
  t.scene_hash = "fnv1a64:0000000000000002";
  t.scene_primitives = 2;
  t.structure.kind = "bvh";
  t.structure.bounds = Bounds3{glm::vec3(2.f, 0.f, 0.f), glm::vec3(3.f, 1.f, 1.f)};
  t.structure.params = {
      {"builder", true, 0.0, "binned"}, {"leaves", false, 2.0, ""}, {"nodes", false, 3.0, ""}};
  auto event = [](EventType type, int32_t node, int32_t depth, float t_min, float t_max) {
    Event e;
    e.type = type;
    e.node = node;
    e.depth = depth;
    e.t_min_node = t_min;
    e.t_max_node = t_max;
    return e;
  };
  auto box = [](int32_t parent, int32_t child, bool hit, float t_near, float t_far) {
    Event e;
    e.type = EventType::box_test;
    e.parent = parent;
    e.node = child;
    e.depth = parent < 0 ? 0 : 1;  // parent -1: the root's own box, tested first
    e.hit = hit;
    e.t_min_node = hit ? t_near : 0.f;
    e.t_max_node = hit ? t_far : 0.f;
    return e;
  };
  auto prim = [](EventType type, int32_t id, bool hit, float at) {
    Event e;
    e.type = type;
    e.prim = id;
    e.hit = hit;
    e.t = at;
    if (type == EventType::hit_accepted) e.reason = AcceptReason::structure_done;
    return e;
  };
  using E = EventType;
  TracedRay a;
  a.ray.origin = glm::vec3(0.f, 0.5f, 0.25f);
  a.ray.direction = glm::vec3(1.f, 0.f, 0.f);
  a.events = {event(E::ray_begin, -1, 0, 0.f, 0.f),
              box(-1, 0, true, 2.f, 3.f),
              event(E::node, 0, 0, 2.f, 3.f),
              box(0, 1, true, 2.f, 2.f),
              box(0, 2, true, 3.f, 3.f),
              event(E::push, 2, 1, 3.f, 3.f),
              event(E::node, 1, 1, 2.f, 2.f),
              event(E::leaf, 1, 1, 2.f, 2.f),
              prim(E::prim_test, 0, true, 2.f),
              event(E::pop, 2, 1, 3.f, 3.f),
              event(E::skip, 2, 1, 3.f, 3.f),
              prim(E::hit_accepted, 0, true, 2.f),
              prim(E::ray_end, 0, true, 2.f)};
  TracedRay b;
  b.kind = RayKind::shadow;
  b.depth = 1;
  b.ray.origin = glm::vec3(3.f, 0.9f, -1.f);
  b.ray.direction = glm::vec3(0.f, 0.f, 1.f);
  b.ray.tmax = 5.f;
  b.events = {event(E::ray_begin, -1, 0, 0.f, 0.f),
              box(-1, 0, true, 1.f, 2.f),
              event(E::node, 0, 0, 1.f, 2.f),
              box(0, 1, false, 0.f, 0.f),
              box(0, 2, true, 1.f, 2.f),
              event(E::node, 2, 1, 1.f, 2.f),
              event(E::leaf, 2, 1, 1.f, 2.f),
              prim(E::prim_test, 1, false, 0.f),
              prim(E::ray_end, -1, false, kInfinity)};
  for (TracedRay* r : {&a, &b})
    for (size_t i = 0; i < r->events.size(); ++i) r->events[i].seq = uint32_t(i);
  t.rays = {a, b};
  TraceNode root;
  root.box = t.structure.bounds;
  root.axis = 0;
  root.children = {1, 2};
  TraceNode left;
  left.id = 1;
  left.parent = 0;
  left.depth = 1;
  left.box = Bounds3{glm::vec3(2.f, 0.f, 0.f), glm::vec3(2.f, 1.f, 1.f)};
  left.leaf = true;
  left.prims = {0};
  TraceNode right = left;
  right.id = 2;
  right.box = Bounds3{glm::vec3(3.f, 0.f, 0.f), glm::vec3(3.f, 1.f, 1.f)};
  right.prims = {1};
  t.nodes = {root, left, right};
  for (int32_t id : {0, 1}) {
    TracePrimitive p;
    p.id = id;
    const float x = 2.f + float(id);
    p.v[0] = glm::vec3(x, 0.f, 0.f);
    p.v[1] = glm::vec3(x, 1.f, 0.f);
    p.v[2] = glm::vec3(x, 0.f, 1.f);
    t.primitives.push_back(p);
  }
  return t;
}

TEST(TraceFile, Version3BvhTraceRoundTripsWithBoxTestsSkipsAndChildren) {
  const Trace t = bvh_trace_by_hand();
  const std::string once = trace_to_json(t);
  const Trace back = parse_trace_json(once, "bvh.json");
  EXPECT_EQ(trace_to_json(back), once);
  EXPECT_EQ(back.version, kTraceVersion);
  EXPECT_NE(once.find("{\"seq\":3,\"type\":\"box_test\",\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,"
                      "\"t_near\":2.0,\"t_far\":2.0}"),
            std::string::npos)
      << once;
  // A missed box has no interval.
  EXPECT_NE(once.find("{\"seq\":3,\"type\":\"box_test\",\"parent\":0,\"node\":1,\"depth\":1,\"hit\":false}"),
            std::string::npos);
  EXPECT_NE(once.find("{\"seq\":10,\"type\":\"skip\",\"node\":2,\"depth\":1,\"t_min\":3.0,\"t_max\":3.0}"),
            std::string::npos);
  EXPECT_NE(once.find("\"leaf\":false,\"axis\":\"x\",\"children\":[1,2]}"), std::string::npos) << once;
  EXPECT_NE(once.find("\"pops\":1,\"box_tests\":3}"), std::string::npos);
  ASSERT_EQ(back.rays.size(), 2u);
  const Event& box = back.rays[0].events[4];
  EXPECT_EQ(box.type, EventType::box_test);
  EXPECT_EQ(box.parent, 0);
  EXPECT_EQ(box.node, 2);
  EXPECT_TRUE(box.hit);
  EXPECT_EQ(box.t_min_node, 3.f);
  EXPECT_EQ(back.rays[0].events[10].type, EventType::skip);
  EXPECT_FALSE(back.rays[1].events[3].hit);
  ASSERT_EQ(back.nodes.size(), 3u);
  EXPECT_EQ(back.nodes[0].children, (std::vector<int32_t>{1, 2}));
  EXPECT_TRUE(back.nodes[1].children.empty());
  // A wide node has no split axis: null, read back as -1.
  Trace wide = t;
  wide.structure.kind = "bvh8";
  wide.nodes[0].axis = -1;
  const std::string wide_text = trace_to_json(wide);
  EXPECT_NE(wide_text.find("\"axis\":null,\"children\":[1,2]"), std::string::npos);
  EXPECT_EQ(parse_trace_json(wide_text, "wide.json").nodes[0].axis, -1);
  // The summary counts box tests and skips.
  const std::string summary = trace_summary(back);
  EXPECT_NE(summary.find("3 box tests, 1 skips"), std::string::npos) << summary;
  EXPECT_NE(summary.find("box_test=6"), std::string::npos) << summary;
}

TEST(TraceFile, Version3CsvAppendsTheParentColumn) {
  const Trace t = bvh_trace_by_hand();
  const std::string path = ::testing::TempDir() + "/bvh_trace.csv";
  write_trace_csv(path, t);
  std::ifstream csv(path);
  std::string header, line;
  std::getline(csv, header);
  EXPECT_EQ(
      header,
      "ray,seq,type,i,j,k,t_enter,t_exit,t_max_x,t_max_y,t_max_z,t_delta_x,t_delta_y,t_delta_z,next_axis,"
      "node,depth,t_min,t_max,prim,hit,t,reason,sample,parent");
  std::vector<std::string> rows;
  while (std::getline(csv, line)) rows.push_back(line);
  ASSERT_EQ(rows.size(), t.rays[0].events.size() + t.rays[1].events.size());
  EXPECT_EQ(rows[1], "0,1,box_test,,,,,,,,,,,,,0,0,2,3,,1,,,,-1");  // the root's box
  EXPECT_EQ(rows[3], "0,3,box_test,,,,,,,,,,,,,1,1,2,2,,1,,,,0");
  EXPECT_EQ(rows[10], "0,10,skip,,,,,,,,,,,,,2,1,3,3,,,,,,");
  EXPECT_EQ(rows[13 + 3], "1,3,box_test,,,,,,,,,,,,,1,1,,,,0,,,,0");
}

TEST(TraceFile, DamagedVersion3TracesAreRefusedWithLineAndPath) {
  const std::string text = trace_to_json(bvh_trace_by_hand());
  const std::string hit_box = "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":2.0,\"t_far\":2.0";
  const int box_line = line_of(text, hit_box);
  expect_rejected(text, hit_box,
                  "\"parent\":7,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":2.0,\"t_far\":2.0",
                  "rays[0].events[3].parent: value 7 out of range -1..2", box_line);
  expect_rejected(text, hit_box, "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,\"t_far\":2.0",
                  "rays[0].events[3]: missing \"t_near\"", box_line);
  expect_rejected(text, hit_box, "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":2.0",
                  "rays[0].events[3]: missing \"t_far\"", box_line);
  expect_rejected(text, hit_box,
                  "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":null,\"t_far\":2.0",
                  "t_near: expected a number, found null", box_line);
  expect_rejected(text, hit_box,
                  "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":\"-inf\",\"t_far\":2.0",
                  "rays[0].events[3].t_near: expected a finite number", box_line);
  expect_rejected(text, hit_box,
                  "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":2.0,\"t_far\":1.0",
                  "rays[0].events[3].t_far: below t_near", box_line);
  expect_rejected(text, hit_box, "\"parent\":0,\"node\":1,\"depth\":1,\"hit\":1,\"t_near\":2.0,\"t_far\":2.0",
                  "rays[0].events[3].hit: expected true or false", box_line);
  expect_rejected(text, hit_box,
                  "\"parent\":0,\"node\":1,\"depth\":0,\"hit\":true,\"t_near\":2.0,\"t_far\":2.0",
                  "rays[0].events[3].depth: expected 1, the depth of node 1 in geometry.nodes", box_line);
  expect_rejected(text, hit_box,
                  "\"parent\":1,\"node\":1,\"depth\":1,\"hit\":true,\"t_near\":2.0,\"t_far\":2.0",
                  "rays[0].events[3].node: a node is not its own child", box_line);
  expect_rejected(text, hit_box,
                  "\"parent\":1,\"node\":2,\"depth\":1,\"hit\":true,\"t_near\":2.0,\"t_far\":2.0",
                  "rays[0].events[3].node: node 2 is not a child of node 1", box_line);
  // The root's own box test names no parent.
  const std::string root_box = "\"parent\":-1,\"node\":0,\"depth\":0";
  expect_rejected(text, root_box, "\"parent\":-1,\"node\":1,\"depth\":1",
                  "rays[0].events[1].parent: only the root's box (node 0) is tested without a parent");
  expect_rejected(text, root_box, "\"parent\":-1,\"node\":0,\"depth\":1",
                  "rays[0].events[1].depth: expected 0, the depth of node 0 in geometry.nodes");
  expect_rejected(text, "\"type\":\"skip\",\"node\":2", "\"type\":\"skip\",\"node\":3",
                  "rays[0].events[10].node: value 3 out of range 0..2");
  expect_rejected(text, "\"type\":\"skip\",\"node\":2,\"depth\":1,\"t_min\":3.0",
                  "\"type\":\"skip\",\"node\":2,\"depth\":1", "rays[0].events[10]: missing \"t_min\"");
  // The nodes: children in range, distinct, present on every inner node; the parent chain consistent.
  const int root_line = line_of(text, "\"children\":[1,2]");
  expect_rejected(text, "\"children\":[1,2]", "\"children\":[1,9]",
                  "geometry.nodes[0].children[1]: value 9 out of range 0..2", root_line);
  expect_rejected(text, "\"children\":[1,2]", "\"children\":[1,1]",
                  "geometry.nodes[0].children[1]: child 1 is listed twice", root_line);
  expect_rejected(text, "\"children\":[1,2]", "\"children\":[]",
                  "geometry.nodes[0].children: expected 1 to 8", root_line);
  expect_rejected(text, "\"children\":[1,2]", "\"children\":[0,2]",
                  "geometry.nodes[0].children[0]: a node is not its own child", root_line);
  expect_rejected(text, ",\"children\":[1,2]", "",
                  "geometry.nodes[0]: missing \"children\" (an inner BVH node lists its children)",
                  root_line);
  expect_rejected(text, "\"children\":[1,2]", "\"children\":[1]",
                  "geometry.nodes[2].parent: node 0 does not list it as a child");
  expect_rejected(text, "{\"id\":2,\"parent\":0,\"depth\":1", "{\"id\":2,\"parent\":0,\"depth\":2",
                  "geometry.nodes[2].depth: expected 1, one below its parent");
  expect_rejected(text, "{\"id\":2,\"parent\":0,\"depth\":1", "{\"id\":2,\"parent\":1,\"depth\":1",
                  "geometry.nodes[2].parent: node 1 does not list it as a child");
  expect_rejected(text, "\"prims\":[1]}", "\"prims\":[1],\"children\":[0]}",
                  "geometry.nodes[2].children: a leaf has no children");
  // Box tests and skips are version 3's: a version 2 document with one is refused.
  expect_rejected(text, "\"version\": 4", "\"version\": 2",
                  "rays[0].events[1].type: event type \"box_test\" needs version 3",
                  line_of(text, "\"type\":\"box_test\""));
}

// ---- the reader on damaged traces ----

// What the reader makes of a text, in words: the trace written back, or the error with its file and line.
std::string new_reader(const std::string& text) {
  try {
    return "trace " + trace_to_json(parse_trace_json(text, "x.json"));
  } catch (const InputError& e) {
    return "error " + e.file() + "|" + std::to_string(e.line()) + "|" + e.what();
  } catch (const nlohmann::json::exception& e) {
    return std::string("json exception ") + e.what();
  } catch (const std::exception& e) {
    return std::string("exception ") + e.what();
  }
}

// A kd trace with every kind of tree event, the nodes, and the build events.
std::string kd_trace_text() {
  Geometry g = test::make_soup(5, 5, 1);
  KdTree tree;
  BuildEventCollector build;
  tree.build(g, build);
  std::vector<RayRequest> rays;
  for (const Ray& r : random_rays(g.bounds(), 3, 4))
    rays.push_back(RayRequest{r, RayKind::primary, 0, false, {0, 0}});
  rays[1].kind = RayKind::shadow;
  Trace t = record_trace(g, tree, rays, "soup", "fnv1a64:0000000000000000");
  t.build = build.events;
  return trace_to_json(t);
}

// Random damage to a trace: a token replaced by another value, a token deleted, a member repeated with
// another value (the last one counts), or bytes changed, cut or inserted. The reader either reads a trace,
// which then reads back the same, or refuses it with an InputError naming the file (a line where there is
// one): never another exception, a crash or a hang. (When the reader moved from nlohmann's DOM to the tape,
// this test also held it to the old reader's exact messages on 4,500 damaged traces, and once on 80,000.)
void expect_reader_survives_damage(const std::string& text, int trials, uint32_t seed) {
  std::vector<std::pair<size_t, size_t>> tokens;  // [begin, end) of strings, numbers, literals
  std::vector<size_t> keys;                       // where a member's key starts
  for (size_t i = 0; i < text.size();) {
    char c = text[i];
    size_t j = i + 1;
    if (c == '"') {
      while (j < text.size() && text[j] != '"') ++j;
      ++j;
      if (j < text.size() && text[j] == ':') keys.push_back(i);
    } else if (std::isalnum(static_cast<unsigned char>(c)) || c == '-') {
      while (j < text.size() && (std::isalnum(static_cast<unsigned char>(text[j])) || text[j] == '.' ||
                                 text[j] == '-' || text[j] == '+'))
        ++j;
    } else {
      ++i;
      continue;
    }
    tokens.emplace_back(i, j);
    i = j;
  }
  const char* values[] = {"0",
                          "1",
                          "2",
                          "-1",
                          "3",
                          "99",
                          "4096",
                          "4097",
                          "1e400",
                          "-0",
                          "0.5",
                          "4294967296",
                          "18446744073709551615",
                          "9223372036854775808",
                          "-9223372036854775809",
                          "1e39",
                          "3.5e38",
                          "1e-50",
                          "null",
                          "true",
                          "false",
                          "\"inf\"",
                          "\"-inf\"",
                          "\"x\"",
                          "\"w\"",
                          "\"cell\"",
                          "\"node\"",
                          "\"split\"",
                          "\"leaf_made\"",
                          "\"prim_test\"",
                          "\"ray_begin\"",
                          "\"ray_end\"",
                          "\"grid\"",
                          "\"kd\"",
                          "\"sphere\"",
                          "\"triangle\"",
                          "\"below\"",
                          "\"budget\"",
                          "\"any_hit\"",
                          "\"shadow\"",
                          "\"box_test\"",
                          "\"skip\"",
                          "\"bvh\"",
                          "[]",
                          "{}",
                          "[0,0,0]",
                          "[1,2]",
                          "[1,2,3,4]",
                          "\"caf\\u00e9\"",
                          "\"\\\"\"",
                          "\"trace\"",
                          "\"\""};
  const std::string bytes = "{}[],:\"\\ 0123456789.-+eE\ntrufalsnx";
  std::mt19937 rng(seed);
  int accepted = 0;
  for (int trial = 0; trial < trials; ++trial) {
    std::string bad = text;
    switch (rng() % 4) {
      case 0: {
        auto [b, e] = tokens[rng() % tokens.size()];
        bad.replace(b, e - b, values[rng() % std::size(values)]);
        break;
      }
      case 1: {
        auto [b, e] = tokens[rng() % tokens.size()];
        bad.erase(b, e - b);
        break;
      }
      case 2: {
        size_t k = keys[rng() % keys.size()];
        size_t colon = bad.find(':', k);
        bad.insert(k, bad.substr(k, colon + 1 - k) + values[rng() % std::size(values)] + ",");
        break;
      }
      case 3: {
        size_t at = rng() % bad.size();
        char c = bytes[rng() % bytes.size()];
        switch (rng() % 3) {
          case 0:
            bad[at] = c;
            break;
          case 1:
            bad.erase(at, 1 + rng() % 3);
            break;
          case 2:
            bad.resize(at);
            break;
        }
        break;
      }
    }
    std::string got = new_reader(bad);
    if (got.rfind("trace ", 0) == 0) {
      ++accepted;
      ASSERT_EQ(new_reader(got.substr(6)), got) << bad;  // what it read writes back and reads the same
    } else {
      ASSERT_EQ(got.rfind("error x.json|", 0), 0u) << got << "\n" << bad;
    }
  }
  EXPECT_GT(accepted, 0);  // some damage is harmless (a repeated key, a number changed within its range)
}

TEST(TraceFile, DamagedTracesAreReadOrRefusedWithTheFileNamed) {
  TrapScene s;
  std::string grid = trace_to_json(s.trace());
  std::string kd = kd_trace_text();
  for (const char* part :
       {"\"type\":\"push\"", "\"type\":\"pop\"", "\"type\":\"leaf\"", "\"type\":\"prim_test\"",
        "\"type\":\"sah_candidate\"", "\"type\":\"split\"", "\"type\":\"leaf_made\"", "\"nodes\": ["})
    EXPECT_NE(kd.find(part), std::string::npos) << part;
  for (const char* part :
       {"\"type\":\"mailbox_hit\"", "\"type\":\"hit_deferred\"", "\"type\":\"sphere\"", "\"pixel\""})
    EXPECT_NE(grid.find(part), std::string::npos) << part;
  EXPECT_EQ(new_reader(grid), "trace " + grid);
  EXPECT_EQ(new_reader(kd), "trace " + kd);
  const std::string bvh = trace_to_json(bvh_trace_by_hand());
  EXPECT_EQ(new_reader(bvh), "trace " + bvh);
  expect_reader_survives_damage(grid, test::budget(3000), 1);
  expect_reader_survives_damage(kd, test::budget(1500), 2);
  expect_reader_survives_damage(bvh, test::budget(1500), 3);
}

}  // namespace
}  // namespace raystep
