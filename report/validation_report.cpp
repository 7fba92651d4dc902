#include "report/validation_report.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <set>
#include <stdexcept>
#include <type_traits>

#include "core/units.hpp"
#include "io/atomic_file.hpp"
#include "io/input_error.hpp"
#include "report/gnuplot.hpp"
#include "report/run_summary.hpp"

namespace shudder::report {

namespace {

namespace fs = std::filesystem;

template <class... A>
std::string fmt(const char* f, A... a) {
  static_assert((!std::is_class_v<A> && ...), "pass .c_str(), not a std::string, to %s");
  char buf[512];
  std::snprintf(buf, sizeof buf, f, a...);
  return buf;
}

const char* verdict(bool ok) { return ok ? "yes" : "NO"; }

/// Time mean of a signal over [t0, t1] (trapezoid on a 10 ms grid of interpolated values).
double mean_over(const dynamics::Recording& rec, const char* name, double t0, double t1) {
  const int n = static_cast<int>(std::lround((t1 - t0) / 0.01));
  double sum = 0.0;
  for (int k = 0; k <= n; ++k) sum += (k == 0 || k == n ? 0.5 : 1.0) * signal_at(rec, name, t0 + (t1 - t0) * k / n);
  return sum / n;
}

/// The pass band as printed: "40–50 Nm", "≥ 105 Nm", "> 150 °C", "5–15 % below".
std::string band_text(const io::ValidationTarget& g) {
  if (!g.has_band()) return "– (reported)";
  const bool percent = g.kind == io::TargetKind::kPercentBelow || g.kind == io::TargetKind::kPercentAbove;
  const char* unit = percent ? "%" : g.unit.c_str();
  std::string text = g.greater_than   ? fmt("> %g %s", *g.greater_than, unit)
                     : g.min && g.max ? fmt("%g–%g %s", *g.min, *g.max, unit)
                     : g.min          ? fmt("≥ %g %s", *g.min, unit)
                                      : fmt("≤ %g %s", *g.max, unit);
  if (g.kind == io::TargetKind::kPercentBelow) text += " below";
  if (g.kind == io::TargetKind::kPercentAbove) text += " above";
  return text;
}

bool in_band(const io::ValidationTarget& g, double v) {
  return (!g.min || v >= *g.min) && (!g.max || v <= *g.max) && (!g.greater_than || v > *g.greater_than);
}

// ---- text output -------------------------------------------------------------------------

/// Display width of UTF-8 text (code points; every character here is one column wide).
std::size_t width(const std::string& s) {
  std::size_t n = 0;
  for (unsigned char ch : s) n += (ch & 0xC0) != 0x80;
  return n;
}

double run_scalar(const dynamics::Recording& rec, const char* name) {
  const auto* s = rec.find_scalar(name);
  return s ? s->value : std::nan("");
}

std::string form_name(clutch::FilmAdvectionForm f) {
  return f == clutch::FilmAdvectionForm::kPaperGLiteral ? "paper_g_literal" : "film_energy_balance";
}

/// Oil-flow constants of every run, grouped: one table row per distinct set.
void write_oil_flow(std::ostream& md, const std::vector<ValidationRun>& runs) {
  std::vector<std::pair<std::string, std::string>> groups;  // (row cells, scenario list)
  for (const auto& r : runs) {
    const auto& th = r.sc.clutch.thermal;
    const auto& f = th.oil_flow;
    const std::string cells = th.interface_oil_cooling
                                  ? fmt("%g | %g | %g | %g | %g | `%s` | %g", f.a, f.b, f.c, f.d, f.e,
                                        form_name(f.form).c_str(), units::m3_s_to_ml_min(th.supply_flow_m3_s))
                                  : std::string("– | – | – | – | – | off (`interface_oil_cooling` disabled) | –");
    auto it = groups.begin();
    while (it != groups.end() && it->first != cells) ++it;
    if (it == groups.end())
      groups.push_back({cells, "`" + r.sc.name + "`"});
    else
      it->second += ", `" + r.sc.name + "`";
  }
  md << "## Calibrated interface oil flow\n\n"
     << "Paper G eq. 12, Q_oil = Q_oiltot · (a·(Δω + 1)^b + c·T_mean^d + e), Δω in rad/s, "
        "T_mean in K (`clutch/oil_flow.hpp`; calibration in `thermal_model.md`). Constants as "
        "loaded from the scenarios (`clutch.thermal.oil_flow`, set by "
        "`[effects.interface_oil_cooling]`):\n\n"
     << "| scenarios | a | b | c | d | e | film_advection | Q_oiltot [ml/min] |\n"
     << "|---|---|---|---|---|---|---|---|\n";
  for (const auto& [cells, names] : groups) md << "| " << names << " | " << cells << " |\n";
  md << "\n";
}

void write_case2(std::ostream& md, const ValidationRun& run) {
  std::set<double> times;
  const auto bp = run.model.cycle.slip_speed_rpm.times_s();
  for (std::size_t i = 0; i < bp.size(); ++i) {
    times.insert(bp[i]);
    if (i + 1 < bp.size()) times.insert(0.5 * (bp[i] + bp[i + 1]));
  }
  md << "## Case 2 (no target)\n\n"
     << "Paper G reports a larger error here: simulated torque low on the up-ramp, high on "
        "parts of the down-ramp; the measured temperature falls more slowly on the down-ramp "
        "because rig parts beyond the insulated discs hold heat (`rig_heat_capacity`, off in "
        "this baseline). Values at the drive's breakpoints and half-way between them:\n\n"
     << "| t [s] | speed [rpm] | torque [Nm] | thermocouple [°C] | IR [°C] | sump [°C] |\n"
     << "|---:|---:|---:|---:|---:|---:|\n";
  for (double t : times) {
    if (t > run.model.settings.duration_s) continue;
    md << fmt("| %.1f | %.1f | %.2f | %.2f | %.2f | %.2f |\n", t, signal_at(run.rec, "speed_rpm", t),
              signal_at(run.rec, "torque_Nm", t), signal_at(run.rec, "temp_C", t), signal_at(run.rec, "ir_temp_C", t),
              signal_at(run.rec, "sump_temp_C", t));
  }
  md << "\n";
}

void write_energy(std::ostream& md, const std::vector<ValidationRun>& runs) {
  md << "## Energy balance\n\n"
     << "Heat generated = stored in the discs + to the sump + to the rig; the relative error "
        "is the residual over the heat generated.\n\n"
     << "| case | generated [J] | stored in discs [J] | to sump [J] | to rig [J] | "
        "relative error |\n|---|---:|---:|---:|---:|---:|\n";
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& r = runs[i].rec;
    md << fmt("| %s | %.1f | %.1f | %.1f | %.1f | %.1e |\n", runs[i].label.c_str(), run_scalar(r, "heat_generated_J"),
              run_scalar(r, "heat_stored_in_discs_J"), run_scalar(r, "heat_to_sump_J"), run_scalar(r, "heat_to_rig_J"),
              run_scalar(r, "energy_balance_relative_error"));
  }
  md << "\n";
}

// ---- plots -------------------------------------------------------------------------------

/// Signal `name` against `x_name` over samples with t0 <= time <= t1.
Series series(const dynamics::Recording& rec, const char* name, std::string label, int color, bool dashed = false,
              const char* x_name = "time_s", double t0 = -1e300, double t1 = 1e300) {
  Series s{std::move(label), {}, {}, color, dashed};
  const auto* t = rec.find("time_s");
  const auto* x = rec.find(x_name);
  const auto* y = rec.find(name);
  if (!t || !x || !y) throw std::runtime_error(std::string("recording lacks signal ") + name);
  for (std::size_t i = 0; i < t->values.size(); ++i) {
    if (t->values[i] < t0 - 1e-9 || t->values[i] > t1 + 1e-9) continue;
    s.x.push_back(x->values[i]);
    s.y.push_back(y->values[i]);
  }
  return s;
}

}  // namespace

