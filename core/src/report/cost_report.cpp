#include "raystep/report/cost_report.h"

#include <algorithm>
#include <cmath>

#include "raystep/render/antialiasing.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

// Counts every query's primitive tests and passes it on. Only the cost report renders through it, so the
// normal renderer keeps its uninstrumented kernels; the counts are summed atomically across render threads.
class CountingAccelerator final : public Accelerator {
 public:
  explicit CountingAccelerator(const Accelerator& inner) : inner_(inner) {}
  std::string name() const override { return inner_.name(); }
  void build(const Geometry&) override {}
  bool intersect(const Ray& ray, Hit* hit) const override {
    CountingRecorder c;
    bool found = inner_.intersect_counted(ray, hit, c);
    add(c);
    return found;
  }
  bool occluded(const Ray& ray) const override {
    CountingRecorder c;
    bool found = inner_.occluded_counted(ray, c);
    add(c);
    return found;
  }
  bool intersect_counted(const Ray& ray, Hit* hit, CountingRecorder& counters) const override {
    CountingRecorder c;
    bool found = inner_.intersect_counted(ray, hit, c);
    add(c);
    counters.rays += c.rays;
    counters.cells += c.cells;
    counters.nodes += c.nodes;
    counters.prim_tests += c.prim_tests;
    counters.prim_hits += c.prim_hits;
    counters.mailbox_hits += c.mailbox_hits;
    return found;
  }
  uint64_t tests() const { return tests_.load(); }

 private:
  void add(const CountingRecorder& c) const { tests_.fetch_add(c.prim_tests, std::memory_order_relaxed); }

  const Accelerator& inner_;
  mutable std::atomic<uint64_t> tests_{0};
};

// The adaptive pattern compared with a k x k one: its finest lattice at least as fine (2^D >= k).
AntiAliasing adaptive_like(int k) {
  AntiAliasing a;
  a.mode = AntiAliasing::Mode::adaptive;
  a.threshold = 0.1f;
  int depth = 1;
  while ((1 << depth) < k && depth < 6) ++depth;
  a.max_depth = depth;
  return a;
}

}  // namespace

