#include "raystep/render/reference.h"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "raystep/render/camera.h"
#include "raystep/render/coverage.h"
#include "raystep/render/pixel_filter.h"
#include "raystep/render/render.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

// Overlaps smaller than this (in square pixels) are taken for shared edges and vertices: a pixel's exact
// value is a sum of areas in pixel units, so such an overlap moves no pixel by more than this.
constexpr double kOverlapTolerance = 1e-6;

// A triangle as it lands on the image: its raster polygon and the one colour the tracer gives it.
struct FlatTriangle {
  std::vector<glm::dvec2> polygon;  // counter-clockwise in raster coordinates (y down)
  glm::dvec2 lo, hi;                // raster bounding box
  glm::vec3 colour;
};

bool is_zero(const glm::vec3& v) {
  return v.x == 0.f && v.y == 0.f && v.z == 0.f;
}

// The part of a convex polygon on the left of the directed line a -> b (counter-clockwise inside).
std::vector<glm::dvec2> clip_half_plane(const std::vector<glm::dvec2>& in, const glm::dvec2& a,
                                        const glm::dvec2& b) {
  std::vector<glm::dvec2> out;
  auto side = [&](const glm::dvec2& p) { return (b.x - a.x) * (p.y - a.y) - (b.y - a.y) * (p.x - a.x); };
  for (size_t i = 0, n = in.size(); i < n; ++i) {
    const glm::dvec2 &s = in[(i + n - 1) % n], &e = in[i];
    const double ds = side(s), de = side(e);
    if ((ds >= 0.0) != (de >= 0.0)) out.push_back(s + (ds / (ds - de)) * (e - s));
    if (de >= 0.0) out.push_back(e);
  }
  return out;
}

// Area of the intersection of two counter-clockwise triangles inside [lo, hi] (convex clipping, one edge of
// b at a time, then the rectangle the filters reach: an overlap beyond it changes no pixel).
double overlap_area(const FlatTriangle& a, const FlatTriangle& b, const glm::dvec2& lo, const glm::dvec2& hi) {
  std::vector<glm::dvec2> p = a.polygon;
  for (int k = 0; k < 3 && p.size() >= 3; ++k) p = clip_half_plane(p, b.polygon[k], b.polygon[(k + 1) % 3]);
  if (p.size() >= 3) p = clip_to_box(p, lo, hi);
  return p.size() >= 3 ? std::fabs(signed_area(p)) : 0.0;
}

// The flat colour the Whitted tracer (render/whitted.cpp) gives material m, or the reason there is none.
// At a hit the tracer starts from ambient * diffuse; lights add diffuse and specular terms that vary with the
// shadow rays and, for point lights, over the surface; secondary rays (mirror, refraction) bring in what they
// see. With neither, every point of a triangle gets exactly ambient * diffuse (there is no emission term).
std::string flat_colour(const Scene& scene, const Material& m, glm::vec3* colour) {
  const RenderSettings& r = scene.render;
  if (!is_zero(m.diffuse) || !is_zero(m.specular))
    for (const Light& light : scene.lights)
      if (!is_zero(light.color * light.intensity))
        return "lights shade material '" + m.name + "' non-uniformly (exact coverage needs flat colours)";
  const bool spawns = m.mirror > 0.f || m.transparency > 0.f;
  if (r.max_depth > 0 && spawns && std::max(m.mirror, m.mirror + m.transparency) >= r.min_weight)
    return "material '" + m.name + "' reflects or refracts (exact coverage needs flat colours)";
  *colour = r.ambient * m.diffuse;  // what WhittedTracer::trace computes first, in the same float arithmetic
  return "";
}

