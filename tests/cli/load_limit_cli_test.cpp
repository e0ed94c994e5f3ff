// Inputs too large for the memory limit (util/memory_limit.h) are refused by the command line: exit 2 and one
// line naming the file, nothing written. RAYSTEP_MEMORY_LIMIT lowered to a few KiB stands in for a huge mesh,
// trace or structure, so that the tests need no big file.
#include <algorithm>
#include <cstdlib>

#include "cli_test_util.h"
#include "raystep/util/memory_limit.h"

namespace raystep::clitest {
namespace {

class LoadLimitCli : public CliTest {
 protected:
  LoadLimitCli() : CliTest("raystep_load_limit_") {}
  void TearDown() override {
    unsetenv("RAYSTEP_MEMORY_LIMIT");  // the child processes inherit it
    CliTest::TearDown();
  }
  static void limit(uint64_t bytes) { setenv("RAYSTEP_MEMORY_LIMIT", std::to_string(bytes).c_str(), 1); }

  // A strip of n triangles; *bytes: the file's size.
  std::string strip(const std::string& name, int n, uint64_t* bytes = nullptr) const {
    std::string s;
    for (int i = 0; i < n + 2; ++i) s += "v " + std::to_string(i) + " " + std::to_string(i % 2) + " 0\n";
    for (int i = 1; i <= n; ++i)
      s += "f " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
    if (bytes) *bytes = s.size();
    return write(name, s);
  }
};

TEST_F(LoadLimitCli, MeshOverTheLimitIsRefusedNamingIt) {
  uint64_t bytes = 0;
  const std::string mesh = strip("strip.obj", 200, &bytes);
  limit(read_memory_estimate(InputKind::obj_mesh, bytes) - 1);
  const std::string out = path("out.png");
  expect_error(run("render " + mesh + " --size 8x8 -o " + out), mesh + ": too large to read", out);
  // Through a scene that names it: the mesh is named, not the scene.
  const std::string scene = write("scene.json", R"({"camera": {"eye": [0, 0, 5], "look_at": [0, 0, 0]},
    "lights": [], "materials": {"white": {"diffuse": 1}},
    "objects": [{"type": "mesh", "material": "white", "file": "strip.obj"}]})");
  expect_error(run("render " + scene + " --size 8x8 -o " + out), mesh + ": too large to read", out);
  // At the estimate itself it is read (and the default structure, bvh8, built).
  limit(std::max(read_memory_estimate(InputKind::obj_mesh, bytes), build_memory_estimate("bvh8", 200)));
  const Outcome ok = run("render " + mesh + " --size 8x8 -o " + out);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

TEST_F(LoadLimitCli, TraceOverTheLimitIsRefusedNamingIt) {
  const std::string trace = path("t.json");
  const Outcome made = run("trace " + scene("cornell.json") + " --accel kd --pixel 160,160 -o " + trace);
  ASSERT_EQ(made.code, 0) << made.err;
  const uint64_t bytes = std::filesystem::file_size(trace);
  limit(read_memory_estimate(InputKind::trace_json, bytes) - 1);
  expect_error(run("trace-info " + trace), trace + ": too large to read");
  limit(read_memory_estimate(InputKind::trace_json, bytes));
  const Outcome ok = run("trace-info " + trace);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

TEST_F(LoadLimitCli, StructureOverTheLimitIsRefusedBeforeItsBuild) {
  const int n = 4000;
  uint64_t bytes = 0;
  const std::string mesh = strip("strip.obj", n, &bytes);
  const std::string rays = path("r.rays"), hits = path("r.hits");
  const Outcome made = run("rays " + mesh + " --kind camera --size 4x4 -o " + rays);
  ASSERT_EQ(made.code, 0) << made.err;
  // Enough to read the mesh and build the BVH, not the BSP tree.
  const uint64_t enough =
      std::max(read_memory_estimate(InputKind::obj_mesh, bytes), build_memory_estimate("bvh", n));
  ASSERT_LT(enough, build_memory_estimate("bsp", n));
  limit(enough);
  expect_error(run("cast " + mesh + " --accel bsp --rays " + rays + " --hits " + hits),
               mesh + ": too large for bsp", hits);
  const std::string out = path("out.png");
  expect_error(run("render " + mesh + " --accel bsp --size 8x8 -o " + out), mesh + ": too large for bsp",
               out);
  const Outcome ok = run("cast " + mesh + " --accel bvh --rays " + rays + " --hits " + hits);
  EXPECT_EQ(ok.code, 0) << ok.err;
}

TEST_F(LoadLimitCli, MalformedLimitIsRefusedByName) {
  setenv("RAYSTEP_MEMORY_LIMIT", "lots", 1);
  const std::string out = path("out.png");
  expect_error(run("render " + strip("strip.obj", 10) + " --size 8x8 -o " + out),
               "RAYSTEP_MEMORY_LIMIT: 'lots'", out);
}

}  // namespace
}  // namespace raystep::clitest
