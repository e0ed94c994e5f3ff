// `raystep figure`: a 2D scene's structure and one ray's walk at a step, as a figure for slides (SVG, PDF or
// PNG), headless (core/include/raystep/figure).
#include <memory>

#include "commands.h"
#include "raystep/accel/plane_outline.h"
#include "raystep/figure/figure_file.h"
#include "raystep/figure/flat_figure.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"

namespace raystep::cli {

int run_figure(const FigureArgs& a) {
  if (a.step && *a.step < 0) throw InputError("", 0, "--step must be 0 or more");
  // Before the (possibly long) build: write_figure would refuse it only after.
  if (!is_figure_path(a.output))
    throw InputError("", 0, "-o " + a.output + ": a figure is written as .svg, .pdf or .png");
  check_output_folder(a.output);
  std::unique_ptr<Accelerator> accel = build_structure(a.structure);
  if (!has_plane_outline(*accel))
    throw InputError(
        "", 0,
        "figure: --accel " + a.structure.accel +
            " is not drawn in 2D (use grid, kd, kd-median, octree, bsp, bvh, bvh-sweep or bvh-median)");
  const Scene scene = load_scene(a.scene);
  if (!scene.flat)
    throw InputError(a.scene, 0,
                     "a 3D scene: a figure draws a 2D scene (\"dimensions\": 2, docs/scene-format.md)");
  TraceArgs ray_args;
  ray_args.ray = a.ray;
  const RayRequest request = trace_ray_by_hand(ray_args, scene);
  check_build_memory(a.scene, a.structure.accel, scene.geometry.size());
  accel->build(scene.geometry);
  const PlaneOutline outline = plane_outline(*accel);
  const Trace trace = record_trace(scene.geometry, *accel, {request}, a.scene, file_content_hash(a.scene));
  FlatFigureInput in;
  in.scene = &scene;
  in.outline = &outline;
  in.trace = &trace;
  in.step = a.step ? *a.step : -1;
  const Figure figure = flat_figure(in);
  write_figure(a.output, figure, a.width);
  std::printf("wrote %s (%s, %zu events, step %d)\n", a.output.c_str(), accel->name().c_str(),
              trace.rays[0].events.size(), a.step ? *a.step : int(trace.rays[0].events.size()) - 1);
  return 0;
}

}  // namespace raystep::cli
