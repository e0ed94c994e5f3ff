// One pixel's anti-aliasing, recorded: where each sample fell, what it saw, and, for adaptive sampling, the
// subdivision tree with the contrast measured at every square against the threshold. The pixel inspector
// and the trace's "pixel" section show it; the renderer runs the very same code with the recording off
// (estimate_pixel in render/antialiasing.h), so what the inspector shows is what the picture used.
#pragma once

#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

#include "raystep/render/antialiasing.h"
#include "raystep/util/random.h"

namespace raystep {

struct PixelSample {
  float px = 0.f, py = 0.f;      // continuous raster position (pixel (x, y) covers [x, x+1) x [y, y+1))
  glm::vec3 colour{0.f};         // the radiance the sample's primary ray brought back
  int stratum[2] = {-1, -1};     // regular, jitter: the cell (i, j) of the k x k lattice it lies in; else -1
  int lattice[2] = {-1, -1};     // adaptive: the lattice point (i, j), spacing 1 / 2^(max_depth+1); else -1
  float weight = 1.f;            // the filter's weight for the pixel's value (box: 1; tent: from the centre)
};

// One square of adaptive sampling, visited depth first (a square, then its four quadrants in the order
// (i0, j0), (i0+h, j0), (i0, j0+h), (i0+h, j0+h)).
struct AdaptiveSquare {
  int parent = -1;               // index in PixelSampling::squares; -1: the whole pixel
  int depth = 0;                 // 0: the whole pixel
  int i0 = 0, j0 = 0, size = 0;  // corner and side, in lattice steps
  int samples[5] = {0, 0, 0, 0, 0};  // indices into PixelSampling::samples: the four corners, then the centre
  int new_samples = 0;           // how many of the five were cast for this square (the others were shared)
  glm::vec3 contrast{0.f};       // (max - min) / (max + min) per channel over the five; 0 where max + min = 0
  enum class Outcome { agree, depth_limit, subdivided } outcome = Outcome::agree;
  int children[4] = {-1, -1, -1, -1};  // subdivided: the quadrants' indices
  glm::vec3 value{0.f};          // the square's estimate: its samples' mean, or its quadrants' mean
};

struct PixelSampling {
  AntiAliasing aa;
  int x = 0, y = 0;
  std::vector<PixelSample> samples;    // in the order the sampler cast them (adaptive: each lattice point once,
                                       // when a square first needs it)
  std::vector<AdaptiveSquare> squares; // adaptive only
  // The tent filter: the samples of the eight neighbouring pixels that it reaches (weight above 0), the
  // neighbours row by row from the top left, each one's samples in the order it cast them. Box: none.
  std::vector<PixelSample> neighbours;
  glm::vec3 box_value{0.f};  // the pixel's own samples box-filtered, bit-identical to estimate_pixel's
  glm::vec3 value{0.f};      // the pixel's value with aa.filter, bit-identical to render_image's
};

// The random stream of pixel (x, y) in a width-wide image: the renderer's (render_image) and the inspector's.
// The pixels just outside the image that the tent filter reaches (x = -1 or width, y = -1) have streams of
// their own, apart from every pixel's inside (y = height needs none: its indices lie past the image's).
inline Pcg32 pixel_rng(uint64_t seed, int x, int y, int width) {
  if (x < 0 || x >= width || y < 0)
    return Pcg32(seed, (uint64_t(1) << 40) + uint64_t(y + 1) * uint64_t(width + 2) + uint64_t(x + 1));
  return Pcg32(seed, uint64_t(y) * uint64_t(width) + uint64_t(x));
}

// Records pixel (x, y)'s own samples exactly as estimate_pixel casts them with the same rng state; its value
// is their box-filtered mean until apply_pixel_filter.
PixelSampling sample_pixel(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance);

// Completes s for its filter as render_image filters with this seed and image width: box changes nothing;
// tent casts the eight neighbours' samples (each pixel's own stream) through radiance, keeps those it reaches
// in s.neighbours, weighs every sample, and sets s.value to the weighted mean.
void apply_pixel_filter(PixelSampling& s, uint64_t seed, int width, const RadianceFn& radiance);

}  // namespace raystep
