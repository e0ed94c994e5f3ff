// A mesh too large for the memory limit (util/memory_limit.h) in the debugger: the scripted mode refuses it
// with the command line's line and exit code 2; opened through the window (the worker reads it) the same line
// goes to the error dialog and the session keeps what it had. RAYSTEP_MEMORY_LIMIT lowered to 100 KiB stands
// in for a huge mesh.
#include <cstdlib>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "viz_test_util.h"

namespace raystep::viztest {
namespace {

class VizLoadLimit : public ::testing::Test {
 protected:
  void SetUp() override {
    // A strip of 4,000 triangles: about 100 KiB of OBJ, which the estimate (8 bytes a byte) puts over the
    // limit; the Cornell box (23 triangles) stays well under it, structure included.
    std::string s;
    for (int i = 0; i < 4002; ++i) s += "v " + std::to_string(i) + " " + std::to_string(i % 2) + " 0\n";
    for (int i = 1; i <= 4000; ++i)
      s += "f " + std::to_string(i) + " " + std::to_string(i + 1) + " " + std::to_string(i + 2) + "\n";
    mesh_ = kOut + "/load_limit_strip.obj";
    std::ofstream(mesh_, std::ios::binary) << s;
    setenv("RAYSTEP_MEMORY_LIMIT", "100K", 1);  // the child processes inherit it
  }
  void TearDown() override { unsetenv("RAYSTEP_MEMORY_LIMIT"); }
  std::string mesh_;
};

TEST_F(VizLoadLimit, ScriptedModeRefusesInOneLineWithExit2) {
  GuiRun r = gui("'" + mesh_ + "' --quit", "load_limit_scripted");
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("error: " + mesh_ + ": too large to read"), std::string::npos) << r.err;
}

TEST_F(VizLoadLimit, WindowShowsTheLineAndKeepsItsScene) {
  const std::string scene = kSourceDir + "/scenes/cornell.json", st = kOut + "/load_limit_gui.json";
  GuiRun r =
      gui("'" + scene + "' --open-bad '" + mesh_ + "' --dump-state '" + st + "' --quit", "load_limit_gui");
  EXPECT_EQ(r.code, 0) << r.err;  // the application went on
  json after = readJson(st);
  EXPECT_EQ(after["last_error"].get<std::string>().rfind(mesh_ + ": too large to read", 0), 0u)
      << after["last_error"];
  EXPECT_NE(after["structure_info"].get<std::string>().find("grid"), std::string::npos)
      << after["structure_info"];
}

}  // namespace
}  // namespace raystep::viztest