std::vector<ValidationRow> evaluate_targets(const io::ValidationSpec& spec, const std::vector<ValidationRun>& runs) {
  std::vector<ValidationRow> rows;
  for (const auto& g : spec.targets) {
    const auto& rec = runs[g.case_index].rec;
    const char* sig = g.signal.c_str();
    const char* u = g.unit.c_str();
    double v = 0.0;
    std::string result;
    switch (g.kind) {
      case io::TargetKind::kValue:
        v = signal_at(rec, sig, g.time_s);
        result = fmt("%.2f %s", v, u);
        break;
      case io::TargetKind::kMean:
        v = mean_over(rec, sig, g.from_s, g.to_s);
        result = fmt("%.2f %s", v, u);
        break;
      case io::TargetKind::kRise: {
        const double a = signal_at(rec, sig, g.from_s), b = signal_at(rec, sig, g.to_s);
        v = b - a;
        result = fmt("%.2f %s (%.2f → %.2f %s)", v, u, a, b, u);
        break;
      }
      case io::TargetKind::kPercentBelow:
      case io::TargetKind::kPercentAbove: {
        const double x = signal_at(rec, sig, g.time_s);
        const double ref = signal_at(runs[*g.reference_index].rec, sig, g.time_s);
        const bool below = g.kind == io::TargetKind::kPercentBelow;
        v = below ? 100 * (1 - x / ref) : 100 * (x / ref - 1);
        result = fmt("%.2f %% %s (%.2f vs %.2f %s)", v, below ? "below" : "above", x, ref, u);
        break;
      }
    }
    rows.push_back({spec.cases[g.case_index].label, g.quantity, band_text(g), result,
                    g.has_band() ? verdict(in_band(g, v)) : "–"});
  }
  return rows;
}

