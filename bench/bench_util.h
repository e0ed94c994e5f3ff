// What the benchmarks share: the mesh they measure on (the Stanford bunny from ../shared/meshes, or a stand-in
// with a mesh's structure when it is not there), their small command lines, whose bad values end the run
// with one line and exit code 2, and the instruction counts' rays and checksum of the hits.
#pragma once

#include <cmath>
#include <cstdio>
#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <string>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/scene/scene.h"
#include "raystep/io/scene_loader.h"

namespace raystep::bench {

// RAYSTEP_SOURCE_DIR is set by bench/CMakeLists.txt for the targets that include this.
inline std::string bunny_path() { return std::string(RAYSTEP_SOURCE_DIR) + "/../shared/meshes/stanford-bunny.obj"; }

// The bunny, or a sphere of 80,000 small triangles seen from the front.
inline Scene bench_scene() {
  std::string mesh = bunny_path();
  if (std::filesystem::exists(mesh)) return load_scene(mesh);
  Scene scene;
  scene.geometry.begin_object("sphere", 0);
  const int rings = 200, segments = 200;
  auto p = [&](int i, int j) {
    float th = 3.14159265f * i / rings, ph = 6.2831853f * j / segments;
    return glm::vec3(std::sin(th) * std::cos(ph), std::cos(th), std::sin(th) * std::sin(ph));
  };
  for (int i = 0; i < rings; ++i)
    for (int j = 0; j < segments; ++j) {
      scene.geometry.add_triangle(p(i, j), p(i + 1, j), p(i + 1, j + 1));
      scene.geometry.add_triangle(p(i, j), p(i + 1, j + 1), p(i, j + 1));
    }
  scene.camera.eye = glm::vec3(0.f, 0.5f, 3.5f);
  return scene;
}

// A command line of "--name value" options and bare words, read in order.
class Args {
 public:
  Args(int argc, char** argv) : argc_(argc), argv_(argv) {}
  // The next word, or false at the end.
  bool next(std::string* word) {
    if (++i_ >= argc_) return false;
    *word = argv_[i_];
    return true;
  }
  // The value of the option just read.
  std::string value() {
    if (i_ + 1 >= argc_) fail(std::string(argv_[i_]) + " needs a value");
    return argv_[++i_];
  }
  // The value as a whole number >= lo.
  long number(long lo) {
    std::string option = argv_[i_], v = value();
    char* end = nullptr;
    long n = std::strtol(v.c_str(), &end, 10);
    if (v.empty() || *end != '\0' || n < lo) fail(option + " '" + v + "': expected a whole number >= " + std::to_string(lo));
    return n;
  }
  [[noreturn]] static void fail(const std::string& what) {
    std::fprintf(stderr, "error: %s\n", what.c_str());
    std::exit(2);
  }

 private:
  int argc_;
  char** argv_;
  int i_ = 0;
};

// The rays the *_instructions programs count on: n "random" rays through the scene's bounds (seed 7), or
// ("primary") a sqrt(n) x sqrt(n) image of the scene's camera.
inline std::vector<Ray> instruction_rays(const std::string& kind, const Scene& scene, size_t n) {
  int side = int(std::lround(std::sqrt(double(n))));
  return kind == "random" ? random_rays(scene.geometry.bounds(), n, 7) : camera_rays(scene.camera, side, side);
}

// FNV-1a over every hit's primitive and the bits of its t, so that two kernels can be shown to find the same
// hits; *found counts the rays that hit something.
inline uint64_t hits_checksum(const std::vector<Hit>& hits, size_t* found) {
  uint64_t h = 14695981039346656037ull;
  *found = 0;
  for (const Hit& hit : hits) {
    uint32_t t;
    std::memcpy(&t, &hit.t, 4);
    h = (h ^ uint32_t(hit.prim)) * 1099511628211ull;
    h = (h ^ t) * 1099511628211ull;
    *found += hit.found();
  }
  return h;
}

}  // namespace raystep::bench
