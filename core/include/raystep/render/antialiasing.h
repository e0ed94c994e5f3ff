// Anti-aliasing by supersampling (the lecture's sampling slides), each pattern box-filtered over the pixel here
// (the tent filter, render/pixel_filter.h, weighs the same samples in render_image and sample_pixel):
// one sample at the centre; a regular k x k grid; jittered (stratified) k x k (Cook 1986), whose error on an
// edge falls as N^-3/4 against N^-1/2 for N uniform random samples (Mitchell 1996); and adaptive
// supersampling (Whitted 1980): sample a square at its corners and centre, and where the samples' contrast
// (max - min) / (max + min) exceeds the threshold in some channel, split it into quadrants, recursively.
#pragma once

#include <cstdint>
#include <functional>

#include <glm/vec3.hpp>

#include "raystep/util/random.h"
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
// adaptive max_depth outside [0, 6], threshold negative or NaN, the tent filter with adaptive sampling.
void validate(const AntiAliasing& aa);
constexpr uint32_t kMaxSamplesPerPixel = 1u << 14;
// The largest number of samples the settings can spend on one pixel.
uint32_t max_samples_per_pixel(const AntiAliasing& aa);

// Estimates pixel (x, y), covering [x, x+1) x [y, y+1), with the settings' pattern; jitter and random draw
// from rng in a fixed order (regular, none and adaptive are deterministic). Adaptive samples the pixel's
// corners and centre (5 samples on a flat pixel) and refines by contrast down to max_depth.
// The box filter's estimate whatever aa.filter says: the tent needs the neighbours' samples too.
PixelEstimate estimate_pixel(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance);

// Casts pixel (x, y)'s samples exactly as estimate_pixel does (same order, same random numbers) and tells each
// to `sample` with its position and radiance; returns how many were cast.
using SampleFn = std::function<void(float px, float py, const glm::vec3& colour)>;
uint32_t cast_pixel_samples(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance,
                            const SampleFn& sample);

// The adaptive scheme's refinement test: contrast (max - min) / (max + min) above threshold in any channel
// (a channel with max + min = 0, black everywhere, has no contrast).
bool contrast_exceeds(const glm::vec3* values, int n, float threshold);

}  // namespace raystep