void print_validation_table(std::ostream& os, const std::vector<ValidationRow>& rows) {
  const std::vector<std::string> head{"case", "quantity", "target", "result", "pass"};
  std::vector<std::size_t> w;
  for (const auto& h : head) w.push_back(width(h));
  const auto cells = [](const ValidationRow& r) {
    return std::vector<std::string>{r.case_label, r.quantity, r.target, r.result, r.pass};
  };
  for (const auto& r : rows) {
    const auto c = cells(r);
    for (std::size_t i = 0; i < c.size(); ++i) w[i] = std::max(w[i], width(c[i]));
  }
  const auto line = [&](const std::vector<std::string>& c) {
    for (std::size_t i = 0; i < c.size(); ++i)
      os << c[i] << (i + 1 < c.size() ? std::string(w[i] - width(c[i]) + 2, ' ') : "");
    os << "\n";
  };
  line(head);
  for (const auto& r : rows) line(cells(r));
}

std::vector<Figure> write_validation_plots(const std::filesystem::path& docs, const io::ValidationSpec& spec,
                                           const std::vector<ValidationRun>& runs) {
  std::vector<Figure> figs;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& r = runs[i].rec;
    Plot p;
    p.title = runs[i].label + " (" + runs[i].sc.name + ")";
    p.xlabel = "time [s]";
    p.ylabel = "torque [Nm]";
    p.y2label = "temperature [°C]";
    p.series = {series(r, "torque_Nm", "torque [Nm] (left axis)", 0)};
    p.series_y2 = {series(r, "temp_C", "thermocouple temp_C [°C] (right axis)", 1),
                   series(r, "ir_temp_C", "IR ir_temp_C [°C] (right axis)", 2, true)};
    if (i == spec.ramp_case) p.series_y2.push_back(series(r, "sump_temp_C", "sump [°C] (right axis)", 7));
    const std::string file = "validation_" + runs[i].sc.name + ".png";
    write_plot((docs / file).string(), p);
    figs.push_back({file, runs[i].label + ": torque and temperatures"});
  }
  if (!spec.comparison.empty()) {  // e.g. Paper G Fig. 14: one load with and without effects.
    Plot p;
    p.title = spec.comparison_title;
    p.xlabel = "time [s]";
    p.ylabel = "torque [Nm] (solid)";
    p.y2label = "thermocouple temp_C [°C] (dashed)";
    for (std::size_t k = 0; k < spec.comparison.size(); ++k) {
      const auto& [index, what] = spec.comparison[k];
      const int color = static_cast<int>(k);
      p.series.push_back(series(runs[index].rec, "torque_Nm", "torque, " + what, color));
      p.series_y2.push_back(series(runs[index].rec, "temp_C", "thermocouple, " + what, color, true));
    }
    write_plot((docs / spec.comparison_file).string(), p);
    figs.push_back({spec.comparison_file, spec.comparison_heading});
  }
  {  // The ramp case against slip speed: up-ramp vs down-ramp.
    const ValidationRun& ramp = runs[spec.ramp_case];
    const auto& r = ramp.rec;
    const auto bp = ramp.model.cycle.slip_speed_rpm.times_s();  // Case 2: 0, 5, 15, 17, 27, 30
    Plot p;
    p.title = ramp.label + ": up-ramp vs down-ramp";
    p.xlabel = "slip speed [rpm]";
    p.ylabel = "torque [Nm] (solid)";
    p.y2label = "thermocouple temp_C [°C] (dashed)";
    if (bp.size() >= 5) {
      p.series = {
          series(r, "torque_Nm", fmt("torque, up-ramp t = %g–%g s", bp[1], bp[2]), 0, false, "speed_rpm", bp[1], bp[2]),
          series(r, "torque_Nm", fmt("torque, down-ramp t = %g–%g s", bp[3], bp[4]), 1, false, "speed_rpm", bp[3],
                 bp[4])};
      p.series_y2 = {series(r, "temp_C", "thermocouple, up-ramp", 0, true, "speed_rpm", bp[1], bp[2]),
                     series(r, "temp_C", "thermocouple, down-ramp", 1, true, "speed_rpm", bp[3], bp[4])};
      write_plot((docs / spec.ramp_plot_file).string(), p);
      figs.push_back({spec.ramp_plot_file, ramp.label + ": torque and thermocouple against slip speed"});
    }
  }
  return figs;
}

