// What the GUI tests share: run raystep-gui in scripted mode (stderr kept beside the artefacts), read its
// state dump, count a colour's pixels in a part of a screenshot. Header-only, for the viz test files.
#pragma once

#include <algorithm>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include "raystep/io/image_io.h"

namespace raystep::viztest {

using nlohmann::json;

inline const std::string kExe = RAYSTEP_GUI_EXE;
inline const std::string kSourceDir = RAYSTEP_SOURCE_DIR;
inline const std::string kOut = RAYSTEP_VIZ_ARTIFACTS;

struct GuiRun {
  int code = -1;
  std::string err;
};

inline std::string slurp(const std::string& path) {
  std::ifstream in(path, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Runs raystep-gui with the arguments (a shell word list); stderr goes to kOut/tag.stderr and into err.
inline GuiRun gui(const std::string& args, const std::string& tag) {
  std::string errFile = kOut + "/" + tag + ".stderr";
  std::string cmd = "'" + kExe + "' " + args + " 2> '" + errFile + "'";
  GuiRun r;
  int status = std::system(cmd.c_str());
  r.code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.err = slurp(errFile);
  return r;
}

// raystep-gui's stderr without Qt's note and the timings: what it says about an error, one line each.
inline std::vector<std::string> errorLines(const std::string& err) {
  std::istringstream lines(err);
  std::vector<std::string> out;
  for (std::string line; std::getline(lines, line);)
    if (line.rfind("QStandardPaths", 0) != 0 && line.rfind("timing: ", 0) != 0) out.push_back(line);
  return out;
}

inline json readJson(const std::string& path) {
  std::ifstream in(path);
  EXPECT_TRUE(in.good()) << path;
  if (!in.good()) return json::object();
  return json::parse(in);
}

inline bool nearColor(const uint8_t* px, const json& rgb, int tol) {
  for (int k = 0; k < 3; ++k)
    if (std::abs(int(px[k]) - rgb[size_t(k)].get<int>()) > tol) return false;
  return true;
}

// Pixels of colour rgb (within tol per channel) in the box [x0, x1] x [y0, y1] of the image.
inline int countColor(const Rgb8Image& img, const json& rgb, double x0, double y0, double x1, double y1,
                      int tol) {
  int n = 0;
  for (int y = std::max(0, int(y0)); y <= std::min(img.height - 1, int(y1)); ++y)
    for (int x = std::max(0, int(x0)); x <= std::min(img.width - 1, int(x1)); ++x)
      n += nearColor(img.at(x, y), rgb, tol);
  return n;
}

// The screen box of projected corners [[x, y], ...].
struct ScreenBox {
  double x0 = 1e9, y0 = 1e9, x1 = -1e9, y1 = -1e9;
};
inline ScreenBox boxOf(const json& corners) {
  ScreenBox b;
  for (const json& c : corners) {
    b.x0 = std::min(b.x0, c[0].get<double>());
    b.x1 = std::max(b.x1, c[0].get<double>());
    b.y0 = std::min(b.y0, c[1].get<double>());
    b.y1 = std::max(b.y1, c[1].get<double>());
  }
  return b;
}

}  // namespace raystep::viztest
