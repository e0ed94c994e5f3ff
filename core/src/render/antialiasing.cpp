#include "raystep/render/antialiasing.h"
#include "raystep/render/pixel_samples.h"

#include <algorithm>
#include <cmath>
#include <string>
#include <type_traits>
#include <vector>

#include "raystep/render/pixel_filter.h"
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

// The recorder every pixel estimate reports to (a template parameter, so that the renderer's instantiation,
// with NullPixelRecorder, compiles to the plain kernel). sample_pixel's recorder keeps what it is told.
// Every call stands inside `if constexpr (Recorder::enabled)`.
struct NullPixelRecorder {
  static constexpr bool enabled = false;
  // A sample cast at (px, py), with its stratum (regular, jitter) or lattice point (adaptive), -1 where none.
  void sample(float, float, const glm::vec3&, int, int, int, int) {}
  // Adaptive: a square is entered (before its five samples) ...
  void open_square(int, int, int, int) {}
  // ... its five samples (indices into the samples so far), of which new_samples were cast for it ...
  void square_samples(const int*, int, const glm::vec3*) {}
  // ... and left with its estimate; subdivided is the sampler's own decision.
  void close_square(bool, const glm::vec3&) {}
};

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
struct Nothing {};

template <typename Recorder>
class AdaptiveSampler {
 public:
  AdaptiveSampler(const AntiAliasing& aa, float x, float y, const RadianceFn& radiance, Recorder& recorder)
      : aa_(aa),
        radiance_(radiance),
        recorder_(recorder),
        x_(x),
        y_(y),
        n_(2 << aa.max_depth),
        inv_n_(1.f / float(n_)) {
    thread_local std::vector<glm::vec3> values;
    thread_local std::vector<uint8_t> taken;
    const size_t points = size_t(n_ + 1) * size_t(n_ + 1);
    if (values.size() < points) values.resize(points);
    taken.assign(points, 0);
    values_ = values.data();
    taken_ = taken.data();
    if constexpr (Recorder::enabled) sample_index_.assign(points, -1);
  }

  // The whole pixel.
  glm::vec3 estimate() { return square(0, 0, n_, 0); }
  uint32_t samples() const { return samples_; }

 private:
  // Radiance at lattice point (i, j), traced once.
  glm::vec3 at(int i, int j) {
    const size_t k = size_t(j) * size_t(n_ + 1) + size_t(i);
    if (!taken_[k]) {
      const float px = x_ + float(i) * inv_n_, py = y_ + float(j) * inv_n_;
      values_[k] = radiance_(px, py);
      taken_[k] = 1;
      if constexpr (Recorder::enabled) {
        sample_index_[k] = int(samples_);
        recorder_.sample(px, py, values_[k], -1, -1, i, j);
      }
      ++samples_;
    }
    return values_[k];
  }

  // The square with corner (i0, j0) and side `size` lattice steps, at subdivision depth `depth`.
  glm::vec3 square(int i0, int j0, int size, int depth) {
    const int h = size / 2;
    if constexpr (Recorder::enabled) recorder_.open_square(i0, j0, size, depth);
    const uint32_t before = samples_;
    const glm::vec3 v[5] = {at(i0, j0), at(i0 + size, j0), at(i0, j0 + size), at(i0 + size, j0 + size),
                            at(i0 + h, j0 + h)};  // corners and centre
    if constexpr (Recorder::enabled) {
      const int corners[5][2] = {
          {i0, j0}, {i0 + size, j0}, {i0, j0 + size}, {i0 + size, j0 + size}, {i0 + h, j0 + h}};
      int index[5];
      for (int s = 0; s < 5; ++s)
        index[s] = sample_index_[size_t(corners[s][1]) * size_t(n_ + 1) + size_t(corners[s][0])];
      recorder_.square_samples(index, int(samples_ - before), v);
    }

    // Leaf: the depth limit is reached, or the samples agree.
    if (depth >= aa_.max_depth || !contrast_exceeds(v, 5, aa_.threshold)) {
      const glm::vec3 value = 0.2f * (v[0] + v[1] + v[2] + v[3] + v[4]);
      if constexpr (Recorder::enabled) recorder_.close_square(false, value);
      return value;
    }

    // Subdivide into quadrants; the pixel value is the area-weighted average of the leaves. The quadrants are
    // visited in sequence, so that the order the samples are cast in is defined (the operands of one sum are
    // evaluated in an unspecified order: GCC took the last quadrant first).
    const glm::vec3 q0 = square(i0, j0, h, depth + 1);
    const glm::vec3 q1 = square(i0 + h, j0, h, depth + 1);
    const glm::vec3 q2 = square(i0, j0 + h, h, depth + 1);
    const glm::vec3 q3 = square(i0 + h, j0 + h, h, depth + 1);
    const glm::vec3 value = 0.25f * (q0 + q1 + q2 + q3);
    if constexpr (Recorder::enabled) recorder_.close_square(true, value);
    return value;
  }