void write_validation_doc(const std::filesystem::path& docs, const io::ValidationSpec& spec,
                          const std::vector<ValidationRun>& runs, const std::vector<ValidationRow>& rows,
                          const std::vector<Figure>& figs, bool plots) {
  const std::string path = (docs / "validation.md").string();
  const std::string tmp = io::temp_path_for(path);
  {
    std::ofstream md(tmp);
    if (!md) throw io::InputError(path, 0, "", "cannot write; check the folder is writable");
    std::size_t checked = 0, passed = 0;
    for (const auto& r : rows) {
      checked += r.pass != "–";
      passed += r.pass == "yes";
    }
    md << "# Validation against Paper G and Paper B\n\n"
       << "Generated by `shudder validate`; do not edit by hand. To regenerate, from the "
          "repository root after building:\n\n"
       << "```text\n./build/app/shudder validate --scenarios scenarios --docs docs\n```\n\n"
       << "Each case runs a scenario with the prescribed-slip rig model and compares it with "
          "the targets of scenarios/validation.toml (from Paper G Figs. 8, 12–14 and Discussion, Paper "
          "B Fig. 6; `docs/physics.md` §5). The command exits 0 when every target passes, 1 when "
          "one fails.\n\n## Cases\n\n| case | scenario | description |\n|---|---|---|\n";
    for (std::size_t i = 0; i < runs.size(); ++i)
      md << "| " << runs[i].label << " | `" << runs[i].sc.name << ".toml` | " << runs[i].sc.description << " |\n";
    md << "\n";
    write_oil_flow(md, runs);
    md << "## Targets and results\n\n"
       << "Values at a time are interpolated linearly in the 100 Hz recording; pass/fail is "
          "decided on the unrounded values. Rows marked – are reported without a target.\n\n"
       << "| case | quantity | target | result | pass |\n|---|---|---|---|---|\n";
    for (const auto& r : rows)
      md << "| " << r.case_label << " | " << r.quantity << " | " << r.target << " | " << r.result << " | "
         << (r.pass == "NO" ? "**NO**" : r.pass) << " |\n";
    md << fmt("\n%zu of %zu targets pass. ", passed, checked)
       << "The targets are bands around the values the papers report (`docs/physics.md` §5), e.g. "
          "Paper B's 15.5 °C rise, where the thesis's Fig. 7 cycle gives > 20 °C.\n\n";
    write_case2(md, runs[spec.ramp_case]);
    write_energy(md, runs);
    md << "## Plots\n\n";
    if (!plots) md << "Not generated (`--no-plots`).\n";
    for (const auto& f : figs) md << "### " << f.heading << "\n\n![" << f.heading << "](" << f.file << ")\n\n";
    md.flush();
    if (!md) {
      io::discard_temp_file(tmp);
      throw io::InputError(path, 0, "", "write failed; check the disk");
    }
  }
  io::commit_temp_file(tmp, path);
}

}  // namespace shudder::report
