// `raystep compare`, `raystep grid-sweep` and `raystep cost`: the structures and the lecture's cost formula
// measured, each written into a report folder (CSV, Markdown, gnuplot PNGs with their scripts) that appears
// whole or not at all.
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <sstream>

#include "commands.h"
#include "output_folder.h"
#include "plot.h"
#include "value_parsers.h"
#include "raystep/accel/accelerator.h"
#include "raystep/report/cost_report.h"
#include "raystep/report/grid_sweep.h"
#include "raystep/report/structure_compare.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep::cli {
namespace {

namespace fs = std::filesystem;

// A progress bar on stderr, only when it is a terminal; redrawn at most ten times a second, erased at the
// end.
class Progress {
 public:
  explicit Progress(std::string label) : label_(std::move(label)), enabled_(::isatty(STDERR_FILENO)) {}
  ~Progress() {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
  }
  void operator()(double f) {
    if (!enabled_) return;
    auto now = std::chrono::steady_clock::now();
    if (drawn_ && f < 1.0 && now - last_ < std::chrono::milliseconds(100)) return;
    last_ = now;
    const int kWidth = 40;
    const int filled = int(std::clamp(f, 0.0, 1.0) * kWidth);
    std::fprintf(stderr, "\r%s [%.*s%*s] %3d%%", label_.c_str(), filled,
                 "========================================", kWidth - filled, "", int(f * 100.0));
    std::fflush(stderr);
    drawn_ = true;
  }

 private:
  std::string label_;
  bool enabled_;
  bool drawn_ = false;
  std::chrono::steady_clock::time_point last_{};
};

std::string fmt(const char* format, double v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, format, v);
  return buf;
}

// Bytes for a reader: B, KiB or MiB.
std::string human_bytes(double b) {
  if (b < 10 * 1024.0) return fmt("%.0f B", b);
  if (b < 10 * 1024.0 * 1024.0) return fmt("%.1f KiB", b / 1024.0);
  return fmt("%.1f MiB", b / (1024.0 * 1024.0));
}

void report_plot(const ReportFolder& folder, const std::string& name, const std::string& body,
                 int width = 960, int height = 640) {
  PlotResult r = plot_png(folder.path(), name, body, width, height);
  if (!r.drawn) std::printf("plot %s.png not drawn: %s\n", name.c_str(), r.message.c_str());
}

}  // namespace

// ---- compare ----

