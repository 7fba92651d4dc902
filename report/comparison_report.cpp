#include "report/comparison_report.hpp"

#include <unistd.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <sstream>

#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "report/gnuplot.hpp"
#include "report/plots.hpp"
#include "report/text_format.hpp"

namespace shudder::report {

namespace {

std::string comparison_number(const char* fmt, double x) { return number(x, fmt); }

}  // namespace

std::string comparison_summary(const studies::Comparison& c) {
  std::ostringstream o;
  o << "Fluids compared at " << comparison_number("%.0f", c.load_N)
    << " N (indices: docs/screening.md; equal viscosity " << comparison_number("%.3g", c.viscosity_cSt)
    << " cSt as Paper E Table 5)\n";
  std::vector<const studies::FluidComparison*> sorted;
  for (const auto& fl : c.fluids) sorted.push_back(&fl);
  std::stable_sort(sorted.begin(), sorted.end(), [](auto a, auto b) { return a->rank < b->rank; });

  // The table's columns after rank, fluid and verdict: header and one cell per fluid (sorted).
  struct Column {
    std::string header;
    std::vector<std::string> cells;
  };
  std::vector<Column> cols;
  const auto column = [&](std::string header, auto cell) {
    Column col{std::move(header), {}};
    for (const auto* fl : sorted) col.cells.push_back(cell(*fl));
    cols.push_back(std::move(col));
  };
  column("breakaway", [](const auto& fl) { return comparison_number("%.3f", fl.breakaway_ratio); });
  column("clutch margin", [](const auto& fl) {
    return std::isfinite(fl.worst_margin_per_s) ? comparison_number("%.3g/s", fl.worst_margin_per_s)
                                                : std::string("n/a");
  });
  for (std::size_t k = 0; k < c.temps_C.size(); ++k)
    column("mu1/mu50@" + comparison_number("%.4g", c.temps_C[k]) + "°C", [&](const auto& fl) {
      return k < fl.screen.indices.size()
                 ? comparison_number("%.4f", fl.screen.indices[k][analysis::Index::kMu1OverMu50].value)
                 : std::string("n/a");
    });
  column("T(" + comparison_number("%.3g", c.viscosity_cSt) + " cSt)", [](const auto& fl) {
    return std::isfinite(fl.equal_viscosity_temp_C) ? comparison_number("%.1f °C", fl.equal_viscosity_temp_C)
                                                    : std::string("n/a");
  });
  column("mu1/mu50 there", [](const auto& fl) {
    return comparison_number("%.4f", fl.at_equal_viscosity[analysis::Index::kMu1OverMu50].value);
  });
  // A column with the same value for every fluid says nothing about the fluids: it is left out
  // and named once below the table.
  std::string equal;
  if (sorted.size() > 1)
    for (auto it = cols.begin(); it != cols.end();) {
      if (std::all_of(it->cells.begin(), it->cells.end(), [&](const auto& x) { return x == it->cells.front(); })) {
        equal += (equal.empty() ? "" : ", ") + it->header + " " + it->cells.front();
        it = cols.erase(it);
      } else {
        ++it;
      }
    }
  // Display width: UTF-8 continuation bytes take no column (°C is 2 bytes, 1 column).
  const auto width = [](const std::string& x) {
    return static_cast<std::size_t>(std::count_if(x.begin(), x.end(), [](char ch) { return (ch & 0xC0) != 0x80; }));
  };
  const auto right = [&](const std::string& x, std::size_t w) {
    return std::string(w > width(x) ? w - width(x) : 0, ' ') + x;
  };
  std::vector<std::size_t> w;
  for (const auto& col : cols) {
    std::size_t m = width(col.header);
    for (const auto& cell : col.cells) m = std::max(m, width(cell));
    w.push_back(m);
  }
  o << "  rank  fluid                     verdict   ";
  for (std::size_t k = 0; k < cols.size(); ++k) o << "  " << right(cols[k].header, w[k]);
  o << "\n";
  for (std::size_t r = 0; r < sorted.size(); ++r) {
    const auto* fl = sorted[r];
    char name[32];
    std::snprintf(name, sizeof name, "%-24.24s", fl->name.c_str());
    char verdict[16];
    std::snprintf(verdict, sizeof verdict, "%-10s", analysis::risk_level_name(fl->screen.verdict.level));
    o << "  " << comparison_number("%4.0f", fl->rank) << "  " << name << "  " << verdict;
    for (std::size_t k = 0; k < cols.size(); ++k) o << "  " << right(cols[k].cells[r], w[k]);
    o << "\n";
  }
  if (!equal.empty()) o << "The same for every fluid, so left out of the table: " << equal << "\n";
  o << "Ranking, best first: verdict (LOW RISK, CAUTION, RISK, NOT JUDGED), then the largest clutch-mode "
       "margin inside the law's data (lower is better), the largest mu1/mu50 (lower is better), the "
       "breakaway ratio (Paper F: lower is better)\n";
  for (const auto& sep : c.separations) o << "  " << sep << "\n";
  for (const auto* fl : sorted) o << "  " << fl->name << ": " << fl->screen.verdict.text << "\n";
  return o.str();
}

Report write_comparison_report(const std::string& dir, const studies::Comparison& c,
                               const std::vector<std::pair<std::string, clutch::Fluid>>& fluids,
                               const std::string& summary_text, const std::vector<std::string>& data_files) {
  namespace fs = std::filesystem;
  make_report_dir(dir);
  Report report;
  const auto path = [&](const std::string& file) { return (fs::path(dir) / file).string(); };
  io::write_text_file_atomically(path("summary.txt"), summary_text);
  report.files.push_back(path("summary.txt"));
  const bool gnuplot = gnuplot_on_path();
  for (double t : c.temps_C) {
    const std::string file = "mu_v_" + comparison_number("%.4g", t) + "C.png";
    if (!gnuplot) {
      report.skipped.push_back(file + ": " + kGnuplotMissing);
      continue;
    }
    Plot p;
    p.title = "mu against slip speed at " + comparison_number("%.4g", t) + " °C, " +
              comparison_number("%.0f", c.load_N) + " N";
    p.xlabel = "slip speed [rpm]";
    p.ylabel = "mu [-]";
    p.caption = "Each fluid's friction coefficient against slip speed (1–120 rpm) at " + comparison_number("%.4g", t) +
                " °C and " + comparison_number("%.0f", c.load_N) +
                " N: a falling curve is the negative slope that feeds shudder.";
    for (const auto& [file_name, fluid] : fluids) {
      Series s;
      s.label = fluid.name;
      for (double rpm = 1.0; rpm <= 120.0; rpm += 1.0) {
        s.x.push_back(rpm);
        s.y.push_back(fluid.friction->mu(analysis::rpm_to_mm_s(rpm), t, c.load_N));
      }
      p.series.push_back(s);
    }
    add_report_plot(report, dir, file, p);
  }
  ReportIndex index;
  index.title = "shudder compare";
  index.summary = summary_text;
  index.data_files = data_files;
  write_report_index(dir, index, report);
  return report;
}

}  // namespace shudder::report