CostReport run_cost_report(const Scene& scene_in, const CostReportOptions& options,
                           const CostReportHooks& hooks) {
  std::vector<std::string> names = options.structures;
  if (names.empty())
    for (const std::string& n : accelerator_names())
      if (n != "brute") names.push_back(n);
  for (const std::string& n : names)
    make_accelerator(n, options.build);  // unknown names fail before any render

  // A copy whose adaptive-termination threshold the report sets per render; the structures are built over it.
  Scene scene = scene_in;
  RenderOptions render = render_options(scene.render);
  if (options.width > 0) render.width = options.width;
  if (options.height > 0) render.height = options.height;
  if (options.aa) render.aa = *options.aa;
  render.threads = options.threads;
  render.progress = false;
  validate(render.aa);

  CostReport report;
  report.scene_path = scene.path;
  report.width = render.width;
  report.height = render.height;
  report.pixels = uint64_t(render.width) * uint64_t(render.height);
  report.samples_per_pixel = max_samples_per_pixel(render.aa);
  report.aa = to_string(render.aa);
  report.primitives = scene.geometry.size();
  report.depth = scene.render.max_depth;
  report.lights = int(scene.lights.size());
  const double m2k2n = double(report.pixels) * report.samples_per_pixel * double(report.primitives);
  report.predicted = m2k2n * std::ldexp(1.0, report.depth);
  report.bound = m2k2n * (std::ldexp(1.0, report.depth + 1) - 1.0) * (1.0 + report.lights);

  // Adaptive termination's threshold: the scene's, or the default when the scene turns it off.
  const float min_weight =
      scene.render.min_weight > 0.f ? scene.render.min_weight : RenderSettings{}.min_weight;
  // The adaptive-sampling comparison: the scene's adaptive pattern against its own full refinement, or an
  // adaptive pattern as fine as the k x k one (k = 4 when the pattern is not a k x k grid).
  const bool aa_adaptive = render.aa.mode == AntiAliasing::Mode::adaptive;
  const bool aa_grid =
      render.aa.mode == AntiAliasing::Mode::regular || render.aa.mode == AntiAliasing::Mode::jitter;
  const int k_compared = aa_grid && render.aa.k >= 2 ? render.aa.k : 4;
  const AntiAliasing adaptive = adaptive_like(k_compared);

  const double renders = 2.0 + double(names.size()) + (aa_adaptive ? 0.0 : 1.0);
  auto cancelled = [&] { return hooks.cancel && hooks.cancel->load(); };
  auto run = [&](const std::string& label, const std::string& accel_name, float weight,
                 const AntiAliasing& aa) -> const CostRow* {
    if (cancelled()) return nullptr;
    scene.render.min_weight = weight;
    std::unique_ptr<Accelerator> accel = make_accelerator(accel_name, options.build);
    accel->build(scene.geometry);
    CountingAccelerator counting(*accel);
    RenderOptions o = render;
    o.aa = aa;
    RenderResult r = render_image(scene, counting, o);
    CostRow row;
    row.label = label;
    row.accel = accel_name;
    row.aa = to_string(aa);
    row.min_weight = weight;
    row.rays = r.rays;
    row.samples_per_pixel = double(r.rays.primary) / double(report.pixels);
    row.rays_per_sample = r.rays.primary ? double(r.rays.total()) / double(r.rays.primary) : 0.0;
    row.tests = counting.tests();
    row.tests_per_ray = r.rays.total() ? double(row.tests) / double(r.rays.total()) : 0.0;
    row.seconds = r.seconds;
    report.rows.push_back(row);
    if (hooks.row_done) hooks.row_done(report.rows.back());
    if (hooks.progress) hooks.progress(double(report.rows.size()) / renders);
    return &report.rows.back();
  };

  // Brute force with the full ray tree, then with adaptive termination: the 2^d factor.
  char weight_text[32];
  std::snprintf(weight_text, sizeof weight_text, "%g", double(min_weight));
  if (!run("brute force, no adaptive termination", "brute", 0.f, render.aa)) return report;
  if (!run(std::string("brute force, adaptive termination (min_weight ") + weight_text + ")", "brute",
           min_weight, render.aa))
    return report;
  const CostRow full = report.rows[0], terminated = report.rows[1];
  // The ray tree's size without its shadow rays: the formula's 2^d counts reflected and refracted rays.
  auto tree_rays = [](const CostRow& row) {
    return row.rays.primary
               ? double(row.rays.primary + row.rays.reflected + row.rays.refracted) / double(row.rays.primary)
               : 0.0;
  };
  report.factors.push_back(
      {"adaptive ray termination", "2^d",
       "ray-tree rays per sample (2^d = " + std::to_string(1ull << std::min(report.depth, 62)) + ")",
       tree_rays(full), tree_rays(terminated)});

  // Each structure, with adaptive termination: the n factor.
  for (const std::string& name : names) {
    const CostRow* row = run(name + ", adaptive termination", name, min_weight, render.aa);
    if (!row) return report;
    report.factors.push_back(
        {"acceleration: " + name, "n", "tests per ray", terminated.tests_per_ray, row->tests_per_ray});
  }

  // Adaptive sampling: the k^2 factor.
  const std::string sampler_accel = names.empty() ? std::string("brute") : names.front();
  if (aa_adaptive) {
    report.factors.push_back({"adaptive sampling (" + report.aa + ") vs. full refinement", "k^2",
                              "samples per pixel", double(max_samples_per_pixel(render.aa)),
                              terminated.samples_per_pixel});
  } else {
    const CostRow* row = run("adaptive sampling " + to_string(adaptive) + ", " + sampler_accel, sampler_accel,
                             min_weight, adaptive);
    if (!row) return report;
    report.factors.push_back({"adaptive sampling (" + row->aa + ") vs. regular:" + std::to_string(k_compared),
                              "k^2", "samples per pixel", double(k_compared * k_compared),
                              row->samples_per_pixel});
  }
  return report;
}

}  // namespace raystep
