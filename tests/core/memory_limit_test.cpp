// The memory limit (util/memory_limit.h): RAYSTEP_MEMORY_LIMIT read strictly, the estimates proportional to
// the input and saturating, and a mesh, a trace or a structure over the limit refused with an InputError that
// names the file, before anything is read or built. A small limit stands in for a huge input.
#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <limits>
#include <optional>
#include <string>

#include "raystep/accel/accelerator.h"
#include "raystep/io/obj.h"
#include "raystep/trace/trace_file.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"

namespace raystep {
namespace {

// Sets RAYSTEP_MEMORY_LIMIT for the scope of a test, and puts back what was there.
class LimitScope {
 public:
  explicit LimitScope(const char* value) {
    if (const char* old = std::getenv("RAYSTEP_MEMORY_LIMIT")) old_ = old;
    if (value)
      setenv("RAYSTEP_MEMORY_LIMIT", value, 1);
    else
      unsetenv("RAYSTEP_MEMORY_LIMIT");
  }
  ~LimitScope() {
    if (old_)
      setenv("RAYSTEP_MEMORY_LIMIT", old_->c_str(), 1);
    else
      unsetenv("RAYSTEP_MEMORY_LIMIT");
  }

 private:
  std::optional<std::string> old_;
};

std::string write_temp(const std::string& name, const std::string& text) {
  std::string path = ::testing::TempDir() + "raystep_memory_limit_test_" + name;
  std::ofstream(path, std::ios::binary) << text;
  return path;
}

// A strip of n triangles.
std::string strip_obj(int n) {
  std::string s;
  for (int i = 0; i < n + 2; ++i) s += "v " + std::to_string(i) + " " + std::to_string(i % 2) + " 0\n";
  for (int i = 1; i <= n; ++i)
    s += "f " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
  return s;
}

TEST(MemoryLimit, DefaultIsThreeQuartersOfPhysicalMemory) {
  LimitScope scope(nullptr);
  const uint64_t physical = physical_memory_bytes();
  ASSERT_GT(physical, 0u);
  EXPECT_EQ(memory_limit_bytes(), physical / 4 * 3);
  LimitScope empty("");
  EXPECT_EQ(memory_limit_bytes(), physical / 4 * 3);
}

TEST(MemoryLimit, VariableTakesBytesOrBinaryUnits) {
  const std::pair<const char*, uint64_t> cases[] = {{"1000", 1000},
                                                    {"4K", 4096},
                                                    {"4k", 4096},
                                                    {"512M", uint64_t(512) << 20},
                                                    {"3G", uint64_t(3) << 30},
                                                    {"2T", uint64_t(2) << 40}};
  for (const auto& [text, bytes] : cases) {
    LimitScope scope(text);
    EXPECT_EQ(memory_limit_bytes(), bytes) << text;
  }
}

TEST(MemoryLimit, MalformedVariableIsRefusedByName) {
  for (const char* text :
       {"abc", "12X", "0", "0G", "1.5G", "-1", "G", "12 M", "99999999999999999999", "20000000000T"}) {
    LimitScope scope(text);
    try {
      memory_limit_bytes();
      ADD_FAILURE() << "accepted " << text;
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), "RAYSTEP_MEMORY_LIMIT") << text;
      EXPECT_NE(e.detail().find(text), std::string::npos) << e.what();
    }
  }
}

TEST(MemoryLimit, EstimatesGrowWithTheInputAndSaturate) {
  for (InputKind kind : {InputKind::obj_mesh, InputKind::trace_json}) {
    const uint64_t one = read_memory_estimate(kind, 1000);
    EXPECT_GE(one, 1000u);  // at least the text itself
    EXPECT_EQ(read_memory_estimate(kind, 2000), 2 * one);
    EXPECT_EQ(read_memory_estimate(kind, std::numeric_limits<uint64_t>::max() / 2),
              std::numeric_limits<uint64_t>::max());
  }
  // Every structure that is built over the primitives has an estimate; brute force builds nothing.
  for (const std::string& name : accelerator_names()) {
    if (name == "brute" || name == "bvol") continue;
    EXPECT_GT(build_memory_estimate(name, 1000), 0u) << name;
    EXPECT_EQ(build_memory_estimate(name, 2000), 2 * build_memory_estimate(name, 1000)) << name;
  }
  EXPECT_EQ(build_memory_estimate("brute", 1000), 0u);
  EXPECT_EQ(build_memory_estimate("no such structure", 1000), 0u);
  // The general BSP tree clips and copies its primitives at every split: the costliest per primitive.
  EXPECT_GT(build_memory_estimate("bsp", 1000), build_memory_estimate("bvh", 1000));
}

TEST(MemoryLimit, FormatsBytesForPeople) {
  EXPECT_EQ(format_bytes(100), "100 bytes");
  EXPECT_EQ(format_bytes(12 * 1024), "12 KiB");
  EXPECT_EQ(format_bytes(uint64_t(88) << 20), "88 MiB");
  EXPECT_EQ(format_bytes(uint64_t(3) << 29), "1.5 GiB");
}

TEST(MemoryLimit, MeshOverTheLimitIsRefusedNamingTheFile) {
  const std::string text = strip_obj(200);
  const std::string path = write_temp("strip.obj", text);
  const uint64_t need = read_memory_estimate(InputKind::obj_mesh, text.size());
  {
    LimitScope scope(std::to_string(need - 1).c_str());
    try {
      load_obj(path);
      ADD_FAILURE() << "loaded over the limit";
    } catch (const InputError& e) {
      EXPECT_EQ(e.file(), path);
      EXPECT_EQ(e.line(), 0);
      EXPECT_EQ(e.detail().rfind("too large to read", 0), 0u) << e.what();
      EXPECT_NE(e.detail().find("RAYSTEP_MEMORY_LIMIT=" + std::to_string(need - 1)), std::string::npos)
          << e.what();
    }
  }
  LimitScope scope(std::to_string(need).c_str());  // exactly enough
  EXPECT_EQ(load_obj(path).triangles.size(), 200u);
}

TEST(MemoryLimit, TraceOverTheLimitIsRefusedNamingTheFile) {
  // Refused before it is parsed: the text need not even be a trace.
  const std::string path = write_temp("trace.json", std::string(4096, ' '));
  LimitScope scope("4K");
  try {
    read_trace_json(path);
    ADD_FAILURE() << "read over the limit";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), path);
    EXPECT_EQ(e.detail().rfind("too large to read", 0), 0u) << e.what();
  }
}

TEST(MemoryLimit, StructureOverTheLimitIsRefusedNamingSceneAndStructure) {
  const uint64_t need = build_memory_estimate("bsp", 1000);
  LimitScope scope(std::to_string(need - 1).c_str());
  try {
    check_build_memory("scene.obj", "bsp", 1000);
    ADD_FAILURE() << "no refusal";
  } catch (const InputError& e) {
    EXPECT_EQ(e.file(), "scene.obj");
    EXPECT_EQ(e.detail().rfind("too large for bsp", 0), 0u) << e.what();
  }
  EXPECT_NO_THROW(check_build_memory("scene.obj", "bvh", 1000));  // the BVH needs less
  LimitScope enough(std::to_string(need).c_str());
  EXPECT_NO_THROW(check_build_memory("scene.obj", "bsp", 1000));
}

}  // namespace
}  // namespace raystep