  const AntiAliasing& aa_;
  const RadianceFn& radiance_;
  Recorder& recorder_;
  const float x_, y_;   // the pixel's corner
  const int n_;         // lattice steps per pixel side: 2^(max_depth + 1)
  const float inv_n_;
  glm::vec3* values_;
  uint8_t* taken_;
  uint32_t samples_ = 0;
  // Recording only: the sample index of each lattice point taken (nothing at all in the renderer's sampler).
  std::conditional_t<Recorder::enabled, std::vector<int>, Nothing> sample_index_;
};

// One sample of a stratified or random pattern: its radiance, told to the recorder.
template <typename Recorder>
glm::vec3 cast_sample(const RadianceFn& radiance, float px, float py, int si, int sj, Recorder& recorder) {
  if constexpr (Recorder::enabled) {
    const glm::vec3 c = radiance(px, py);
    recorder.sample(px, py, c, si, sj, -1, -1);
    return c;
  } else {
    return radiance(px, py);  // no named copy: GCC kept one on the stack (6 instructions a sample)
  }
}

// Every pattern's kernel, the renderer's (NullPixelRecorder) and the inspector's (PixelSamplingRecorder).
template <typename Recorder>
PixelEstimate estimate_pixel_with(const AntiAliasing& aa, int x, int y, Pcg32& rng,
                                  const RadianceFn& radiance, Recorder& recorder) {
  PixelEstimate e;
  const float fx = float(x), fy = float(y);
  switch (aa.mode) {
    case AntiAliasing::Mode::none: {
      e.value = cast_sample(radiance, fx + 0.5f, fy + 0.5f, -1, -1, recorder);
      e.samples = 1;
      break;
    }

    case AntiAliasing::Mode::regular:   // k x k grid, the centres of the strata
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
          e.value +=
              cast_sample(radiance, fx + (float(i) + u) * inv_k, fy + (float(j) + v) * inv_k, i, j, recorder);
        }
      e.samples = uint32_t(k * k);
      e.value /= float(e.samples);
      break;
    }

    case AntiAliasing::Mode::random: {  // k samples uniform over the pixel
      for (int i = 0; i < aa.k; ++i) {
        float u = rng.uniform(), v = rng.uniform();
        e.value += cast_sample(radiance, fx + u, fy + v, -1, -1, recorder);
      }
      e.samples = uint32_t(aa.k);
      e.value /= float(e.samples);
      break;
    }

    case AntiAliasing::Mode::adaptive: {
      AdaptiveSampler<Recorder> sampler(aa, fx, fy, radiance, recorder);
      e.value = sampler.estimate();
      e.samples = sampler.samples();
      break;
    }
  }
  return e;
}

// Keeps what the kernel reports: the samples in order and the adaptive squares depth first.
class PixelSamplingRecorder {
 public:
  static constexpr bool enabled = true;
  explicit PixelSamplingRecorder(PixelSampling& out) : out_(out) {}

  void sample(float px, float py, const glm::vec3& colour, int si, int sj, int li, int lj) {
    PixelSample s;
    s.px = px;
    s.py = py;
    s.colour = colour;
    s.stratum[0] = si;
    s.stratum[1] = sj;
    s.lattice[0] = li;
    s.lattice[1] = lj;
    out_.samples.push_back(s);
  }

  void open_square(int i0, int j0, int size, int depth) {
    AdaptiveSquare q;
    q.parent = open_.empty() ? -1 : open_.back();
    q.depth = depth;
    q.i0 = i0;
    q.j0 = j0;
    q.size = size;
    const int index = int(out_.squares.size());
    if (q.parent >= 0) {
      AdaptiveSquare& parent = out_.squares[size_t(q.parent)];
      for (int& c : parent.children)
        if (c < 0) {
          c = index;
          break;
        }
    }
    out_.squares.push_back(q);
    open_.push_back(index);
  }

