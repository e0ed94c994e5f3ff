#include "raystep/report/aa_report.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>

#include "raystep/io/image_io.h"
#include "raystep/render/antialiasing.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

constexpr int kMaxSeeds = 1000;
// Deterministic methods give the same picture every time; they are rendered this many times (at most the
// seed count) only so that their time is a median like the random methods', not one noisy measurement.
constexpr int kTimingRuns = 3;

const char* method_name(AntiAliasing::Mode mode) {
  switch (mode) {
    case AntiAliasing::Mode::none:
      return "none";
    case AntiAliasing::Mode::regular:
      return "regular";
    case AntiAliasing::Mode::jitter:
      return "jitter";
    case AntiAliasing::Mode::random:
      return "random";
    case AntiAliasing::Mode::adaptive:
      return "adaptive";
  }
  return "?";
}

// The method's name in the rows and the slopes: the pattern, "+tent" for the tent filter's.
std::string method_of(const AntiAliasing& aa) {
  return std::string(method_name(aa.mode)) + (aa.filter == AntiAliasing::Filter::tent ? "+tent" : "");
}

bool is_random(const AntiAliasing& aa) {
  return aa.mode == AntiAliasing::Mode::jitter || aa.mode == AntiAliasing::Mode::random;
}

// Rough primary rays per pixel, only to weigh the renders in the progress fraction.
double expected_samples(const AntiAliasing& aa) {
  switch (aa.mode) {
    case AntiAliasing::Mode::none:
      return 1.0;
    case AntiAliasing::Mode::regular:
    case AntiAliasing::Mode::jitter:
      return double(aa.k) * double(aa.k);
    case AntiAliasing::Mode::random:
      return double(aa.k);
    case AntiAliasing::Mode::adaptive:
      return 8.0;  // 5 on flat pixels, more on edges
  }
  return 1.0;
}

// "jitter:4" -> "jitter-4", "adaptive:0.1:3" -> "adaptive-0.1-3": a file name without the colon.
std::string file_stem(const std::string& spec) {
  std::string s = spec;
  std::replace(s.begin(), s.end(), ':', '-');
  return s;
}

double median(std::vector<double> v) {
  std::sort(v.begin(), v.end());
  const size_t n = v.size();
  return n == 0 ? 0.0 : n % 2 ? v[n / 2] : 0.5 * (v[n / 2 - 1] + v[n / 2]);
}

}  // namespace

std::vector<std::string> default_aa_methods() {
  std::vector<std::string> m = {"none"};
  for (int k = 2; k <= 8; ++k) m.push_back("regular:" + std::to_string(k));
  for (int k = 2; k <= 8; ++k) m.push_back("jitter:" + std::to_string(k));
  for (int n = 4; n <= 64; n *= 2) m.push_back("random:" + std::to_string(n));
  // Depth sets the finest lattice an edge pixel is refined to (and its cost); the threshold, how much
  // contrast triggers refinement. On a black-and-white scene every threshold below 1 refines the same pixels
  // (their contrast is 1 or 0), so depths 1 and 2 are there to show the trade-off on such a scene too.
  for (const char* s : {"adaptive:0.1:1", "adaptive:0.1:2", "adaptive:0.4:3", "adaptive:0.2:3",
                        "adaptive:0.1:3", "adaptive:0.05:3", "adaptive:0.02:3"})
    m.push_back(s);
  // Sampling and pre-filtering combined: the same samples weighed by the tent over the neighbours too.
  for (const char* s : {"regular:4+tent", "jitter:2+tent", "jitter:4+tent", "jitter:8+tent"}) m.push_back(s);
  return m;
}

std::vector<AntiAliasing> parse_aa_methods(const std::vector<std::string>& specs) {
  if (specs.empty()) throw InputError("", 0, "bad method list: it is empty");
  std::vector<AntiAliasing> out;
  for (const std::string& spec : specs) {
    try {
      out.push_back(parse_antialiasing(spec));
      validate(out.back());
    } catch (const InputError& e) {
      throw InputError("", 0, "bad method list: " + e.detail());
    }
  }
  return out;
}

