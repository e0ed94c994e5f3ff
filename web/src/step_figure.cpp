#include "step_figure.h"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "raystep/accel/bvh.h"
#include "raystep/accel/bvh_sah_curve.h"
#include "raystep/accel/kdtree.h"
#include "raystep/accel/kdtree_sah_curve.h"
#include "raystep/figure/figure_file.h"
#include "raystep/figure/flat_aa_figure.h"
#include "raystep/figure/sah_curve_figure.h"
#include "raystep/io/image_io.h"
#include "raystep/lesson/lesson_figure.h"
#include "raystep/lesson/tree_nodes.h"
#include "raystep/render/camera.h"
#include "raystep/render/reference.h"
#include "raystep/render/render.h"
#include "raystep/render/whitted.h"
#include "raystep/report/bvol_report.h"
#include "raystep/scene/antialiasing_spec.h"
#include "raystep/trace/heatmap.h"
#include "raystep/util/xml_escape.h"

namespace raystep::web {

namespace {

// The step's anti-aliasing: its spec, or the scene's own ("" or "scene").
AntiAliasing step_antialiasing(const StepWorld& w) {
  return w.aa.empty() || w.aa == "scene" ? w.scene->render.aa : parse_antialiasing(w.aa);
}

std::string num(double v, int digits = 3) {
  char b[48];
  std::snprintf(b, sizeof b, "%.*f", digits, v);
  std::string s = b;
  if (s.find('.') != std::string::npos) {
    while (s.back() == '0') s.pop_back();
    if (s.back() == '.') s.pop_back();
  }
  return s;
}

std::string png_url(const Image& image) {
  const std::vector<uint8_t> png = png_bytes(image);
  return "data:image/png;base64," + base64(std::string(png.begin(), png.end()), false);
}

// A picture's pixels enlarged without smoothing, with an SVG over it in the picture's own pixel units.
std::string pixelated(const Image& image, int view_width, const std::string& overlay, const std::string& alt) {
  const int h = int(std::lround(double(view_width) * image.height / image.width));
  return "<div class=\"raster\" style=\"width:" + std::to_string(view_width) + "px;height:" + std::to_string(h) +
         "px\"><img alt=\"" + xml_escape(alt) + "\" src=\"" + png_url(image) + "\" width=\"" +
         std::to_string(view_width) + "\" height=\"" + std::to_string(h) +
         "\"><svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" + std::to_string(view_width) + "\" height=\"" +
         std::to_string(h) + "\" viewBox=\"0 0 " + std::to_string(image.width) + " " +
         std::to_string(image.height) + "\" preserveAspectRatio=\"none\">" + overlay + "</svg></div>";
}

Image crop(const Image& image, int x0, int y0, int w, int h) {
  Image out(w, h);
  for (int y = 0; y < h; ++y)
    for (int x = 0; x < w; ++x) out.at(x, y) = image.at(x0 + x, y0 + y);
  return out;
}

// The lines between pixels, one pixel wide on the screen.
std::string pixel_grid(int w, int h) {
  std::string d;
  for (int x = 1; x < w; ++x) d += "M" + std::to_string(x) + " 0V" + std::to_string(h);
  for (int y = 1; y < h; ++y) d += "M0 " + std::to_string(y) + "H" + std::to_string(w);
  return "<path class=\"pixel-grid\" d=\"" + d +
         "\" fill=\"none\" stroke=\"#808080\" stroke-opacity=\"0.55\" stroke-width=\"1\" "
         "vector-effect=\"non-scaling-stroke\"/>";
}

std::string frame(double x, double y, double w, double h) {
  const std::string at = "x=\"" + num(x) + "\" y=\"" + num(y) + "\" width=\"" + num(w) + "\" height=\"" + num(h) +
                         "\" fill=\"none\" vector-effect=\"non-scaling-stroke\"";
  return "<rect class=\"frame\" " + at + " stroke=\"#1a1a1f\" stroke-width=\"5\"/><rect class=\"frame\" " + at +
         " stroke=\"#ffd000\" stroke-width=\"2.5\"/>";
}

std::string value_text(const glm::vec3& v) {
  if (v.x == v.y && v.y == v.z) return num(v.x, 4);
  return "(" + num(v.x, 3) + ", " + num(v.y, 3) + ", " + num(v.z, 3) + ")";
}

// The pixel inspector: the traced pixel enlarged over what its square sees (traced at 120 x 120 points), the
// k x k strata dashed (regular, jittered), adaptive sampling's squares, every sample a disc in the colour its
// ray brought back, numbered in the order they were cast; the value, and the exact one where there is one.
std::string inspector_html(const LessonState& s, const StepWorld& w, const TracePixel& p, int size,
                           std::string* words) {
  const PixelSampling& ps = p.sampling;
  const ProjectiveCamera camera(w.scene->camera, w.width, w.height);
  const WhittedTracer tracer(*w.scene, *w.accel);
  RayCounts counts;
  constexpr int n = 120;
  Image backdrop(n, n);
  for (int j = 0; j < n; ++j)
    for (int i = 0; i < n; ++i)
      backdrop.at(i, j) = tracer.trace_primary(
          camera.generate(float(ps.x) + (float(i) + 0.5f) / n, float(ps.y) + (float(j) + 0.5f) / n), &counts);
  std::string svg;
  // In the overlay's units a pixel is n wide: 0..n.
  auto u = [&](float v) { return num(double(v) * n, 2); };
  const AntiAliasing& aa = ps.aa;
  if ((aa.mode == AntiAliasing::Mode::regular || aa.mode == AntiAliasing::Mode::jitter) && aa.k > 1) {
    std::string d;
    for (int k = 1; k < aa.k; ++k) {
      const std::string c = u(float(k) / float(aa.k));
      d += "M" + c + " 0V" + std::to_string(n) + "M0 " + c + "H" + std::to_string(n);
    }
    svg += "<path class=\"strata\" d=\"" + d +
           "\" stroke=\"#8a8a8a\" stroke-width=\"1.5\" stroke-dasharray=\"6,4\" vector-effect=\"non-scaling-stroke\"/>";
  }
  for (size_t q = 0; q < ps.squares.size(); ++q) {
    const AdaptiveSquare& sq = ps.squares[q];
    float lo[2] = {1e9f, 1e9f}, hi[2] = {-1e9f, -1e9f};
    for (int c = 0; c < 4; ++c) {
      const PixelSample& smp = ps.samples[size_t(sq.samples[c])];
      lo[0] = std::min(lo[0], smp.px - float(ps.x));
      hi[0] = std::max(hi[0], smp.px - float(ps.x));
      lo[1] = std::min(lo[1], smp.py - float(ps.y));
      hi[1] = std::max(hi[1], smp.py - float(ps.y));
    }
    const bool chosen = s.square && size_t(*s.square) == q;
    svg += "<rect class=\"square" + std::string(chosen ? " selected" : "") + "\" x=\"" + u(lo[0]) + "\" y=\"" +
           u(lo[1]) + "\" width=\"" + u(hi[0] - lo[0]) + "\" height=\"" + u(hi[1] - lo[1]) +
           "\" fill=\"none\" stroke=\"" + (chosen ? "#ffd000" : "#ffffff") + "\" stroke-width=\"" +
           (chosen ? "3" : "1.2") + "\" vector-effect=\"non-scaling-stroke\"/>";
  }
  const float r = ps.samples.size() > 64 ? 0.012f : ps.samples.size() > 16 ? 0.022f : 0.035f;
  for (size_t i = 0; i < ps.samples.size(); ++i) {
    const PixelSample& smp = ps.samples[i];
    const glm::vec3 c = smp.colour;
    char fill[8];
    std::snprintf(fill, sizeof fill, "#%02x%02x%02x", srgb_encode8(c.r), srgb_encode8(c.g), srgb_encode8(c.b));
    const bool dark = 0.2126f * c.r + 0.7152f * c.g + 0.0722f * c.b < 0.18f;
    const bool picked = s.sample && size_t(*s.sample) == i;
    svg += "<circle class=\"sample" + std::string(picked ? " selected" : "") + "\" cx=\"" +
           u(smp.px - float(ps.x)) + "\" cy=\"" + u(smp.py - float(ps.y)) + "\" r=\"" +
           u(picked ? r * 1.5f : r) + "\" fill=\"" + fill + "\" stroke=\"" + (dark ? "#ffffff" : "#1a1a1f") +
           "\" stroke-width=\"" + (picked ? "3" : "1.5") + "\" vector-effect=\"non-scaling-stroke\"><title>sample " +
           std::to_string(i) + ": " + value_text(c) + "</title></circle>";
  }
  *words = "Pixel (" + std::to_string(ps.x) + ", " + std::to_string(ps.y) + ") enlarged: " +
           std::to_string(ps.samples.size()) + " samples (" + to_string(aa) + "), the pixel's value " +
           value_text(ps.value);
  const std::optional<glm::vec3> exact =
      p.exact ? p.exact : exact_pixel_value(*w.scene, w.width, w.height, ps.x, ps.y, aa.filter);
  if (exact)
    *words += "; exact coverage " + value_text(*exact) + ", error " +
              (ps.value.x >= exact->x ? "+" : "") + num(double(ps.value.x - exact->x), 4);
  return pixelated(backdrop, size, svg, "pixel (" + std::to_string(ps.x) + ", " + std::to_string(ps.y) + ")");
}

ordered picture_figure(const LessonStep& step, const StepWorld& w, int width) {
  const LessonState& s = step.state;
  const AntiAliasing aa = step_antialiasing(w);
  Image image;
  std::string words;
  bool heat = !s.heat.empty() && s.heat != "none";
  if (heat) {
    const HeatQuantity q = parse_heat_quantity(s.heat);
    const HeatMap map = scene_heatmap(*w.scene, *w.accel, aa, w.width, w.height, q, 0);
    image = heatmap_image(map);
    words = std::string("Heat map: ") + heat_quantity_label(q) + " per pixel, " + std::to_string(w.width) + " × " +
            std::to_string(w.height) + " pixels; mean " + num(map.mean_value * map.unit, 2) + ", most " +
            num(map.max_value * map.unit, 3) + " (the colour bar on the right)";
  } else {
    RenderOptions options = render_options(w.scene->render);
    options.aa = aa;
    options.width = w.width;
    options.height = w.height;
    image = render_image(*w.scene, *w.accel, options).image;
    const uint32_t n = max_samples_per_pixel(aa);
    words = "The picture, " + std::to_string(w.width) + " × " + std::to_string(w.height) + " pixels, " +
            (aa.mode == AntiAliasing::Mode::none
                 ? std::string("one ray through each pixel's centre")
                 : to_string(aa) + ": " + (aa.mode == AntiAliasing::Mode::adaptive ? "at most " : "") +
                       std::to_string(n) + (n == 1 ? " ray" : " rays") + " per pixel");
  }
  // Zoomed on the traced pixel: the part of the picture a view `width` wide shows at that zoom.
  int x0 = 0, y0 = 0, cw = image.width, ch = image.height;
  const bool zoomed = w.pixel && s.zoom && *s.zoom > 1.0 && !heat;
  if (zoomed) {
    cw = std::clamp(int(std::ceil(width / *s.zoom)), 1, w.width);
    ch = std::clamp(int(std::ceil(width * 0.6 / *s.zoom)), 1, w.height);
    x0 = std::clamp((*w.pixel)[0] - cw / 2, 0, w.width - cw);
    y0 = std::clamp((*w.pixel)[1] - ch / 2, 0, w.height - ch);
    image = crop(image, x0, y0, cw, ch);
    words += "; shown " + num(*s.zoom, 1) + " times larger around the framed pixel";
  }
  std::string overlay;
  if (double(width) / cw >= 6.0) overlay += pixel_grid(cw, ch);
  if (w.pixel) {
    overlay += frame((*w.pixel)[0] - x0, (*w.pixel)[1] - y0, 1, 1);
    if (!zoomed) words += "; pixel (" + std::to_string((*w.pixel)[0]) + ", " + std::to_string((*w.pixel)[1]) + ") framed";
  }
  std::string html = pixelated(image, width, overlay, words);
  if (s.inspect && w.trace && w.trace->pixel) {
    std::string inspected;
    const std::string enlarged = inspector_html(s, w, *w.trace->pixel, std::min(width, 360), &inspected);
    html += "<div class=\"inspector\">" + enlarged + "<p class=\"inspector-words\">" + xml_escape(inspected) +
            "</p></div>";
  }
  return {{"kind", "picture"}, {"html", html}, {"caption", words}};
}

// The selected node's SAH cost curve (kd-tree or binary BVH), its path as the step names it; nullopt for
// another structure.
std::optional<Figure> curve_figure(const StepWorld& w, const std::string& path) {
  const uint32_t node = uint32_t(std::max(0, w.node));
  if (const auto* kd = dynamic_cast<const KdTree*>(w.accel.get()))
    return sah_curve_figure(record_sah_curve(kd->geometry(), kd->options(), node), path);
  if (const auto* bvh = dynamic_cast<const Bvh*>(w.accel.get()))
    return sah_curve_figure(record_bvh_sah_curve(bvh->geometry(), bvh->options(), node), path);
  return std::nullopt;
}

std::optional<ordered> chart_figure(const LessonStep& step, const StepWorld& w, int width, bool with_tree) {
  std::optional<Figure> f =
      curve_figure(w, step.state.node.by == NodeSpec::By::path ? step.state.node.path : std::string());
  if (!f) return std::nullopt;
  std::string html;
  std::string words = f->caption[0] + "; " + f->caption[1];
  if (with_tree) {
    std::string shape;
    if (const auto* kd = dynamic_cast<const KdTree*>(w.accel.get())) {
      const KdTreeStats t = kd_tree_stats(kd->data(), kd->options());
      shape = "The kd-tree: " + std::to_string(t.nodes) + " nodes, " + std::to_string(t.leaves) + " leaves (" +
              std::to_string(t.empty_leaves) + " empty), depth " + std::to_string(t.max_depth) + ", " +
              std::to_string(t.references) + " references, SAH cost " + num(t.sah_cost, 1);
    } else if (const auto* bvh = dynamic_cast<const Bvh*>(w.accel.get())) {
      const BvhStats t = bvh_stats(bvh->data(), bvh->options());
      shape = "The BVH: " + std::to_string(t.nodes) + " nodes, " + std::to_string(t.leaves) + " leaves, depth " +
              std::to_string(t.max_depth) + ", SAH cost " + num(t.sah_cost, 1);
    }
    html += "<p class=\"tree-shape\">" + xml_escape(shape) + "</p>";
    words = shape + "; " + words;
  }
  f->caption.clear();  // the page's caption gives the words, in the page's type
  f->caption_points = 0.f;
  html += figure_svg(*f, std::max(width, 760), false);
  return ordered{{"kind", with_tree ? "tree" : "chart"}, {"html", html}, {"caption", words}};
}

// A Markdown pipe table (a header row, the |---| row, then rows) as an HTML table: cmark reads no tables.
std::string pipe_table_html(const std::string& markdown) {
  std::string html = "<table>\n";
  size_t row = 0, at = 0;
  while (at < markdown.size()) {
    size_t end = markdown.find('\n', at);
    if (end == std::string::npos) end = markdown.size();
    std::string line = markdown.substr(at, end - at);
    at = end + 1;
    if (line.size() < 2 || line[0] != '|') continue;
    if (line.find("---") != std::string::npos) continue;  // the alignment row
    const char* cell = row++ == 0 ? "th" : "td";
    html += "<tr>";
    size_t from = 1;
    for (size_t bar; (bar = line.find('|', from)) != std::string::npos; from = bar + 1) {
      std::string text = line.substr(from, bar - from);
      const size_t a = text.find_first_not_of(' '), b = text.find_last_not_of(' ');
      text = a == std::string::npos ? "" : text.substr(a, b - a + 1);
      html += std::string("<") + cell + ">" + xml_escape(text) + "</" + cell + ">";
    }
    html += "</tr>\n";
  }
  return html + "</table>\n";
}

std::optional<ordered> report_figure(const LessonStep& step, const StepWorld& w) {
  std::string html, words;
  if (step.state.report.find("bvol") != std::string::npos) {
    const std::vector<BvolReportRow> rows = run_bvol_report(*w.scene, BvolReportOptions{});
    html += pipe_table_html(bvol_report_markdown(rows));
    words = "The bounding-volume kinds on this scene, measured when the page was made (one ray per pixel, " +
            std::to_string(rows.empty() ? 0 : rows.front().rays) + " rays)";
  }
  if (html.empty()) return std::nullopt;
  return ordered{{"kind", "report"}, {"html", "<div class=\"report\">" + html + "</div>"}, {"caption", words}};
}

}  // namespace

std::optional<ordered> step_figure_json(const LessonStep& step, const StepWorld& w, int width) {
  if (!w.scene || !w.accel) return std::nullopt;
  const LessonState& s = step.state;
  if (w.scene->flat) {  // the walk's 2D picture is the figure, or the pixels' anti-aliasing in the plane
    if (!s.flat_aa) return std::nullopt;
    FlatAaInput in;
    in.scene = w.scene.get();
    in.accel = w.accel.get();
    in.aa = step_antialiasing(w);
    in.width = w.width;
    in.height = w.height;
    const FlatAa fa = flat_aa_figure(in);
    std::string words;
    for (const std::string& line : fa.figure.caption) words += (words.empty() ? "" : "; ") + line;
    return ordered{
        {"kind", "picture"}, {"html", figure_svg(fa.figure, std::max(width, 900), false)}, {"caption", words}};
  }
  switch (lesson_figure(s)) {
    case LessonFigure::view3d:
      if (w.trace) return std::nullopt;  // the walk in the 3D view
      [[fallthrough]];                   // no walk: the tree, or the picture
    case LessonFigure::tree:
      if (auto f = chart_figure(step, w, width, true)) return f;
      return picture_figure(step, w, width);
    case LessonFigure::chart:
      if (auto f = chart_figure(step, w, width, false)) return f;
      return picture_figure(step, w, width);
    case LessonFigure::report:
      if (auto f = report_figure(step, w)) return f;
      return picture_figure(step, w, width);
    case LessonFigure::picture:
      return picture_figure(step, w, width);
  }
  return std::nullopt;
}

}  // namespace raystep::web
