// Anti-aliasing by supersampling, every pattern box-filtered over the pixel (the lecture's sampling slides):
// one sample at the centre; a regular k x k grid; jittered (stratified) k x k (Cook 1986), whose error on an
// edge falls as N^-3/4 against N^-1/2 for N uniform random samples (Mitchell 1996); and adaptive
// supersampling (Whitted 1980): sample a square at its corners and centre, and where the samples' contrast
// (max - min) / (max + min) exceeds the threshold in some channel, split it into quadrants, recursively.
#pragma once

#include <cstdint>
#include <functional>

#include <glm/vec3.hpp>

#include "raystep/render/sampler.h"
#include "raystep/scene/scene.h"

namespace raystep {

// Radiance arriving through continuous raster position (px, py).
using RadianceFn = std::function<glm::vec3(float px, float py)>;

struct PixelEstimate {
  glm::vec3 value{0.f};  // box-filtered pixel value
  uint32_t samples = 0;  // primary rays (radiance calls) spent on the pixel
};

// Settings: regular and jitter take k x k samples, random takes N = k samples (k is the sample count there),
// adaptive uses threshold and max_depth.
// Throws InputError("", 0, ...) for settings out of range: k < 1, more than kMaxSamplesPerPixel samples,
// adaptive max_depth outside [0, 6], threshold negative or NaN.
void validate(const AntiAliasing& aa);
constexpr uint32_t kMaxSamplesPerPixel = 1u << 14;
// The largest number of samples the settings can spend on one pixel.
uint32_t max_samples_per_pixel(const AntiAliasing& aa);

// Estimates pixel (x, y), covering [x, x+1) x [y, y+1), with the settings' pattern; jitter and random draw
// from rng in a fixed order (regular, none and adaptive are deterministic). Adaptive samples the pixel's
// corners and centre (5 samples on a flat pixel) and refines by contrast down to max_depth.
PixelEstimate estimate_pixel(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance);

// The adaptive scheme's refinement test: contrast (max - min) / (max + min) above threshold in any channel
// (a channel with max + min = 0, black everywhere, has no contrast).
bool contrast_exceeds(const glm::vec3* values, int n, float threshold);

}  // namespace raystep
