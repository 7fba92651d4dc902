// gnuplot driver; see gnuplot.hpp. POSIX (mkdtemp, posix_spawnp, waitpid).
#include "report/gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <regex>
#include <stdexcept>
#include <string>
#include <system_error>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

extern char** environ;

namespace shudder::report {
namespace {

namespace fs = std::filesystem;

// Colour-blind-friendly palette (matplotlib "tab10" order).
constexpr const char* kPalette[] = {"#1f77b4", "#d62728", "#2ca02c", "#ff7f0e", "#9467bd",
                                    "#8c564b", "#e377c2", "#7f7f7f", "#bcbd22", "#17becf"};
constexpr int kPaletteSize = static_cast<int>(std::size(kPalette));

/// A gnuplot single-quoted string literal ('' stands for a quote; no line breaks).
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (char c : s) {
    if (c == '\'')
      out += "''";
    else if (c == '\n' || c == '\r')
      out += ' ';
    else
      out += c;
  }
  return out + "'";
}

/// A gnuplot string expression for text with line breaks: the lines quoted, joined by "\n".
std::string multiline_quoted(const std::string& s) {
  std::string out;
  std::size_t from = 0;
  for (;;) {
    const std::size_t nl = s.find('\n', from);
    out += quoted(s.substr(from, nl == std::string::npos ? std::string::npos : nl - from));
    if (nl == std::string::npos) return out;
    out += ".\"\\n\".";
    from = nl + 1;
  }
}

/// Removes its directory (and contents) when it goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "shudder-plot-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error(std::string("cannot create a temporary directory for gnuplot: ") + std::strerror(errno));
    path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

/// Characters (UTF-8 code points) in `s`.
std::size_t utf8_length(const std::string& s) {
  const auto starts_a_character = [](char c) { return (static_cast<unsigned char>(c) & 0xC0) != 0x80; };
  return static_cast<std::size_t>(std::count_if(s.begin(), s.end(), starts_a_character));
}

void check_series(const Series& s) {
  if (s.x.size() != s.y.size())
    throw std::invalid_argument("plot series '" + s.label + "': x has " + std::to_string(s.x.size()) +
                                " values, y has " + std::to_string(s.y.size()));
  if (s.x.empty()) throw std::invalid_argument("plot series '" + s.label + "' has no points");
}

/// One gnuplot index block per series (blocks separated by two blank lines); a non-finite
/// point becomes a single blank line, which breaks the curve there.
void write_data(const fs::path& file, const Plot& plot) {
  std::ofstream out(file);
  char line[64];
  const auto block = [&](const Series& s) {
    for (std::size_t i = 0; i < s.x.size(); ++i) {
      if (!std::isfinite(s.x[i]) || !std::isfinite(s.y[i])) {
        out << "\n";
        continue;
      }
      std::snprintf(line, sizeof line, "%.10g %.10g\n", s.x[i], s.y[i]);
      out << line;
    }
    out << "\n\n";
  };
  for (const auto& s : plot.series) block(s);
  for (const auto& s : plot.series_y2) block(s);
  if (!out.flush()) throw std::runtime_error("cannot write gnuplot data file " + file.string());
}

/// The map as "x y value" lines, one block per x (blank line between blocks); NaN for
/// non-finite values, which gnuplot leaves unpainted.
void write_map_data(const fs::path& file, const ColorMap& map) {
  std::ofstream out(file);
  char line[96];
  const std::size_t ny = map.y.size();
  for (std::size_t i = 0; i < map.x.size(); ++i) {
    for (std::size_t j = 0; j < ny; ++j) {
      const double v = map.values[i * ny + j];
      if (std::isfinite(v))
        std::snprintf(line, sizeof line, "%.10g %.10g %.10g\n", map.x[i], map.y[j], v);
      else
        std::snprintf(line, sizeof line, "%.10g %.10g NaN\n", map.x[i], map.y[j]);
      out << line;
    }
    out << "\n";
  }
  if (!out.flush()) throw std::runtime_error("cannot write gnuplot data file " + file.string());
}

void check_uniform(const std::vector<double>& v, const char* axis) {
  if (v.size() < 2) throw std::invalid_argument(std::string("colour map: the ") + axis + " grid needs >= 2 values");
  const double step = (v.back() - v.front()) / static_cast<double>(v.size() - 1);
  if (!(step > 0) || !std::isfinite(step))
    throw std::invalid_argument(std::string("colour map: the ") + axis + " grid must increase");
  for (std::size_t i = 0; i < v.size(); ++i)
    if (std::abs(v[i] - (v.front() + step * static_cast<double>(i))) > 1e-6 * step)
      throw std::invalid_argument(std::string("colour map: the ") + axis +
                                  " grid must be uniformly spaced (gnuplot `with image`)");
}

void check_map(const ColorMap& map) {
  check_uniform(map.x, "x");
  check_uniform(map.y, "y");
  if (map.values.size() != map.x.size() * map.y.size())
    throw std::invalid_argument("colour map: " + std::to_string(map.values.size()) + " values for a " +
                                std::to_string(map.x.size()) + " x " + std::to_string(map.y.size()) + " grid");
}

/// "[a:b]" of a grid's pixel extent: half a step beyond the first and last points.
std::string pixel_range(const std::vector<double>& v) {
  const double half = 0.5 * (v.back() - v.front()) / static_cast<double>(v.size() - 1);
  char buf[80];
  std::snprintf(buf, sizeof buf, "[%.10g:%.10g]", v.front() - half, v.back() + half);
  return buf;
}

/// "[lo:hi]" in whole decades around the positive y values, at most 8 decades under the
/// largest (a log axis would otherwise stretch to round-off floors); "[*:*]" if none.
std::string log_range(const std::vector<Series>& all) {
  double lo = INFINITY, hi = 0.0;
  for (const auto& v : all)
    for (double y : v.y)
      if (std::isfinite(y) && y > 0) lo = std::min(lo, y), hi = std::max(hi, y);
  if (!(hi > 0)) return "[*:*]";
  lo = std::max(lo, hi * 1e-8);
  char buf[80];
  std::snprintf(buf, sizeof buf, "[%.10g:%.10g]", std::pow(10.0, std::floor(std::log10(lo))),
                std::pow(10.0, std::ceil(std::log10(hi) + 1e-9)));
  return buf;
}

/// The colour map's settings: grey background (shows through unpainted pixels), palette,
/// colour range and bar label.
void map_settings(std::ostringstream& s, const ColorMap& map) {
  double lo = map.min, hi = map.max;
  if (std::isnan(lo) || std::isnan(hi)) {
    double dlo = INFINITY, dhi = -INFINITY;
    for (double v : map.values)
      if (std::isfinite(v)) dlo = std::min(dlo, v), dhi = std::max(dhi, v);
    if (!(dlo <= dhi)) dlo = -1.0, dhi = 1.0;  // nothing finite: any range
    // A signed quantity's range always includes 0, so white means 0 on every map.
    if (map.diverging) dlo = std::min(dlo, 0.0), dhi = std::max(dhi, 0.0);
    if (std::isnan(lo)) lo = dlo;
    if (std::isnan(hi)) hi = dhi;
  }
  if (!(hi > lo)) {
    const double pad = std::max(1e-12, 1e-3 * std::abs(hi));
    lo -= pad;
    hi += pad;
  }
  char buf[256];
  s << "set object 1 rectangle from graph 0,0 to graph 1,1 behind fillcolor rgb '#c8c8c8' "
       "fillstyle solid 1.0 noborder\n";
  if (map.diverging && lo < 0 && hi > 0) {
    std::snprintf(buf, sizeof buf, "set palette defined (%.10g '#2166ac', 0 '#f7f7f7', %.10g '#b2182b')\n", lo, hi);
    s << buf;
  } else if (map.diverging && lo >= 0) {
    s << "set palette defined (0 '#f7f7f7', 1 '#b2182b')\n";
  } else if (map.diverging) {
    s << "set palette defined (0 '#2166ac', 1 '#f7f7f7')\n";
  } else {
    s << "set palette defined (0 '#440154', 0.25 '#3b528b', 0.5 '#21908d', 0.75 '#5dc963', "
         "1 '#fde725')\n";
  }
  std::snprintf(buf, sizeof buf, "set cbrange [%.10g:%.10g]\n", lo, hi);
  s << buf << "set cblabel " << quoted(map.label) << "\n"
    << "set colorbox\nset cbtics out\n";
}

/// "[lo:hi]" spanning the finite y values with 5 % headroom either side, so no curve runs
/// along a border (gnuplot's `set offsets` covers only the left axis); "[*:*]" if none.
std::string padded_range(const std::vector<Series>& all) {
  double lo = INFINITY, hi = -INFINITY;
  for (const auto& v : all)
    for (double y : v.y)
      if (std::isfinite(y)) lo = std::min(lo, y), hi = std::max(hi, y);
  if (!(lo <= hi)) return "[*:*]";
  const double pad = hi > lo ? 0.05 * (hi - lo) : std::max(1.0, 0.05 * std::abs(hi));
  char buf[80];
  std::snprintf(buf, sizeof buf, "[%.10g:%.10g]", lo - pad, hi + pad);
  return buf;
}

/// The figure's panels row by row.
std::vector<const Plot*> multiplot_panels(const MultiPlot& figure) {
  std::vector<const Plot*> out;
  for (const auto& row : figure.rows)
    for (const auto& p : row) out.push_back(&p);
  return out;
}

/// Relative height of row `r` (1 where row_heights gives none).
double row_height(const MultiPlot& figure, std::size_t r) {
  return r < figure.row_heights.size() && figure.row_heights[r] > 0 ? figure.row_heights[r] : 1.0;
}

/// The terminal for `svg` or PNG at the figure's size, writing to `output`.
void terminal_text(std::ostringstream& s, int width_px, int height_px, bool svg, const std::string& output) {
  const std::string size = std::to_string(width_px) + "," + std::to_string(height_px);
  s << "set encoding utf8\n";
  if (svg) {
    s << "set terminal svg size " << size << " font 'sans,13' noenhanced background rgb 'white'\n";
  } else {
    s << "if (strstrt(GPVAL_TERMINALS, 'pngcairo') > 0) {\n"
      << "  set terminal pngcairo size " << size << " font 'sans,11' noenhanced\n"
      << "} else {\n"
      << "  set terminal png size " << size << " noenhanced\n"
      << "}\n";
  }
  s << "set output " << quoted(output) << "\n";
}

/// One panel's settings and plot command (its title, axes, legend, labels, curves, map).
void panel_text(std::ostringstream& s, const Plot& plot, const fs::path& data, const fs::path& map_data) {
  // Legend entries; two columns unless an entry is long (> 40 characters), which would widen
  // the legend past the plot.
  std::size_t entries = 0, longest = 0;
  for (const auto* group : {&plot.series, &plot.series_y2})
    for (const auto& v : *group) {
      if (v.label.empty()) continue;
      ++entries;
      longest = std::max(longest, utf8_length(v.label));
    }
  const std::size_t columns = longest > 40 ? 1 : 2;
  if (!plot.title.empty()) s << "set title " << quoted(plot.title) << "\n";
  s << "set xlabel " << quoted(plot.xlabel) << "\n"
    << "set ylabel " << quoted(plot.ylabel) << "\n"
    << "set grid xtics ytics lc rgb '#d0d0d0' lt 1\n"
    // Legend below the axes (it can never hide a curve), in at most two columns, with a
    // bottom margin reserved for tic labels, x label and legend rows so they do not collide.
    << "set key below horizontal center box Left reverse maxcols " << columns << " spacing 1.2 width 2\n"
    << "set bmargin " << 5 + 1.3 * ((entries + columns - 1) / columns) << "\n"
    << (entries == 0 ? "unset key\n" : "") << "set border 3\nset xtics nomirror out\nset ytics nomirror out\n"
    << "set autoscale xfixmin\nset autoscale xfixmax\n";
  const bool map = !plot.map.empty();
  if (map) {
    map_settings(s, plot.map);
    s << "set xrange " << pixel_range(plot.map.x) << "\n"
      << "set yrange " << pixel_range(plot.map.y) << "\n";
  } else if (plot.log_y) {
    s << "set logscale y 10\nset format y '%g'\nset yrange " << log_range(plot.series) << "\n";
  } else {
    s << "set yrange " << padded_range(plot.series) << "\n";
  }
  if (!std::isnan(plot.x_min) || !std::isnan(plot.x_max)) {
    // An open end (NaN) stays with gnuplot's autoscale ("*").
    const auto end = [](double v) {
      char buf[32];
      std::snprintf(buf, sizeof buf, "%.10g", v);
      return std::isnan(v) ? std::string("*") : std::string(buf);
    };
    s << "set xrange [" << end(plot.x_min) << ":" << end(plot.x_max) << "]\n";
  }
  if (!plot.labels.empty()) s << "set style textbox opaque fillcolor rgb 'white' noborder\n";
  int label_id = 1;
  for (const auto& l : plot.labels) {
    char buf[96];
    std::snprintf(buf, sizeof buf, " at %.10g,%.10g offset character 1,0.8 front boxed\n", l.x, l.y);
    s << "set label " << label_id++ << " " << multiline_quoted(l.text) << buf;
  }
  if (!plot.series_y2.empty()) {
    s << "set border 11\nset y2tics nomirror out\nset y2label " << quoted(plot.y2label) << "\n"
      << "set y2range " << padded_range(plot.series_y2) << "\n";
  }
  int next_color = 0;
  std::string sep = "plot ";
  int index = 0;
  if (map) {
    s << sep << quoted(map_data.string()) << " using 1:2:3 with image notitle";
    sep = ", \\\n     ";
  }
  const auto entry = [&](const Series& v, const char* axes) {
    const int c = v.color >= 0 ? v.color : next_color++;
    const std::string color = v.rgb.empty() ? kPalette[c % kPaletteSize] : v.rgb;
    s << sep << quoted(data.string()) << " index " << index++ << " using 1:2 axes " << axes;
    if (v.style == SeriesStyle::kPoints)
      s << " with points pt " << v.point_type << " ps " << v.point_size;
    else
      s << (v.style == SeriesStyle::kLinesPoints ? " with linespoints" : " with lines") << " lw " << v.line_width
        << " dt "
        << (v.dash_type > 0 ? v.dash_type
            : v.dashed      ? 2
                            : 1);
    if (v.style == SeriesStyle::kLinesPoints) {
      s << " pt " << v.point_type << " ps " << v.point_size;
      if (v.point_interval > 0) s << " pi " << v.point_interval;
    }
    s << " lc rgb '" << color << "' ";
    if (v.label.empty())
      s << "notitle";
    else
      s << "title " << quoted(v.label);
    sep = ", \\\n     ";
  };
  for (const auto& v : plot.series) entry(v, "x1y1");
  for (const auto& v : plot.series_y2) entry(v, "x1y2");
  s << "\n";
}

/// The whole script: one panel as a plain plot; several as a multiplot, each panel placed by
/// origin and size (rows top to bottom, the row's panels side by side at equal widths), with
/// fixed left and right margins so the time axes of stacked panels line up.
std::string script_text(const MultiPlot& figure, bool svg, const std::string& output, const std::vector<fs::path>& data,
                        const std::vector<fs::path>& map_data) {
  std::ostringstream s;
  terminal_text(s, figure.width_px, figure.height_px, svg, output);
  const std::vector<const Plot*> panels = multiplot_panels(figure);
  if (panels.size() == 1 && figure.title.empty()) {
    panel_text(s, *panels.front(), data.front(), map_data.front());
  } else {
    bool right_axis = false;
    for (const Plot* p : panels) right_axis = right_axis || !p->series_y2.empty() || !p->map.empty();
    // The figure's title takes a band at the top: 3 text lines' worth of the height.
    const double top = figure.title.empty() ? 1.0 : 1.0 - std::min(0.12, 3.0 * 18.0 / figure.height_px);
    if (!figure.title.empty())
      s << "set multiplot title " << quoted(figure.title) << "\n";
    else
      s << "set multiplot\n";
    double total = 0.0;
    for (std::size_t r = 0; r < figure.rows.size(); ++r) total += row_height(figure, r);
    double y = top;
    std::size_t k = 0;
    for (std::size_t r = 0; r < figure.rows.size(); ++r) {
      const double h = top * row_height(figure, r) / total;
      y -= h;
      const auto& row = figure.rows[r];
      for (std::size_t c = 0; c < row.size(); ++c, ++k) {
        char buf[160];
        const double w = 1.0 / static_cast<double>(row.size());
        std::snprintf(buf, sizeof buf, "set origin %.6f,%.6f\nset size %.6f,%.6f\n", w * static_cast<double>(c),
                      std::max(0.0, y), w, h);
        s << "reset\nset encoding utf8\n" << buf << "set lmargin 11\nset rmargin " << (right_axis ? 11 : 4) << "\n";
        panel_text(s, row[c], data[k], map_data[k]);
      }
    }
    s << "unset multiplot\n";
  }
  s << "set output\n";
  return s.str();
}

/// Runs `gnuplot script` with stdin from /dev/null and stdout+stderr into `log`.
/// Returns the exit status; throws std::runtime_error if gnuplot cannot be started.
int run_gnuplot(const fs::path& script, const fs::path& log) {
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 0, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 1, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&fa, 1, 2);
  std::string prog = "gnuplot", arg = script.string();
  char* argv[] = {prog.data(), arg.data(), nullptr};
  pid_t pid = 0;
  const int err = ::posix_spawnp(&pid, "gnuplot", &fa, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&fa);
  if (err != 0)
    throw std::runtime_error(std::string("cannot run gnuplot: ") + std::strerror(err) +
                             "; install gnuplot (Debian: gnuplot-nox) and put it on PATH");
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0) {
    if (errno != EINTR) throw std::runtime_error("waiting for gnuplot failed");
  }
  if (WIFEXITED(status) && WEXITSTATUS(status) == 127)
    throw std::runtime_error("gnuplot not found; install gnuplot (Debian: gnuplot-nox)");
  return WIFEXITED(status) ? WEXITSTATUS(status) : 128 + WTERMSIG(status);
}