double loglog_slope(const std::vector<double>& x, const std::vector<double>& y) {
  double sx = 0, sy = 0, sxx = 0, sxy = 0;
  int n = 0;
  for (size_t i = 0; i < std::min(x.size(), y.size()); ++i) {
    if (!(x[i] > 0.0) || !(y[i] > 0.0) || !std::isfinite(x[i]) || !std::isfinite(y[i])) continue;
    const double lx = std::log(x[i]), ly = std::log(y[i]);
    sx += lx;
    sy += ly;
    sxx += lx * lx;
    sxy += lx * ly;
    ++n;
  }
  const double denominator = n * sxx - sx * sx;
  if (n < 2 || !(std::fabs(denominator) > 1e-12 * std::max(1.0, n * sxx)))
    return std::numeric_limits<double>::quiet_NaN();
  return (n * sxy - sx * sy) / denominator;
}

AaReport run_aa_report(const Scene& scene, const Accelerator& accel, const AaReportOptions& options,
                       const AaReportHooks& hooks) {
  // Options first, all of them, before any render.
  const std::vector<std::string> specs = options.methods.empty() ? default_aa_methods() : options.methods;
  const std::vector<AntiAliasing> methods = parse_aa_methods(specs);
  if (options.width < 0 || options.height < 0 || (options.width == 0) != (options.height == 0))
    throw InputError("", 0, "bad size: width and height must both be positive (or both 0: the scene's size)");
  if (options.seeds < 1 || options.seeds > kMaxSeeds)
    throw InputError(
        "", 0,
        "bad seed count " + std::to_string(options.seeds) + ": expected 1.." + std::to_string(kMaxSeeds));
  if (options.threads < 0) throw InputError("", 0, "threads must be >= 0");
  const std::string& ref_spec = options.reference;
  if (ref_spec != "exact" && ref_spec != "auto" && ref_spec.rfind("jitter:", 0) != 0)
    throw InputError("", 0, "bad reference '" + ref_spec + "': expected exact, jitter:K (K >= 1) or auto");

  AaReport report;
  report.scene_path = scene.path;
  report.width = options.width > 0 ? options.width : scene.render.width;
  report.height = options.height > 0 ? options.height : scene.render.height;
  const double pixels = double(report.width) * double(report.height);

  // Progress: each render weighed by its expected rays.
  auto runs_of = [&](const AntiAliasing& aa) {
    return is_random(aa) ? options.seeds : std::min(kTimingRuns, options.seeds);
  };
  double total_work = 0.0, work_done = 0.0;
  for (const AntiAliasing& aa : methods) total_work += runs_of(aa) * expected_samples(aa);
  double reference_work = 1.0;
  if (ref_spec.rfind("jitter:", 0) == 0) {
    try {
      const AntiAliasing aa = parse_antialiasing(ref_spec);
      reference_work = 2.0 * expected_samples(aa);
    } catch (const InputError&) {
      // make_reference below says what is wrong with it
    }
  } else if (ref_spec == "auto" && !exact_coverage_unavailable(scene, report.width, report.height).empty()) {
    reference_work = 2.0 * 16.0 * 16.0;
  }
  std::vector<AntiAliasing::Filter> filters;  // the methods' filters, box first
  for (AntiAliasing::Filter f : {AntiAliasing::Filter::box, AntiAliasing::Filter::tent})
    for (const AntiAliasing& aa : methods)
      if (aa.filter == f) {
        filters.push_back(f);
        break;
      }
  total_work += reference_work * double(filters.size());
  auto progress = [&](double done) {
    if (hooks.progress) hooks.progress(std::min(1.0, done / total_work));
  };
  auto cancelled = [&] { return hooks.cancel && hooks.cancel->load(); };

  // The references, one per filter.
  std::vector<Image> reference_images;
  for (AntiAliasing::Filter filter : filters) {
    const double before = work_done;
    progress(work_done);
    const auto ref_start = std::chrono::steady_clock::now();
    Reference reference =
        make_reference(scene, accel, report.width, report.height, ref_spec, options.threads,
                       [&](double f) { progress(before + f * reference_work); }, filter);
    AaReference info;
    info.kind = reference.kind;
    info.rmse = reference.estimated_rmse;
    info.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - ref_start).count();
    report.references.push_back(info);
    work_done = before + reference_work;
    progress(work_done);
    if (!hooks.image_dir.empty())
      write_pfm(hooks.image_dir + (filter == AntiAliasing::Filter::tent ? "/reference-tent.pfm" : "/reference.pfm"),
                reference.image);
    reference_images.push_back(std::move(reference.image));
  }
  report.reference_kind = report.references[0].kind;
  report.reference_rmse = report.references[0].rmse;
  report.reference_seconds = report.references[0].seconds;
  auto reference_of = [&](const AntiAliasing& aa) -> size_t {
    return size_t(std::find(filters.begin(), filters.end(), aa.filter) - filters.begin());
  };

  // Every method over its seeds.
  for (size_t m = 0; m < methods.size() && !cancelled(); ++m) {
    const AntiAliasing& aa = methods[m];
    AaReportRow row;
    row.method = method_of(aa);
    row.spec = to_string(aa);
    const Image& reference = reference_images[reference_of(aa)];
    row.reference = report.references[reference_of(aa)].kind;
    const bool random = is_random(aa);
    const int runs = runs_of(aa);
    row.seeds = random ? runs : 1;
    RenderOptions o;
    o.aa = aa;
    o.width = report.width;
    o.height = report.height;
    o.threads = options.threads;
    std::vector<double> seconds, max_errors;
    double primary = 0, shadow = 0, reflected = 0, refracted = 0;
    bool complete = true;
    for (int run = 0; run < runs; ++run) {
      if (cancelled()) {
        complete = false;
        break;
      }
      o.seed = random ? uint64_t(run + 1) : 0;  // seeds 1..seeds; the renderer seeds each pixel from it
      const RenderResult r = render_image(scene, accel, o);
      seconds.push_back(r.seconds);
      work_done += expected_samples(aa);
      progress(work_done);
      if (!random && run > 0) continue;  // a deterministic method's repeat is only timed
      primary += double(r.rays.primary);
      shadow += double(r.rays.shadow);
      reflected += double(r.rays.reflected);
      refracted += double(r.rays.refracted);
      row.seed_rmse.push_back(rmse(r.image, reference));
      max_errors.push_back(max_abs_error(r.image, reference));
      if (!hooks.image_dir.empty()) {
        const std::string name =
            file_stem(row.spec) + (random ? "-seed" + std::to_string(o.seed) : "") + ".pfm";
        write_pfm(hooks.image_dir + "/" + name, r.image);
        row.images.push_back(name);
      }
    }
    if (!complete) break;  // a method without all its seeds would not compare with the others

    const double n = double(row.seed_rmse.size());
    row.rays.primary = uint64_t(std::llround(primary / n));
    row.rays.shadow = uint64_t(std::llround(shadow / n));
    row.rays.reflected = uint64_t(std::llround(reflected / n));
    row.rays.refracted = uint64_t(std::llround(refracted / n));
    row.rays_per_pixel = primary / n / pixels;
    row.seconds = median(seconds);
    double sum = 0.0, sum_max = 0.0;
    row.rmse_min = row.seed_rmse[0];
    row.rmse_max = row.seed_rmse[0];
    for (size_t i = 0; i < row.seed_rmse.size(); ++i) {
      sum += row.seed_rmse[i];
      sum_max += max_errors[i];
      row.rmse_min = std::min(row.rmse_min, row.seed_rmse[i]);
      row.rmse_max = std::max(row.rmse_max, row.seed_rmse[i]);
    }
    row.rmse = sum / n;
    row.max_error = sum_max / n;
    double var = 0.0;
    for (double e : row.seed_rmse) var += (e - row.rmse) * (e - row.rmse);
    row.rmse_stddev = row.seed_rmse.size() > 1 ? std::sqrt(var / (n - 1.0)) : 0.0;  // sample std deviation
    report.rows.push_back(row);
    if (hooks.row_done) hooks.row_done(report, report.rows.back());
  }

  // Slopes per method, in the order the methods first appear.
  std::vector<std::string> names;
  for (const AaReportRow& row : report.rows)
    if (std::find(names.begin(), names.end(), row.method) == names.end()) names.push_back(row.method);
  for (const std::string& name : names) {
    // Adaptive sampling's rays are an outcome of the scene and its settings, not a sample count it was given:
    // no theory gives it a slope, and a fit across depths and thresholds would mean nothing.
    if (name == "adaptive") continue;
    std::vector<double> x, y;
    for (const AaReportRow& row : report.rows)
      if (row.method == name) {
        x.push_back(row.rays_per_pixel);
        y.push_back(row.rmse);
      }
    const double slope = loglog_slope(x, y);
    if (std::isfinite(slope)) report.slopes.emplace_back(name, slope);
  }
  if (!cancelled()) progress(total_work);
  return report;
}

}  // namespace raystep
