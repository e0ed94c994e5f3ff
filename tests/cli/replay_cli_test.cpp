// `raystep replay`: the storyboard of a trace (docs/replay-format.md) as JSON and as text, one state per
// event, each a JSON object with the documented keys and the walk's own numbers; bad traces, walks, rays and
// steps exit 2 with one line; -o writes atomically.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include <string>

#include "cli_test_util.h"

namespace {

using namespace raystep::clitest;
using nlohmann::json;

class ReplayCli : public CliTest {
 protected:
  ReplayCli() : CliTest("raystep_replay_cli_") {}
};

const std::string kCornell = std::string(RAYSTEP_SOURCE_DIR) + "/scenes/cornell.json";

TEST_F(ReplayCli, EveryEventHasAStateWithTheWalksNumbers) {
  ASSERT_EQ(run("trace " + kCornell + " --accel kd --pixel 160,200 --size 320x240 -o " + path("t.json")).code,
            0);
  const json trace = json::parse(slurp(path("t.json")));
  Outcome r = run("replay " + path("t.json") + " --format json -o " + path("s.json"));
  ASSERT_EQ(r.code, 0) << r.err;
  const json doc = json::parse(slurp(path("s.json")));
  EXPECT_EQ(doc["format"], "raystep-replay");
  EXPECT_EQ(doc["version"], 1);
  ASSERT_EQ(doc["walks"].size(), 1u);
  EXPECT_EQ(doc["walks"][0]["structure"], "kd");
  const json& events = trace["rays"][0]["events"];
  const json& states = doc["walks"][0]["rays"][0]["states"];
  ASSERT_EQ(states.size(), events.size());
  int pushes = 0, pops = 0, tests = 0, crossings = 0;
  size_t deepest = 0;
  for (size_t i = 0; i < states.size(); ++i) {
    const json& s = states[i];
    const std::string type = events[i]["type"];
    EXPECT_EQ(s["step"], i);
    EXPECT_EQ(s["type"], type);
    pushes += type == "push";
    pops += type == "pop";
    tests += type == "prim_test";
    EXPECT_EQ(s["counters"]["pushes"], pushes);
    EXPECT_EQ(s["counters"]["pops"], pops);
    EXPECT_EQ(s["counters"]["prim_tests"], tests);
    EXPECT_EQ(s["stack"].size(), size_t(pushes - pops));
    deepest = std::max(deepest, s["stack"].size());
    EXPECT_EQ(s["mailbox"].size(), size_t(tests));
    if (type == "push") EXPECT_EQ(s["stack"].back()["node"], events[i]["node"]);
    if (s.contains("crossing")) ++crossings;
    EXPECT_TRUE(s["why"].is_string());
    for (const char* key :
         {"line", "interval", "cell", "visited_cells", "node", "visited_nodes", "prims", "nearest", "ended"})
      EXPECT_TRUE(s.contains(key)) << key;
  }
  EXPECT_GT(deepest, 0u);
  EXPECT_GT(crossings, 0);
  EXPECT_TRUE(states.back()["ended"]);
  EXPECT_EQ(states.back()["nearest"]["status"], "accepted");
  // One step alone is the same state as in the whole storyboard.
  Outcome one = run("replay " + path("t.json") + " --step 6 --format json");
  ASSERT_EQ(one.code, 0) << one.err;
  EXPECT_EQ(json::parse(one.out)["walks"][0]["rays"][0]["states"][0], states[6]);
  // The text form: the event's line and its Why.
  Outcome text = run("replay " + path("t.json") + " --step 6");
  ASSERT_EQ(text.code, 0) << text.err;
  EXPECT_NE(text.out.find(std::string(states[6]["line"])), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("why: " + std::string(states[6]["why"]).substr(0, 30)), std::string::npos)
      << text.out;
}

TEST_F(ReplayCli, AMultiWalkTraceHasAStoryboardPerWalk) {
  ASSERT_EQ(
      run("trace " + kCornell + " --accel grid,bvh8 --pixel 160,200 --size 320x240 -o " + path("m.json"))
          .code,
      0);
  Outcome r = run("replay " + path("m.json") + " --step 1000000 --format json");
  ASSERT_EQ(r.code, 0) << r.err;
  const json doc = json::parse(r.out);
  EXPECT_EQ(doc["trace_version"], 5);
  ASSERT_EQ(doc["walks"].size(), 2u);
  EXPECT_EQ(doc["walks"][0]["structure"], "grid");
  EXPECT_EQ(doc["walks"][1]["structure"], "bvh8");
  for (const json& w : doc["walks"]) {
    const json& ray = w["rays"][0];
    ASSERT_EQ(ray["states"].size(), 1u);
    EXPECT_EQ(ray["states"][0]["step"], int(ray["events"]) - 1);  // clamped to the last event
    EXPECT_TRUE(ray["states"][0]["ended"]);
  }
  Outcome walk1 = run("replay " + path("m.json") + " --walk 1 --ray 0 --step 3 --format json");
  ASSERT_EQ(walk1.code, 0) << walk1.err;
  EXPECT_EQ(json::parse(walk1.out)["walks"][0]["walk"], 1);
}

TEST_F(ReplayCli, BadInputExits2WithOneLine) {
  ASSERT_EQ(
      run("trace " + kCornell + " --accel grid --pixel 160,200 --size 320x240 -o " + path("t.json")).code, 0);
  expect_error(run("replay " + path("t.json") + " --walk 1"), path("t.json") + ": --walk 1");
  expect_error(run("replay " + path("t.json") + " --ray 3"), path("t.json") + ": --ray 3");
  expect_error(run("replay " + path("t.json") + " --step -2"), "replay: --step -2");
  expect_error(run("replay " + path("missing.json")), path("missing.json"));
  const std::string cut = write("cut.json", slurp(path("t.json")).substr(0, 900));
  expect_error(run("replay " + cut), cut + ":");
  Outcome both = run("replay " + path("t.json") + " --step 2 --all");
  EXPECT_EQ(both.code, 2);
  // A refused run leaves no output behind.
  expect_error(run("replay " + path("t.json") + " --walk 4 -o " + path("out.json")),
               path("t.json") + ": --walk 4");
  EXPECT_FALSE(std::filesystem::exists(path("out.json")));
}

}  // namespace
