// raystep_kd_instructions primary|random MESH [N]: traces N primary rays (a sqrt(N) x sqrt(N) image of the mesh's
// camera) or N random rays through the SAH kd-tree with the null recorder, counting instructions only around the
// traversal (callgrind client requests), and prints the walk's counters per ray (nodes, leaves, primitive tests,
// mailbox hits) and a checksum of the hits, so that a change to the kernel can be shown to find the same hits.
// Run under `valgrind --tool=callgrind --instr-atstart=no`.
#include <valgrind/callgrind.h>

#include <cstdio>
#include <string>

#include "bench_util.h"
#include "raystep/accel/kdtree.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: raystep_kd_instructions primary|random MESH.obj [N]\n");
    return 2;
  }
  std::string kind = argv[1];
  size_t n = argc > 3 ? std::stoul(argv[3]) : 16384;
  try {
    Scene scene = load_scene(argv[2]);
    KdTree tree;
    tree.build(scene.geometry);
    std::vector<Ray> rays = bench::instruction_rays(kind, scene, n);
    std::vector<Hit> hits(rays.size());
    CALLGRIND_START_INSTRUMENTATION;
    for (size_t i = 0; i < rays.size(); ++i) tree.intersect(rays[i], &hits[i]);
    CALLGRIND_STOP_INSTRUMENTATION;
    size_t found = 0;
    uint64_t h = bench::hits_checksum(hits, &found);
    CountingRecorder c;
    for (const Ray& r : rays) {
      Hit hit;
      tree.traverse(r, &hit, false, c);
    }
    double k = 1.0 / double(rays.size());
    std::printf("%s: %zu rays, %zu hits, hits checksum %016llx; per ray: %.2f nodes, %.2f leaves, %.2f pushes, "
                "%.2f prim tests, %.2f mailbox hits\n",
                kind.c_str(), rays.size(), found, (unsigned long long)h, c.nodes * k, c.leaves * k, c.pushes * k,
                c.prim_tests * k, c.mailbox_hits * k);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
