// gnuplot driver; see gnuplot.hpp. POSIX (mkdtemp, posix_spawnp, waitpid).
#include "io/gnuplot.hpp"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <sstream>
#include <stdexcept>
#include <system_error>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"

extern char** environ;

namespace shudder::io {
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
    if (c == '\'') out += "''";
    else if (c == '\n' || c == '\r') out += ' ';
    else out += c;
  }
  return out + "'";
}

/// Removes its directory (and contents) when it goes out of scope.
struct TempDir {
  fs::path path;
  TempDir() {
    std::string pattern = (fs::temp_directory_path() / "shudder-plot-XXXXXX").string();
    if (!::mkdtemp(pattern.data()))
      throw std::runtime_error(std::string("cannot create a temporary directory for gnuplot: ") +
                               std::strerror(errno));
    path = pattern;
  }
  ~TempDir() {
    std::error_code ec;
    fs::remove_all(path, ec);
  }
  TempDir(const TempDir&) = delete;
  TempDir& operator=(const TempDir&) = delete;
};

void check_series(const Series& s) {
  if (s.x.size() != s.y.size())
    throw std::invalid_argument("plot series '" + s.label + "': x has " +
                                std::to_string(s.x.size()) + " values, y has " +
                                std::to_string(s.y.size()));
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

std::string script_text(const Plot& plot, bool svg, const std::string& output,
                        const fs::path& data) {
  std::ostringstream s;
  const std::size_t entries = plot.series.size() + plot.series_y2.size();
  const std::string size = std::to_string(plot.width_px) + "," + std::to_string(plot.height_px);
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
  if (!plot.title.empty()) s << "set title " << quoted(plot.title) << "\n";
  s << "set xlabel " << quoted(plot.xlabel) << "\n"
    << "set ylabel " << quoted(plot.ylabel) << "\n"
    << "set grid xtics ytics lc rgb '#d0d0d0' lt 1\n"
    // Legend below the axes (it can never hide a curve), in at most two columns, with a
    // bottom margin reserved for tic labels, x label and legend rows so they do not collide.
    << "set key below horizontal center box Left reverse maxcols 2 spacing 1.2 width 2\n"
    << "set bmargin " << 5 + 1.3 * ((entries + 1) / 2) << "\n"
    << "set border 3\nset xtics nomirror out\nset ytics nomirror out\n"
    << "set autoscale xfixmin\nset autoscale xfixmax\n";
  s << "set yrange " << padded_range(plot.series) << "\n";
  if (!plot.series_y2.empty()) {
    s << "set border 11\nset y2tics nomirror out\nset y2label " << quoted(plot.y2label) << "\n"
      << "set y2range " << padded_range(plot.series_y2) << "\n";
  }
  int next_color = 0;
  std::string sep = "plot ";
  int index = 0;
  const auto entry = [&](const Series& v, const char* axes) {
    const int c = v.color >= 0 ? v.color : next_color++;
    s << sep << quoted(data.string()) << " index " << index++ << " using 1:2 axes " << axes
      << " with lines lw 2 dt " << (v.dashed ? 2 : 1) << " lc rgb '"
      << kPalette[c % kPaletteSize] << "' ";
    if (v.label.empty()) s << "notitle";
    else s << "title " << quoted(v.label);
    sep = ", \\\n     ";
  };
  for (const auto& v : plot.series) entry(v, "x1y1");
  for (const auto& v : plot.series_y2) entry(v, "x1y2");
  s << "\nset output\n";
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

std::string read_tail(const fs::path& file, std::size_t max_chars) {
  std::ifstream in(file);
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  if (text.size() > max_chars) text = "..." + text.substr(text.size() - max_chars);
  while (!text.empty() && (text.back() == '\n' || text.back() == ' ')) text.pop_back();
  return text;
}

}  // namespace

void write_plot(const std::string& path, const Plot& plot) {
  const std::string ext = fs::path(path).extension().string();
  const bool svg = ext == ".svg";
  if (!svg && ext != ".png")
    throw InputError(path, 0, "", "unsupported plot format '" + ext + "'; use .png or .svg");
  if (plot.series.empty()) throw std::invalid_argument("plot '" + plot.title + "' has no series");
  if (plot.width_px < 100 || plot.height_px < 100)
    throw std::invalid_argument("plot '" + plot.title + "': image smaller than 100 px");
  for (const auto& s : plot.series) check_series(s);
  for (const auto& s : plot.series_y2) check_series(s);

  // Claim the temporary output ourselves first: an unwritable destination is the user's
  // problem (InputError), not gnuplot's.
  const std::string tmp = temp_path_for(path);
  if (!std::ofstream(tmp))
    throw InputError(path, 0, "", std::string("cannot write plot: ") + std::strerror(errno) +
                                      "; check the directory exists and is writable");
  try {
    TempDir dir;
    const fs::path data = dir.path / "data.txt", script = dir.path / "plot.gp",
                   log = dir.path / "gnuplot.log";
    write_data(data, plot);
    {
      std::ofstream out(script);
      out << script_text(plot, svg, tmp, data);
      if (!out.flush()) throw std::runtime_error("cannot write gnuplot script " + script.string());
    }
    const int status = run_gnuplot(script, log);
    std::error_code ec;
    if (status != 0 || fs::file_size(tmp, ec) == 0 || ec)
      throw std::runtime_error("gnuplot failed (exit status " + std::to_string(status) +
                               ") writing " + path + ": " + read_tail(log, 600));
  } catch (...) {
    discard_temp_file(tmp);
    throw;
  }
  commit_temp_file(tmp, path);
}

}  // namespace shudder::io
