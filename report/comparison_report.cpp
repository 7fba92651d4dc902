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

std::string comparison_summary(const rig_models::Comparison& c) {
  std::ostringstream o;
  o << "Fluids compared at " << comparison_number("%.0f", c.load_N) << " N (indices: docs/screening.md; equal viscosity "
    << comparison_number("%.3g", c.viscosity_cSt) << " cSt as Paper E Table 5)\n";
  o << "  rank  fluid                     verdict     breakaway  max margin";
  for (double t : c.temps_C) {
    const std::string h = "mu1/mu50@" + comparison_number("%.4g", t) + "°C";
    o << "  " << std::string(h.size() < 16 ? 16 - h.size() : 0, ' ') << h;  // °C is 2 bytes, 1 column
  }
  o << "  T(" << comparison_number("%.3g", c.viscosity_cSt) << " cSt)  mu1/mu50 there\n";
  std::vector<const rig_models::FluidComparison*> sorted;
  for (const auto& fl : c.fluids) sorted.push_back(&fl);
  std::stable_sort(sorted.begin(), sorted.end(), [](auto a, auto b) { return a->rank < b->rank; });
  for (const auto* fl : sorted) {
    char name[32];
    std::snprintf(name, sizeof name, "%-24.24s", fl->name.c_str());
    o << "  " << comparison_number("%4.0f", fl->rank) << "  " << name << "  ";
    char verdict[16];
    std::snprintf(verdict, sizeof verdict, "%-10s", analysis::risk_level_name(fl->screen.verdict.level));
    o << verdict << "  " << comparison_number("%9.3f", fl->breakaway_ratio) << "  "
      << (std::isfinite(fl->worst_margin_per_s) ? comparison_number("%8.3g/s", fl->worst_margin_per_s) : std::string("   n/a    "));
    for (const auto& at : fl->screen.indices) o << comparison_number("  %14.4f", at[analysis::Index::kMu1OverMu50].value);
    o << (std::isfinite(fl->equal_viscosity_temp_C) ? comparison_number("  %8.1f °C", fl->equal_viscosity_temp_C) : std::string("       n/a  "))
      << comparison_number("  %14.4f", fl->at_equal_viscosity[analysis::Index::kMu1OverMu50].value) << "\n";
  }
  o << "Ranking: verdict, then largest stability margin, largest mu1/mu50, breakaway ratio (Paper F: lower is better)\n";
  for (const auto& s : c.separations) o << "  " << s << "\n";
  for (const auto* fl : sorted) o << "  " << fl->name << ": " << fl->screen.verdict.text << "\n";
  return o.str();
}

Report write_comparison_report(const std::string& dir, const rig_models::Comparison& c,
                               const std::vector<std::pair<std::string, clutch::Fluid>>& fluids,
                               const std::string& summary_text) {
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
    p.title = "mu against slip speed at " + comparison_number("%.4g", t) + " °C, " + comparison_number("%.0f", c.load_N) + " N";
    p.xlabel = "slip speed [rpm]";
    p.ylabel = "mu [-]";
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
  return report;
}

}  // namespace shudder::report
