// Multi-walk traces (trace/multi_trace.h) and the cost along t (trace/walk_cost.h): each walk equals the
// single structure's trace event for event, the JSON round trip is exact, damaged files are refused with the
// file, line and path, and the cost along t never decreases and ends at the counters' cost.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <cmath>
#include <fstream>
#include <random>

#include "raystep/accel/structure_options.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/trace/record_trace.h"
#include "raystep/trace/walk_cost.h"
#include "raystep/util/error.h"
#include "test_scenes.h"

namespace raystep {
namespace {

struct Walks {
  Geometry g = test::make_soup(16, 150, 4);
  std::vector<std::unique_ptr<Accelerator>> accels;
  std::vector<RayRequest> rays;

  explicit Walks(const std::vector<std::string>& names) {
    for (const std::string& n : names) {
      accels.push_back(make_accelerator(n, StructureOptions{}));
      accels.back()->build(g);
    }
    // Rays from outside the soup towards random points inside it, and one that misses everything.
    std::mt19937 rng(7);
    std::uniform_real_distribution<float> u(-1.5f, 1.5f);
    for (int i = 0; i < 12; ++i) {
      RayRequest r;
      r.ray.origin = glm::vec3(u(rng), u(rng), -6.f);
      r.ray.direction = glm::vec3(u(rng), u(rng), 6.f) - r.ray.origin;
      r.has_pixel = true;
      r.pixel[0] = i;
      rays.push_back(r);
    }
    RayRequest miss;
    miss.ray.origin = glm::vec3(10.f, 10.f, 10.f);
    miss.ray.direction = glm::vec3(1.f, 0.f, -0.f);
    rays.push_back(miss);
  }
  std::vector<const Accelerator*> pointers() const {
    std::vector<const Accelerator*> p;
    for (const auto& a : accels) p.push_back(a.get());
    return p;
  }
  MultiTrace record() const {
    return record_walks(g, pointers(), rays, "soup.json", "fnv1a64:0123456789abcdef");
  }
};

const std::vector<std::string> kSix = {"grid", "kd", "bvh", "octree", "bsp", "bvh8"};
const std::vector<std::string> kOthers = {"kd-median", "bvh-sweep", "bvh-median", "bvh4"};

TEST(MultiTrace, EachWalkIsTheSingleStructuresTraceEventForEvent) {
  for (const auto& names : {kSix, kOthers}) {
    Walks w(names);
    MultiTrace m = w.record();
    ASSERT_EQ(m.walks.size(), names.size());
    EXPECT_EQ(m.scene_primitives, w.g.size());
    size_t events = 0;
    for (size_t i = 0; i < names.size(); ++i) {
      Trace single = record_trace(w.g, *w.accels[i], w.rays, "soup.json", "fnv1a64:0123456789abcdef");
      EXPECT_EQ(m.walks[i].structure.kind, names[i]);
      EXPECT_EQ(trace_to_json(m.walks[i]), trace_to_json(single)) << names[i];
      for (const TracedRay& r : m.walks[i].rays) events += r.events.size();
    }
    EXPECT_GT(events, 100u);
  }
}

TEST(MultiTrace, JsonRoundTripIsExactAndCsvHasAWalkColumn) {
  Walks w(kSix);
  MultiTrace m = w.record();
  const std::string text = multi_trace_to_json(m);
  EXPECT_EQ(nlohmann::json::parse(text)["version"], 5);
  MultiTrace back = parse_multi_trace_json(text, "multi.json");
  EXPECT_EQ(back.version, kMultiTraceVersion);
  ASSERT_EQ(back.walks.size(), m.walks.size());
  EXPECT_EQ(back.scene_path, "soup.json");
  EXPECT_EQ(multi_trace_to_json(back), text);
  for (size_t i = 0; i < m.walks.size(); ++i)
    EXPECT_EQ(trace_to_json(back.walks[i]), trace_to_json(m.walks[i]));

  const std::string dir = ::testing::TempDir();
  write_multi_trace_csv(dir + "/multi.csv", m);
  std::ifstream in(dir + "/multi.csv");
  std::string line;
  std::getline(in, line);
  EXPECT_EQ(line.rfind("walk,ray,seq,type,", 0), 0u) << line;
  size_t rows = 0, events = 0;
  std::vector<size_t> per_walk(m.walks.size(), 0);
  while (std::getline(in, line)) {
    ++rows;
    ++per_walk.at(std::stoul(line.substr(0, line.find(','))));
  }
  for (size_t i = 0; i < m.walks.size(); ++i) {
    size_t n = 0;
    for (const TracedRay& r : m.walks[i].rays) n += r.events.size();
    EXPECT_EQ(per_walk[i], n);
    events += n;
  }
  EXPECT_EQ(rows, events);
}

TEST(MultiTrace, SingleTracesKeepTheirReaderAndForm) {
  Walks w(kSix);
  MultiTrace m = w.record();
  const std::string single = trace_to_json(m.walks[1]);
  EXPECT_EQ(nlohmann::json::parse(single)["version"], kTraceVersion);
  // The single trace's reader refuses the multi-walk form in one line that says what it is.
  try {
    parse_trace_json(multi_trace_to_json(m), "multi.json");
    ADD_FAILURE() << "a single trace reader accepted a multi-walk trace";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("several structures"), std::string::npos) << e.what();
  }
  EXPECT_THROW(parse_multi_trace_json(single, "single.json"), InputError);
}

void expect_refused(const nlohmann::ordered_json& doc, const std::string& message_part) {
  try {
    parse_multi_trace_json(doc.dump(1), "bad.json");
    ADD_FAILURE() << "accepted a damaged multi-walk trace (" << message_part << ")";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "bad.json");
    EXPECT_NE(std::string(e.what()).find(message_part), std::string::npos) << e.what();
    EXPECT_EQ(std::string(e.what()).find('\n'), std::string::npos) << e.what();
  }
}