// The scene's triangles on screen, or the reason the exact reference does not apply.
std::string flat_triangles(const Scene& scene, int width, int height, AntiAliasing::Filter filter,
                           std::vector<FlatTriangle>* out) {
  if (scene.camera.type != CameraType::orthographic)
    return "the camera is a pinhole (exact coverage needs an orthographic camera)";
  if (!scene.geometry.all_triangles()) return "the scene has spheres (exact coverage needs triangles only)";
  const ProjectiveCamera camera(scene.camera, width, height);
  const Geometry& g = scene.geometry;
  for (uint32_t id = 0; id < g.size(); ++id) {
    FlatTriangle t;
    if (std::string why = flat_colour(scene, scene.materials[g.material(id)], &t.colour); !why.empty())
      return why;
    // Camera rays start on the eye plane and go forwards: a triangle behind it is never seen, one across it
    // is cut by it.
    int in_front = 0;
    for (int k = 0; k < 3; ++k)
      in_front += glm::dot(g.vertex(id, k) - camera.eye(), -camera.w()) > 0.f ? 1 : 0;
    if (in_front == 0) continue;
    if (in_front < 3) return "a triangle crosses the camera's eye plane";
    t.polygon.resize(3);
    for (int k = 0; k < 3; ++k) camera.project(g.vertex(id, k), &t.polygon[k]);
    const double area = signed_area(t.polygon);
    if (area == 0.0) continue;  // seen edge-on: covers nothing
    if (area < 0.0) std::swap(t.polygon[1], t.polygon[2]);
    t.lo = glm::min(t.polygon[0], glm::min(t.polygon[1], t.polygon[2]));
    t.hi = glm::max(t.polygon[0], glm::max(t.polygon[1], t.polygon[2]));
    out->push_back(std::move(t));
  }
  // No two triangles may overlap on screen, else the nearer hides part of the other and areas do not add.
  // Sweep over x: only triangles whose x ranges meet are compared.
  std::vector<size_t> order(out->size());
  for (size_t i = 0; i < order.size(); ++i) order[i] = i;
  std::sort(order.begin(), order.end(), [&](size_t a, size_t b) { return (*out)[a].lo.x < (*out)[b].lo.x; });
  for (size_t i = 0; i < order.size(); ++i) {
    const FlatTriangle& a = (*out)[order[i]];
    for (size_t j = i + 1; j < order.size() && (*out)[order[j]].lo.x < a.hi.x; ++j) {
      const FlatTriangle& b = (*out)[order[j]];
      if (b.lo.y >= a.hi.y || a.lo.y >= b.hi.y) continue;
      const double reach = filter_reach(filter);
      if (overlap_area(a, b, glm::dvec2(-reach), glm::dvec2(width + reach, height + reach)) > kOverlapTolerance)
        return "two triangles overlap on screen";
    }
  }
  return "";
}

std::vector<FlatTriangle> flat_triangles_or_throw(const Scene& scene, int width, int height,
                                                  AntiAliasing::Filter filter) {
  std::vector<FlatTriangle> triangles;
  if (width <= 0 || height <= 0) throw InputError("", 0, "image size must be positive");
  if (std::string why = flat_triangles(scene, width, height, filter, &triangles); !why.empty())
    throw InputError("", 0, "no exact reference: " + why);
  return triangles;
}

// Pixel (x, y) given the coverage of each triangle, weighed by the filter (which integrates to 1):
// background * (1 - sum coverage) + sum coverage * colour.
struct PixelSum {
  glm::dvec3 colour{0.0};
  double coverage = 0.0;
  void add(double c, const glm::vec3& col) {
    coverage += c;
    colour += c * glm::dvec3(col);
  }
  glm::vec3 value(const glm::vec3& background) const {
    return glm::vec3(glm::dvec3(background) * (1.0 - coverage) + colour);
  }
};

void check_sizes(const Image& a, const Image& b) {
  if (a.width != b.width || a.height != b.height)
    throw std::invalid_argument("images differ in size: " + std::to_string(a.width) + "x" +
                                std::to_string(a.height) + " and " + std::to_string(b.width) + "x" +
                                std::to_string(b.height));
}

double filtered_coverage(const FlatTriangle& t, int x, int y, AntiAliasing::Filter filter) {
  return filter == AntiAliasing::Filter::tent ? pixel_tent_coverage(t.polygon, x, y)
                                              : pixel_coverage(t.polygon, x, y);
}

}  // namespace

std::string exact_coverage_unavailable(const Scene& scene, int width, int height, AntiAliasing::Filter filter) {
  if (width <= 0 || height <= 0) return "the image size is not positive";
  std::vector<FlatTriangle> triangles;
  return flat_triangles(scene, width, height, filter, &triangles);
}

Image render_exact_coverage(const Scene& scene, int width, int height, AntiAliasing::Filter filter) {
  const std::vector<FlatTriangle> triangles = flat_triangles_or_throw(scene, width, height, filter);
  std::vector<PixelSum> sums(size_t(width) * size_t(height));
  // Each triangle touches only the pixels whose filters reach its bounding box.
  const int reach = filter_reach(filter);
  for (const FlatTriangle& t : triangles) {
    const int x0 = std::max(0, int(std::floor(t.lo.x)) - reach),
              x1 = std::min(width - 1, int(std::ceil(t.hi.x)) - 1 + reach);
    const int y0 = std::max(0, int(std::floor(t.lo.y)) - reach),
              y1 = std::min(height - 1, int(std::ceil(t.hi.y)) - 1 + reach);
    for (int y = y0; y <= y1; ++y)
      for (int x = x0; x <= x1; ++x) {
        const double c = filtered_coverage(t, x, y, filter);
        if (c > 0.0) sums[size_t(y) * size_t(width) + size_t(x)].add(c, t.colour);
      }
  }
  Image image(width, height);
  for (size_t i = 0; i < sums.size(); ++i) image.pixels[i] = sums[i].value(scene.render.background);
  return image;
}

