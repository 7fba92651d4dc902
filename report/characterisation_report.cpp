#include "report/characterisation_report.hpp"

#include <unistd.h>

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

namespace fs = std::filesystem;

namespace {

std::string f(const char* fmt, double x) { return number(x, fmt); }

Plot titled(const std::string& title, const std::string& ylabel) {
  Plot p;
  p.title = title;
  p.xlabel = "sliding speed [mm/s]";
  p.ylabel = ylabel;
  return p;
}

std::string load_tag(double load_N) { return f("%.4g", load_N / 1000.0) + "kN"; }

}  // namespace

std::string characterisation_summary(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                     const std::string& fluid_path) {
  std::ostringstream o;
  int up = 0;
  for (const auto& r : c.used) up += r.direction == analysis::RampDirection::kUp;
  o << "characterise: " << c.used.size() << " ramps used (" << up << " up, " << c.used.size() - std::size_t(up)
    << " down), " << c.rejected.size() << " rejected\n"
    << "  friction radius " << f("%.4g", c.effective_radius_mm) << " mm ("
    << clutch::radius_convention_name(s.conversion.convention())
    << (s.conversion.source.empty() ? "" : ": " + s.conversion.source) << "; recorded in the fluid file), "
    << s.conversion.interfaces << " interface(s), bearing drag mu " << f("%.4g", s.conversion.bearing_drag_mu) << "\n"
    << "  compensation: " << analysis::compensation_name(s.compensation);
  if (s.compensation == analysis::Compensation::kLinear)
    o << " (alpha " << f("%.4g", c.alpha_per_C) << " 1/°C, " << (c.alpha_fitted ? "fitted" : "given") << ")";
  o << "; law: " << analysis::law_name(s.law) << "\n"
    << "  data: " << f("%.4g", c.min_speed_mm_s) << "-" << f("%.4g", c.max_speed_mm_s) << " mm/s, "
    << f("%.4g", c.min_temp_C) << "-" << f("%.4g", c.max_temp_C) << " °C, " << c.loads_N.size() << " load(s) x "
    << c.temps_C.size() << " temperature(s)\n"
    << "  row (kN, °C)   ramps up/down   rms resid   max resid   up-down gap raw -> compensated\n";
  for (const auto& r : c.rows)
    o << "  " << f("%6.3g", r.load_N / 1000.0) << f(" %7.3g", r.temp_C) << "      " << f("%3.0f", r.ramps_up) << "/"
      << f("%-3.0f", r.ramps_down) << "        " << f("%.2e", r.rms_residual) << "    " << f("%.2e", r.max_residual)
      << "    " << f("%.2e", r.up_down_gap_raw) << " -> " << f("%.2e", r.up_down_gap_comp) << "\n";
  for (const auto& w : c.warnings) o << "  warning: " << w << "\n";
  for (std::size_t i = 0; i < c.rejected.size() && i < 5; ++i)
    o << "  rejected: run " << c.rejected[i].run << " " << f("%.3g", c.rejected[i].t_start_s) << "-"
      << f("%.3g", c.rejected[i].t_end_s) << " s: " << c.rejected[i].reason << "\n";
  if (c.rejected.size() > 5) o << "  (" << c.rejected.size() - 5 << " more rejections in the JSON)\n";
  o << "  wrote " << fluid_path << "\n";
  return o.str();
}

std::string breakaway_range(const analysis::BreakawayMeasurement& m) {
  char buf[96];
  std::snprintf(buf, sizeof buf, "%.3f–%.3f", m.min_ratio, m.max_ratio);
  return buf;
}

std::string breakaway_summary(const analysis::BreakawayMeasurement& m, double written_ratio,
                              const std::string& source) {
  std::ostringstream o;
  char buf[256];
  std::snprintf(buf, sizeof buf, "breakaway ratio (mu_s / mu_k(v_min), written): %.4g — ", written_ratio);
  o << buf << source << "\n";
  for (const auto& e : m.events) {
    std::snprintf(buf, sizeof buf,
                  "  start from rest: run %zu at %.3f s, %.2f rpm, %.1f °C, %.4g kN: peak mu %.4f / mu_k %.4f = %.4f\n",
                  e.run + 1, e.t_peak_s, e.speed_rpm, e.temp_C, e.load_N / 1000.0, e.mu_peak, e.mu_kinetic, e.ratio);
    o << buf;
  }
  return o.str();
}