int run_compare(const CompareArgs& a) {
  ReportFolder folder(a.output);
  StructureCompareOptions options;
  options.structures = parse_names("--accel", a.accel);
  options.build.bsp = bsp_options(a.structure);
  if (a.rays > (uint64_t(1) << 26)) throw InputError("", 0, "--rays must be at most 67108864");
  options.random_rays = a.rays;
  if (a.reps < 1 || a.reps > 1000) throw InputError("", 0, "--reps must be 1..1000");
  options.reps = a.reps;
  if (a.size) parse_size(*a.size, &options.camera_width, &options.camera_height);
  for (const std::string& name : options.structures) {
    try {
      make_accelerator(name, options.build);
    } catch (const InputError& e) {
      throw InputError("", 0, "--accel: " + e.detail());
    }
  }
  Scene scene = load_scene(a.scene);

  StructureComparison c;
  {
    Progress progress("compare");
    StructureCompareHooks hooks;
    hooks.progress = [&](double f) { progress(f); };
    c = compare_structures(scene, options, hooks);
  }

  // The measured cost of a ray in the SAH's units: t_t per step, t_i per primitive test (the BVH's options).
  const float t_i = options.build.bvh.t_i, t_t = options.build.bvh.t_t;
  auto cost_per_ray = [&](const StructureRaySet& s) {
    return double(t_t) * s.steps_per_ray + double(t_i) * s.tests_per_ray;
  };
  // report.csv: one row per structure.
  write_file_atomically(folder.file("report.csv"), [&](std::ostream& out) {
    out << "structure,steps,build_ms,memory_bytes,camera_mrays_per_s,random_mrays_per_s,camera_steps_per_ray,"
           "random_steps_per_ray,camera_tests_per_ray,random_tests_per_ray,camera_rays,random_rays,"
           "checked_rays,disagreements,ties,nodes,max_depth,sah_cost,epo,camera_cost_per_ray,"
           "random_cost_per_ray\n";
    char buf[512];
    for (const StructureCompareRow& r : c.rows) {
      std::snprintf(buf, sizeof buf,
                    "%s,%s,%.4f,%" PRIu64 ",%.5g,%.5g,%.4f,%.4f,%.4f,%.4f,%" PRIu64 ",%" PRIu64 ",%" PRIu64
                    ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%d,%.6g,%.6g,%.6g,%.6g\n",
                    r.name.c_str(), r.steps.c_str(), r.build_seconds * 1e3, r.memory_bytes,
                    r.camera.mrays_per_second, r.random.mrays_per_second, r.camera.steps_per_ray,
                    r.random.steps_per_ray, r.camera.tests_per_ray, r.random.tests_per_ray, r.camera.rays,
                    r.random.rays, r.camera.checked + r.random.checked, r.disagreements(), r.ties(),
                    r.tree_nodes, r.tree_depth, r.sah_cost, r.epo, cost_per_ray(r.camera),
                    cost_per_ray(r.random));
      out << buf;
    }
  });

  // report.md and stdout: the same table.
  std::ostringstream md;
  md << "# Structures compared: " << a.scene << "\n\n"
     << c.primitives << " primitives; camera rays " << c.camera_width << "x" << c.camera_height << " ("
     << c.camera_rays << "), random rays " << c.random_rays << "; one thread, median of " << options.reps
     << " passes.\n"
     << "Disagreements: rays whose nearest hit differs from brute force's (hit against miss, or another t), "
        "checked on "
     << c.camera_checked << " camera and " << c.random_checked
     << " random rays; a tie (another primitive at exactly the same t) is not an error.\n\n"
     << "| structure | build ms | memory | Mrays/s camera | Mrays/s random | steps/ray camera | "
        "steps/ray random | tests/ray camera | tests/ray random | disagreements | ties | nodes (depth) |\n"
     << "|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const StructureCompareRow& r : c.rows) {
    md << "| " << r.name << " | " << fmt("%.2f", r.build_seconds * 1e3) << " | "
       << human_bytes(double(r.memory_bytes)) << " | " << fmt("%.3g", r.camera.mrays_per_second) << " | "
       << fmt("%.3g", r.random.mrays_per_second) << " | "
       << (r.steps == "-" ? std::string("-") : fmt("%.2f", r.camera.steps_per_ray) + " " + r.steps) << " | "
       << (r.steps == "-" ? std::string("-") : fmt("%.2f", r.random.steps_per_ray) + " " + r.steps) << " | "
       << fmt("%.2f", r.camera.tests_per_ray) << " | " << fmt("%.2f", r.random.tests_per_ray) << " | "
       << r.disagreements() << " | " << r.ties() << " | "
       << (r.tree_depth < 0 ? std::string("-")
                            : std::to_string(r.tree_nodes) + " (" + std::to_string(r.tree_depth) + ")")
       << " |\n";
  }
  bool any_bvh = false;
  for (const StructureCompareRow& r : c.rows) any_bvh |= std::isfinite(r.sah_cost);
  if (any_bvh) {
    md << "\nBounding volume hierarchies: the SAH cost predicts the cost of a random line through the root (t_t "
          "per node, t_i = "
       << fmt("%g", t_i)
       << " per primitive test); EPO (end-point overlap) the cost of boxes around surface points whose "
          "subtree lacks the triangle; measured: t_t steps + t_i tests per ray.\n\n"
       << "| structure | SAH cost (predicted) | EPO | measured cost/ray camera | measured cost/ray random |\n"
       << "|---|---:|---:|---:|---:|\n";
    for (const StructureCompareRow& r : c.rows)
      if (std::isfinite(r.sah_cost))
        md << "| " << r.name << " | " << fmt("%.1f", r.sah_cost) << " | " << fmt("%.2f", r.epo) << " | "
           << fmt("%.1f", cost_per_ray(r.camera)) << " | " << fmt("%.1f", cost_per_ray(r.random)) << " |\n";
  }
  std::string subset_only;
  for (const StructureCompareRow& r : c.rows)
    if (r.camera.rays < c.camera_rays || r.random.rays < c.random_rays)
      subset_only += (subset_only.empty() ? "" : ", ") + r.name;
  if (!subset_only.empty())
    md << "\nTraced on the checked rays only (all rays would take more than "
       << fmt("%.3g", double(options.test_budget)) << " primitive tests): " << subset_only
       << "; their Mrays/s and work per ray are over those rays.\n";
  write_file_atomically(folder.file("report.md"), [&](std::ostream& out) { out << md.str(); });

  // Plots: speed, and the work per ray, one bar pair per structure, on log axes (brute force is orders of
  // magnitude apart from the trees).
  const std::string common =
      "set datafile separator ','\nset style data histograms\nset style histogram clustered gap 1\n"
      "set style fill solid 0.85 border -1\nset boxwidth 0.9\nset key top left\nset grid ytics\n"
      "set logscale y\nset xtics nomirror\n";
  report_plot(folder, "speed",
              common +
                  "set title 'Rays per second, one thread (higher is better)'\n"
                  "set ylabel 'million rays per second (log scale)'\nset xlabel 'structure'\n"
                  "plot 'report.csv' every ::1 using 5:xtic(1) title 'camera rays' lc rgb '#1f77b4', "
                  "'' every ::1 using 6 title 'random rays' lc rgb '#ff7f0e'\n");
  // Tests and steps are different units of work: two panels. Brute force walks no structure, so it has no
  // bar in the right one.
  report_plot(folder, "work",
              common +
                  "set multiplot layout 1,2 title 'Work per ray (lower is better)'\n"
                  "set title 'ray-primitive tests per ray'\nset ylabel 'tests per ray (log scale)'\n"
                  "set xlabel 'structure'\n"
                  "plot 'report.csv' every ::1 using 9:xtic(1) title 'camera rays' lc rgb '#1f77b4', "
                  "'' every ::1 using 10 title 'random rays' lc rgb '#ff7f0e'\n"
                  "set title 'steps per ray: boxes entered (bvol), cells (grid), nodes (kd)'\n"
                  "set ylabel 'steps per ray (log scale)'\n"
                  "plot 'report.csv' every ::1 using ($7>0?$7:1/0):xtic(1) title 'camera rays' lc rgb "
                  "'#1f77b4', '' every ::1 using ($8>0?$8:1/0) title 'random rays' lc rgb '#ff7f0e'\n"
                  "unset multiplot\n",
              1200, 560);
  // Predicted against measured: each BVH a point (its SAH cost, its measured cost per ray), named.
  if (any_bvh)
    report_plot(folder, "predicted_vs_measured",
                "set datafile separator ','\nset key top left\nset grid\n"
                "set title 'BVHs: the SAH cost against the measured cost of a ray'\n"
                "set xlabel 'SAH cost of the tree (predicted, random lines through the root)'\n"
                "set ylabel 'measured t_t steps + t_i tests per ray'\nset offsets graph 0.1, graph 0.25, "
                "graph 0.1, graph 0.1\n"
                "plot 'report.csv' every ::1 using ($18==$18?$18:1/0):21 with points pt 7 ps 1.5 lc rgb "
                "'#ff7f0e' title 'random rays', "
                "'' every ::1 using ($18==$18?$18:1/0):20 with points pt 5 ps 1.5 lc rgb '#1f77b4' title "
                "'camera rays', "
                "'' every ::1 using ($18==$18?$18:1/0):21:1 with labels offset 0,1 font ',9' notitle\n");
  folder.commit();
  std::printf("%s", md.str().c_str());
  uint64_t bad = 0;
  for (const StructureCompareRow& r : c.rows) bad += r.disagreements();
  std::printf("\nwrote %s (report.csv, report.md, speed.png, work.png%s)\n", a.output.c_str(),
              any_bvh ? ", predicted_vs_measured.png" : "");
  if (bad > 0) std::printf("WARNING: %" PRIu64 " disagreements with brute force\n", bad);
  return 0;
}

