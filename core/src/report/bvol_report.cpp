#include "raystep/report/bvol_report.h"

#include <algorithm>
#include <filesystem>
#include <iomanip>
#include <sstream>

#include "camera_size.h"
#include "raystep/accel/bounding_volumes.h"
#include "raystep/accel/brute_force.h"
#include "raystep/render/camera.h"
#include "raystep/util/error.h"
#include "timing.h"

namespace raystep {

using report_timing::Clock;
using report_timing::median;
using report_timing::seconds_since;

std::vector<BvolReportRow> run_bvol_report(const Scene& scene, const BvolReportOptions& options) {
  if (options.reps < 1 || options.reps > 100)
    throw InputError("", 0, "bvol-report: --reps must be in 1..100");
  if (options.camera_width > 4096 || options.camera_height > 4096)
    throw InputError("", 0, "bvol-report: --size at most 4096x4096");
  if (scene.geometry.size() == 0) throw InputError(scene.path, 0, "the scene has no primitives");
  int w = options.camera_width, h = options.camera_height;
  report_camera_size(scene, 160, &w, &h);
  const std::vector<Ray> rays = camera_rays(scene.camera, w, h);
  BruteForce brute;
  brute.build(scene.geometry);
  std::vector<Hit> reference(rays.size());
  for (size_t i = 0; i < rays.size(); ++i) brute.intersect(rays[i], &reference[i]);

  std::vector<BvolReportRow> rows;
  const double n = double(std::max<size_t>(rays.size(), 1));
  for (const std::string& kind : bvol_kind_names()) {
    BvolReportRow row;
    row.scene = std::filesystem::path(scene.path).filename().string();
    row.kind = kind;
    row.objects = scene.geometry.objects().size();
    row.primitives = scene.geometry.size();
    row.rays = rays.size();
    BoundingVolumes bvol(*parse_bvol_kind(kind));
    std::vector<double> builds;
    for (int r = 0; r < options.reps; ++r) {
      auto t0 = Clock::now();
      bvol.build(scene.geometry);
      builds.push_back(seconds_since(t0));
    }
    row.build_seconds = median(builds);
    // Counted pass (and the check against brute force), then reps uninstrumented timed passes.
    CountingRecorder c;
    for (size_t i = 0; i < rays.size(); ++i) {
      Hit hit;
      bvol.intersect_counted(rays[i], &hit, c);
      row.disagreements += hit.prim != reference[i].prim || hit.t != reference[i].t;
    }
    row.volume_tests_per_ray = double(c.volume_tests) / n;
    row.volume_hits_per_ray = double(c.volume_hits) / n;
    row.entered_per_ray = double(c.nodes) / n;
    row.false_positives_per_ray = double(c.volume_false_positives) / n;
    row.false_positive_rate = c.nodes ? double(c.volume_false_positives) / double(c.nodes) : 0.0;
    row.prim_tests_per_ray = double(c.prim_tests) / n;
    std::vector<double> passes;
    for (int r = 0; r < options.reps; ++r) {
      auto t0 = Clock::now();
      for (const Ray& ray : rays) {
        Hit hit;
        bvol.intersect(ray, &hit);
      }
      passes.push_back(seconds_since(t0));
    }
    row.ns_per_ray = median(passes) * 1e9 / n;
    rows.push_back(row);
  }
  return rows;
}

std::string bvol_report_csv(const std::vector<BvolReportRow>& rows) {
  std::ostringstream out;
  out << "scene,kind,objects,primitives,rays,build_ms,volume_tests_per_ray,volume_hits_per_ray,"
         "entered_per_ray,false_positives_per_ray,false_positive_rate,prim_tests_per_ray,ns_per_ray,"
         "disagreements\n";
  out << std::setprecision(6);
  for (const BvolReportRow& r : rows)
    out << r.scene << ',' << r.kind << ',' << r.objects << ',' << r.primitives << ',' << r.rays << ','
        << r.build_seconds * 1e3 << ',' << r.volume_tests_per_ray << ',' << r.volume_hits_per_ray << ','
        << r.entered_per_ray << ',' << r.false_positives_per_ray << ',' << r.false_positive_rate << ','
        << r.prim_tests_per_ray << ',' << r.ns_per_ray << ',' << r.disagreements << '\n';
  return out.str();
}

std::string bvol_report_markdown(const std::vector<BvolReportRow>& rows) {
  std::ostringstream out;
  out << "| scene | kind | objects | prims | volume tests/ray | entered/ray | false pos./ray | false-pos. "
         "rate | "
         "prim tests/ray | build ms | ns/ray | disagreements |\n"
         "|---|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|\n";
  out << std::fixed;
  for (const BvolReportRow& r : rows) {
    out << "| " << r.scene << " | " << r.kind << " | " << r.objects << " | " << r.primitives << " | "
        << std::setprecision(1) << r.volume_tests_per_ray << " | " << std::setprecision(2)
        << r.entered_per_ray << " | " << r.false_positives_per_ray << " | " << std::setprecision(1)
        << 100.0 * r.false_positive_rate << "% | " << r.prim_tests_per_ray << " | " << std::setprecision(3)
        << r.build_seconds * 1e3 << " | " << std::setprecision(0) << r.ns_per_ray << " | " << r.disagreements
        << " |\n";
  }
  return out.str();
}

}  // namespace raystep
