// The lecture's first half in its own picture: a 2D scene's polygon on the pixel grid, three panels side by
// side in the plane. Sampled: each pixel's value as the renderer computes it with the anti-aliasing given
// (regular, jittered, random or adaptive supersampling, the very samples of render/pixel_samples.h through the
// real camera, tracer and structure), its samples drawn inside it (white where they see the polygon). Exact:
// each pixel's pre-filtered value, the area of the polygon inside it (render/reference.h). Error: sampled
// minus exact per pixel, red above and blue below. The caption gives the mean and largest error.
#pragma once

#include <string>

#include "raystep/accel/accelerator.h"
#include "raystep/figure/figure.h"
#include "raystep/render/antialiasing.h"
#include "raystep/scene/scene.h"

namespace raystep {

struct FlatAaInput {
  const Scene* scene = nullptr;        // a 2D scene (scene->flat)
  const Accelerator* accel = nullptr;  // built over scene->geometry
  AntiAliasing aa;
  int width = 0, height = 0;  // the picture's pixels (0: the scene's render size)
  bool column = false;        // the panels one above the other (a tall view), not side by side
};

struct FlatAa {
  Figure figure;
  int pixels = 0;
  bool exact = false;  // false: the scene has no exact reference (why_not says why); no exact and error panels
  std::string why_not;
  double mean_abs_error = 0.0, max_abs_error = 0.0;  // over the pixels, the grey values in [0, 1]
  size_t samples = 0;                                // cast in all
};

// The most pixels the figure draws (its SVG stays a slide's size).
constexpr int kFlatAaMaxPixels = 4096;

// Throws InputError("", 0, ...) for a 3D scene, settings out of range or more than kFlatAaMaxPixels pixels.
FlatAa flat_aa_figure(const FlatAaInput& input);

}  // namespace raystep