TEST(MultiTrace, DamagedFilesAreRefusedWithTheWalksPath) {
  Walks w({"grid", "kd", "bvh"});
  const std::string text = multi_trace_to_json(w.record());
  using J = nlohmann::ordered_json;
  const J doc = J::parse(text);
  {
    J d = doc;
    d["walks"].erase(1);
    d["walks"].erase(1);
    expect_refused(d, "walks: expected 2 to 6 walks, found 1");
  }
  {
    J d = doc;
    for (int i = 0; i < 4; ++i) d["walks"].push_back(doc["walks"][0]);
    expect_refused(d, "walks: expected 2 to 6 walks, found 7");
  }
  {
    J d = doc;
    d["walks"][2]["geometry"]["nodes"].erase(0);  // the root, which every event names first
    expect_refused(d, "walks[2].");
  }
  {
    J d = doc;
    d["walks"][1]["rays"][0]["events"][1]["node"] = 1 << 30;
    expect_refused(d, "walks[1].rays[0].events[1].node");
  }
  {
    J d = doc;
    d["walks"][1]["rays"][3]["origin"][0] = 5.0;
    expect_refused(d, "walks[1].rays[3]: not the same ray as walks[0].rays[3]");
  }
  {
    J d = doc;
    d["walks"][2]["rays"].erase(0);
    expect_refused(d, "walks[2].rays: 12 rays, but walks[0] has 13");
  }
  {
    J d = doc;
    d["walks"][0].erase("structure");
    expect_refused(d, "walks[0]: missing \"structure\"");
  }
  {
    J d = doc;
    d["walks"][1]["rays"][0]["events"][0]["type"] = "teleport";
    expect_refused(d, "walks[1].rays[0].events[0].type: unknown event type");
  }
  // Truncated: an InputError, not a crash.
  EXPECT_THROW(parse_multi_trace_json(text.substr(0, text.size() / 2), "cut.json"), InputError);
}

TEST(MultiTrace, RecordWalksRefusesBadLists) {
  Walks w({"grid", "kd", "bvh", "octree", "bsp", "bvh8", "bvh4", "brute"});
  auto p = w.pointers();
  EXPECT_THROW(record_walks(w.g, {p[0]}, w.rays, "s", "h"), InputError);
  EXPECT_THROW(record_walks(w.g, {p.begin(), p.begin() + 7}, w.rays, "s", "h"), InputError);
  EXPECT_THROW(record_walks(w.g, {p[0], p[7]}, w.rays, "s", "h"), InputError);  // brute records no events
}

TEST(WalkCost, MonotoneAlongTAndEqualToTheCountersAtTheEnd) {
  Walks w(kSix);
  MultiTrace m = w.record();
  const CostModel model;  // the lecture's t_t = 1, t_i = 80
  int hits = 0;
  for (const Trace& walk : m.walks)
    for (const TracedRay& ray : walk.rays) {
      const WalkCost c = walk_cost(ray, model);
      uint32_t steps = 0, tests = 0, mailbox = 0;
      for (const Event& e : ray.events) {
        steps += e.type == EventType::cell || e.type == EventType::node;
        tests += e.type == EventType::prim_test;
        mailbox += e.type == EventType::mailbox_hit;
      }
      EXPECT_EQ(c.steps, steps);
      EXPECT_EQ(c.prim_tests, tests);
      EXPECT_EQ(c.mailbox_hits, mailbox);
      EXPECT_EQ(c.total, model.t_t * steps + model.t_i * tests);
      ASSERT_EQ(c.points.size(), steps + 1u);
      EXPECT_EQ(c.points.back().cost, c.total);
      for (size_t i = 1; i < c.points.size(); ++i) {
        EXPECT_LE(c.points[i - 1].t, c.points[i].t) << walk.structure.kind;
        EXPECT_LE(c.points[i - 1].cost, c.points[i].cost) << walk.structure.kind;
      }
      EXPECT_EQ(cost_at(c, kInfinity), c.total);
      EXPECT_EQ(cost_at(c, c.points.back().t), c.total);
      EXPECT_EQ(cost_at(c, -kInfinity), 0.0);
      double previous = 0.0;
      for (float t = -8.f; t <= 16.f; t += 0.25f) {
        const double v = cost_at(c, t);
        EXPECT_LE(previous, v);
        previous = v;
      }
      if (c.hit) {
        ++hits;
        EXPECT_EQ(c.t_hit, ray.events.back().t);
        EXPECT_LE(c.t_hit, c.points.back().t);
      }
    }
  EXPECT_GT(hits, 12);  // most rays hit, in every structure
}

TEST(WalkCost, TheStructuresOwnConstantsWhereTheTraceHasThem) {
  TraceStructure s;
  EXPECT_EQ(structure_cost_model(s).t_i, 80.0);
  s.params = {{"t_i", false, 20.0, ""}, {"t_t", false, 2.0, ""}};
  EXPECT_EQ(structure_cost_model(s).t_i, 20.0);
  EXPECT_EQ(structure_cost_model(s).t_t, 2.0);
  Walks w({"grid", "kd"});
  MultiTrace m = w.record();
  const std::string table = multi_trace_summary(m, CostModel{}, false);
  EXPECT_NE(table.find("grid"), std::string::npos) << table;
  EXPECT_NE(table.find("kd"), std::string::npos) << table;
}

}  // namespace
}  // namespace raystep
