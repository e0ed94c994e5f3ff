#include "raystep/figure/figure_file.h"

#include <cairo-pdf.h>
#include <cairo.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <sstream>

#include "raystep/util/atomic_file.h"
#include "raystep/util/error.h"
#include "raystep/util/xml_escape.h"

namespace raystep {

namespace {

// Scene coordinates to the page's (points, y down), the caption below the picture.
struct Page {
  float scale, width, height, picture_height;
  glm::vec2 lo, hi;
  Page(const Figure& f, int w) : lo(f.lo), hi(f.hi) {
    width = float(w);
    scale = width / std::max(1e-30f, f.hi.x - f.lo.x);
    picture_height = (f.hi.y - f.lo.y) * scale;
    height = std::ceil(picture_height + f.caption_points);
  }
  glm::vec2 operator()(glm::vec2 p) const { return {(p.x - lo.x) * scale, (hi.y - p.y) * scale}; }
};

constexpr float kCaptionPoints = 13.f;

std::string rgb(glm::vec3 c) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "#%02x%02x%02x", int(std::lround(std::clamp(c.r, 0.f, 1.f) * 255)),
                int(std::lround(std::clamp(c.g, 0.f, 1.f) * 255)),
                int(std::lround(std::clamp(c.b, 0.f, 1.f) * 255)));
  return buf;
}

std::string num(float v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.2f", double(v));
  return buf;
}

std::string svg_style(const FigureStyle& s, bool fillable) {
  std::string out;
  if (fillable && s.fill_opacity > 0.f)
    out += " fill=\"" + rgb(s.fill) + "\"" +
           (s.fill_opacity < 1.f ? " fill-opacity=\"" + num(s.fill_opacity) + "\"" : "");
  else
    out += " fill=\"none\"";
  if (s.has_stroke) {
    out += " stroke=\"" + rgb(s.stroke) + "\" stroke-width=\"" + num(s.stroke_width) + "\"";
    if (s.dashed)
      out += " stroke-dasharray=\"" + num(3.f * s.stroke_width) + "," + num(2.f * s.stroke_width) + "\"";
  }
  return out;
}

std::string svg_points(const Page& page, const std::vector<glm::vec2>& points) {
  std::string out;
  for (const glm::vec2& p : points) {
    const glm::vec2 q = page(p);
    out += (out.empty() ? "" : " ") + num(q.x) + "," + num(q.y);
  }
  return out;
}

// The figure through cairo: the same items on a PDF page or a PNG image.
void draw_cairo(cairo_t* cr, const Figure& f, const Page& page) {
  cairo_set_source_rgb(cr, 1, 1, 1);
  cairo_paint(cr);
  cairo_set_line_join(cr, CAIRO_LINE_JOIN_ROUND);
  cairo_set_line_cap(cr, CAIRO_LINE_CAP_ROUND);
  for (const FigureLayer& layer : f.layers)
    for (const FigureItem& it : layer.items) {
      const FigureStyle& s = it.style;
      cairo_new_path(cr);
      if (it.kind == FigureItem::Kind::text) {  // centred on its point
        cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
        cairo_set_font_size(cr, it.radius);
        cairo_text_extents_t e;
        cairo_text_extents(cr, it.text.c_str(), &e);
        const glm::vec2 p = page(it.points[0]);
        cairo_set_source_rgb(cr, s.fill.r, s.fill.g, s.fill.b);
        cairo_move_to(cr, p.x - e.width / 2 - e.x_bearing, p.y + 0.35 * it.radius);
        cairo_show_text(cr, it.text.c_str());
        continue;
      }
      if (it.kind == FigureItem::Kind::circle) {
        const glm::vec2 c = page(it.points[0]);
        cairo_arc(cr, c.x, c.y, it.radius * page.scale, 0, 2 * M_PI);
      } else {
        for (size_t i = 0; i < it.points.size(); ++i) {
          const glm::vec2 q = page(it.points[i]);
          if (i == 0)
            cairo_move_to(cr, q.x, q.y);
          else
            cairo_line_to(cr, q.x, q.y);
        }
        if (it.kind == FigureItem::Kind::polygon) cairo_close_path(cr);
      }
      const bool fillable = it.kind == FigureItem::Kind::polygon || it.kind == FigureItem::Kind::circle;
      if (fillable && s.fill_opacity > 0.f) {
        cairo_set_source_rgba(cr, s.fill.r, s.fill.g, s.fill.b, s.fill_opacity);
        cairo_fill_preserve(cr);
      }
      if (s.has_stroke) {
        cairo_set_source_rgb(cr, s.stroke.r, s.stroke.g, s.stroke.b);
        cairo_set_line_width(cr, s.stroke_width);
        const double dash[2] = {3.0 * s.stroke_width, 2.0 * s.stroke_width};
        cairo_set_dash(cr, dash, s.dashed ? 2 : 0, 0);
        cairo_stroke(cr);
      }
      cairo_new_path(cr);
    }
  cairo_select_font_face(cr, "sans-serif", CAIRO_FONT_SLANT_NORMAL, CAIRO_FONT_WEIGHT_NORMAL);
  cairo_set_font_size(cr, kCaptionPoints);
  cairo_set_source_rgb(cr, 0.1, 0.1, 0.12);
  for (size_t i = 0; i < f.caption.size(); ++i) {
    cairo_move_to(cr, 6.0, page.picture_height + 18.0 + 16.0 * double(i));
    cairo_show_text(cr, f.caption[i].c_str());
  }
}

