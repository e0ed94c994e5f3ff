// The reference an anti-aliased picture is measured against. Exact where the lecture's pre-filter is exact:
// flat-coloured triangles seen orthographically, no two overlapping on screen, so that a pixel's true value
// is the background plus each triangle's colour times the area of the pixel it covers (render/coverage.h).
// Elsewhere a stratified render with many samples: the mean of two independent seeds, whose own error is
// estimated from their difference (the RMS difference of two renders is sqrt(2) times either one's RMS error,
// and their mean's error is 1/sqrt(2) of either one's: RMS difference / 2) and stated with the figures.
#pragma once

#include <functional>
#include <optional>
#include <string>
#include <vector>

#include "raystep/accel/accelerator.h"
#include "raystep/render/image.h"
#include "raystep/scene/scene.h"

namespace raystep {

// Why a scene has no exact reference ("" when it has one): perspective camera, a sphere, lights or a
// reflection depth that shade a triangle non-uniformly, overlapping triangles on screen, ...
// The filter: box (the pixel's area) or tent (render/pixel_filter.h; triangles may then not overlap within
// the one-pixel frame around the image either, which the border pixels' tents reach).
std::string exact_coverage_unavailable(const Scene& scene, int width, int height,
                                       AntiAliasing::Filter filter = AntiAliasing::Filter::box);

// The exact pre-filtered picture, the polygons' coverage weighed by the filter (render/coverage.h). Throws
// InputError("", 0, reason) when exact_coverage_unavailable is not "".
Image render_exact_coverage(const Scene& scene, int width, int height,
                            AntiAliasing::Filter filter = AntiAliasing::Filter::box);

// One pixel's exact value, for the pixel inspector; nullopt when the scene has no exact reference.
std::optional<glm::vec3> exact_pixel_value(const Scene& scene, int width, int height, int x, int y,
                                           AntiAliasing::Filter filter = AntiAliasing::Filter::box);

struct Reference {
  Image image;
  std::string kind;             // "exact" or "jitter:K", with "+tent" for the tent filter"
  double estimated_rmse = 0.0;  // 0 for exact; for jitter:K the estimate from two seeds (RMS difference / 2)
};

// spec: "exact", "jitter:K" or "auto" (exact where available, else jitter:16), pre-filtered by the filter
// (a jitter:K reference is rendered with it). Throws InputError("", 0, ...)
// for another spec, or "exact" on a scene without an exact reference (the message gives the reason).
// progress (optional) receives the fraction done in [0, 1]. Exact coverage is cheap and single-threaded; a
// jitter:K reference is two renders (seeds 0x5eed0001 and 0x5eed0002, which no report uses) and their mean.
Reference make_reference(const Scene& scene, const Accelerator& accel, int width, int height,
                         const std::string& spec, int threads,
                         const std::function<void(double)>& progress = nullptr,
                         AntiAliasing::Filter filter = AntiAliasing::Filter::box);

// Errors over the three channels of every pixel: root mean square, largest absolute, and per pixel (the
// largest channel's absolute error, row-major: the "error against the reference" heat map).
double rmse(const Image& a, const Image& b);        // throws std::invalid_argument on a size mismatch
double max_abs_error(const Image& a, const Image& b);
std::vector<float> pixel_errors(const Image& a, const Image& b);

}  // namespace raystep
