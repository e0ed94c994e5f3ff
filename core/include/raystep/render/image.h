// A rendered image: linear floating-point RGB, row-major, y = 0 the top row (raster order, as the camera
// generates it). Encoding for display (sRGB, 8 bit) happens only on output, in io/image_io.h.
// Also the sample-count map: samples per pixel shown through a perceptual colour ramp (viridis-like).
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

#include <glm/vec3.hpp>

namespace raystep {

struct Image {
  int width = 0, height = 0;
  std::vector<glm::vec3> pixels;  // linear float RGB, width * height, row-major, top row first

  Image() = default;
  Image(int w, int h, const glm::vec3& fill = glm::vec3(0.f))
      : width(w), height(h), pixels(size_t(w) * size_t(h), fill) {}

  glm::vec3& at(int x, int y) { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
  const glm::vec3& at(int x, int y) const { return pixels[size_t(y) * size_t(width) + size_t(x)]; }
};

// The sRGB transfer curve (IEC 61966-2-1) and its inverse, on [0, 1]: what output encodes with (io/image_io.h).
float srgb_encode(float linear);
float srgb_decode(float encoded);
// Linear value -> 8-bit sRGB code, clamped (NaN -> 0) and rounded to nearest.
uint8_t srgb_encode8(float linear);

// The perceptual colour ramp for t in [0, 1] (clamped; NaN maps to 0): matplotlib's viridis through nine
// stops, linearly interpolated in sRGB and returned as linear RGB so that write_png reproduces the stops.
glm::vec3 viridis(float t);

// Samples per pixel as an image: count / max_count through viridis (0 samples: the darkest colour).
// *max_count (if not null) receives the largest count, the value of the brightest colour, for a legend.
// Throws std::invalid_argument if counts.size() != w * h.
Image sample_count_image(const std::vector<uint32_t>& counts, int w, int h, uint32_t* max_count);

}  // namespace raystep
