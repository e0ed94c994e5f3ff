// `raystep figure`: a 2D scene's structure and one ray's walk at a step, as a figure for slides (SVG, PDF or
// PNG), headless (core/include/raystep/figure).
#include <memory>

#include "commands.h"
#include "raystep/accel/plane_outline.h"
#include "raystep/figure/figure_file.h"
#include "raystep/figure/flat_aa_figure.h"
#include "raystep/figure/flat_figure.h"
#include "raystep/io/scene_loader.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/record_trace.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"
#include "value_parsers.h"

namespace raystep::cli {

int run_figure(const FigureArgs& a) {
  if (a.step && *a.step < 0) throw InputError("", 0, "--step must be 0 or more");
  // Before the (possibly long) build: write_figure would refuse it only after.
  if (!is_figure_path(a.output))
    throw InputError("", 0, "-o " + a.output + ": a figure is written as .svg, .pdf or .png");
  check_output_folder(a.output);
  std::unique_ptr<Accelerator> accel = build_structure(a.structure);
  if (!has_plane_outline(*accel))
    throw InputError("", 0,
                     "figure: --accel " + a.structure.accel +
                         " is not drawn in 2D (use " + recorded_structure_list() + ")");
  const Scene scene = load_scene(a.scene);
  if (!scene.flat)
    throw InputError(a.scene, 0,
                     "a 3D scene: a figure draws a 2D scene (\"dimensions\": 2, docs/scene-format.md)");
  if (a.aa) {  // the anti-aliasing figure: the pixels over the polygon, sampled, exact and the error
    if (a.ray || a.step)
      throw InputError("", 0, "--aa draws the pixels, not a walk: give no --ray or --step");
    FlatAaInput in;
    in.scene = &scene;
    in.aa = parse_antialiasing(*a.aa);
    if (a.size) parse_size(*a.size, &in.width, &in.height);
    check_build_memory(a.scene, a.structure.accel, scene.geometry.size());
    accel->build(scene.geometry);
    in.accel = accel.get();
    const FlatAa aa = flat_aa_figure(in);
    write_figure(a.output, aa.figure, a.width);
    std::printf("wrote %s (%s, %d pixels, %zu samples", a.output.c_str(), to_string(in.aa).c_str(), aa.pixels,
                aa.samples);
    if (aa.exact)
      std::printf("; error mean %.4f, largest %.4f)\n", aa.mean_abs_error, aa.max_abs_error);
    else
      std::printf("; no exact coverage: %s)\n", aa.why_not.c_str());
    return 0;
  }
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
