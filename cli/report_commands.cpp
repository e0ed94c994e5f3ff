// `raystep aa-report`: speed against error for every anti-aliasing method, written as a folder of CSV,
// Markdown, PFM images and gnuplot plots (see commands.h).
#include <unistd.h>

#include <algorithm>
#include <cinttypes>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <iomanip>
#include <map>
#include <regex>
#include <sstream>

#include "commands.h"
#include "plot.h"
#include "raystep/accel/structure_options.h"
#include "raystep/render/antialiasing.h"
#include "raystep/report/aa_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/io/scene_loader.h"
#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"

namespace raystep::cli {
namespace {

namespace fs = std::filesystem;

// The theory at edges (Mitchell 1996), by method: the exponent of N in RMSE ~ N^slope.
// One colour per method, the same in both plots and for the method's theory line.
std::string method_colour(const std::string& method) {
  if (method == "regular") return "#1b9e77";
  if (method == "jitter") return "#d95f02";
  if (method == "random") return "#7570b3";
  if (method == "adaptive") return "#e7298a";
  return "#000000";
}

std::string theory_text(const std::string& method) {
  if (const size_t plus = method.find("+tent"); plus != std::string::npos)
    return "as " + method.substr(0, plus) + " (the tent weighs the same samples), against the tent's reference";
  if (method == "jitter") return "-3/4 (stratified samples on an edge)";
  if (method == "regular")
    return "-1/2 for edges along the grid (the estimate moves in steps of 1/k); about -1 for slanted edges "
           "(the k columns' rounding errors cancel)";
  if (method == "random") return "-1/2 (Monte Carlo)";
  if (method == "adaptive") return "none: the samples go where the contrast is";
  return "";
}

std::vector<std::string> split_list(const std::string& list) {
  std::vector<std::string> out;
  std::stringstream ss(list);
  std::string item;
  while (std::getline(ss, item, ',')) out.push_back(item);
  if (!list.empty() && list.back() == ',') out.push_back("");
  return out;
}

// "WxH" with 1 <= W, H <= 16384 (as `render --size`).
void parse_report_size(const std::string& spec, int* w, int* h) {
  static const std::regex re("([0-9]{1,5})x([0-9]{1,5})");
  std::smatch m;
  if (std::regex_match(spec, m, re)) {
    const int ww = std::stoi(m[1]), hh = std::stoi(m[2]);
    if (ww >= 1 && hh >= 1 && ww <= 16384 && hh <= 16384) {
      *w = ww;
      *h = hh;
      return;
    }
  }
  throw InputError("", 0, "--size '" + spec + "': expected WxH with 1 <= W, H <= 16384");
}

std::string fmt(double v, int digits = 6) {
  if (!std::isfinite(v)) return "nan";
  char buf[64];
  std::snprintf(buf, sizeof buf, "%.*g", digits, v);
  return buf;
}

// A progress bar on stderr, only when stderr is a terminal; redrawn at most every percent.
class ReportProgress {
 public:
  ReportProgress() : enabled_(::isatty(STDERR_FILENO) != 0) {}
  ~ReportProgress() { finish(); }
  void update(double f, const std::string& what) {
    if (!enabled_) return;
    const int percent = int(f * 100.0);
    if (percent == last_ && what == what_) return;
    last_ = percent;
    what_ = what;
    const int kWidth = 40, filled = int(f * kWidth);
    std::fprintf(stderr, "\r\033[K[%.*s%*s] %3d%% %s", filled,
                 "========================================", kWidth - filled, "", percent, what.c_str());
    std::fflush(stderr);
    drawn_ = true;
  }
  void finish() {
    if (drawn_) std::fprintf(stderr, "\r\033[K");
    drawn_ = false;
  }

