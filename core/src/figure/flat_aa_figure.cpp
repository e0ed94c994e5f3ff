#include "raystep/figure/flat_aa_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "raystep/render/camera.h"
#include "raystep/render/pixel_samples.h"
#include "raystep/render/reference.h"
#include "raystep/render/whitted.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/util/error.h"

namespace raystep {

namespace {

const glm::vec3 kInk(0.15f, 0.15f, 0.18f), kGrid(0.55f, 0.55f, 0.6f), kOver(0.85f, 0.15f, 0.1f),
    kUnder(0.15f, 0.35f, 0.85f), kEdge(1.f, 0.55f, 0.1f);

float grey(const glm::vec3& c) { return std::clamp((c.r + c.g + c.b) / 3.f, 0.f, 1.f); }

FigureItem square(glm::vec2 lo, glm::vec2 hi, glm::vec3 fill, float opacity, const std::string& css) {
  FigureItem it;
  it.kind = FigureItem::Kind::polygon;
  it.points = {lo, {hi.x, lo.y}, hi, {lo.x, hi.y}};
  it.style.has_stroke = false;
  it.style.fill = fill;
  it.style.fill_opacity = opacity;
  it.css = css;
  return it;
}

}  // namespace

FlatAa flat_aa_figure(const FlatAaInput& in) {
  if (!in.scene || !in.scene->flat)
    throw InputError("", 0, "a figure draws a 2D scene (\"dimensions\": 2); this scene is 3D");
  if (!in.accel) throw InputError("", 0, "the anti-aliasing figure needs a built structure");
  const Scene& scene = *in.scene;
  const int w = in.width > 0 ? in.width : scene.render.width, h = in.height > 0 ? in.height : scene.render.height;
  if (w < 1 || h < 1 || int64_t(w) * h > kFlatAaMaxPixels)
    throw InputError("", 0,
                     "the anti-aliasing figure draws at most " + std::to_string(kFlatAaMaxPixels) + " pixels; " +
                         std::to_string(w) + "x" + std::to_string(h) + " is " + std::to_string(int64_t(w) * h) +
                         " (give a smaller --size)");
  max_samples_per_pixel(in.aa);  // throws for settings out of range
  const ProjectiveCamera camera(scene.camera, w, h);
  const WhittedTracer tracer(scene, *in.accel);
  RayCounts counts;
  const RadianceFn radiance = [&](float x, float y) { return tracer.trace_primary(camera.generate(x, y), &counts); };
  // Raster to plane: the orthographic camera looks straight down (y up in the plane, down in the raster).
  auto plane = [&](float x, float y) { return glm::vec2(camera.generate(x, y).origin); };
  const glm::vec2 lo = plane(0.f, float(h)), hi = plane(float(w), 0.f);
  const float pixel = (hi.x - lo.x) / float(w);
  // Panel k's offset from the first: to the right, or (a column) down, with room for its title above.
  const glm::vec2 step = in.column ? glm::vec2(0.f, -((hi.y - lo.y) + 2.6f * pixel))
                                   : glm::vec2((hi.x - lo.x) * 1.08f, 0.f);

  FlatAa out;
  out.pixels = w * h;
  out.why_not = exact_coverage_unavailable(scene, w, h, in.aa.filter);
  out.exact = out.why_not.empty();
  const int panels = out.exact ? 3 : 1;
  Figure& fig = out.figure;
  const glm::vec2 last = step * float(panels - 1);
  fig.lo = glm::min(lo, lo + last) - glm::vec2(0.5f * pixel);
  fig.hi = glm::max(hi, hi + last) + glm::vec2(0.5f * pixel, 2.7f * pixel);

  FigureLayer values{"pixels", {}}, dots{"samples", {}}, grid{"grid", {}}, shapes{"polygon", {}},
      titles{"titles", {}};
  double sum = 0.0;
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) {
      Pcg32 rng = pixel_rng(scene.render.seed, x, y, w);
      PixelSampling s = sample_pixel(in.aa, x, y, rng, radiance);
      apply_pixel_filter(s, scene.render.seed, w, radiance);
      out.samples += s.samples.size() + s.neighbours.size();
      const float v = grey(s.value);
      const glm::vec2 a = plane(float(x), float(y + 1)), b = plane(float(x + 1), float(y));
      values.items.push_back(square(a, b, glm::vec3(v), 1.f, "sampled"));
      for (const PixelSample& p : s.samples) {
        FigureItem d;
        d.kind = FigureItem::Kind::circle;
        d.points = {plane(p.px, p.py)};
        // Small enough that sixteen leave the pixel's grey readable: white where the sample saw the polygon,
        // red where it saw the background.
        d.radius = 0.045f * pixel;
        d.style.fill = grey(p.colour) > 0.5f ? glm::vec3(1.f) : glm::vec3(0.8f, 0.1f, 0.1f);
        d.style.fill_opacity = 1.f;
        d.style.has_stroke = false;
        d.css = grey(p.colour) > 0.5f ? "sample in" : "sample out";
        dots.items.push_back(d);
      }
      if (!out.exact) continue;
      const float e = grey(*exact_pixel_value(scene, w, h, x, y, in.aa.filter));
      const glm::vec2 shift = step;
      values.items.push_back(square(a + shift, b + shift, glm::vec3(e), 1.f, "exact"));
      const float err = v - e;
      sum += std::fabs(double(err));
      out.max_abs_error = std::max(out.max_abs_error, double(std::fabs(err)));
      // The error: white at 0, red where the samples saw too much, blue too little (full colour at 0.5).
      values.items.push_back(square(a + 2.f * shift, b + 2.f * shift, err >= 0.f ? kOver : kUnder,
                                    std::min(1.f, 2.f * std::fabs(err)), "error"));
    }
  out.mean_abs_error = out.exact ? sum / double(out.pixels) : 0.0;
  // The pixel grid and the shapes over each panel.
  for (int k = 0; k < panels; ++k) {
    const glm::vec2 shift = step * float(k);
    for (int x = 0; x <= w; ++x) {
      FigureItem l;
      l.kind = FigureItem::Kind::line;
      l.points = {plane(float(x), float(h)) + shift, plane(float(x), 0.f) + shift};
      l.style.stroke = kGrid;
      l.style.stroke_width = 0.4f;
      l.css = "pixel-grid";
      grid.items.push_back(l);
    }
    for (int y = 0; y <= h; ++y) {
      FigureItem l;
      l.kind = FigureItem::Kind::line;
      l.points = {plane(0.f, float(y)) + shift, plane(float(w), float(y)) + shift};
      l.style.stroke = kGrid;
      l.style.stroke_width = 0.4f;
      l.css = "pixel-grid";
      grid.items.push_back(l);
    }
    for (const FlatShape& sh : scene.flat->shapes) {
      FigureItem it;
      if (sh.kind == FlatShape::Kind::circle) {
        it.kind = FigureItem::Kind::circle;
        it.points = {sh.center + shift};
        it.radius = sh.radius;
      } else {
        it.kind = sh.kind == FlatShape::Kind::polygon ? FigureItem::Kind::polygon : FigureItem::Kind::polyline;
        for (const glm::vec2& p : sh.points) it.points.push_back(p + shift);
      }
      it.style.stroke = kEdge;
      it.style.stroke_width = 1.4f;
      it.style.fill_opacity = 0.f;
      it.css = "edge";
      shapes.items.push_back(it);
    }
    static const char* kTitles[3] = {"sampled", "exact coverage (pre-filter)", "error: sampled - exact"};
    titles.items.push_back(figure_text(glm::vec2(lo.x + 0.5f * (hi.x - lo.x), hi.y + 1.2f * pixel) + shift,
                                       kTitles[k], 12.f, kInk, "title"));
  }
  fig.layers = {std::move(values), std::move(grid), std::move(shapes), std::move(dots), std::move(titles)};
  char line[256];
  std::snprintf(line, sizeof line, "%s: %dx%d pixels, %zu samples (%.2f a pixel)", to_string(in.aa).c_str(), w, h,
                out.samples, double(out.samples) / double(out.pixels));
  fig.caption.push_back(line);
  if (out.exact) {
    std::snprintf(line, sizeof line, "error against the exact coverage: mean |e| %.4f, largest %.4f", out.mean_abs_error,
                  out.max_abs_error);
    fig.caption.push_back(line);
  } else {
    fig.caption.push_back("no exact coverage: " + out.why_not);
  }
  fig.caption_points = 16.f * float(fig.caption.size()) + 8.f;
  return out;
}

}  // namespace raystep
