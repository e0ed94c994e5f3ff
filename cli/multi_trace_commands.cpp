// `raystep trace --accel A,B,...`: the same ray(s) through two to six structures, written as one multi-walk
// trace (core/trace/multi_trace.h), and `raystep trace-info` on such a file: each walk's cost along t.
#include <algorithm>
#include <cmath>
#include <cstdio>
#include <memory>
#include <set>

#include "commands.h"
#include "raystep/accel/accelerator.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/multi_trace.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"

namespace raystep::cli {

int run_multi_trace(const TraceArgs& a) {
  if (a.secondary && !a.pixel) throw InputError("", 0, "trace: --secondary goes with --pixel");
  if (a.aa) throw InputError("", 0, "trace: --aa records one structure's pixel (give one --accel name)");
  if (a.build_events)
    throw InputError("", 0, "trace: --build-events records one kd-tree's build (give one --accel name)");
  const std::vector<std::string> names =
      parse_walk_list(a.structure.accel, "trace: --accel '" + a.structure.accel + "'", kMinWalks, kMaxWalks);
  // Every structure made (not built) before the scene is read: a wrong option costs nothing.
  std::vector<std::unique_ptr<Accelerator>> accels;
  for (const std::string& n : names) {
    StructureArgs s = a.structure;
    s.accel = n;
    accels.push_back(build_structure(s));
  }
  check_output_folder(a.output);
  Scene scene = load_scene(a.scene);

  std::vector<RayRequest> requests;
  int w = scene.render.width, h = scene.render.height, px = 0, py = 0;
  if (!a.pixel) {
    requests.push_back(trace_ray_by_hand(a, scene));
  } else {
    if (a.size) parse_size(*a.size, &w, &h);
    std::vector<float> p = parse_numbers("--pixel", *a.pixel, 2);
    if (p[0] != std::floor(p[0]) || p[1] != std::floor(p[1]) || p[0] < 0 || p[1] < 0 || p[0] >= w ||
        p[1] >= h)
      throw InputError("", 0,
                       "--pixel '" + *a.pixel + "': outside the " + std::to_string(w) + "x" +
                           std::to_string(h) + " image");
    px = int(p[0]);
    py = int(p[1]);
  }
  std::vector<const Accelerator*> built;
  for (auto& accel : accels) {
    check_build_memory(a.scene, accel->name(), scene.geometry.size());
    accel->build(scene.geometry);
    built.push_back(accel.get());
  }
  // The pixel's rays (with --secondary its ray tree) are spawned once, by the first structure, and every
  // structure walks exactly those: the walks differ only in the structure.
  if (a.pixel) requests = pixel_rays(scene, *built.front(), w, h, px, py, a.secondary);
  MultiTrace m = record_walks(scene.geometry, built, requests, a.scene, file_content_hash(a.scene));
  if (a.format == "csv")
    write_multi_trace_csv(a.output, m);
  else
    write_multi_trace_json(a.output, m);
  std::printf("%s", multi_trace_summary(m, CostModel{}, false).c_str());
  std::printf("wrote %s\n", a.output.c_str());
  return 0;
}

int run_multi_trace_info(const std::string& path, const MultiTrace& m, bool own_costs) {
  std::printf("%s: valid raystep trace, version %d (%zu walks)\n", path.c_str(), m.version, m.walks.size());
  std::printf("%s", multi_trace_summary(m, CostModel{}, own_costs).c_str());
  return 0;
}

}  // namespace raystep::cli