 private:
  bool enabled_;
  bool drawn_ = false;
  int last_ = -1;
  std::string what_;
};

const AaReportRow* find_row(const AaReport& r, const std::string& spec) {
  for (const AaReportRow& row : r.rows)
    if (row.spec == spec) return &row;
  return nullptr;
}

void write_csv(const std::string& path, const AaReport& r) {
  const double pixels = double(r.width) * double(r.height);
  write_file_atomically(path, [&](std::ostream& out) {
    out << "method,spec,samples_per_pixel,rays_primary,rays_shadow,rays_reflected,rays_refracted,rays_total,"
           "rays_per_pixel,seconds,rmse,rmse_min,rmse_max,rmse_stddev,max_error,seeds,images\n";
    for (const AaReportRow& row : r.rows) {
      std::string images;
      for (const std::string& name : row.images) images += (images.empty() ? "" : ";") + ("images/" + name);
      out << row.method << ',' << row.spec << ',' << fmt(row.rays_per_pixel, 9) << ',' << row.rays.primary
          << ',' << row.rays.shadow << ',' << row.rays.reflected << ',' << row.rays.refracted << ','
          << row.rays.total() << ',' << fmt(double(row.rays.total()) / pixels, 9) << ','
          << fmt(row.seconds, 6) << ',' << fmt(row.rmse, 9) << ',' << fmt(row.rmse_min, 9) << ','
          << fmt(row.rmse_max, 9) << ',' << fmt(row.rmse_stddev, 9) << ',' << fmt(row.max_error, 9) << ','
          << row.seeds << ',' << images << '\n';
    }
  });
}

// Whether adaptive sampling reaches jitter:4's RMSE with at most 35% of its rays (the goal), and if
// not, what comes closest and why.
std::string adaptive_verdict(const AaReport& r) {
  std::ostringstream s;
  const AaReportRow* j4 = find_row(r, "jitter:4");
  std::vector<const AaReportRow*> adaptive;
  for (const AaReportRow& row : r.rows)
    if (row.method == "adaptive") adaptive.push_back(&row);
  if (!j4 || adaptive.empty()) {
    s << "No verdict: it needs jitter:4 and at least one adaptive method among the methods.\n";
    return s.str();
  }
  const double budget = 0.35 * double(j4->rays.total());
  s << "Goal: an adaptive method with RMSE <= jitter:4's (" << fmt(j4->rmse, 4)
    << ") on at most 35% of its rays (" << fmt(budget / (double(r.width) * r.height), 3)
    << " rays per pixel).\n\n";
  const AaReportRow* best = nullptr;  // the cheapest that reaches the error
  for (const AaReportRow* a : adaptive)
    if (a->rmse <= j4->rmse && (!best || a->rays.total() < best->rays.total())) best = a;
  if (best && double(best->rays.total()) <= budget) {
    s << "**Reached** by " << best->spec << ": RMSE " << fmt(best->rmse, 4) << " with "
      << fmt(100.0 * double(best->rays.total()) / double(j4->rays.total()), 3) << "% of jitter:4's rays ("
      << fmt(best->rays_per_pixel, 3) << " per pixel against 16).\n";
    return s.str();
  }
  const double pixels = double(r.width) * double(r.height);
  const double floor_share = 5.0 / j4->rays_per_pixel;  // every pixel's 4 corners and centre
  s << "**Not reached** at " << r.width << " x " << r.height << ". ";
  if (best)
    s << "The cheapest adaptive method as accurate as jitter:4, " << best->spec << " (RMSE "
      << fmt(best->rmse, 4) << "), casts "
      << fmt(100.0 * double(best->rays.total()) / double(j4->rays.total()), 3)
      << "% of its rays: " << fmt(best->rays_per_pixel, 3) << " per pixel, of which "
      << fmt(best->rays_per_pixel - 5.0, 3) << " go to refining edge pixels. ";
  const AaReportRow* closest = nullptr;  // the most accurate within the budget
  for (const AaReportRow* a : adaptive)
    if (double(a->rays.total()) <= budget && (!closest || a->rmse < closest->rmse)) closest = a;
  if (closest)
    s << "Within the budget the most accurate is " << closest->spec << " (RMSE " << fmt(closest->rmse, 4)
      << ", " << fmt(closest->rays_per_pixel, 3)
      << " rays per pixel): its edge pixels are estimated on too coarse a "
      << "lattice. ";
  s << "Why: every pixel costs adaptive sampling at least 5 rays (4 corners and the centre), "
    << fmt(100.0 * floor_share, 3) << "% of jitter:4's, which leaves "
    << fmt(std::max(0.0, budget / pixels - 5.0), 2)
    << " rays per pixel, averaged over the image, for the pixels an edge crosses. At this size the edge "
       "pixels "
       "are too large a share of the image for that. "
    << "What would: the same scene at a finer size (edge pixels are a share that halves each time the "
       "resolution doubles, while the 5-ray floor stays), or adaptive sampling that shares corner samples "
       "between neighbouring pixels (a flat pixel would then cost about 2 rays instead of 5).\n";
  return s.str();
}

// Adaptive rows at one depth whose pictures are the same whatever the threshold: the scene is black and
// white.
std::string same_thresholds(const AaReport& r) {
  std::map<std::pair<int, std::pair<double, double>>, std::vector<std::string>> groups;
  for (const AaReportRow& row : r.rows)
    if (row.method == "adaptive")
      groups[{parse_antialiasing(row.spec).max_depth, {row.rays_per_pixel, row.rmse}}].push_back(row.spec);
  std::string s;
  for (const auto& [key, specs] : groups) {
    if (specs.size() < 2) continue;
    s += "\n" + std::to_string(specs.size()) + " thresholds at depth " + std::to_string(key.first) +
         " gave the same picture (";
    for (size_t i = 0; i < specs.size(); ++i) s += (i ? ", " : "") + specs[i];
    s += "): where every pixel is one of two colours, the contrast (max - min) / (max + min) of its samples "
         "is "
         "0 or 1, so any threshold below 1 refines the same pixels; only the depth changes the cost.\n";
  }
  return s;
}

void write_markdown(const std::string& path, const AaReport& r, const std::string& command) {
  write_file_atomically(path, [&](std::ostream& out) {
    out << "# Anti-aliasing: error against rays and time\n\n";
    out << "Scene `" << r.scene_path << "`, " << r.width << " x " << r.height << " pixels. Command: `"
        << command << "`\n\n";
    out << "Reference: ";
    if (r.reference_kind == "exact")
      out << "**exact** area coverage (flat-coloured triangles seen orthographically: each pixel is the "
             "background plus each triangle's colour times the area it covers), so the errors below are the "
             "methods' own";
    else
      out << "**" << r.reference_kind
          << "**, the mean of two renders with independent seeds; its own RMSE is "
          << "estimated at " << fmt(r.reference_rmse, 3)
          << " (half the RMS difference of the two), so errors much below that are not resolved";
    out << " (" << fmt(r.reference_seconds, 3) << " s). Images: `images/` (PFM, linear).\n\n";
    for (size_t i = 1; i < r.references.size(); ++i)
      out << "The methods with the tent filter (`+tent`: sampling and pre-filtering combined, each sample "
             "weighed by (1 - |dx|)(1 - |dy|) from the pixel's centre, the neighbours' samples too) are "
             "measured against the scene pre-filtered by the same tent: **"
          << r.references[i].kind << "**"
          << (r.references[i].rmse > 0.0 ? ", its own RMSE estimated at " + fmt(r.references[i].rmse, 3) : "")
          << " (" << fmt(r.references[i].seconds, 3) << " s).\n\n";
    out << "RMSE over the three channels of every pixel, against the reference; for jitter and random the "
           "mean "
           "over seeds 1..N with its spread (min..max). Max error: the largest pixel error (mean over "
           "seeds). "
           "Seconds: median wall time of one render.";
    std::vector<double> times;
    for (const AaReportRow& row : r.rows) times.push_back(row.seconds);
    std::sort(times.begin(), times.end());
    if (!times.empty() && times[times.size() / 2] < 0.01)
      out << " Most renders here take under 10 ms, where starting the threads weighs as much as tracing: for "
             "times that mean something, use a larger `--size`.";
    out << "\n\n";
    out << "| method | spec | samples per pixel N | rays: primary | shadow | reflected | refracted | seconds "
           "| "
           "RMSE | "
           "spread (min..max) | max error | seeds |\n";
    out << "|---|---|---:|---:|---:|---:|---:|---:|---:|---|---:|---:|\n";
    for (const AaReportRow& row : r.rows)
      out << "| " << row.method << " | " << row.spec << " | " << fmt(row.rays_per_pixel, 4) << " | "
          << row.rays.primary << " | " << row.rays.shadow << " | " << row.rays.reflected << " | "
          << row.rays.refracted << " | " << fmt(row.seconds, 3) << " | " << fmt(row.rmse, 4) << " | "
          << (row.seeds > 1 ? fmt(row.rmse_min, 3) + "..." + fmt(row.rmse_max, 3) : std::string("-")) << " | "
          << fmt(row.max_error, 3) << " | " << row.seeds << " |\n";
    out << "\n## Slopes: RMSE ~ N^slope\n\n"
        << "Least-squares fit of log(RMSE) against log(N), N the samples (primary rays) per pixel, over each "
           "method's sample "
           "counts.\n\n| method | fitted slope | theory at edges |\n|---|---:|---|\n";
    for (const auto& [method, slope] : r.slopes)
      out << "| " << method << " | " << fmt(slope, 3) << " | " << theory_text(method) << " |\n";
    out << "\n## Adaptive sampling against jitter:4\n\n" << adaptive_verdict(r) << same_thresholds(r);
    out << "\n## Plots\n\n![error against rays](error_vs_rays.png)\n\n![error against "
           "time](error_vs_time.png)\n\n"
        << "Each plot is drawn by gnuplot from `report.csv` with the script beside it (`gnuplot "
           "error_vs_rays.gp` "
           "in this folder draws it again).\n";
  });
}

// One gnuplot script: RMSE against column x_col of report.csv, one line per method with the seeds' spread
// as error bars, and the theory's slopes as dashed lines through a measured point.
std::string plot_body(const AaReport& r, bool against_time) {
  std::vector<std::string> methods;
  for (const AaReportRow& row : r.rows)
    if (std::find(methods.begin(), methods.end(), row.method) == methods.end()) methods.push_back(row.method);
  // CSV columns: 3 samples_per_pixel, 10 seconds, 11 rmse, 12 rmse_min, 13 rmse_max.
  const int x_col = against_time ? 10 : 3;
  auto x_of = [&](const AaReportRow& row) { return against_time ? row.seconds : row.rays_per_pixel; };
  double x_lo = INFINITY, x_hi = 0, y_lo = INFINITY, y_hi = 0;
  for (const AaReportRow& row : r.rows) {
    if (x_of(row) > 0) {
      x_lo = std::min(x_lo, x_of(row));
      x_hi = std::max(x_hi, x_of(row));
    }
    if (row.rmse_min > 0) y_lo = std::min(y_lo, row.rmse_min);
    y_hi = std::max(y_hi, row.rmse_max);
  }
  std::ostringstream s;
  s << "# RMSE against " << (against_time ? "render time" : "rays per pixel")
    << ", from report.csv (columns: 3 samples_per_pixel, 10 seconds, 11 rmse, 12 rmse_min, 13 rmse_max).\n"
    << "set datafile separator ','\n"
    << "set logscale xy\n"
    << "set grid xtics ytics mxtics mytics lc rgb '#dddddd'\n"
    // Every curve falls from left to right: the top right corner stays free for the key (the y range is
    // raised so that the data fill the lower 70% of the plot).
    << "set key inside top right box opaque samplen 3 title \"error bars: spread over seeds (min..max)\\n"
       "dashed: the theory at edges\"\n"
    << "set title \"" << (against_time ? "Error against render time" : "Error against rays") << " — "
    << fs::path(r.scene_path).filename().string() << ", " << r.width << "x" << r.height << ", reference "
    << r.reference_kind << "\"\n";
  if (against_time)
    s << "set xlabel 'wall time of one render (seconds, log scale)'\n";
  else
    s << "set xlabel 'samples per pixel N = primary rays per pixel (log scale)'\n";
  s << "set ylabel 'RMSE against the reference (log scale)'\n";
  if (x_hi > 0) s << "set xrange [" << fmt(x_lo / 1.5) << ":" << fmt(x_hi * 1.5) << "]\n";
  if (y_hi > 0) {
    const double lo = y_lo / 1.6, hi = y_hi * 1.3;
    s << "set yrange [" << fmt(lo) << ":" << fmt(lo * std::pow(hi / lo, 1.0 / 0.7)) << "]\n";
  }
  // Each theory line is drawn in its method's colour through that method's first measured point, so that
  // where the theory holds the line lies along the measurements and the two slopes are compared at a glance.
  struct Theory {
    const char* method;
    double slope;
    const char* label;
    const char* dash;
  };
  const Theory theories[] = {{"random", -0.5, "^-1/2 (random)", "2"},
                             {"jitter", -0.75, "^-3/4 (jitter)", "3"},
                             {"regular", -1.0, "^-1 (regular, slanted edges)", "4"}};
  std::vector<std::string> items;
  for (const std::string& m : methods)
    items.push_back("'report.csv' every ::1 using (strcol(1) eq '" + m + "' ? $" + std::to_string(x_col) +
                    " : NaN):11:12:13 with yerrorlines lw 2 pt 7 ps 0.8 lc rgb '" + method_colour(m) +
                    "' title '" + m + "'");
  const std::string var = against_time ? "t" : "N";
  for (const Theory& t : theories) {
    const AaReportRow* anchor = nullptr;
    for (const AaReportRow& row : r.rows)
      if (row.method == t.method && x_of(row) > 0 && row.rmse > 0 &&
          (!anchor || row.rays_per_pixel < anchor->rays_per_pixel))
        anchor = &row;
    if (!anchor) continue;
    items.push_back(fmt(anchor->rmse, 9) + " * (x / " + fmt(x_of(*anchor), 9) + ")**(" + fmt(t.slope) +
                    ") with lines dt " + t.dash + " lw 1.5 lc rgb '" + method_colour(t.method) +
                    "' title 'theory " + var + t.label + ", through " + anchor->spec + "'");
  }
  // Adaptive points are labelled by depth, once per depth at its first point ("depth 3, T 0.4 → 0.02": the
  // line runs from the first threshold to the last): the student cannot tell them apart otherwise, and a
  // label per point overlaps its neighbours.
  std::vector<std::pair<const AaReportRow*, std::vector<float>>> labels;  // first row, thresholds in order
  for (const AaReportRow& row : r.rows) {
    if (row.method != "adaptive") continue;
    const AntiAliasing aa = parse_antialiasing(row.spec);
    auto same_depth = std::find_if(labels.begin(), labels.end(), [&](const auto& l) {
      return parse_antialiasing(l.first->spec).max_depth == aa.max_depth;
    });
    if (same_depth != labels.end())
      same_depth->second.push_back(aa.threshold);
    else
      labels.push_back({&row, {aa.threshold}});
  }
  for (const auto& [row, thresholds] : labels) {
    std::string text = "depth " + std::to_string(parse_antialiasing(row->spec).max_depth) + ", threshold " +
                       fmt(thresholds.front(), 3);
    if (thresholds.size() > 1) text += " → " + fmt(thresholds.back(), 3);
    s << "set label '" << text << "' at " << fmt(x_of(*row), 9) << "," << fmt(row->rmse, 9)
      << " offset -1,-0.9 right font ',9' tc rgb '" << method_colour("adaptive") << "'\n";
  }
  s << "plot \\\n";
  for (size_t i = 0; i < items.size(); ++i) s << "  " << items[i] << (i + 1 < items.size() ? ", \\\n" : "\n");
  if (items.empty()) s << "  NaN notitle\n";
  return s.str();
}

// Replace DIR by the finished folder: rename the old one aside, the new one in, then delete the old one.
void replace_folder(const fs::path& temp, const fs::path& dir) {
  std::error_code ec;
  fs::path old;
  if (fs::exists(dir)) {
    if (!fs::is_directory(dir)) throw InputError(dir.string(), 0, "cannot write the report: not a folder");
    old = dir.string() + ".old." + std::to_string(::getpid());
    fs::rename(dir, old, ec);
    if (ec) throw InputError(dir.string(), 0, "cannot replace the folder: " + ec.message());
  }
  fs::rename(temp, dir, ec);
  if (ec) {
    if (!old.empty()) fs::rename(old, dir);
    throw InputError(dir.string(), 0, "cannot write the report: " + ec.message());
  }
  if (!old.empty()) fs::remove_all(old, ec);
}

// Removes the temporary folder unless the report was moved into place (and, on Ctrl-C, the signal handler
// removes it: TemporaryFolderOnSignal).
struct TempFolder {
  fs::path path;
  bool keep = false;
  TemporaryFolderOnSignal on_signal{path.string()};
  ~TempFolder() {
    std::error_code ec;
    if (!keep) fs::remove_all(path, ec);
  }
};

}  // namespace

int run_aa_report(const AaReportArgs& a) {
  // Every option checked before the scene is loaded or anything rendered.
  AaReportOptions options;
  if (a.methods) {
    options.methods = split_list(*a.methods);
    if (options.methods.empty()) throw InputError("", 0, "--methods: the list is empty");
    for (const std::string& spec : options.methods) {
      try {
        validate(parse_antialiasing(spec));
      } catch (const InputError& e) {
        throw InputError("", 0, "--methods: " + e.detail());
      }
    }
  }
  options.reference = a.reference;
  if (a.reference != "exact" && a.reference != "auto") {
    bool ok = a.reference.rfind("jitter:", 0) == 0;
    if (ok) {
      try {
        validate(parse_antialiasing(a.reference));
      } catch (const InputError&) {
        ok = false;
      }
    }
    if (!ok) throw InputError("", 0, "--reference '" + a.reference + "': expected exact, jitter:K or auto");
  }
  if (a.size) parse_report_size(*a.size, &options.width, &options.height);
  if (a.seeds < 1 || a.seeds > 1000) throw InputError("", 0, "--seeds must be 1..1000");
  if (a.threads < 0 || a.threads > 256) throw InputError("", 0, "--threads must be 0..256 (0: all cores)");
  options.seeds = a.seeds;
  options.threads = a.threads;
  const fs::path dir = fs::path(a.output).lexically_normal();
  if (dir.empty() || dir.filename().empty() || dir.filename() == "." || dir.filename() == "..")
    throw InputError(a.output, 0, "-o: expected a folder name");
  const fs::path parent = fs::absolute(dir).parent_path();
  if (!fs::is_directory(parent))
    throw InputError(a.output, 0, "cannot write: folder '" + parent.string() + "' does not exist");
  if (fs::exists(dir) && !fs::is_directory(dir)) throw InputError(a.output, 0, "exists and is not a folder");

  Scene scene = load_scene(a.scene);
  if (options.width == 0) {
    options.width = scene.render.width;
    options.height = scene.render.height;
  }
  if (a.reference == "exact")
    if (std::string why = exact_coverage_unavailable(scene, options.width, options.height); !why.empty())
      throw InputError("", 0, "--reference exact: " + why + "; use --reference jitter:K or auto");
  std::unique_ptr<Accelerator> accel;
  try {
    accel = make_accelerator(a.accel, StructureOptions{});
  } catch (const InputError& e) {
    throw InputError("", 0, "--accel: " + e.detail());
  }
  accel->build(scene.geometry);

  // Absolute: gnuplot runs with the report folder as its working directory.
  TempFolder temp{fs::absolute(dir).string() + ".tmp." + std::to_string(::getpid())};
  fs::remove_all(temp.path);
  fs::create_directories(temp.path / "images");

  ReportProgress bar;
  std::string current = "reference";
  AaReportHooks hooks;
  hooks.image_dir = (temp.path / "images").string();
  hooks.progress = [&](double f) { bar.update(f, current); };
  hooks.row_done = [&](const AaReport&, const AaReportRow& row) { current = "after " + row.spec; };
  const AaReport report = raystep::run_aa_report(scene, *accel, options, hooks);
  bar.finish();

  std::ostringstream command;
  command << "raystep aa-report " << a.scene;
  if (a.methods) command << " --methods " << *a.methods;
  command << " --reference " << a.reference << " --size " << report.width << "x" << report.height
          << " --seeds " << a.seeds << " -o " << a.output;
  write_csv((temp.path / "report.csv").string(), report);
  write_markdown((temp.path / "report.md").string(), report, command.str());
  std::vector<std::string> plot_notes;
  for (const bool against_time : {false, true}) {
    const std::string name = against_time ? "error_vs_time" : "error_vs_rays";
    const PlotResult p = plot_png(temp.path.string(), name, plot_body(report, against_time), 960, 760);
    if (!p.drawn) plot_notes.push_back(p.message);
  }
  replace_folder(temp.path, dir);
  temp.keep = true;

  std::printf("aa-report: %s, %dx%d, reference %s", report.scene_path.c_str(), report.width, report.height,
              report.reference_kind.c_str());
  if (report.reference_kind != "exact") std::printf(" (its own RMSE about %.3g)", report.reference_rmse);
  for (size_t i = 1; i < report.references.size(); ++i)
    std::printf("; +tent against %s", report.references[i].kind.c_str());
  std::printf("\n%-18s %10s %10s %12s %10s\n", "method", "rays/px", "seconds", "rmse", "max err");
  for (const AaReportRow& row : report.rows)
    std::printf("%-18s %10.3f %10.4f %12.6f %10.4f\n", row.spec.c_str(), row.rays_per_pixel, row.seconds,
                row.rmse, row.max_error);
  for (const auto& [method, slope] : report.slopes)
    std::printf("slope %-9s %6.3f (theory %s)\n", method.c_str(), slope, theory_text(method).c_str());
  for (const std::string& note : plot_notes) std::printf("plots: %s\n", note.c_str());
  std::printf("wrote %s/ (report.csv, report.md, images/, plots)\n", dir.string().c_str());
  return 0;
}

}  // namespace raystep::cli
