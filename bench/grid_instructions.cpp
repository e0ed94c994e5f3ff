// raystep_grid_instructions null|hookfree|counting [MESH]: traces the primary rays of a mesh through the grid
// with one kernel variant, counting instructions only around the traversal (callgrind client requests).
// Run under `valgrind --tool=callgrind --instr-atstart=no`; scripts/callgrind-recorders.sh does it for all three.
#include <valgrind/callgrind.h>

#include <cstdio>
#include <string>

#include "grid_hookfree.h"
#include "raystep/accel/grid.h"
#include "raystep/render/camera.h"
#include "raystep/scene/ray_sets.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/error.h"

using namespace raystep;

// The measured loop: only the traversal is counted, and the variant is chosen outside it.
template <class Trace>
size_t count_loop(const std::vector<Ray>& rays, Trace trace) {
  size_t hits = 0;
  CALLGRIND_START_INSTRUMENTATION;
  for (const Ray& r : rays) {
    Hit h;
    hits += trace(r, &h);
  }
  CALLGRIND_STOP_INSTRUMENTATION;
  return hits;
}

int main(int argc, char** argv) {
  if (argc < 3) {
    std::fprintf(stderr, "usage: raystep_grid_instructions null|hookfree|counting MESH.obj\n");
    return 2;
  }
  std::string variant = argv[1];
  try {
    Scene scene = load_scene(argv[2]);
    UniformGrid grid;
    grid.build(scene.geometry);
    std::vector<Ray> rays = camera_rays(scene.camera, 128, 128);
    size_t hits;
    CountingRecorder counting;
    if (variant == "hookfree")
      hits = count_loop(rays, [&](const Ray& r, Hit* h) { return bench::grid_intersect_hookfree(grid, r, h); });
    else if (variant == "counting")
      hits = count_loop(rays, [&](const Ray& r, Hit* h) { return grid.traverse(r, h, false, counting); });
    else  // the null recorder as every caller runs it: through intersect, out of line (recorded_walk.h)
      hits = count_loop(rays, [&](const Ray& r, Hit* h) { return grid.intersect(r, h); });
    std::printf("%s: %zu rays, %zu hits\n", variant.c_str(), rays.size(), hits);
  } catch (const InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  }
  return 0;
}