cairo_status_t write_to_stream(void* closure, const unsigned char* data, unsigned int length) {
  static_cast<std::ostream*>(closure)->write(reinterpret_cast<const char*>(data), std::streamsize(length));
  return static_cast<std::ostream*>(closure)->good() ? CAIRO_STATUS_SUCCESS : CAIRO_STATUS_WRITE_ERROR;
}

bool ends_with(const std::string& s, const std::string& tail) {
  return s.size() >= tail.size() && s.compare(s.size() - tail.size(), tail.size(), tail) == 0;
}

}  // namespace

bool is_figure_path(const std::string& path) {
  return ends_with(path, ".svg") || ends_with(path, ".pdf") || ends_with(path, ".png");
}

std::string figure_svg(const Figure& f, int width, bool standalone) {
  const Page page(f, width);
  std::ostringstream out;
  if (standalone) out << "<?xml version=\"1.0\" encoding=\"UTF-8\"?>\n";
  out << "<svg xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(page.width) << "\" height=\""
      << num(page.height) << "\" viewBox=\"0 0 " << num(page.width) << " " << num(page.height) << "\">\n";
  if (standalone) out << "<rect id=\"background\" width=\"100%\" height=\"100%\" fill=\"#ffffff\"/>\n";
  for (const FigureLayer& layer : f.layers) {
    out << "<g id=\"" << xml_escape(layer.name) << "\" stroke-linecap=\"round\" stroke-linejoin=\"round\">\n";
    for (const FigureItem& it : layer.items) {
      const std::string cls = it.css.empty() ? "" : " class=\"" + xml_escape(it.css) + "\"";
      switch (it.kind) {
        case FigureItem::Kind::line: {
          const glm::vec2 a = page(it.points[0]), b = page(it.points[1]);
          out << "  <line" << cls << " x1=\"" << num(a.x) << "\" y1=\"" << num(a.y) << "\" x2=\"" << num(b.x)
              << "\" y2=\"" << num(b.y) << "\"" << svg_style(it.style, false) << "/>\n";
          break;
        }
        case FigureItem::Kind::polyline:
          out << "  <polyline" << cls << " points=\"" << svg_points(page, it.points) << "\""
              << svg_style(it.style, false) << "/>\n";
          break;
        case FigureItem::Kind::polygon:
          out << "  <polygon" << cls << " points=\"" << svg_points(page, it.points) << "\""
              << svg_style(it.style, true) << "/>\n";
          break;
        case FigureItem::Kind::circle: {
          const glm::vec2 c = page(it.points[0]);
          out << "  <circle" << cls << " cx=\"" << num(c.x) << "\" cy=\"" << num(c.y) << "\" r=\""
              << num(it.radius * page.scale) << "\"" << svg_style(it.style, true) << "/>\n";
          break;
        }
        case FigureItem::Kind::text: {
          const glm::vec2 p = page(it.points[0]);
          out << "  <text" << cls << " x=\"" << num(p.x) << "\" y=\"" << num(p.y + 0.35f * it.radius)
              << "\" font-size=\"" << num(it.radius)
              << "\" font-family=\"sans-serif\" text-anchor=\"middle\" fill=\"" << rgb(it.style.fill)
              << "\" stroke=\"none\">" << xml_escape(it.text) << "</text>\n";
          break;
        }
      }
    }
    out << "</g>\n";
  }
  if (!f.caption.empty()) {
    out << "<g id=\"caption\" font-family=\"sans-serif\" font-size=\"" << num(kCaptionPoints)
        << "\" fill=\"#1a1a1f\">\n";
    for (size_t i = 0; i < f.caption.size(); ++i)
      out << "  <text x=\"6\" y=\"" << num(page.picture_height + 18.f + 16.f * float(i)) << "\">"
          << xml_escape(f.caption[i]) << "</text>\n";
    out << "</g>\n";
  }
  out << "</svg>\n";
  return out.str();
}

void write_figure(const std::string& path, const Figure& f, int width) {
  if (width < 16 || width > 16384) throw InputError("", 0, "--width must be 16..16384");
  if (ends_with(path, ".svg")) {
    const std::string text = figure_svg(f, width);
    write_file_atomically(path, [&](std::ostream& out) { out << text; });
    return;
  }
  if (!is_figure_path(path))
    throw InputError("", 0, "-o " + path + ": a figure is written as .svg, .pdf or .png");
  const bool pdf = ends_with(path, ".pdf");
  const Page page(f, width);
  write_file_atomically(path, [&](std::ostream& out) {
    cairo_surface_t* surface =
        pdf ? cairo_pdf_surface_create_for_stream(write_to_stream, &out, page.width, page.height)
            : cairo_image_surface_create(CAIRO_FORMAT_RGB24, int(page.width), int(page.height));
    cairo_t* cr = cairo_create(surface);
    draw_cairo(cr, f, page);
    cairo_destroy(cr);
    cairo_status_t status = CAIRO_STATUS_SUCCESS;
    if (pdf)
      cairo_surface_finish(surface);
    else
      status = cairo_surface_write_to_png_stream(surface, write_to_stream, &out);
    if (status == CAIRO_STATUS_SUCCESS) status = cairo_surface_status(surface);
    cairo_surface_destroy(surface);
    if (status != CAIRO_STATUS_SUCCESS)
      throw InputError(path, 0, std::string("cannot draw the figure: ") + cairo_status_to_string(status));
  });
}

}  // namespace raystep