// gnuplot's own cause, without our script: gnuplot echoes the offending script line and a
// caret, then writes `"FILE" line N: MESSAGE`; the first such MESSAGE that is not a warning is
// the cause (else the first warning). "" if none.
std::string gnuplot_cause(const fs::path& log) {
  std::ifstream in(log);
  const std::regex located(R"re(line [0-9]+: *(.*\S))re");
  std::smatch m;
  std::string warning;
  for (std::string line; std::getline(in, line);) {
    if (!std::regex_search(line, m, located)) continue;
    if (m[1].str().rfind("warning:", 0) != 0) return m[1].str();
    if (warning.empty()) warning = m[1].str();
  }
  return warning;
}

void check_plot(const Plot& plot) {
  if (plot.series.empty() && plot.map.empty()) throw std::invalid_argument("plot '" + plot.title + "' has no series");
  if (!plot.map.empty()) {
    check_map(plot.map);
    if (!plot.series_y2.empty())
      throw std::invalid_argument("plot '" + plot.title + "': a colour map takes no right axis");
  }
  for (const auto& s : plot.series) check_series(s);
  for (const auto& s : plot.series_y2) check_series(s);
}

}  // namespace

MultiPlot single_panel(const Plot& plot) {
  MultiPlot f;
  f.caption = plot.caption;
  f.rows = {{plot}};
  f.width_px = plot.width_px;
  f.height_px = plot.height_px;
  return f;
}

