#pragma once
// Line plots through gnuplot (an external, maintained tool; Debian package gnuplot-nox).
// write_plot() writes the series to a data file and a script in a fresh temporary directory,
// runs `gnuplot` on the script (no shell), and renames the finished image onto `path`, so a
// reader never sees half an image. The format follows the extension: .png -> pngcairo (or
// libgd png when gnuplot lacks cairo), .svg -> svg. Output is date-free: the same plot gives
// the same bytes.
//
// Beyond line plots: point markers, text labels, a logarithmic y axis and a colour map with a
// colour bar under the curves (spectrograms, stability maps).
//
// Several panels in one image (MultiPlot): a time history above a zoomed detail, two quantities
// with their own zeros.
//
// Errors: unsupported extension or unwritable destination -> io::InputError; empty plots,
// series whose x and y differ in length or a malformed colour map -> std::invalid_argument;
// gnuplot missing or failing -> std::runtime_error quoting gnuplot's own message.

#include <cmath>
#include <string>
#include <vector>

namespace shudder::report {

enum class SeriesStyle { kLines, kPoints, kLinesPoints };

struct Series {
  std::string label;         // legend entry, e.g. "torque [Nm]"; empty = no legend entry
  std::vector<double> x, y;  // equal lengths; non-finite values leave a gap in the line
  int color = -1;            // index into a fixed palette; -1 = next colour in order
  bool dashed = false;
  SeriesStyle style = SeriesStyle::kLines;
  int point_type = 7;  // gnuplot point type: 7 filled circle, 6 open circle, 5 filled
                       // square, 9 filled triangle, 2 cross, 1 plus
  double point_size = 1.2;
  double line_width = 2.0;
  std::string rgb = "";    // e.g. "#000000": this colour instead of the palette's
  int dash_type = 0;       // gnuplot dash type (2 dashed, 3 dotted, 4 dash-dot); 0 = by `dashed`
  int point_interval = 0;  // kLinesPoints: a marker every this many points; 0 = every point
};

/// Text at a data position (left axes), drawn above the curves with a small offset.
struct Label {
  double x = 0.0, y = 0.0;
  std::string text;  // '\n' breaks the line
};

/// A colour map drawn under the curves (gnuplot `with image`): one pixel per grid point, a
/// colour bar on the right. The grid must be uniform in x and in y (within 1e-6 of a step).
struct ColorMap {
  std::vector<double> x;        // (n_x) increasing, uniform, >= 2 values
  std::vector<double> y;        // (n_y) increasing, uniform, >= 2 values
  std::vector<double> values;   // (n_x * n_y): value at (x[i], y[j]) is values[i * n_y + j];
                                // non-finite = no pixel (the grey background shows)
  std::string label;            // colour-bar label with the unit
  bool diverging = false;       // blue-white-red with white at 0 (signed quantities such as a
                                // margin; the automatic range then includes 0); otherwise a
                                // sequential (viridis-like) palette
  double min = NAN, max = NAN;  // colour range; NaN = the finite data's range
  bool empty() const { return x.empty(); }
};

struct Plot {
  std::string title;
  std::string caption;                   // what the plot shows, for a report's index.html (not drawn)
  std::string xlabel, ylabel, y2label;   // include the unit, e.g. "time [s]"
  std::vector<Series> series;            // plotted against the left y axis
  std::vector<Series> series_y2;         // plotted against the right y axis (if any)
  int width_px = 1000, height_px = 600;  // image size (SVG: same numbers, in user units)
  bool log_y = false;                    // logarithmic left y axis (non-positive values: gaps)
  double x_min = NAN, x_max = NAN;       // x range; NaN = the data's (or the map's) extent
  std::vector<Label> labels;
  ColorMap map;  // optional; not combined with series_y2
};

/// One image of several panels (gnuplot multiplot): `rows` from top to bottom, a row's panels
/// side by side at equal widths, each with its own title, axes, legend and labels; stacked
/// panels share left and right margins so their x axes line up. A figure of one panel and no
/// title is drawn exactly as write_plot draws that panel.
struct MultiPlot {
  std::string title;                    // above every panel; empty = none
  std::string caption;                  // what the figure shows, for a report's index.html (not drawn)
  std::vector<std::vector<Plot>> rows;  // panels; a panel's own width_px/height_px are ignored
  std::vector<double> row_heights;      // relative heights of the rows; missing = 1
  int width_px = 1000, height_px = 600;
};

/// The figure of `plot` alone (its caption and size).
MultiPlot single_panel(const Plot& plot);

/// Renders `plot` to `path` (.png or .svg). Replaces an existing file.
void write_plot(const std::string& path, const Plot& plot);

/// Renders `figure` to `path` (.png or .svg), through a temporary name and a rename.
void write_multiplot(const std::string& path, const MultiPlot& figure);

/// True when an executable `gnuplot` is on PATH: reports list their plots as skipped without it.
bool gnuplot_on_path();

}  // namespace shudder::report
