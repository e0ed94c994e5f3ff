#include "raystep/render/image.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace raystep {

// ---- sRGB transfer curve (IEC 61966-2-1) ----

float srgb_encode(float linear) {
  if (linear <= 0.0031308f) return 12.92f * linear;
  return 1.055f * std::pow(linear, 1.f / 2.4f) - 0.055f;
}

float srgb_decode(float encoded) {
  if (encoded <= 0.04045f) return encoded / 12.92f;
  return std::pow((encoded + 0.055f) / 1.055f, 2.4f);
}

uint8_t srgb_encode8(float linear) {
  if (!(linear > 0.f)) return 0;  // also NaN
  if (linear >= 1.f) return 255;
  return uint8_t(std::lround(srgb_encode(linear) * 255.f));
}

glm::vec3 viridis(float t) {
  // matplotlib's viridis at t = 0, 1/8, ..., 1 (sRGB codes): #440154 #472d7b #3b528b #2c728e #21918c
  // #28ae80 #5ec962 #addc30 #fde725.
  static const uint8_t kStops[9][3] = {{68, 1, 84},    {71, 45, 123},  {59, 82, 139},
                                       {44, 114, 142}, {33, 145, 140}, {40, 174, 128},
                                       {94, 201, 98},  {173, 220, 48}, {253, 231, 37}};
  if (!(t > 0.f)) t = 0.f;  // also NaN
  if (t > 1.f) t = 1.f;
  float s = t * 8.f;
  int i = std::min(int(s), 7);
  float f = s - float(i);
  glm::vec3 c;
  for (int a = 0; a < 3; ++a) {
    float encoded = ((1.f - f) * kStops[i][a] + f * kStops[i + 1][a]) / 255.f;
    c[a] = srgb_decode(encoded);
  }
  return c;
}

Image sample_count_image(const std::vector<uint32_t>& counts, int w, int h, uint32_t* max_count) {
  if (w < 0 || h < 0 || counts.size() != size_t(w) * size_t(h))
    throw std::invalid_argument("sample_count_image: counts.size() != width * height");
  uint32_t most = 0;
  for (uint32_t c : counts) most = std::max(most, c);
  if (max_count) *max_count = most;
  Image image(w, h);
  for (size_t i = 0; i < counts.size(); ++i)
    image.pixels[i] = viridis(most > 0 ? float(double(counts[i]) / double(most)) : 0.f);
  return image;
}

}  // namespace raystep
