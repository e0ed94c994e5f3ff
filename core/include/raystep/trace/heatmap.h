// Heat maps of traversal work: one primary ray through each pixel's centre, counted by a CountingRecorder
// (cells or nodes visited, primitive tests, mailbox hits, or BVH box tests), shown on a perceptual colour ramp
// with a colour bar beside the image. The picture of where a structure spends its effort; and, from a render,
// where anti-aliasing spent its samples (adaptive sampling's rays per pixel).
#pragma once

#include <cstdint>
#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/render/antialiasing.h"
#include "raystep/render/image.h"
#include "raystep/scene/scene.h"

namespace raystep {

enum class HeatQuantity { cells, tests, mailbox, samples, error, boxes };

// "cells" (cells or tree nodes visited, BVH nodes included), "tests" (ray-primitive tests), "mailbox" (tests
// skipped by mailboxes), "boxes" (bounding-box tests: a BVH's child boxes, its root's included), "samples"
// (primary rays per pixel under the picture's anti-aliasing: from a render, not a traversal), "error".
HeatQuantity parse_heat_quantity(const std::string& name);  // throws InputError for another name
const char* heat_quantity_label(HeatQuantity q);

struct HeatMap {
  int width = 0, height = 0;
  HeatQuantity quantity = HeatQuantity::cells;
  std::vector<uint32_t> values;  // row-major, y = 0 at the top
  double unit = 1.0;             // a value v stands for v * unit (error: thousandths, unit 1e-3)
  uint32_t max_value = 0;
  double mean_value = 0.0;
};

// Parallel over rows (threads 0: all cores); the same values whatever the thread count. Traversal quantities
// only: throws InputError("", 0, ...) for samples, which a render counts (samples_heatmap).
HeatMap compute_heatmap(const Camera& camera, const Accelerator& accel, int width, int height, HeatQuantity q,
                        int threads);

// The samples map of a render (RenderResult::samples, row-major width x height) as a heat map of samples.
HeatMap samples_heatmap(const std::vector<uint32_t>& samples, int width, int height);

// The per-pixel error of a picture against its reference (render/reference.h pixel_errors), in thousandths.
HeatMap error_heatmap(const std::vector<float>& errors, int width, int height);

// The map of quantity q over the scene's picture at width x height, as the debugger's image view shows it: a
// traversal quantity through `accel` (compute_heatmap), the samples a render with `aa` cast per pixel, or its
// error against the exact picture pre-filtered with aa's own filter (throws InputError("", 0, why) when the
// scene has no exact reference).
HeatMap scene_heatmap(const Scene& scene, const Accelerator& accel, const AntiAliasing& aa, int width, int height,
                      HeatQuantity q, int threads);

// The map on the colour ramp (0 .. max_value), with a colour bar (bottom 0, top max) in a strip on the right.
Image heatmap_image(const HeatMap& heat);

}  // namespace raystep
