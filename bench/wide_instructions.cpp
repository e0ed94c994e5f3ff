// raystep_wide_instructions primary|random MESH [N] [4|8] [scalar|sse|avx2]: traces N primary rays (a sqrt(N)
// x sqrt(N) image of the mesh's camera) or N random rays through the wide BVH (8-wide unless told) with the
// null recorder, counting instructions only around the traversal (callgrind client requests), and prints the
// walk's counters per ray (nodes, box tests, leaves, pushes, skips, primitive tests), the kernel level, and a
// checksum of the hits, so that a change to the kernel can be shown to find the same hits. Outside valgrind
// it also prints the traversal's time (best of 5). Run under `valgrind --tool=callgrind --instr-atstart=no`.
#include <valgrind/callgrind.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <string>

#include "bench_util.h"
#include "raystep/accel/wide_bvh.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr,
                 "usage: raystep_wide_instructions primary|random MESH.obj [N] [4|8] [scalar|sse|avx2]\n");
    return 2;
  }
  std::string kind = argv[1];
  size_t n = argc > 3 ? std::stoul(argv[3]) : 16384;
  int width = argc > 4 ? std::stoi(argv[4]) : 8;
  if (argc > 5) {
    std::string level = argv[5];
    WideSimd simd = level == "scalar" ? WideSimd::scalar : level == "sse" ? WideSimd::sse : WideSimd::avx2;
    if (!WideBvh::force_simd(simd)) {
      std::fprintf(stderr, "error: this CPU cannot run the %s kernel\n", level.c_str());
      return 2;
    }
  }
  try {
    Scene scene = load_scene(argv[2]);
    WideBvh wide(width);
    wide.build(scene.geometry);
    std::vector<Ray> rays = bench::instruction_rays(kind, scene, n);
    std::vector<Hit> hits(rays.size());
    CALLGRIND_START_INSTRUMENTATION;
    for (size_t i = 0; i < rays.size(); ++i) wide.intersect(rays[i], &hits[i]);
    CALLGRIND_STOP_INSTRUMENTATION;
    double best_ms = 0.0;
    if (!RUNNING_ON_VALGRIND) {
      for (int r = 0; r < 5; ++r) {
        auto t0 = std::chrono::steady_clock::now();
        for (size_t i = 0; i < rays.size(); ++i) wide.intersect(rays[i], &hits[i]);
        double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - t0).count();
        best_ms = r == 0 ? ms : std::min(best_ms, ms);
      }
    }
    size_t found = 0;
    uint64_t h = bench::hits_checksum(hits, &found);
    CountingRecorder c;
    for (const Ray& r : rays) {
      Hit hit;
      wide.intersect_counted(r, &hit, c);
    }
    double k = 1.0 / double(rays.size());
    std::printf("memory: %.2f MB\n", double(wide.memory_bytes()) / 1e6);
    std::printf(
        "%s %s %s: %zu rays, %zu hits, hits checksum %016llx; per ray: %.2f nodes, %.2f box tests, %.2f "
        "leaves, "
        "%.2f pushes, %.2f skips, %.2f prim tests; %.3f Mrays/s\n",
        wide.name().c_str(), WideBvh::simd_level(), kind.c_str(), rays.size(), found, (unsigned long long)h,
        c.nodes * k, c.box_tests * k, c.leaves * k, c.pushes * k, c.skips * k, c.prim_tests * k,
        best_ms > 0 ? double(rays.size()) / (best_ms * 1e3) : 0.0);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
