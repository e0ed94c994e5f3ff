// raystep: the command line. Parses arguments (the only place that includes CLI11) and runs a subcommand.
// Any bad input prints one line "error: FILE:LINE: what" and exits with code 2.
#include <CLI/CLI.hpp>

#include <cstdio>
#include <exception>

#include "commands.h"
#include "raystep/accel/accelerator.h"
#include "raystep/accel/bvh_names.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace {

std::string accel_help() {
  std::string s = "acceleration structure:";
  for (const std::string& n : raystep::accelerator_names()) s += " " + n;
  s += " (bounding-volume kinds: bvol-sphere bvol-kdop bvol-obb)";
  return s;
}

void add_kd_options(CLI::App* cmd, raystep::cli::StructureArgs& s);
void add_bvh_options(CLI::App* cmd, raystep::cli::StructureArgs& s);

// --accel and every structure's build options.
void add_structure_options(CLI::App* cmd, raystep::cli::StructureArgs& s, const std::string& default_accel) {
  s.accel = default_accel;
  cmd->add_option("--accel", s.accel, accel_help())->capture_default_str();
  cmd->add_option("--grid-res", s.grid_res, "grid: explicit resolution NX,NY,NZ");
  cmd->add_option("--grid-density", s.grid_density, "grid: d in max(nx,ny,nz) = d * cbrt(primitives)")
      ->capture_default_str();
  cmd->add_option("--grid-insert", s.grid_insert,
                  "grid: exact (triangle-box overlap) | bbox (bounding boxes)")
      ->capture_default_str()
      ->check(CLI::IsMember({"exact", "bbox"}));
  add_kd_options(cmd, s);
  add_bvh_options(cmd, s);
  cmd->add_option("--octree-leaf", s.octree_leaf,
                  "octree: K, a cell with more than K primitives is split into eight (1..16777216)")
      ->capture_default_str();
  cmd->add_option("--bsp-directions", s.bsp_directions,
                  "bsp: candidate plane directions: both | kdop (13 k-DOP directions) | autopartition (the "
                  "primitives' own planes)")
      ->capture_default_str();
  cmd->add_option(
         "--bsp-candidates", s.bsp_candidates,
         "bsp: at most this many candidate positions per direction per node (and a quarter as many primitive "
         "planes; as many with autopartition alone), 1..4096")
      ->capture_default_str();
}

// The kd-tree's build options (also for the sah and kdtree-stats commands).
void add_kd_options(CLI::App* cmd, raystep::cli::StructureArgs& s) {
  cmd->add_option("--ti", s.kd_ti, "kd, bvh: t_i, the cost of a ray-primitive test")->capture_default_str();
  cmd->add_option("--tt", s.kd_tt, "kd, bvh: t_t, the cost of a traversal step")->capture_default_str();
  cmd->add_option("--empty-bonus", s.kd_empty_bonus, "kd: bonus in [0,1) for splits that cut off empty space")
      ->capture_default_str();
  cmd->add_option("--max-depth", s.kd_max_depth,
                  "kd: depth limit (0: max(8, 1.2 log2 N); with an empty bonus 8 + 1.3 log2 N); "
                  "bvh: 0..64 (0: 64); octree: 0..20 (0: ceil(log2(N) / 2) + 6 in 8..20)")
      ->capture_default_str();
  cmd->add_option("--leaf-size", s.kd_leaf_size, "kd: a node with at most this many primitives is a leaf")
      ->capture_default_str();
  cmd->add_option("--mailbox", s.kd_mailbox, "kd: mailboxes on | off")
      ->capture_default_str()
      ->check(CLI::IsMember({"on", "off"}));
}

// The BVH's own build and traversal options (t_i, t_t and --max-depth are shared with the kd-tree's).
void add_bvh_options(CLI::App* cmd, raystep::cli::StructureArgs& s) {
  cmd->add_option("--bins", s.bvh_bins, "bvh: bins per axis of the binned SAH, 2..256")
      ->capture_default_str();
  cmd->add_option("--bvh-leaf", s.bvh_leaf, "bvh: a node with at most this many primitives is a leaf")
      ->capture_default_str();
  cmd->add_option("--bvh-max-leaf", s.bvh_max_leaf,
                  "bvh: a node with more primitives is split even when a leaf would cost less")
      ->capture_default_str();
  cmd->add_option("--bvh-order", s.bvh_order,
                  "bvh: nearer child first by entry distance (entry) or by the split axis's direction (axis)")
      ->capture_default_str();
  cmd->add_option("--sbvh-alpha", s.sbvh_alpha,
                  "sbvh: try spatial splits where the object split's children overlap by more than this share "
                  "of the root's area")
      ->capture_default_str();
  cmd->add_option("--sbvh-budget", s.sbvh_budget,
                  "sbvh: at most this many extra references per primitive made by spatial splits, 0..16")
      ->capture_default_str();
}

}  // namespace

