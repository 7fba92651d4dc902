#pragma once
// Line plots through gnuplot (an external, maintained tool; Debian package gnuplot-nox).
// write_plot() writes the series to a data file and a script in a fresh temporary directory,
// runs `gnuplot` on the script (no shell), and renames the finished image onto `path`, so a
// reader never sees half an image. The format follows the extension: .png -> pngcairo (or
// libgd png when gnuplot lacks cairo), .svg -> svg. Output is date-free: the same plot gives
// the same bytes.
//
// Errors: unsupported extension or unwritable destination -> io::InputError; empty plots or
// series whose x and y differ in length -> std::invalid_argument; gnuplot missing or failing
// -> std::runtime_error quoting gnuplot's own message.

#include <string>
#include <vector>

namespace shudder::io {

struct Series {
  std::string label;           // legend entry, e.g. "torque [Nm]"; empty = no legend entry
  std::vector<double> x, y;    // equal lengths; non-finite values leave a gap in the line
  int color = -1;              // index into a fixed palette; -1 = next colour in order
  bool dashed = false;
};

struct Plot {
  std::string title;
  std::string xlabel, ylabel, y2label;  // include the unit, e.g. "time [s]"
  std::vector<Series> series;           // plotted against the left y axis
  std::vector<Series> series_y2;        // plotted against the right y axis (if any)
  int width_px = 1000, height_px = 600; // image size (SVG: same numbers, in user units)
};

/// Renders `plot` to `path` (.png or .svg). Replaces an existing file.
void write_plot(const std::string& path, const Plot& plot);

}  // namespace shudder::io