std::string method_comparison_summary(const studies::InverseCharacterisation& r,
                                      const analysis::CharacterisationSettings& sensor_settings) {
  std::ostringstream o;
  const auto& nodes = r.inverse.node_speeds_mm_s;
  const std::size_t mid = nodes.size() / 2;
  o << "methods: sensor (" << analysis::compensation_name(sensor_settings.compensation)
    << " compensation with the temperature channel) vs inverse (the same compensation with the interface\n"
    << "  temperature of the clutch and thermal model, replayed with the runs' inputs and calibrated on their "
       "temperature)\n"
    << "  row (kN, °C)   rms resid sensor / inverse   max resid sensor / inverse   mu at "
    << f("%.3g", r.inverse.node_rpm.front()) << "/" << f("%.3g", r.inverse.node_rpm[mid]) << "/"
    << f("%.3g", r.inverse.node_rpm.back()) << " rpm sensor -> inverse\n";
  for (std::size_t i = 0; i < r.inverse.rows.size() && i < r.sensor.rows.size(); ++i) {
    const auto& a = r.sensor.rows[i];
    const auto& b = r.inverse.rows[i];
    const auto mu = [&](const analysis::Characterisation& c, std::size_t k) {
      return f("%.4f", c.law->mu(nodes[k], b.temp_C, b.load_N));
    };
    o << "  " << f("%6.3g", b.load_N / 1000.0) << f(" %7.3g", b.temp_C) << "      " << f("%.2e", a.rms_residual)
      << " / " << f("%.2e", b.rms_residual) << "          " << f("%.2e", a.max_residual) << " / "
      << f("%.2e", b.max_residual) << "        " << mu(r.sensor, 0) << "/" << mu(r.sensor, mid) << "/"
      << mu(r.sensor, nodes.size() - 1) << " -> " << mu(r.inverse, 0) << "/" << mu(r.inverse, mid) << "/"
      << mu(r.inverse, nodes.size() - 1) << "\n";
  }
  o << "  replayed torque vs measured (rms): sensor law " << f("%.3g", r.torque_rms_sensor_Nm) << " N m, inverse law "
    << f("%.3g", r.torque_rms_Nm) << " N m\n"
    << "  thermal calibration (Paper G eq. 12 oil flow): e " << f("%.4g", r.oil_flow_start.e) << " -> "
    << f("%.4g", r.oil_flow.e) << ", a " << f("%.4g", r.oil_flow_start.a) << " -> " << f("%.4g", r.oil_flow.a)
    << "; temperature rms " << f("%.3g", r.temp_rms_start_C) << " -> " << f("%.3g", r.temp_rms_C) << " °C\n"
    << "  converged after " << r.iterations << " law updates (" << r.replays << " replays of every run), last change "
    << f("%.2g", r.last_change_mu) << " in mu\n";
  return o.str();
}

Report write_characterisation_report(const std::string& dir, const analysis::Characterisation& c,
                                     const std::string& summary_text, const std::vector<std::string>& data_files) {
  make_report_dir(dir);
  Report report;
  const auto path = [&](const std::string& file) { return (fs::path(dir) / file).string(); };
  io::write_text_file_atomically(path("summary.txt"), summary_text);
  report.files.push_back(path("summary.txt"));

  std::vector<std::pair<std::string, Plot>> plots;
  Plot residuals = titled("law - measured mu (binned means)", "residual [-]");
  for (std::size_t il = 0; il < c.loads_N.size(); ++il) {
    const std::string tag = load_tag(c.loads_N[il]);
    Plot mu_v = titled("measured (points, compensated) and fitted (lines) mu at " + tag, "mu [-]");
    Plot ud = titled("up (o) / down (x) ramps at " + tag + ": raw dashed, compensated solid", "mu [-]");
    int colour = 0;
    for (const auto& r : c.rows) {
      if (r.i_load != il) continue;
      const std::string t = f("%.3g °C", r.temp_C);
      Series pts{t + " measured", r.bin_speed_mm_s, r.bin_mu, colour, false, SeriesStyle::kPoints, 7, 0.8};
      std::vector<double> vf, mf, res;
      for (int k = 0; k <= 80; ++k) {
        const double v = c.min_speed_mm_s * std::pow(c.max_speed_mm_s / c.min_speed_mm_s, k / 80.0);
        vf.push_back(v);
        mf.push_back(c.law->mu(v, r.temp_C, r.load_N));
      }
      for (std::size_t b = 0; b < r.bin_mu.size(); ++b)
        res.push_back(c.law->mu(r.bin_speed_mm_s[b], r.temp_C, r.load_N) - r.bin_mu[b]);
      mu_v.series.push_back(pts);
      mu_v.series.push_back({"", vf, mf, colour});
      residuals.series.push_back(
          {tag + " " + t, r.bin_speed_mm_s, res, colour, false, SeriesStyle::kLinesPoints, 7, 0.6, 1.0});
      ud.series.push_back(
          {t + " up raw", c.node_speeds_mm_s, r.up_raw, colour, true, SeriesStyle::kLinesPoints, 6, 0.8, 1.0});
      ud.series.push_back({"", c.node_speeds_mm_s, r.down_raw, colour, true, SeriesStyle::kLinesPoints, 2, 0.8, 1.0});
      ud.series.push_back({"", c.node_speeds_mm_s, r.up_comp, colour, false, SeriesStyle::kLinesPoints, 6, 0.8, 1.5});
      ud.series.push_back({"", c.node_speeds_mm_s, r.down_comp, colour, false, SeriesStyle::kLinesPoints, 2, 0.8, 1.5});
      colour = (colour + 1) % 8;
    }
    mu_v.caption = "Friction coefficient against sliding speed at " + tag +
                   ": the measured ramps' binned means (points, temperature-compensated) and the fitted law "
                   "(lines), one colour per row temperature.";
    ud.caption = "Up (circles) and down (crosses) ramps' node means at " + tag +
                 ": raw dashed, temperature-compensated solid; the gap between them is what compensation removes.";
    plots.emplace_back("mu_v_" + tag + ".png", mu_v);
    plots.emplace_back("up_down_" + tag + ".png", ud);
  }
  residuals.caption = "Fitted law minus measured friction coefficient (binned means) against sliding speed, per row.";
  plots.emplace_back("residuals.png", residuals);
  const bool gnuplot = gnuplot_on_path();
  for (auto& [file, plot] : plots) {
    if (gnuplot)
      add_report_plot(report, dir, file, plot);
    else
      report.skipped.push_back(file + ": " + kGnuplotMissing);
  }
  ReportIndex index;
  index.title = "shudder characterise";
  index.summary = summary_text;
  index.data_files = data_files;
  write_report_index(dir, index, report);
  return report;
}

}  // namespace shudder::report