// ---- grid-sweep ----

int run_grid_sweep_command(const GridSweepArgs& a) {
  ReportFolder folder(a.output);
  GridSweepOptions options;
  if (a.densities) {
    // In increasing order, each once: the rows are a curve against d.
    options.densities = parse_densities(*a.densities);
    std::sort(options.densities.begin(), options.densities.end());
    options.densities.erase(std::unique(options.densities.begin(), options.densities.end()),
                            options.densities.end());
  }
  if (a.rays > (uint64_t(1) << 26)) throw InputError("", 0, "--rays must be at most 67108864");
  options.random_rays = a.rays;
  if (a.reps < 1 || a.reps > 1000) throw InputError("", 0, "--reps must be 1..1000");
  options.reps = a.reps;
  if (a.size) parse_size(*a.size, &options.camera_width, &options.camera_height);
  Scene scene = load_scene(a.scene);

  GridSweep sweep;
  {
    Progress progress("grid-sweep");
    const size_t total = options.densities.empty() ? 9 : options.densities.size();
    size_t done = 0;
    progress(0.0);
    sweep = run_grid_sweep(scene, options,
                           [&](const GridSweepRow&) { progress(double(++done) / double(total)); });
  }

  write_file_atomically(folder.file("report.csv"), [&](std::ostream& out) {
    out << "density,nx,ny,nz,cells,references_per_prim,bytes,build_ms,cells_per_ray,tests_per_ray,"
           "mailbox_per_ray,trace_ms,mrays_per_s,coarsened\n";
    char buf[400];
    for (const GridSweepRow& r : sweep.rows) {
      std::snprintf(buf, sizeof buf, "%g,%d,%d,%d,%" PRIu64 ",%.4f,%.0f,%.4f,%.4f,%.4f,%.4f,%.4f,%.5g,%d\n",
                    double(r.density), r.resolution[0], r.resolution[1], r.resolution[2], r.cells,
                    r.references_per_prim, r.bytes, r.build_seconds * 1e3, r.cells_per_ray, r.tests_per_ray,
                    r.mailbox_per_ray, r.trace_seconds * 1e3, r.mrays_per_second, r.coarsened ? 1 : 0);
      out << buf;
    }
  });

  // The fastest density, to set the rule's d = 3 against.
  size_t best = 0;
  for (size_t i = 1; i < sweep.rows.size(); ++i)
    if (sweep.rows[i].trace_seconds < sweep.rows[best].trace_seconds) best = i;
  const GridSweepRow* rule = nullptr;
  for (const GridSweepRow& r : sweep.rows)
    if (r.density == 3.f) rule = &r;

  std::ostringstream md;
  md << "# Grid density sweep: " << a.scene << "\n\n"
     << sweep.primitives << " primitives, " << sweep.rays
     << " rays (camera and random); max(nx, ny, nz) = d * cbrt(n); one thread, median of " << options.reps
     << " passes.\n\n"
     << "| d | resolution | cells | refs/prim | memory | build ms | cells/ray | tests/ray | mailbox/ray "
        "| "
        "trace ms | Mrays/s |\n"
     << "|---:|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  for (const GridSweepRow& r : sweep.rows) {
    md << "| " << fmt("%g", r.density) << " | " << r.resolution[0] << "x" << r.resolution[1] << "x"
       << r.resolution[2] << (r.coarsened ? " (coarsened)" : "") << " | " << r.cells << " | "
       << fmt("%.2f", r.references_per_prim) << " | " << human_bytes(r.bytes) << " | "
       << fmt("%.2f", r.build_seconds * 1e3) << " | " << fmt("%.2f", r.cells_per_ray) << " | "
       << fmt("%.2f", r.tests_per_ray) << " | " << fmt("%.2f", r.mailbox_per_ray) << " | "
       << fmt("%.2f", r.trace_seconds * 1e3) << " | " << fmt("%.3g", r.mrays_per_second) << " |\n";
  }
  if (!sweep.rows.empty()) {
    md << "\nFastest trace: d = " << fmt("%g", sweep.rows[best].density) << " ("
       << fmt("%.2f", sweep.rows[best].trace_seconds * 1e3) << " ms).";
    if (rule)
      md << " The rule's default d = 3: " << fmt("%.2f", rule->trace_seconds * 1e3) << " ms, "
         << fmt("%.2f", rule->trace_seconds / sweep.rows[best].trace_seconds) << "x the fastest.";
    md << "\n";
  }
  write_file_atomically(folder.file("report.md"), [&](std::ostream& out) { out << md.str(); });

  // One figure, four panels sharing the log x axis of d, each with the default d = 3 marked.
  std::ostringstream gp;
  // The x axis spans the densities measured and the default d = 3, with a tic at each.
  float d_lo = 3.f, d_hi = 3.f;
  std::string tics = "'3' 3";
  for (const GridSweepRow& r : sweep.rows) {
    d_lo = std::min(d_lo, r.density);
    d_hi = std::max(d_hi, r.density);
    if (r.density != 3.f) tics += ", '" + fmt("%g", r.density) + "' " + fmt("%g", r.density);
  }
  gp << "set datafile separator ','\nset logscale x 2\nset xrange [" << fmt("%g", d_lo * 0.8) << ":"
     << fmt("%g", d_hi * 1.25) << "]\nset grid\nset key top left\nset xtics (" << tics
     << ")\n"
        "set multiplot layout 2,2 title 'Uniform grid: max(nx,ny,nz) = d * cbrt(n), n = "
     << sweep.primitives << ", " << sweep.rays << " rays; dashed line: the default d = 3'\n"
     << "mark = \"set arrow 1 from 3, graph 0 to 3, graph 1 nohead dt 2 lw 2 lc rgb '#d62728'\"\n"
     << "set xlabel 'd (log scale)'\n"
        "@mark\nset title 'Cells walked per ray (grows with d)'\nset ylabel 'cells per ray'\n"
        "plot 'report.csv' using 1:9 with linespoints pt 7 lw 2 notitle\n"
        "set key top right\nset logscale y\nset title 'Primitive tests per ray (falls with d)'\nset ylabel "
        "'per ray (log scale)'\n"
        "plot 'report.csv' using 1:10 with linespoints pt 7 lw 2 title 'tests', '' using 1:11 with "
        "linespoints "
        "pt 6 lw 1 title 'tests skipped by the mailbox'\n"
        "unset logscale y\nset title 'References per primitive (memory grows with d)'\n"
        "set ylabel 'references per primitive'\n"
        "plot 'report.csv' using 1:6 with linespoints pt 7 lw 2 notitle\n"
        "set key bottom right\nset logscale y\nset title 'Time, one thread (the circle: the fastest trace)'\n"
        "set ylabel 'milliseconds (log scale)'\n"
        "plot 'report.csv' using 1:12 with linespoints pt 7 lw 2 title 'trace', '' using 1:8 with "
        "linespoints "
        "pt 5 lw 1 title 'build'\n"
        "unset multiplot\n";
  std::string script = gp.str();
  if (!sweep.rows.empty()) {
    // The fastest density circled in the time panel (the last one).
    const std::string circle = "set object 2 circle at " + fmt("%g", sweep.rows[best].density) + "," +
                               fmt("%g", sweep.rows[best].trace_seconds * 1e3) +
                               " size screen 0.012 fc rgb '#d62728' lw 2 front\n";
    script.insert(script.rfind("plot 'report.csv' using 1:12"), circle);
  }
  report_plot(folder, "sweep", script, 1200, 900);
  folder.commit();
  std::printf("%s", md.str().c_str());
  std::printf("\nwrote %s (report.csv, report.md, sweep.png)\n", a.output.c_str());
  return 0;
}

