#include "raystep/trace/heatmap.h"

#include <algorithm>
#include <cmath>

#include <tbb/blocked_range.h>
#include <tbb/parallel_for.h>
#include <tbb/task_arena.h>

#include "raystep/render/camera.h"
#include "raystep/render/reference.h"
#include "raystep/render/render.h"
#include "raystep/util/error.h"

namespace raystep {

HeatQuantity parse_heat_quantity(const std::string& name) {
  if (name == "cells" || name == "nodes") return HeatQuantity::cells;  // grid cells or tree nodes
  if (name == "tests") return HeatQuantity::tests;
  if (name == "mailbox") return HeatQuantity::mailbox;
  if (name == "samples") return HeatQuantity::samples;
  if (name == "error") return HeatQuantity::error;
  if (name == "boxes") return HeatQuantity::boxes;
  throw InputError(
      "", 0,
      "unknown heat map quantity '" + name + "' (cells or nodes, tests, mailbox, boxes, samples, error)");
}

const char* heat_quantity_label(HeatQuantity q) {
  switch (q) {
    case HeatQuantity::cells:
      return "cells or nodes visited";
    case HeatQuantity::tests:
      return "ray-primitive tests";
    case HeatQuantity::mailbox:
      return "mailbox hits (tests skipped)";
    case HeatQuantity::samples:
      return "samples (primary rays) per pixel";
    case HeatQuantity::error:
      return "error against the reference (thousandths)";
    case HeatQuantity::boxes:
      return "bounding-box tests";
  }
  return "";
}

namespace {

void finish_statistics(HeatMap& heat) {
  uint64_t sum = 0;
  heat.max_value = 0;
  for (uint32_t v : heat.values) {
    heat.max_value = std::max(heat.max_value, v);
    sum += v;
  }
  heat.mean_value = heat.values.empty() ? 0.0 : double(sum) / double(heat.values.size());
}

}  // namespace

HeatMap compute_heatmap(const Camera& camera, const Accelerator& accel, int width, int height, HeatQuantity q,
                        int threads) {
  if (q == HeatQuantity::samples)
    throw InputError("", 0, "the samples map comes from a render, not a traversal (samples_heatmap)");
  if (q == HeatQuantity::error)
    throw InputError("", 0,
                     "the error map compares a render with its reference, not a traversal (error_heatmap)");
  ProjectiveCamera cam(camera, width, height);
  HeatMap heat;
  heat.width = width;
  heat.height = height;
  heat.quantity = q;
  heat.values.assign(size_t(width) * height, 0);
  auto rows = [&](int y0, int y1) {
    for (int y = y0; y < y1; ++y)
      for (int x = 0; x < width; ++x) {
        CountingRecorder c;
        Hit hit;
        accel.intersect_counted(cam.generate(float(x) + 0.5f, float(y) + 0.5f), &hit, c);
        uint64_t v = q == HeatQuantity::cells   ? c.cells + c.nodes
                     : q == HeatQuantity::tests ? c.prim_tests
                     : q == HeatQuantity::boxes ? c.box_tests
                                                : c.mailbox_hits;
        heat.values[size_t(y) * width + x] = uint32_t(std::min<uint64_t>(v, UINT32_MAX));
      }
  };
  tbb::task_arena arena(threads > 0 ? threads : tbb::task_arena::automatic);
  arena.execute([&] {
    tbb::parallel_for(tbb::blocked_range<int>(0, height),
                      [&](const tbb::blocked_range<int>& r) { rows(r.begin(), r.end()); });
  });
  finish_statistics(heat);
  return heat;
}

HeatMap samples_heatmap(const std::vector<uint32_t>& samples, int width, int height) {
  if (width < 1 || height < 1 || samples.size() != size_t(width) * size_t(height))
    throw InputError("", 0,
                     "samples map: " + std::to_string(samples.size()) + " values for a " +
                         std::to_string(width) + "x" + std::to_string(height) + " picture");
  HeatMap heat;
  heat.width = width;
  heat.height = height;
  heat.quantity = HeatQuantity::samples;
  heat.values = samples;
  finish_statistics(heat);
  return heat;
}

HeatMap error_heatmap(const std::vector<float>& errors, int width, int height) {
  if (width < 1 || height < 1 || errors.size() != size_t(width) * size_t(height))
    throw InputError("", 0,
                     "error map: " + std::to_string(errors.size()) + " values for a " +
                         std::to_string(width) + "x" + std::to_string(height) + " picture");
  HeatMap heat;
  heat.width = width;
  heat.height = height;
  heat.quantity = HeatQuantity::error;
  heat.unit = 1e-3;
  heat.values.resize(errors.size());
  for (size_t i = 0; i < errors.size(); ++i) {
    // Thousandths, rounded; NaN (no value) as 0 and anything beyond the range clamped.
    const double v = std::isnan(errors[i]) ? 0.0 : std::round(double(errors[i]) * 1e3);
    heat.values[i] = uint32_t(std::clamp(v, 0.0, double(UINT32_MAX)));
  }
  finish_statistics(heat);
  return heat;
}

Image heatmap_image(const HeatMap& heat) {
  // The map, then a strip on the right: a gap and a vertical colour bar (bottom 0, top max_value).
  const int gap = std::max(2, heat.width / 64), bar = std::max(8, heat.width / 24);
  Image img;
  img.width = heat.width + 2 * gap + bar;
  img.height = heat.height;
  img.pixels.assign(size_t(img.width) * img.height, glm::vec3(0.02f));
  float scale = heat.max_value > 0 ? 1.f / float(heat.max_value) : 0.f;
  for (int y = 0; y < heat.height; ++y)
    for (int x = 0; x < heat.width; ++x)
      img.at(x, y) = viridis(float(heat.values[size_t(y) * heat.width + x]) * scale);
  const int margin = std::max(1, heat.height / 32);
  for (int y = margin; y < heat.height - margin; ++y) {
    float t = 1.f - float(y - margin) / float(std::max(1, heat.height - 2 * margin - 1));
    for (int x = heat.width + gap; x < heat.width + gap + bar; ++x) img.at(x, y) = viridis(t);
  }
  return img;
}

HeatMap scene_heatmap(const Scene& scene, const Accelerator& accel, const AntiAliasing& aa, int width, int height,
                      HeatQuantity q, int threads) {
  if (q != HeatQuantity::samples && q != HeatQuantity::error)
    return compute_heatmap(scene.camera, accel, width, height, q, threads);
  RenderOptions options = render_options(scene.render);
  options.aa = aa;
  options.width = width;
  options.height = height;
  options.threads = threads;
  const RenderResult r = render_image(scene, accel, options);
  if (q == HeatQuantity::samples) return samples_heatmap(r.samples, width, height);
  return error_heatmap(pixel_errors(r.image, render_exact_coverage(scene, width, height, aa.filter)), width, height);
}

}  // namespace raystep