std::optional<glm::vec3> exact_pixel_value(const Scene& scene, int width, int height, int x, int y,
                                           AntiAliasing::Filter filter) {
  std::vector<FlatTriangle> triangles;
  if (width <= 0 || height <= 0 || !flat_triangles(scene, width, height, filter, &triangles).empty())
    return std::nullopt;
  PixelSum sum;
  const double reach = filter_reach(filter);
  for (const FlatTriangle& t : triangles)
    if (t.lo.x < x + 1.0 + reach && t.hi.x > x - reach && t.lo.y < y + 1.0 + reach && t.hi.y > y - reach)
      sum.add(filtered_coverage(t, x, y, filter), t.colour);
  return sum.value(scene.render.background);
}

Reference make_reference(const Scene& scene, const Accelerator& accel, int width, int height,
                         const std::string& spec, int threads, const std::function<void(double)>& progress,
                         AntiAliasing::Filter filter) {
  auto report = [&](double f) {
    if (progress) progress(f);
  };
  std::string kind = spec;
  if (spec == "auto")
    kind = exact_coverage_unavailable(scene, width, height, filter).empty() ? "exact" : "jitter:16";
  const std::string suffix = filter == AntiAliasing::Filter::tent ? "+tent" : "";
  Reference ref;
  if (kind == "exact") {
    report(0.0);
    ref.image = render_exact_coverage(scene, width, height, filter);
    ref.kind = "exact" + suffix;
    report(1.0);
    return ref;
  }
  AntiAliasing aa;
  bool bad = kind.rfind("jitter:", 0) != 0;
  if (!bad) {
    try {
      aa = parse_antialiasing(kind);
    } catch (const InputError&) {
      bad = true;
    }
  }
  if (!bad && aa.filter != AntiAliasing::Filter::box) bad = true;  // the filter is the methods', not the spec's
  if (bad) throw InputError("", 0, "bad reference '" + spec + "': expected exact, jitter:K (K >= 1) or auto");
  aa.filter = filter;
  // Two independent renders (seeds no report uses): their mean is the reference; the mean's own error is
  // the RMS difference of the two over 2 (each render's is that over sqrt(2), and averaging two independent
  // errors divides it by sqrt(2) again).
  RenderOptions o;
  o.aa = aa;
  o.width = width;
  o.height = height;
  o.threads = threads;
  report(0.0);
  o.seed = 0x5eed0001;
  const RenderResult a = render_image(scene, accel, o);
  report(0.5);
  o.seed = 0x5eed0002;
  const RenderResult b = render_image(scene, accel, o);
  ref.image = a.image;
  for (size_t i = 0; i < ref.image.pixels.size(); ++i)
    ref.image.pixels[i] = 0.5f * (a.image.pixels[i] + b.image.pixels[i]);
  ref.kind = to_string(aa);
  ref.estimated_rmse = rmse(a.image, b.image) / 2.0;
  report(1.0);
  return ref;
}

double rmse(const Image& a, const Image& b) {
  check_sizes(a, b);
  if (a.pixels.empty()) return 0.0;
  double sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) {
      const double d = double(a.pixels[i][c]) - double(b.pixels[i][c]);
      sum += d * d;
    }
  return std::sqrt(sum / (3.0 * double(a.pixels.size())));
}

double max_abs_error(const Image& a, const Image& b) {
  check_sizes(a, b);
  double m = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i)
    for (int c = 0; c < 3; ++c) m = std::max(m, std::fabs(double(a.pixels[i][c]) - double(b.pixels[i][c])));
  return m;
}

std::vector<float> pixel_errors(const Image& a, const Image& b) {
  check_sizes(a, b);
  std::vector<float> e(a.pixels.size());
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const glm::vec3 d = glm::abs(a.pixels[i] - b.pixels[i]);
    e[i] = std::max(d.x, std::max(d.y, d.z));
  }
  return e;
}

}  // namespace raystep
