// Plots as PNG, drawn by gnuplot (Debian's gnuplot-nox: a well-kept plotting program that needs no display).
// Each plot is a gnuplot script kept beside its PNG and reading the report's own CSV, so a student can
// restyle a plot and run `gnuplot NAME.gp` again in the report's folder. Without gnuplot the scripts and data
// are still written and the report says, in one line, how to draw them.
#pragma once

#include <string>

namespace raystep::cli {

struct PlotResult {
  bool drawn = false;
  std::string message;  // why not drawn (gnuplot missing, or its first error line)
};

// Writes DIR/NAME.gp (`set terminal pngcairo`, `set output 'NAME.png'`, then body) and runs gnuplot on it in
// DIR; the PNG appears atomically (drawn to a temporary file, then renamed). body refers to data files by
// their names relative to DIR. Throws InputError if the script cannot be written.
PlotResult plot_png(const std::string& dir, const std::string& name, const std::string& body, int width = 960,
                    int height = 640);

// True when gnuplot can be run.
bool gnuplot_available();

}  // namespace raystep::cli