void write_plot(const std::string& path, const Plot& plot) { write_multiplot(path, single_panel(plot)); }

void write_multiplot(const std::string& path, const MultiPlot& figure) {
  const std::string ext = fs::path(path).extension().string();
  const bool svg = ext == ".svg";
  if (!svg && ext != ".png")
    throw io::InputError(path, 0, "", "unsupported plot format '" + ext + "'; use .png or .svg");
  const std::vector<const Plot*> panels = multiplot_panels(figure);
  if (panels.empty()) throw std::invalid_argument("figure '" + figure.title + "' has no panels");
  for (const Plot* p : panels) check_plot(*p);
  if (figure.width_px < 100 || figure.height_px < 100)
    throw std::invalid_argument("plot '" + (figure.title.empty() ? panels.front()->title : figure.title) +
                                "': image smaller than 100 px");

  // Claim the temporary output ourselves first: an unwritable destination is the user's
  // problem (io::InputError), not gnuplot's.
  const std::string tmp = io::temp_path_for(path);
  if (!std::ofstream(tmp))
    throw io::InputError(
        path, 0, "",
        std::string("cannot write plot: ") + std::strerror(errno) + "; check the directory exists and is writable");
  try {
    TempDir dir;
    const fs::path script = dir.path / "plot.gp", log = dir.path / "gnuplot.log";
    // One data file (and one map file) per panel: data.txt, map.txt for the first.
    std::vector<fs::path> data, map_data;
    for (std::size_t k = 0; k < panels.size(); ++k) {
      const std::string suffix = k == 0 ? "" : "_" + std::to_string(k);
      data.push_back(dir.path / ("data" + suffix + ".txt"));
      map_data.push_back(dir.path / ("map" + suffix + ".txt"));
      write_data(data.back(), *panels[k]);
      if (!panels[k]->map.empty()) write_map_data(map_data.back(), panels[k]->map);
    }
    {
      std::ofstream out(script);
      out << script_text(figure, svg, tmp, data, map_data);
      if (!out.flush()) throw std::runtime_error("cannot write gnuplot script " + script.string());
    }
    const int status = run_gnuplot(script, log);
    std::error_code ec;
    if (status != 0 || fs::file_size(tmp, ec) == 0 || ec) {
      const std::string cause = gnuplot_cause(log);
      throw std::runtime_error(
          "gnuplot could not draw " + path + ": " +
          (cause.empty() ? "it exited with status " + std::to_string(status) + " without writing the image" : cause));
    }
  } catch (...) {
    io::discard_temp_file(tmp);
    throw;
  }
  io::commit_temp_file(tmp, path);
}

bool gnuplot_on_path() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string d;
  while (std::getline(dirs, d, ':')) {
    const std::string exe = (d.empty() ? std::string(".") : d) + "/gnuplot";
    if (::access(exe.c_str(), X_OK) == 0) return true;
  }
  return false;
}

}  // namespace shudder::report
