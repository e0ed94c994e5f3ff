// The render loop: every pixel estimated with the anti-aliasing pattern (render/antialiasing.h) through the
// Whitted tracer (render/whitted.h), in parallel over rows with TBB. Each pixel draws its random numbers
// from its own stream (util/random.h), so the image is bit-identical whatever the thread count. With the
// tent filter (render/pixel_filter.h) each sample is shared among the pixels whose tents reach it, and the
// pixels of a one-pixel frame around the image cast their samples too, for the border pixels' tents.
#pragma once

#include <cstdint>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/render/image.h"
#include "raystep/render/whitted.h"
#include "raystep/scene/scene.h"

namespace raystep {

struct RenderOptions {
  AntiAliasing aa;
  int width = 320, height = 240;
  int threads = 0;        // 0: all cores
  uint64_t seed = 0;
  bool progress = false;  // a progress bar on stderr, if it is a terminal and the render takes over ~0.5 s
};

// The scene's own settings (size, anti-aliasing, seed).
RenderOptions render_options(const RenderSettings& settings);

struct RenderResult {
  Image image;
  std::vector<uint32_t> samples;  // primary rays per pixel (its own samples), row-major like the image
  RayCounts rays;
  double seconds = 0.0;           // wall-clock time of the render
};

// Throws InputError for options out of range (image size, anti-aliasing settings, threads < 0).
// The accelerator must be built over scene.geometry.
RenderResult render_image(const Scene& scene, const Accelerator& accel, const RenderOptions& options);

}  // namespace raystep