// ---- cost ----

int run_cost(const CostArgs& a) {
  std::optional<ReportFolder> folder;
  if (!a.output.empty()) folder.emplace(a.output);
  CostReportOptions options;
  if (a.size) parse_size(*a.size, &options.width, &options.height);
  if (a.aa) options.aa = parse_antialiasing(*a.aa);
  if (a.accel) {
    options.structures = parse_names("--accel", *a.accel);
    for (const std::string& name : options.structures) {
      try {
        make_accelerator(name, options.build);
      } catch (const InputError& e) {
        throw InputError("", 0, "--accel: " + e.detail());
      }
    }
  }
  if (a.threads < 0 || a.threads > 256) throw InputError("", 0, "--threads must be 0..256 (0: all cores)");
  options.threads = a.threads;
  Scene scene = load_scene(a.scene);

  CostReport r;
  {
    Progress progress("cost");
    CostReportHooks hooks;
    hooks.progress = [&](double f) { progress(f); };
    progress(0.0);
    r = run_cost_report(scene, options, hooks);
  }

  std::ostringstream t;
  t << "The lecture's cost formula, m^2 k^2 n 2^d ray-primitive tests, with real numbers\n"
    << "scene: " << a.scene << "\n"
    << "  m^2 = " << r.width << " x " << r.height << " = " << r.pixels << " pixels\n"
    << "  k^2 = " << fmt("%g", r.samples_per_pixel) << " samples per pixel (aa " << r.aa << ")\n"
    << "  n   = " << r.primitives << " primitives\n"
    << "  d   = " << r.depth << " (ray-tree depth), L = " << r.lights << " lights\n"
    << "predicted m^2 k^2 n 2^d                  = " << fmt("%.4g", r.predicted) << " tests\n"
    << "bound m^2 k^2 n (2^(d+1) - 1)(1 + L)     = " << fmt("%.4g", r.bound)
    << " tests (every ray of a full ray tree, and a shadow ray per light at each hit)\n\n";
  char line[400];
  std::snprintf(line, sizeof line, "%-52s %10s %10s %10s %14s %10s %10s %9s\n", "render", "samples/px",
                "rays/sample", "rays", "tests", "tests/ray", "of formula", "time s");
  t << line;
  for (const CostRow& row : r.rows) {
    std::snprintf(line, sizeof line, "%-52s %10.2f %10.2f %10" PRIu64 " %14" PRIu64 " %10.2f %9.2f%% %9.3f\n",
                  row.label.c_str(), row.samples_per_pixel, row.rays_per_sample, row.rays.total(), row.tests,
                  row.tests_per_ray, r.predicted > 0 ? 100.0 * double(row.tests) / r.predicted : 0.0,
                  row.seconds);
    t << line;
  }
  t << "\n";
  std::snprintf(line, sizeof line, "%-60s %-5s %-34s %10s %10s %9s\n", "technique", "cuts", "measured as",
                "before", "after", "cut");
  t << line;
  for (const CostFactor& f : r.factors) {
    std::snprintf(line, sizeof line, "%-60s %-5s %-34s %10.3f %10.3f %8.2fx\n", f.technique.c_str(),
                  f.factor.c_str(), f.measure.c_str(), f.before, f.after, f.cut());
    t << line;
  }
  // What a student asks next: why the counts fall short of the formula, and why a cut may be 1x.
  if (!r.rows.empty() && r.rows[0].rays.primary > 0) {
    const CostRow& full = r.rows[0];
    const double primary = double(full.rays.primary);
    const double tree = double(full.rays.primary + full.rays.reflected + full.rays.refracted) / primary;
    const double shadow = double(full.rays.shadow) / primary;
    t << "\nwhy brute force makes "
      << fmt("%.2f%%", r.predicted > 0 ? 100.0 * double(full.tests) / r.predicted : 0)
      << " of the formula's tests:\n  a sample's ray tree has " << fmt("%.2f", tree)
      << " rays, not 2^d = " << fmt("%.0f", std::ldexp(1.0, r.depth))
      << ": the formula lets every hit spawn a reflected and a refracted ray,\n"
         "  but only mirror and glass materials do; add "
      << fmt("%.2f", shadow) << " shadow rays per sample, which stop at their first hit.\n";
    if (!r.factors.empty() && r.factors[0].cut() < 1.005)
      t << "  adaptive termination cuts nothing here: no path's weight (the product of the mirror and\n"
           "  transparency factors along it) fell below min_weight before the depth limit.\n";
  }
  std::printf("%s", t.str().c_str());

  if (folder) {
    write_file_atomically(folder->file("report.csv"), [&](std::ostream& out) {
      out << "render,accel,aa,min_weight,samples_per_pixel,rays_per_sample,primary,shadow,reflected,"
             "refracted,"
             "tests,tests_per_ray,fraction_of_formula,seconds,predicted,bound\n";
      char buf[512];
      for (const CostRow& row : r.rows) {
        std::snprintf(buf, sizeof buf,
                      "\"%s\",%s,%s,%g,%.4f,%.4f,%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64 ",%" PRIu64
                      ",%.4f,%.6g,%.4f,%.17g,%.17g\n",
                      row.label.c_str(), row.accel.c_str(), row.aa.c_str(), double(row.min_weight),
                      row.samples_per_pixel, row.rays_per_sample, row.rays.primary, row.rays.shadow,
                      row.rays.reflected, row.rays.refracted, row.tests, row.tests_per_ray,
                      r.predicted > 0 ? double(row.tests) / r.predicted : 0.0, row.seconds, r.predicted,
                      r.bound);
        out << buf;
      }
    });
    // The printed tables and their explanation, as the terminal showed them.
    write_file_atomically(folder->file("report.txt"), [&](std::ostream& out) { out << t.str(); });
    write_file_atomically(folder->file("factors.csv"), [&](std::ostream& out) {
      out << "technique,factor,measure,before,after,cut\n";
      for (const CostFactor& f : r.factors)
        out << "\"" << f.technique << "\"," << f.factor << ",\"" << f.measure << "\"," << f.before << ","
            << f.after << "," << f.cut() << "\n";
    });
    std::ostringstream md;
    md << "# The cost formula with real numbers: " << a.scene << "\n\n"
       << "m^2 = " << r.pixels << " pixels (" << r.width << "x" << r.height
       << "), k^2 = " << fmt("%g", r.samples_per_pixel) << " samples per pixel (" << r.aa
       << "), n = " << r.primitives << " primitives, d = " << r.depth << ", L = " << r.lights
       << " lights.\n\n"
       << "Predicted m^2 k^2 n 2^d = " << fmt("%.4g", r.predicted)
       << " tests; strict bound m^2 k^2 n (2^(d+1) - 1)(1 + L) = " << fmt("%.4g", r.bound) << ".\n\n"
       << "| render | samples/px | rays/sample | rays | tests | tests/ray | of formula | time s |\n"
       << "|---|---:|---:|---:|---:|---:|---:|---:|\n";
    for (const CostRow& row : r.rows)
      md << "| " << row.label << " | " << fmt("%.2f", row.samples_per_pixel) << " | "
         << fmt("%.2f", row.rays_per_sample) << " | " << row.rays.total() << " | " << row.tests << " | "
         << fmt("%.2f", row.tests_per_ray) << " | "
         << fmt("%.2f%%", r.predicted > 0 ? 100.0 * double(row.tests) / r.predicted : 0.0) << " | "
         << fmt("%.3f", row.seconds) << " |\n";
    md << "\n| technique | cuts | measured as | before | after | cut |\n|---|---|---|---:|---:|---:|\n";
    for (const CostFactor& f : r.factors)
      md << "| " << f.technique << " | " << f.factor << " | " << f.measure << " | " << fmt("%.3f", f.before)
         << " | " << fmt("%.3f", f.after) << " | " << fmt("%.2fx", f.cut()) << " |\n";
    write_file_atomically(folder->file("report.md"), [&](std::ostream& out) { out << md.str(); });
    folder->commit();
    std::printf("\nwrote %s (report.csv, factors.csv, report.md, report.txt)\n", a.output.c_str());
  }
  return 0;
}

}  // namespace raystep::cli
