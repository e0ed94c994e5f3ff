// raystep_bvh_instructions null|hookfree|intersect|counting primary|random MESH [N] [entry|axis]: traces N
// primary rays (a sqrt(N) x sqrt(N) image of the mesh's camera) or N random rays through the binned-SAH BVH
// with one kernel variant (intersect: Bvh::intersect, the library's own null-recorder entry point), counting
// instructions only around the traversal (callgrind client requests), and prints the walk's counters per ray
// and a checksum of the hits (the variants must find the same hits). Run under
// `valgrind --tool=callgrind --instr-atstart=no`.
#include <valgrind/callgrind.h>

#include <cmath>
#include <cstdio>
#include <cstring>
#include <string>

#include "bvh_hookfree.h"
#include "raystep/accel/bvh.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;

// The measured loop: only the traversal is counted, and the variant is chosen outside it.
template <class Trace>
void count_loop(const std::vector<Ray>& rays, std::vector<Hit>& hits, Trace trace) {
  CALLGRIND_START_INSTRUMENTATION;
  for (size_t i = 0; i < rays.size(); ++i) trace(rays[i], &hits[i]);
  CALLGRIND_STOP_INSTRUMENTATION;
}

int main(int argc, char** argv) {
  if (argc < 4) {
    std::fprintf(
        stderr,
        "usage: raystep_bvh_instructions null|hookfree|intersect|counting primary|random MESH.obj [N] "
        "[entry|axis]\n");
    return 2;
  }
  std::string variant = argv[1], kind = argv[2];
  size_t n = argc > 4 ? std::stoul(argv[4]) : 16384;
  BvhOrder order =
      argc > 5 && std::string(argv[5]) == "axis" ? BvhOrder::split_axis : BvhOrder::entry_distance;
  try {
    Scene scene = load_scene(argv[3]);
    BvhOptions options;
    options.threads = 1;
    Bvh bvh(options, order);
    bvh.build(scene.geometry);
    int side = int(std::lround(std::sqrt(double(n))));
    std::vector<Ray> rays =
        kind == "random" ? random_rays(scene.geometry.bounds(), n, 7) : camera_rays(scene.camera, side, side);
    std::vector<Hit> hits(rays.size());
    CountingRecorder counting;
    NullRecorder null_rec;
    if (variant == "hookfree")
      count_loop(rays, hits,
                 [&](const Ray& r, Hit* h) { return bench::bvh_traverse_hookfree(bvh, r, h, false); });
    else if (variant == "counting")
      count_loop(rays, hits, [&](const Ray& r, Hit* h) { return bvh.traverse(r, h, false, counting); });
    else if (variant == "intersect")
      count_loop(rays, hits, [&](const Ray& r, Hit* h) { return bvh.intersect(r, h); });
    else
      count_loop(rays, hits, [&](const Ray& r, Hit* h) { return bvh.traverse(r, h, false, null_rec); });
    uint64_t h = 14695981039346656037ull;
    size_t found = 0;
    for (const Hit& hit : hits) {
      uint32_t t;
      std::memcpy(&t, &hit.t, 4);
      h = (h ^ uint32_t(hit.prim)) * 1099511628211ull;
      h = (h ^ t) * 1099511628211ull;
      found += hit.found();
    }
    CountingRecorder c;
    for (const Ray& r : rays) {
      Hit hit;
      bvh.traverse(r, &hit, false, c);
    }
    double k = 1.0 / double(rays.size());
    std::printf(
        "%s %s (%s order): %zu rays, %zu hits, hits checksum %016llx; per ray: %.2f nodes, %.2f leaves, "
        "%.2f box tests, %.2f pushes, %.2f skips, %.2f prim tests\n",
        variant.c_str(), kind.c_str(), order == BvhOrder::split_axis ? "axis" : "entry", rays.size(), found,
        (unsigned long long)h, c.nodes * k, c.leaves * k, c.box_tests * k, c.pushes * k, c.skips * k,
        c.prim_tests * k);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
