// A figure written as SVG (hand-written: text as <text>, one <g id=...> per layer, a class on each item, so
// that an instructor can restyle it), PDF or PNG (drawn by cairo), by the file's extension; atomically.
#pragma once

#include <string>

#include "raystep/figure/figure.h"

namespace raystep {

// The SVG document of the figure, `width` points wide (the height follows the figure's aspect). Not
// standalone: the <svg> element alone, transparent, for a page that stacks several (the browser player).
std::string figure_svg(const Figure& figure, int width, bool standalone = true);
// True for a path a figure can be written to: .svg, .pdf or .png.
bool is_figure_path(const std::string& path);
// .svg, .pdf or .png (width in pixels for PNG, points otherwise); InputError("", 0, ...) for another.
void write_figure(const std::string& path, const Figure& figure, int width);

}  // namespace raystep