  void square_samples(const int* index, int new_samples, const glm::vec3* v) {
    AdaptiveSquare& q = out_.squares[size_t(open_.back())];
    for (int s = 0; s < 5; ++s) q.samples[s] = index[s];
    q.new_samples = new_samples;
    for (int c = 0; c < 3; ++c) {
      float lo = v[0][c], hi = v[0][c];
      for (int s = 1; s < 5; ++s) {
        lo = std::min(lo, v[s][c]);
        hi = std::max(hi, v[s][c]);
      }
      q.contrast[c] = hi + lo > 0.f ? (hi - lo) / (hi + lo) : 0.f;
    }
  }

  void close_square(bool subdivided, const glm::vec3& value) {
    AdaptiveSquare& q = out_.squares[size_t(open_.back())];
    q.value = value;
    q.outcome = subdivided      ? AdaptiveSquare::Outcome::subdivided
                : exceeds_at(q) ? AdaptiveSquare::Outcome::depth_limit
                                : AdaptiveSquare::Outcome::agree;
    open_.pop_back();
  }

 private:
  // The sampler's own test, for a leaf's outcome (at the depth limit the sampler does not evaluate it).
  bool exceeds_at(const AdaptiveSquare& q) const {
    glm::vec3 v[5];
    for (int s = 0; s < 5; ++s) v[s] = out_.samples[size_t(q.samples[s])].colour;
    return contrast_exceeds(v, 5, out_.aa.threshold);
  }

  PixelSampling& out_;
  std::vector<int> open_;  // the squares entered and not yet left, innermost last
};

// Tells every sample to a function (render_image's tent filter and sample_pixel's neighbours).
class SampleFnRecorder : public NullPixelRecorder {
 public:
  static constexpr bool enabled = true;
  explicit SampleFnRecorder(const SampleFn& fn) : fn_(fn) {}
  void sample(float px, float py, const glm::vec3& colour, int, int, int, int) { fn_(px, py, colour); }

 private:
  const SampleFn& fn_;
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
  if (aa.mode == AntiAliasing::Mode::adaptive && aa.filter == AntiAliasing::Filter::tent)
    throw InputError("", 0, "anti-aliasing adaptive: the tent filter needs samples spread evenly over the pixel");
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
  NullPixelRecorder none;
  return estimate_pixel_with(aa, x, y, rng, radiance, none);
}

uint32_t cast_pixel_samples(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance,
                            const SampleFn& sample) {
  SampleFnRecorder recorder(sample);
  return estimate_pixel_with(aa, x, y, rng, radiance, recorder).samples;
}

PixelSampling sample_pixel(const AntiAliasing& aa, int x, int y, Pcg32& rng, const RadianceFn& radiance) {
  validate(aa);
  PixelSampling out;
  out.aa = aa;
  out.x = x;
  out.y = y;
  PixelSamplingRecorder recorder(out);
  out.value = estimate_pixel_with(aa, x, y, rng, radiance, recorder).value;
  out.box_value = out.value;
  return out;
}

void apply_pixel_filter(PixelSampling& s, uint64_t seed, int width, const RadianceFn& radiance) {
  if (s.aa.filter == AntiAliasing::Filter::box) return;
  const float cx = float(s.x) + 0.5f, cy = float(s.y) + 0.5f;
  FilterSum rows[3];  // the source rows y - 1, y, y + 1 (pixel_filter.h: the order render_image adds in)
  s.neighbours.clear();
  for (int dy = -1; dy <= 1; ++dy)
    for (int dx = -1; dx <= 1; ++dx) {
      FilterSum& row = rows[dy + 1];
      if (dx == 0 && dy == 0) {
        for (PixelSample& p : s.samples) {
          p.weight = tent_weight(p.px - cx, p.py - cy);
          row.add(p.weight, p.colour);
        }
        continue;
      }
      Pcg32 rng = pixel_rng(seed, s.x + dx, s.y + dy, width);
      cast_pixel_samples(s.aa, s.x + dx, s.y + dy, rng, radiance, [&](float px, float py, const glm::vec3& c) {
        const float w = tent_weight(px - cx, py - cy);
        if (!(w > 0.f)) return;
        PixelSample p;
        p.px = px;
        p.py = py;
        p.colour = c;
        p.weight = w;
        s.neighbours.push_back(p);
        row.add(w, c);
      });
    }
  FilterSum sum = rows[0];
  sum.add(rows[1]);
  sum.add(rows[2]);
  s.value = sum.value();
}

}  // namespace raystep
