// The house's floors: core's concerns in order, each built only on the ones below it (docs/developers.md). A
// header or source of one concern that includes a higher concern's header is a step back up, and fails here
// with the file and the include.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <vector>

namespace raystep {
namespace {

// Lowest first.
const std::vector<std::string> kLayers = {"util", "geometry", "scene",  "record", "accel",  "render",
                                          "io",   "trace",    "replay", "figure", "report", "lesson"};

int layer(const std::string& concern) {
  auto it = std::find(kLayers.begin(), kLayers.end(), concern);
  return it == kLayers.end() ? -1 : int(it - kLayers.begin());
}

TEST(IncludeLayers, NoConcernIncludesAHigherOne) {
  namespace fs = std::filesystem;
  const fs::path core = fs::path(RAYSTEP_SOURCE_DIR) / "core";
  const std::regex include("#include \"raystep/([a-z_]+)/[a-z_0-9]+\\.h\"");
  int files = 0, includes = 0;
  for (const char* top : {"include/raystep", "src"}) {
    for (const fs::directory_entry& e : fs::recursive_directory_iterator(core / top)) {
      if (!e.is_regular_file()) continue;
      const std::string ext = e.path().extension().string();
      if (ext != ".h" && ext != ".cpp" && ext != ".inc") continue;
      const std::string concern = fs::relative(e.path(), core / top).begin()->string();
      const int own = layer(concern);
      EXPECT_GE(own, 0) << e.path() << ": the concern " << concern
                        << " is not in kLayers (and docs/developers.md)";
      std::ifstream in(e.path());
      std::stringstream text;
      text << in.rdbuf();
      const std::string s = text.str();
      ++files;
      for (std::sregex_iterator m(s.begin(), s.end(), include), end; m != end; ++m) {
        ++includes;
        const int to = layer((*m)[1]);
        EXPECT_GE(to, 0) << e.path() << " includes " << (*m)[0] << ": an unknown concern";
        EXPECT_LE(to, own) << fs::relative(e.path(), core) << " (" << concern << ") includes " << (*m)[0]
                           << ", a higher concern";
      }
    }
  }
  EXPECT_GT(files, 200);
  EXPECT_GT(includes, 500);
}

}  // namespace
}  // namespace raystep
