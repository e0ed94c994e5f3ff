// `raystep export-vtk`: the scene's geometry, a structure's cells and recorded walks as VTK XML files for
// ParaView (docs/vtk-export.md), written into a folder that appears whole or not at all. The VTK side is
// the raystep_vtk_export library; a raystep built without VTK has the command but refuses it in one line.
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <memory>
#include <optional>

#include "commands.h"
#include "raystep/util/error.h"
#include "raystep/util/memory_limit.h"

#ifdef RAYSTEP_HAVE_VTK_EXPORT
#include "output_folder.h"
#include "raystep/accel/accelerator.h"
#include "raystep/io/scene_loader.h"
#include "raystep/trace/pixel_rays.h"
#include "raystep/trace/record_trace.h"
#include "raystep/trace/trace_file.h"
#include "raystep/vtk_export/structure_cells.h"
#include "raystep/vtk_export/vtk_export.h"
#endif

namespace raystep::cli {

#ifndef RAYSTEP_HAVE_VTK_EXPORT

int run_export_vtk(const ExportVtkArgs&) {
  throw InputError("", 0,
                   "export-vtk: this raystep was built without VTK (install VTK 9's development files, "
                   "e.g. Debian's libvtk9-dev, and configure again)");
}

#else

namespace {

// A build parameter of two traces of the same structure: equal numbers up to the JSON round trip.
bool same_param(const TraceParam& a, const TraceParam& b) {
  if (a.key != b.key || a.is_text != b.is_text) return false;
  if (a.is_text) return a.text == b.text;
  return std::fabs(a.number - b.number) <= 1e-6 * std::max(1.0, std::fabs(a.number));
}

std::string param_text(const TraceParam& p) {
  if (p.is_text) return p.key + "=" + p.text;
  char buf[64];
  std::snprintf(buf, sizeof buf, "=%g", p.number);
  return p.key + buf;
}

// The structure rebuilt for a trace must be the one the trace was recorded through: its build parameters
// and sizes (nodes, leaves, references, resolution) as a trace of it would state them.
void check_same_structure(const Trace& trace, const Trace& rebuilt, const std::string& trace_path) {
  const auto& want = trace.structure.params;
  const auto& have = rebuilt.structure.params;
  for (const TraceParam& w : want) {
    const TraceParam* h = nullptr;
    for (const TraceParam& p : have)
      if (p.key == w.key) h = &p;
    if (!h || !same_param(w, *h))
      throw InputError(
          trace_path, 0,
          "the trace's " + trace.structure.kind + " has " + param_text(w) + ", the one built here " +
              (h ? param_text(*h) : "no " + w.key) +
              " (give the trace's build options, or leave out --accel to use the trace's own nodes)");
  }
  if (trace.structure.kind == "grid" && trace.structure.resolution != rebuilt.structure.resolution)
    throw InputError(trace_path, 0,
                     "the trace's grid has another resolution than the one built here (give its --grid-res)");
}

}  // namespace

int run_export_vtk(const ExportVtkArgs& a) {
  if (a.size && !a.pixel) throw InputError("", 0, "export-vtk: --size goes with --pixel");
  if (a.secondary && !a.pixel) throw InputError("", 0, "export-vtk: --secondary goes with --pixel");
  if (a.max_cells < 1 || a.max_cells > (uint64_t(1) << 26))
    throw InputError("", 0, "--max-cells must be 1..67108864");
  if (!a.trace && a.structure.accel.empty())
    throw InputError("", 0, "export-vtk: give --accel NAME (or --trace T.json, whose structure is used)");
  ReportFolder folder(a.output);
  Scene scene = load_scene(a.scene);
  const std::string scene_hash = file_content_hash(a.scene);

  std::optional<Trace> trace;
  if (a.trace) {
    trace = read_trace_json(*a.trace);
    if (trace->scene_hash != scene_hash || trace->scene_primitives != scene.geometry.size())
      throw InputError(*a.trace, 0,
                       "a trace of another scene (" + trace->scene_path + ", " + trace->scene_hash +
                           "), not of " + a.scene + " (" + scene_hash + ")");
    if (!a.structure.accel.empty() && a.structure.accel != trace->structure.kind)
      throw InputError(*a.trace, 0,
                       "the trace walks a " + trace->structure.kind + ", not --accel " + a.structure.accel);
  }

  vtk_export::StructureCells structure;
  if (!a.structure.accel.empty()) {
    std::unique_ptr<Accelerator> accel = build_structure(a.structure);
    if (!vtk_export::exports_structure(*accel))
      throw InputError("", 0,
                       "export-vtk: --accel " + a.structure.accel + " has no VTK export (use " +
                           vtk_export::exported_structure_names() + ")");
    // The pixel is checked before the (possibly long) build.
    int w = scene.render.width, h = scene.render.height, px = 0, py = 0;
    if (a.pixel) {
      if (!records_events(*accel))
        throw InputError("", 0, "export-vtk: --accel " + a.structure.accel + " records no walk for --pixel");
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
    check_build_memory(a.scene, a.structure.accel, scene.geometry.size());
    accel->build(scene.geometry);
    if (trace)
      check_same_structure(*trace, record_trace(scene.geometry, *accel, {}, a.scene, scene_hash), *a.trace);
    structure = vtk_export::structure_cells(*accel, size_t(a.max_cells));
    if (a.pixel)
      trace = record_trace(scene.geometry, *accel, pixel_rays(scene, *accel, w, h, px, py, a.secondary),
                           a.scene, scene_hash);
  } else {
    structure = vtk_export::trace_structure_cells(*trace);
  }

  vtk_export::ExportInput input;
  input.geometry = &scene.geometry;
  input.structure = &structure;
  input.trace = trace ? &*trace : nullptr;
  input.trace_name = a.trace ? *a.trace : a.scene;
  const vtk_export::ExportSummary summary = vtk_export::write_vtk_export(folder.path(), input);
  folder.commit();

  std::printf("geometry: %zu primitives (%zu triangles; spheres tessellated)\n", scene.geometry.size(),
              scene.geometry.triangle_count());
  std::printf("structure: %s, %zu of %zu cells or nodes\n", structure.kind.c_str(), structure.cells.size(),
              structure.total);
  if (!structure.note.empty()) std::printf("  %s\n", structure.note.c_str());
  if (!structure.planes.empty())
    std::printf("planes: %zu splitting planes, each clipped to its node's cell\n", structure.planes.size());
  if (trace)
    for (size_t r = 0; r < trace->rays.size(); ++r) {
      const TracedRay& ray = trace->rays[r];
      std::printf("ray %zu: %s, %zu cells or nodes in its walk, %zu primitive tests, ", r,
                  ray_kind_name(ray.kind), summary.visited[r], summary.tests[r]);
      if (!ray.events.empty() && ray.events.back().hit)
        std::printf("hit primitive %d at t = %g\n", ray.events.back().prim, double(ray.events.back().t));
      else
        std::printf("no hit\n");
    }
  // The blocks: all of them, or with many rays the first and the last.
  std::printf("wrote %s/%s (%zu files, blocks:", a.output.c_str(), vtk_export::kMultiBlockFile,
              summary.files.size());
  const size_t n = summary.blocks.size();
  for (size_t i = 0; i < n; ++i) {
    if (n > 8 && i == 4) {
      std::printf(" ..");
      i = n - 2;
    }
    std::printf(" \"%s\"", summary.blocks[i].c_str());
  }
  std::printf(")\n");
  return 0;
}

#endif

}  // namespace raystep::cli
