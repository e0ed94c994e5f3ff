// raystep_bench_bvh_build [MESH.obj] [--threads N]: build time of the three BVH builders at 1x, 4x and 16x
// the mesh's triangles (copies side by side, each offset by the mesh's extent), median of 3 builds, one
// thread by default, with ms / (N log2 N) to show the growth is N log N, and the tree's statistics (nodes,
// leaves, depth, SAH cost). Without a mesh argument it uses ../shared/meshes/stanford-bunny.obj beside the
// repository, and skips (exit 0) when that file is absent.
#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <string>
#include <vector>

#include "bench_util.h"
#include "raystep/accel/bvh_build.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;
using Clock = std::chrono::steady_clock;

namespace {

// k copies of the mesh's triangles in a row along x, one extent apart.
Geometry replicate(const Geometry& g, int k) {
  Geometry out;
  out.begin_object("copies", 0);
  glm::vec3 step(1.1f * g.bounds().extent().x, 0.f, 0.f);
  int side = int(std::lround(std::sqrt(double(k))));
  for (int c = 0; c < k; ++c) {
    glm::vec3 offset =
        float(c % side) * step + float(c / side) * glm::vec3(0.f, 1.1f * g.bounds().extent().y, 0.f);
    for (uint32_t id = 0; id < g.size(); ++id)
      out.add_triangle(g.vertex(id, 0) + offset, g.vertex(id, 1) + offset, g.vertex(id, 2) + offset);
  }
  return out;
}

}  // namespace

int main(int argc, char** argv) {
  std::string mesh = bench::bunny_path();
  int threads = 1;
  bench::Args args(argc, argv);
  for (std::string a; args.next(&a);) {
    if (a == "--threads")
      threads = int(args.number(0));
    else if (a.rfind("--", 0) == 0)
      bench::Args::fail("unknown option " + a + " (--threads N)");
    else
      mesh = a;
  }
  if (!std::filesystem::exists(mesh)) {
    std::printf("skipped: %s not found (the shared meshes are not part of the repository)\n", mesh.c_str());
    return 0;
  }
  try {
    Scene scene = load_scene(mesh);
    std::printf("mesh: %s (%zu triangles); %d thread(s); median of 3 builds\n", mesh.c_str(),
                scene.geometry.size(), threads);
    std::printf("%-11s %5s %10s %10s %16s %9s %9s %6s %10s\n", "builder", "copies", "triangles", "build_ms",
                "ns/(N log2 N)", "nodes", "leaves", "depth", "SAH_cost");
    for (BvhBuilder builder : {BvhBuilder::binned, BvhBuilder::sweep, BvhBuilder::median})
      for (int k : {1, 4, 16}) {
        Geometry g = replicate(scene.geometry, k);
        BvhOptions o;
        o.builder = builder;
        o.threads = threads;
        std::vector<double> ms;
        BvhData d;
        for (int r = 0; r < 3; ++r) {
          auto t0 = Clock::now();
          d = build_bvh(g, o);
          ms.push_back(std::chrono::duration<double, std::milli>(Clock::now() - t0).count());
        }
        std::sort(ms.begin(), ms.end());
        double n = double(g.size());
        BvhStats s = bvh_stats(d, o);
        const char* name = builder == BvhBuilder::binned  ? "bvh"
                           : builder == BvhBuilder::sweep ? "bvh-sweep"
                                                          : "bvh-median";
        std::printf("%-11s %5d %10zu %10.1f %16.2f %9zu %9zu %6d %10.2f\n", name, k, g.size(), ms[1],
                    ms[1] * 1e6 / (n * std::log2(n)), s.nodes, s.leaves, s.max_depth, s.sah_cost);
      }
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