int main(int argc, char** argv) {
  using namespace raystep::cli;
  raystep::remove_temporary_files_on_signals();
  CLI::App app{"raystep: a step-debugger for anti-aliased, accelerated ray tracing"};
  app.set_version_flag("--version", "raystep 0.1.0");
  app.require_subcommand(1);

  RenderArgs render;
  CLI::App* render_cmd = app.add_subcommand("render", "Render a scene (or a bare OBJ mesh) to an image");
  render_cmd->add_option("scene", render.scene, "scene .json or mesh .obj")->required();
  render_cmd->add_option("-o,--output", render.output, "output image (.png, or .pfm for linear floats)")
      ->required();
  add_structure_options(render_cmd, render.structure, "bvh8");
  render_cmd
      ->add_option(
          "--heatmap", render.heatmap,
          "write a heat map of per-pixel work instead of the picture: cells (or nodes) | tests | mailbox"
          " | boxes (bvh: bounding-box tests)")
      ->check(CLI::IsMember({"cells", "nodes", "tests", "mailbox", "boxes"}));
  render_cmd->add_option(
      "--aa", render.aa,
      "anti-aliasing: none | regular:K | jitter:K | random:N | adaptive:T[:D]; +tent after any but "
      "adaptive: the tent filter over the neighbours' samples too");
  render_cmd->add_option("--size", render.size, "image size WxH (default: the scene's)");
  render_cmd->add_option("--threads", render.threads, "threads, 0..256 (0: all cores)")
      ->capture_default_str();
  render_cmd->add_option("--seed", render.seed, "sampling seed (default: the scene's)");
  render_cmd->add_option("--samples-map", render.samples_map, "also write a PNG of samples per pixel");

  CastArgs cast;
  CLI::App* cast_cmd = app.add_subcommand("cast", "Batch nearest-hit queries, to compare structures");
  cast_cmd->add_option("scene", cast.scene, "scene .json or mesh .obj")->required();
  cast_cmd->add_option("--rays", cast.rays, "input rays (.rays: 32 bytes per ray)")->required();
  cast_cmd->add_option("--hits", cast.hits, "output hits (.hits: 8 bytes per ray)")->required();
  add_structure_options(cast_cmd, cast.structure, "bvh8");
  cast_cmd->add_option("--threads", cast.threads, "threads, 0..256 (0: all cores)")->capture_default_str();
  cast_cmd->add_option("--reps", cast.reps, "timed passes; trace_ms is their median")->capture_default_str();

  RaysArgs rays;
  CLI::App* rays_cmd = app.add_subcommand("rays", "Write a ray set for comparing structures");
  rays_cmd->add_option("scene", rays.scene, "scene .json or mesh .obj")->required();
  rays_cmd->add_option("--kind", rays.kind, "camera (one per pixel, row-major) | random | edges")
      ->required()
      ->check(CLI::IsMember({"camera", "random", "edges"}));
  rays_cmd->add_option("--count", rays.count, "number of rays (random, edges)")->capture_default_str();
  rays_cmd->add_option("--seed", rays.seed, "random seed")->capture_default_str();
  rays_cmd->add_option("--size", rays.size, "camera rays: image size WxH (default: the scene's)");
  rays_cmd->add_option("-o,--output", rays.output, "output .rays file")->required();

  InfoArgs info;
  CLI::App* info_cmd =
      app.add_subcommand("info", "Describe a scene or mesh: primitives, bounds, degenerate triangles");
  info_cmd->add_option("scene", info.scene, "scene .json or mesh .obj")->required();

  TraceArgs trace;
  CLI::App* trace_cmd = app.add_subcommand(
      "trace",
      "Record one ray's traversal, event by event, to a trace file (--accel A,B,...: through 2 to 6 "
      "structures, one file)");
  trace_cmd->add_option("scene", trace.scene, "scene .json or mesh .obj")->required();
  add_structure_options(trace_cmd, trace.structure, "grid");
  auto* pixel_opt =
      trace_cmd->add_option("--pixel", trace.pixel, "the primary ray of pixel X,Y (0,0: top left)");
  auto* ray_opt = trace_cmd->add_option(
      "--ray", trace.ray,
      "a ray given by hand: ox,oy,oz,dx,dy,dz (a 2D scene: ox,oy,dx,dy; none: its own ray)");
  pixel_opt->excludes(ray_opt);
  trace_cmd->add_flag("--secondary", trace.secondary,
                      "with --pixel: also the shadow, reflected, refracted rays");
  trace_cmd->add_flag("--build-events", trace.build_events,
                      "kd: also log the whole build (every candidate, split and leaf), streamed to the file");
  trace_cmd->add_option("--size", trace.size, "image size WxH for --pixel (default: the scene's)");
  trace_cmd->add_option(
      "--aa", trace.aa,
      "with --pixel: record the anti-aliased pixel, every sample and its rays: none | regular:K | "
      "jitter:K | random:N | adaptive:T[:D] | scene (the scene's setting)");
  trace_cmd->add_option("--seed", trace.seed, "with --aa: the sampling seed (default: the scene's)");
  trace_cmd->add_option("--format", trace.format, "json (the trace format) | csv (one event per row)")
      ->capture_default_str()
      ->check(CLI::IsMember({"json", "csv"}));
  trace_cmd->add_option("-o,--output", trace.output, "output trace file")->required();

  SahArgs sah;
  CLI::App* sah_cmd =
      app.add_subcommand("sah",
                         "Write the SAH cost curve of one kd-tree or BVH node (x, y and z), or of one "
                         "BSP node by orientation (13 k-DOP directions and the primitives' own planes)");
  sah_cmd->add_option("scene", sah.scene, "scene .json or mesh .obj")->required();
  sah.structure.accel = "kd";
  sah_cmd
      ->add_option("--accel", sah.structure.accel,
                   "kd (SAH) | bvh (binned SAH) | bvh-sweep | bvh-median | bvh-sbvh (spatial splits) | bsp")
      ->capture_default_str()
      ->check(CLI::IsMember({"kd", "bvh", "bvh-sweep", "bvh-median", "bvh-sbvh", "bsp"}));
  auto* node_opt = sah_cmd->add_option("--node", sah.node, "node id (0: the root; ids as in traces)");
  auto* path_opt =
      sah_cmd->add_option("--path", sah.path, "node by its path from the root: L below, R above, e.g. LRL");
  node_opt->excludes(path_opt);
  add_kd_options(sah_cmd, sah.structure);
  add_bvh_options(sah_cmd, sah.structure);
  sah_cmd->add_option("--bsp-directions", sah.structure.bsp_directions, "bsp: both | kdop | autopartition")
      ->capture_default_str();
  sah_cmd
      ->add_option("--bsp-candidates", sah.structure.bsp_candidates,
                   "bsp: candidate positions per direction per node (a quarter as many own planes), 1..4096")
      ->capture_default_str();
  sah_cmd->add_option("-o,--output", sah.output, "output curve: .csv (one row per candidate) or .json")
      ->required();

  KdStatsArgs kd_stats;
  CLI::App* kd_stats_cmd = app.add_subcommand(
      "kdtree-stats", "kd-tree statistics, and each node's predicted entry probability against measurement");
  kd_stats_cmd->add_option("scene", kd_stats.scene, "scene .json or mesh .obj")->required();
  kd_stats.structure.accel = "kd";
  kd_stats_cmd->add_option("--accel", kd_stats.structure.accel, "kd (SAH) | kd-median")
      ->capture_default_str()
      ->check(CLI::IsMember({"kd", "kd-median"}));
  add_kd_options(kd_stats_cmd, kd_stats.structure);
  kd_stats_cmd->add_option("--lines", kd_stats.lines, "random lines through the root for the measurement")
      ->capture_default_str();
  kd_stats_cmd->add_option("--seed", kd_stats.seed, "random seed")->capture_default_str();
  kd_stats_cmd
      ->add_option("--rays", kd_stats.rays,
                   "camera rays (at most this many, the scene's camera) and random rays for the measured cost")
      ->capture_default_str();
  kd_stats_cmd->add_option("--csv", kd_stats.csv,
                           "also write every node's row (id, depth, predicted, measured)");

  KdStatsArgs bvh_stats;
  CLI::App* bvh_stats_cmd = app.add_subcommand(
      "bvh-stats",
      "BVH statistics (sibling overlap, SAH cost), and each node's predicted entry probability against "
      "measurement");
  bvh_stats_cmd->add_option("scene", bvh_stats.scene, "scene .json or mesh .obj")->required();
  bvh_stats.structure.accel = "bvh";
  bvh_stats_cmd
      ->add_option("--accel", bvh_stats.structure.accel,
                   "bvh (binned SAH) | bvh-sweep | bvh-median | bvh-sbvh (spatial splits)")
      ->capture_default_str()
      ->check(CLI::IsMember(raystep::binary_bvh_names()));
  add_kd_options(bvh_stats_cmd, bvh_stats.structure);
  add_bvh_options(bvh_stats_cmd, bvh_stats.structure);
  bvh_stats_cmd->add_option("--lines", bvh_stats.lines, "random lines through the root for the measurement")
      ->capture_default_str();
  bvh_stats_cmd
      ->add_option("--rays", bvh_stats.rays,
                   "camera rays (at most this many, the scene's camera) and random rays for the measured cost")
      ->capture_default_str();
  bvh_stats_cmd->add_option("--quality-csv", bvh_stats.quality_csv,
                            "also write the quality metrics (SAH, EPO, histograms, measured cost) as one CSV row");
  bvh_stats_cmd->add_option("--seed", bvh_stats.seed, "random seed")->capture_default_str();
  bvh_stats_cmd->add_option("--csv", bvh_stats.csv,
                            "also write every node's row (id, depth, predicted, measured)");

  CompareArgs compare;
  CLI::App* compare_cmd = app.add_subcommand(
      "compare",
      "Structures side by side: build time, memory, Mrays/s, work per ray, disagreements with brute force");
  compare_cmd->add_option("scene", compare.scene, "scene .json or mesh .obj")->required();
  compare_cmd->add_option("--accel", compare.accel, "comma-separated structures: " + accel_help().substr(24))
      ->capture_default_str();
  compare_cmd->add_option("--rays", compare.rays, "random rays (besides one camera ray per pixel)")
      ->capture_default_str();
  compare_cmd->add_option("--size", compare.size,
                          "camera rays: image size WxH (default: the scene's, at most 512)");
  compare_cmd->add_option("--reps", compare.reps, "timed passes; the median is reported")
      ->capture_default_str();
  compare_cmd->add_option("-o,--output", compare.output, "report folder (report.csv, report.md, PNG plots)")
      ->required();
  compare_cmd
      ->add_option("--bsp-directions", compare.structure.bsp_directions, "bsp: both | kdop | autopartition")
      ->capture_default_str();
  compare_cmd
      ->add_option(
          "--bsp-candidates", compare.structure.bsp_candidates,
          "bsp: candidate positions per direction per node (a quarter as many primitive planes), 1..4096")
      ->capture_default_str();

  BvolReportArgs bvol_report;
  CLI::App* bvol_report_cmd = app.add_subcommand(
      "bvol-report",
      "Kinds of bounding volumes (bvol, bvol-sphere, bvol-kdop, bvol-obb) on camera rays: volume "
      "tests, false positives, primitive tests, build time and time per ray");
  bvol_report_cmd->add_option("scenes", bvol_report.scenes, "scene .json files (default: scenes/*.json)");
  bvol_report_cmd->add_option("--size", bvol_report.size,
                              "camera rays: image size WxH (default: the scene's, at most 160 on a side)");
  bvol_report_cmd->add_option("--reps", bvol_report.reps, "timed passes; the median is reported")
      ->capture_default_str();
  bvol_report_cmd->add_option("-o,--output", bvol_report.output,
                              "report folder (bvol_report.csv, bvol_report.md)");

  GridSweepArgs sweep;
  CLI::App* sweep_cmd = app.add_subcommand(
      "grid-sweep",
      "The grid's density d in max(nx,ny,nz) = d*cbrt(n) against cells, tests, memory and time");
  sweep_cmd->add_option("scene", sweep.scene, "scene .json or mesh .obj")->required();
  sweep_cmd->add_option("--densities", sweep.densities,
                        "comma-separated d values in (0, 64], measured in increasing order "
                        "(default: 0.5,0.75,1,1.5,2,3,4,6,8)");
  sweep_cmd->add_option("--rays", sweep.rays, "random rays (besides one camera ray per pixel)")
      ->capture_default_str();
  sweep_cmd->add_option("--size", sweep.size,
                        "camera rays: image size WxH (default: the scene's, at most 256)");
  sweep_cmd->add_option("--reps", sweep.reps, "timed passes; the median is reported")->capture_default_str();
  sweep_cmd->add_option("-o,--output", sweep.output, "report folder (report.csv, report.md, sweep.png)")
      ->required();

  CostArgs cost;
  CLI::App* cost_cmd = app.add_subcommand(
      "cost",
      "The lecture's cost formula m^2 k^2 n 2^d against the tests counted, and what each technique cuts");
  cost_cmd->add_option("scene", cost.scene, "scene .json or mesh .obj")->required();
  cost_cmd->add_option("--size", cost.size, "image size WxH (default: the scene's)");
  cost_cmd->add_option(
      "--aa", cost.aa,
      "anti-aliasing: none | regular:K | jitter:K | random:N | adaptive:T[:D] (+tent: the tent filter)");
  cost_cmd->add_option("--accel", cost.accel, "comma-separated structures (default: all but brute)");
  cost_cmd->add_option("--threads", cost.threads, "threads, 0..256 (0: all cores)")->capture_default_str();
  cost_cmd->add_option("-o,--output", cost.output,
                       "also write a report folder (report.csv, factors.csv, report.md)");

  TraceInfoArgs trace_info;
  CLI::App* trace_info_cmd = app.add_subcommand("trace-info", "Validate a trace file and summarise it");
  trace_info_cmd->add_option("trace", trace_info.trace, "trace .json")->required();
  trace_info_cmd->add_flag(
      "--own-costs", trace_info.own_costs,
      "a multi-walk trace: cost each walk by its structure's own t_t, t_i (default 1, 80)");

  ReplayArgs replay;
  CLI::App* replay_cmd = app.add_subcommand("replay",
                                            "A trace's replay states, event by event, as the debugger's "
                                            "state panel shows them (docs/replay-format.md)");
  replay_cmd->add_option("trace", replay.trace, "trace .json")->required();
  CLI::Option* replay_step =
      replay_cmd->add_option("--step", replay.step, "only the state after this event (0-based)");
  replay_cmd->add_flag("--all", "every step (the default)")->excludes(replay_step);
  replay_cmd->add_option("--walk", replay.walk, "a multi-walk trace: only this walk (0-based)");
  replay_cmd->add_option("--ray", replay.ray, "only this ray (0-based)");
  replay_cmd->add_option("--format", replay.format, "text (for reading) | json (the storyboard)")
      ->check(CLI::IsMember({"text", "json"}))
      ->capture_default_str();
  replay_cmd->add_option("-o,--output", replay.output,
                         "write to this file (atomically) instead of standard output");

  ExportHtmlArgs html;
  CLI::App* html_cmd = app.add_subcommand(
      "export-html", "A trace, or a 2D scene's ray, as one page that steps through the walk in a browser (offline)");
  html_cmd->add_option("input", html.input, "a trace .json (raystep trace), or a 2D scene .json")->required();
  add_structure_options(html_cmd, html.structure, "kd");
  html_cmd->add_option("--ray", html.ray, "a 2D scene: the ray ox,oy,dx,dy (default: the scene's own)");
  html_cmd->add_option("--title", html.title, "the page's heading");
  html_cmd->add_option("--width", html.width, "a 2D scene: the picture's width in CSS pixels")
      ->check(CLI::Range(120, 4000));
  html_cmd->add_option("-o,--output", html.output, "page.html (written atomically)")->required();

  FigureArgs figure;
  CLI::App* figure_cmd = app.add_subcommand(
      "figure",
      "A 2D scene's structure and one ray's walk at a step, as a figure for slides (SVG, PDF or PNG)");
  figure_cmd->add_option("scene", figure.scene, "a 2D scene .json (\"dimensions\": 2)")->required();
  add_structure_options(figure_cmd, figure.structure, "kd");
  figure_cmd->add_option("--ray", figure.ray, "the ray ox,oy,dx,dy (default: the scene's own)");
  figure_cmd->add_option("--step", figure.step, "draw the walk after this event (0-based; default: its end)");
  CLI::Option* figure_aa = figure_cmd->add_option(
      "--aa", figure.aa,
      "instead of the walk, the anti-aliasing: sampled, exact coverage and error per pixel (none, regular:K, "
      "jitter:K, random:N, adaptive:T[:D], +tent)");
  figure_cmd->add_option("--size", figure.size, "with --aa: the pixels WxH (default: the scene's; at most 4096)")
      ->needs(figure_aa);
  figure_cmd->add_option("--width", figure.width, "the figure's width in points (PNG: pixels)")
      ->capture_default_str();
  figure_cmd->add_option("-o,--output", figure.output, "fig.svg, fig.pdf or fig.png")->required();

  CLI::App* lesson_cmd =
      app.add_subcommand("lesson", "Lessons (docs/lesson-format.md): check them, show a step as a command");
  lesson_cmd->require_subcommand(1);
  LessonCheckArgs lesson_check;
  CLI::App* lesson_check_cmd =
      lesson_cmd->add_subcommand("check", "Enter every step of lessons headless and answer every question");
  lesson_check_cmd->add_option("lessons", lesson_check.paths,
                               "lesson files (.md) or folders of them (default: lessons)");
  LessonCommandArgs lesson_command;
  CLI::App* lesson_command_cmd =
      lesson_cmd->add_subcommand("command", "Print the raystep-gui command line that shows a step");
  lesson_command_cmd->add_option("lesson", lesson_command.file, "lesson file (.md)")->required();
  lesson_command_cmd->add_option("step", lesson_command.step, "the step, 1-based")->required();
  LessonAnswersArgs lesson_answers;
  CLI::App* lesson_answers_cmd =
      lesson_cmd->add_subcommand("answers", "Print every question's computed answer and its reason");
  lesson_answers_cmd->add_option("lesson", lesson_answers.file, "lesson file (.md)")->required();
  LessonAnswersArgs lesson_numbers;
  CLI::App* lesson_numbers_cmd = lesson_cmd->add_subcommand(
      "numbers", "Print every number of a lesson's text ({{...}}) as written and as the tool computes it");
  lesson_numbers_cmd->add_option("lesson", lesson_numbers.file, "lesson file (.md)")->required();
  CLI::App* lesson_facts_cmd =
      lesson_cmd->add_subcommand("facts", "List the facts and functions a lesson's numbers can use");

  AaReportArgs aa_report;
  CLI::App* aa_report_cmd = app.add_subcommand(
      "aa-report",
      "Anti-aliasing speed against error: every method rendered, timed and measured, with plots");
  aa_report_cmd->add_option("scene", aa_report.scene, "scene .json or mesh .obj")->required();
  aa_report_cmd->add_option(
      "--methods", aa_report.methods,
      "comma-separated anti-aliasing specs, e.g. none,jitter:2,jitter:4,adaptive:0.1:3 "
      "(default: none, regular:2..8, jitter:2..8, random:4..64, adaptive at 5 thresholds)");
  aa_report_cmd
      ->add_option(
          "--reference", aa_report.reference,
          "exact (area coverage) | jitter:K (two seeds) | auto (exact where possible, else jitter:16)")
      ->capture_default_str();
  aa_report_cmd->add_option("--size", aa_report.size, "image size WxH (default: the scene's)");
  aa_report_cmd->add_option("--seeds", aa_report.seeds, "seeds of each jitter and random method")
      ->capture_default_str();
  aa_report_cmd->add_option("--threads", aa_report.threads, "threads, 0..256 (0: all cores)")
      ->capture_default_str();
  aa_report_cmd->add_option("--accel", aa_report.accel, accel_help())->capture_default_str();
  aa_report_cmd
      ->add_option("-o,--output", aa_report.output,
                   "report folder (replaced): report.csv, report.md, images/*.pfm, *.png plots")
      ->required();

  ExportVtkArgs export_vtk;
  CLI::App* export_vtk_cmd = app.add_subcommand(
      "export-vtk", "Write the scene, a structure's cells and recorded walks as VTK files for ParaView");
  export_vtk_cmd->add_option("scene", export_vtk.scene, "scene .json or mesh .obj")->required();
  add_structure_options(export_vtk_cmd, export_vtk.structure, "");
  auto* export_pixel_opt = export_vtk_cmd->add_option("--pixel", export_vtk.pixel,
                                                      "record the primary ray of pixel X,Y (0,0: top left)");
  auto* export_trace_opt = export_vtk_cmd->add_option(
      "--trace", export_vtk.trace,
      "a trace of the scene (raystep trace): its rays; without --accel its own nodes");
  export_pixel_opt->excludes(export_trace_opt);
  export_vtk_cmd->add_flag("--secondary", export_vtk.secondary,
                           "with --pixel: also the shadow, reflected, refracted rays");
  export_vtk_cmd->add_option("--size", export_vtk.size, "image size WxH for --pixel (default: the scene's)");
  export_vtk_cmd
      ->add_option("--max-cells", export_vtk.max_cells,
                   "at most this many structure cells: trees cut by depth, grids merged into blocks")
      ->capture_default_str();
  export_vtk_cmd
      ->add_option("-o,--output", export_vtk.output, "output folder (replaced): raystep.vtm and raystep/")
      ->required();

  HardCasesArgs hardcases;
  CLI::App* hardcases_cmd = app.add_subcommand(
      "hardcases",
      "The hard-case battery for every structure: leaks, disagreements with a double-precision brute force, "
      "crashes (exit 0: none; 1: any; 2: bad input)");
  hardcases_cmd->add_option(
      "mesh", hardcases.mesh,
      "a .obj mesh (default: the built-in meshes); the inside rays need it closed: every "
      "edge shared by an even number of triangles");
  hardcases_cmd->add_option(
      "--accel", hardcases.accel,
      "comma-separated structures, or all (default: brute,grid,kd,bvh,bvh-sbvh,bvh4,bvh8,bvh8-sbvh,octree,bsp)");
  hardcases_cmd
      ->add_option("--rays", hardcases.rays, "rays per scale on the mesh, up to 65536 (0: automatic)")
      ->capture_default_str();
  hardcases_cmd->add_option("--seed", hardcases.seed, "seed of the generated rays")->capture_default_str();
  hardcases_cmd
      ->add_option("--time-limit", hardcases.time_limit,
                   "seconds per structure before it counts as a crash (a hang)")
      ->capture_default_str();
  hardcases_cmd->add_option("-o,--output", hardcases.output, "also write the report: .csv or .json");

  try {
    app.parse(argc, argv);
  } catch (const CLI::CallForHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForAllHelp& e) {
    return app.exit(e);
  } catch (const CLI::CallForVersion& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::fprintf(stderr, "error: %s (see raystep --help)\n", e.what());
    return 2;
  }

  try {
    if (*render_cmd) return run_render(render);
    if (*aa_report_cmd) return run_aa_report(aa_report);
    if (*cast_cmd) return run_cast(cast);
    if (*rays_cmd) return run_rays(rays);
    if (*info_cmd) return run_info(info);
    if (*trace_cmd) return run_trace(trace);
    if (*trace_info_cmd) return run_trace_info(trace_info);
    if (*replay_cmd) return run_replay(replay);
    if (*figure_cmd) return run_figure(figure);
    if (*html_cmd) return run_export_html(html);
    if (*sah_cmd) return run_sah(sah);
    if (*kd_stats_cmd) return run_kdtree_stats(kd_stats);
    if (*bvh_stats_cmd) return run_bvh_stats(bvh_stats);
    if (*compare_cmd) return run_compare(compare);
    if (*sweep_cmd) return run_grid_sweep_command(sweep);
    if (*bvol_report_cmd) return run_bvol_report(bvol_report);
    if (*cost_cmd) return run_cost(cost);
    if (*lesson_check_cmd) return run_lesson_check(lesson_check);
    if (*lesson_command_cmd) return run_lesson_command(lesson_command);
    if (*lesson_answers_cmd) return run_lesson_answers(lesson_answers);
    if (*lesson_numbers_cmd) return run_lesson_numbers(lesson_numbers);
    if (*lesson_facts_cmd) return run_lesson_facts();
    if (*export_vtk_cmd) return run_export_vtk(export_vtk);
    if (*hardcases_cmd) return run_hardcases(hardcases);
  } catch (const raystep::InputError& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 2;
  } catch (const std::bad_alloc&) {
    std::fprintf(stderr, "error: out of memory\n");
    return 2;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "error: %s\n", e.what());
    return 1;
  }
  return 1;
}
