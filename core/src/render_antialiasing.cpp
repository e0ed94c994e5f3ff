#include "raystep/render/antialiasing.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

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

// Adaptive supersampling after Whitted (1980): a square is sampled at its four corners and its centre;
// where these samples differ too much (contrast above the threshold) it is split into quadrants, whose
// corners and centres include the parent's samples, recursively down to max_depth. A leaf's value is the
// average of its five samples, a parent's the average of its quadrants', so the pixel is the area-weighted
// average of its leaf squares.
// Why corners rather than 2 x 2 jittered samples: a straight edge that crosses a square always separates
// two of its corners, so an edge is never missed, while four jittered samples all land on the same side
// of it about half of the time (measured on the lecture's polygon scene, where that left adaptive
// sampling worse than 16 jittered samples). What corners and centre can miss is a feature that touches
// none of them: a sliver or an object smaller than the square.
// Every sample lies on the lattice of spacing 2^-(max_depth+1) over the pixel; a sample shared by
// neighbouring squares is taken once.
class AdaptiveSampler {
 public:
  AdaptiveSampler(const AntiAliasing& aa, float x, float y, const RadianceFn& radiance)
      : aa_(aa), radiance_(radiance), x_(x), y_(y), n_(2 << aa.max_depth), inv_n_(1.f / float(n_)) {
    thread_local std::vector<glm::vec3> values;
    thread_local std::vector<uint8_t> taken;
    const size_t points = size_t(n_ + 1) * size_t(n_ + 1);
    if (values.size() < points) values.resize(points);
    taken.assign(points, 0);
    values_ = values.data();
    taken_ = taken.data();
  }

  // The whole pixel.
  glm::vec3 estimate() { return square(0, 0, n_, 0); }
  uint32_t samples() const { return samples_; }

 private:
  // Radiance at lattice point (i, j), traced once.
  glm::vec3 at(int i, int j) {
    const size_t k = size_t(j) * size_t(n_ + 1) + size_t(i);
    if (!taken_[k]) {
      values_[k] = radiance_(x_ + float(i) * inv_n_, y_ + float(j) * inv_n_);
      taken_[k] = 1;
      ++samples_;
    }
    return values_[k];
  }

  // The square with corner (i0, j0) and side `size` lattice steps, at subdivision depth `depth`.
  glm::vec3 square(int i0, int j0, int size, int depth) {
    const int h = size / 2;
    const glm::vec3 v[5] = {at(i0, j0), at(i0 + size, j0), at(i0, j0 + size), at(i0 + size, j0 + size),
                            at(i0 + h, j0 + h)};  // corners and centre

    // Leaf: the depth limit is reached, or the samples agree.
    if (depth >= aa_.max_depth || !contrast_exceeds(v, 5, aa_.threshold))
      return 0.2f * (v[0] + v[1] + v[2] + v[3] + v[4]);

    // Subdivide into quadrants; the pixel value is the area-weighted average of the leaves.
    return 0.25f * (square(i0, j0, h, depth + 1) + square(i0 + h, j0, h, depth + 1) +
                    square(i0, j0 + h, h, depth + 1) + square(i0 + h, j0 + h, h, depth + 1));
  }

  const AntiAliasing& aa_;
  const RadianceFn& radiance_;
  const float x_, y_;   // the pixel's corner
  const int n_;         // lattice steps per pixel side: 2^(max_depth + 1)
  const float inv_n_;
  glm::vec3* values_;
  uint8_t* taken_;
  uint32_t samples_ = 0;
};

}  // namespace

void validate(const AntiAliasing& aa) {
  const std::string mode = mode_name(aa.mode);
  const bool uses_k = aa.mode == AntiAliasing::Mode::regular || aa.mode == AntiAliasing::Mode::jitter ||
                      aa.mode == AntiAliasing::Mode::random;
  if (uses_k && aa.k < 1) throw InputError("", 0, "anti-aliasing " + mode + ": k must be at least 1");
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
    case AntiAliasing::Mode::adaptive: {
      // Fully refined: the (2^d + 1)^2 corners of the finest grid and the 4^d centres of its squares.
      const uint32_t side = (1u << aa.max_depth) + 1u;
      return side * side + (1u << (2 * aa.max_depth));
    }
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
      AdaptiveSampler sampler(aa, fx, fy, radiance);
      e.value = sampler.estimate();
      e.samples = sampler.samples();
      break;
    }
  }
  return e;
}

}  // namespace raystep
