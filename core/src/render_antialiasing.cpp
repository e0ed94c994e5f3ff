#include "raystep/render/antialiasing.h"

#include <algorithm>
#include <cmath>
#include <string>

#include <glm/vec2.hpp>

#include "raystep/util/error.h"

namespace raystep {

namespace {

const char* mode_name(AntiAliasing::Mode mode) {
  switch (mode) {
    case AntiAliasing::Mode::none: return "none";
    case AntiAliasing::Mode::regular: return "regular";
    case AntiAliasing::Mode::jitter: return "jitter";
    case AntiAliasing::Mode::random: return "random";
    case AntiAliasing::Mode::adaptive: return "adaptive";
  }
  return "?";
}

struct Sample {
  glm::vec2 p;   // raster position
  glm::vec3 L;   // radiance
};

// Adaptive subdivision (Whitted 1980) of the square [x0, x0+s) x [y0, y0+s): one jittered sample per
// quadrant, where `known` (if any) is a sample already taken inside the square and stands for its quadrant.
// Returns the square's value: the average of its four samples at a leaf, else of its quadrants' values, so
// the pixel is the area-weighted average of its leaf squares.
struct AdaptiveSampler {
  const AntiAliasing& aa;
  Pcg32& rng;
  const RadianceFn& radiance;
  uint32_t samples = 0;

  glm::vec3 square(float x0, float y0, float s, int depth, const Sample* known) {
    float h = 0.5f * s;
    int known_quadrant = -1;
    if (known) known_quadrant = (known->p.x >= x0 + h ? 1 : 0) + (known->p.y >= y0 + h ? 2 : 0);

    // Step 1: a 2 x 2 jittered pattern, reusing the known sample in its quadrant.
    Sample q[4];
    for (int i = 0; i < 4; ++i) {
      if (i == known_quadrant) {
        q[i] = *known;
        continue;
      }
      float qx = x0 + (i & 1) * h, qy = y0 + (i >> 1) * h;
      float u = rng.uniform(), v = rng.uniform();
      q[i].p = glm::vec2(qx + u * h, qy + v * h);
      q[i].L = radiance(q[i].p.x, q[i].p.y);
      ++samples;
    }

    // Step 2: refine where the contrast is high, down to max_depth.
    glm::vec3 values[4] = {q[0].L, q[1].L, q[2].L, q[3].L};
    if (depth < aa.max_depth && contrast_exceeds(values, 4, aa.threshold)) {
      glm::vec3 sum(0.f);
      for (int i = 0; i < 4; ++i) sum += square(x0 + (i & 1) * h, y0 + (i >> 1) * h, h, depth + 1, &q[i]);
      return 0.25f * sum;
    }
    return 0.25f * (values[0] + values[1] + values[2] + values[3]);
  }
};

}  // namespace

void validate(const AntiAliasing& aa) {
  std::string mode = mode_name(aa.mode);
  if (aa.k < 1) throw InputError("", 0, "anti-aliasing " + mode + ": k must be at least 1");
  uint64_t samples = 1;
  switch (aa.mode) {
    case AntiAliasing::Mode::none: break;
    case AntiAliasing::Mode::regular:
    case AntiAliasing::Mode::jitter: samples = uint64_t(aa.k) * uint64_t(aa.k); break;
    case AntiAliasing::Mode::random: samples = uint64_t(aa.k); break;
    case AntiAliasing::Mode::adaptive:
      if (aa.max_depth < 0 || aa.max_depth > 6)
        throw InputError("", 0, "anti-aliasing adaptive: max_depth must lie in [0, 6]");
      if (!(aa.threshold >= 0.f)) throw InputError("", 0, "anti-aliasing adaptive: threshold must be >= 0");
      break;
  }
  if (samples > kMaxSamplesPerPixel)
    throw InputError("", 0, "anti-aliasing " + mode + ": " + std::to_string(samples) +
                                " samples per pixel, at most " + std::to_string(kMaxSamplesPerPixel) +
                                " allowed");
}

uint32_t max_samples_per_pixel(const AntiAliasing& aa) {
  switch (aa.mode) {
    case AntiAliasing::Mode::none: return 1;
    case AntiAliasing::Mode::regular:
    case AntiAliasing::Mode::jitter: return uint32_t(aa.k * aa.k);
    case AntiAliasing::Mode::random: return uint32_t(aa.k);
    case AntiAliasing::Mode::adaptive: return 1u << (2 * (aa.max_depth + 1));  // 4^(max_depth + 1)
  }
  return 1;
}

bool contrast_exceeds(const glm::vec3* values, int n, float threshold) {
  for (int c = 0; c < 3; ++c) {
    float lo = values[0][c], hi = values[0][c];
    for (int i = 1; i < n; ++i) {
      lo = std::min(lo, values[i][c]);
      hi = std::max(hi, values[i][c]);
    }
    // (hi - lo) / (hi + lo) > threshold, multiplied out: no division, and black (hi + lo = 0) never refines.
    if (hi + lo > 0.f && hi - lo > threshold * (hi + lo)) return true;
  }
  return false;
}

PixelEstimate estimate_pixel(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance) {
  PixelEstimate e;
  const float fx = float(x), fy = float(y);
  switch (aa.mode) {
    case AntiAliasing::Mode::none:
      e.value = radiance(fx + 0.5f, fy + 0.5f);
      e.samples = 1;
      break;

    case AntiAliasing::Mode::regular:  // k x k grid, the centres of the strata
    case AntiAliasing::Mode::jitter: {  // k x k strata, one uniform sample in each
      const int k = aa.k;
      const float inv_k = 1.f / float(k);
      for (int j = 0; j < k; ++j)
        for (int i = 0; i < k; ++i) {
          float u = 0.5f, v = 0.5f;
          if (aa.mode == AntiAliasing::Mode::jitter) {
            u = rng.uniform();
            v = rng.uniform();
          }
          e.value += radiance(fx + (float(i) + u) * inv_k, fy + (float(j) + v) * inv_k);
        }
      e.samples = uint32_t(k * k);
      e.value /= float(e.samples);
      break;
    }

    case AntiAliasing::Mode::random: {  // k samples uniform over the pixel
      for (int i = 0; i < aa.k; ++i) {
        float u = rng.uniform(), v = rng.uniform();
        e.value += radiance(fx + u, fy + v);
      }
      e.samples = uint32_t(aa.k);
      e.value /= float(e.samples);
      break;
    }

    case AntiAliasing::Mode::adaptive: {
      AdaptiveSampler sampler{aa, rng, radiance};
      e.value = sampler.square(fx, fy, 1.f, 0, nullptr);
      e.samples = sampler.samples;
      break;
    }
  }
  return e;
}

}  // namespace raystep
