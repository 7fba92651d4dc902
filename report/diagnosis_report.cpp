// Report directory of a diagnosis; see diagnosis_report.hpp and docs/formats/diagnosis_json.md.
#include "report/diagnosis_report.hpp"

#include <unistd.h>

#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <set>
#include <sstream>
#include <stdexcept>

#include "io/atomic_file.hpp"
#include "report/diagnosis_narrative.hpp"
#include "report/gnuplot.hpp"
#include "report/plots.hpp"
#include "io/input_error.hpp"
#include "core/nan.hpp"

namespace shudder::report {

namespace {

namespace fs = std::filesystem;
using analysis::CandidateScore;
using analysis::RunTraces;

std::string fixed(double x, const char* fmt = "%.4g") {
  if (!std::isfinite(x)) return "–";
  char buf[48];
  std::snprintf(buf, sizeof buf, fmt, x);
  return buf;
}

/// A Markdown table cell: '|' would end the cell and a line break the row.
std::string cell(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '|')
      out += "\\|";
    else if (c == '\n' || c == '\r' || c == '\t')
      out += ' ';
    else
      out += c;
  }
  return out;
}

std::string parameters_text(const std::vector<std::pair<std::string, double>>& p) {
  if (p.empty()) return "(none)";
  std::string s;
  for (std::size_t i = 0; i < p.size(); ++i) s += (i ? ", " : "") + p[i].first + " = " + fixed(p[i].second);
  return s;
}

void candidate_table(std::ostringstream& md, const std::vector<CandidateScore>& cands) {
  if (cands.empty()) {
    md << "(no candidates)\n\n";
    return;
  }
  md << "| effect | parameters | fit misfit | hold-out misfit | score | gain | signature correlation "
        "| evaluations | note |\n"
     << "|---|---|---:|---:|---:|---:|---:|---:|---|\n";
  for (const auto& c : cands)
    md << "| " << cell(effects_label(c.effect, c.joint_with)) << " | " << cell(parameters_text(c.parameters)) << " | "
       << fixed(c.fit_misfit) << " | " << fixed(c.holdout_misfit) << " | " << fixed(c.score) << " | "
       << fixed(c.gain, "%+.4g") << " | " << fixed(c.signature_correlation, "%+.3f") << " | " << c.evaluations << " | "
       << cell(c.failure.empty() ? "" : "failed: " + c.failure) << " |\n";
  md << "\n";
}

/// Run names go into gnuplot titles; control characters there would break the script line.
std::string printable(const std::string& s) {
  std::string out;
  for (char c : s) out += static_cast<unsigned char>(c) < 0x20 ? ' ' : c;
  return out;
}

Series line(const std::vector<double>& t, const std::vector<double>& y, std::string label, const std::string& rgb,
            bool dashed, double width) {
  Series s;
  s.label = std::move(label);
  s.x = t;
  s.y = y;
  s.rgb = rgb;
  s.dashed = dashed;
  s.line_width = width;
  return s;
}

/// model − measured; NaN (a gap in the line) where either is missing or not finite.
std::vector<double> residual(const std::vector<double>& model, const std::vector<double>& measured) {
  std::vector<double> r(measured.size(), kNaN);
  if (model.size() != measured.size()) return r;
  for (std::size_t i = 0; i < r.size(); ++i)
    if (std::isfinite(model[i]) && std::isfinite(measured[i])) r[i] = model[i] - measured[i];
  return r;
}

// Measured black and thin (it carries the noise), baseline orange dashed, final blue solid.
Plot signal_plot(const RunTraces& tr, const char* what, const char* ylabel, const std::vector<double>& measured,
                 const std::vector<double>& baseline, const std::vector<double>& final) {
  Plot p;
  p.title = printable(tr.run) + ": " + what + ", measured vs model";
  p.caption = std::string("The run's measured ") + what +
              " (thin black), the baseline model (orange dashed) and the "
              "final model with the effects the diagnosis added (blue) against time.";
  p.xlabel = "time [s]";
  p.ylabel = ylabel;
  const std::size_t n = tr.time_s.size();
  if (measured.size() == n) p.series.push_back(line(tr.time_s, measured, "measured", "#000000", false, 1.0));
  if (baseline.size() == n) p.series.push_back(line(tr.time_s, baseline, "baseline model", "#ff7f0e", true, 2.0));
  if (final.size() == n)
    p.series.push_back(line(tr.time_s, final, "final model (effects added)", "#1f77b4", false, 2.0));
  return p;
}

/// One residual panel: baseline (dashed) and final (solid) model − measured, and its zero line.
Plot residual_panel(const RunTraces& tr, const std::string& title, const std::string& ylabel,
                    const std::vector<double>& measured, const std::vector<double>& baseline,
                    const std::vector<double>& final, const std::string& rgb) {
  Plot p;
  p.title = title;
  p.xlabel = "time [s]";
  p.ylabel = ylabel;
  p.series.push_back(line(tr.time_s, residual(baseline, measured), "baseline (dashed)", rgb, true, 1.5));
  p.series.push_back(line(tr.time_s, residual(final, measured), "final", rgb, false, 2.0));
  p.series.push_back(line({tr.time_s.front(), tr.time_s.back()}, {0.0, 0.0}, "", "#000000", false, 0.8));
  return p;
}

// Torque and temperature residuals in panels of their own, one above the other: each has its
// own zero line on its own axis (two y axes on one panel put their zeros at different heights).
MultiPlot residual_plot(const RunTraces& tr) {
  MultiPlot f;
  f.title = printable(tr.run) + ": residual model − measured (dashed: baseline, solid: final)";
  f.caption =
      "Model minus measurement against time, before (baseline, dashed) and after (final, solid) the effects "
      "the diagnosis added: torque above, temp_C below, each panel with its own zero line.";
  const std::size_t n = tr.time_s.size();
  if (tr.torque_measured.size() == n)
    f.rows.push_back({residual_panel(tr, "torque residual", "torque residual [N m]", tr.torque_measured,
                                     tr.torque_baseline, tr.torque_final, "#1f77b4")});
  if (tr.temp_measured.size() == n)
    f.rows.push_back({residual_panel(tr, "temp_C residual", "temperature residual [°C]", tr.temp_measured,
                                     tr.temp_baseline, tr.temp_final, "#d62728")});
  f.height_px = f.rows.size() > 1 ? 820 : 480;
  return f;
}

}  // namespace

std::string diagnosis_run_stem(const std::string& run) {
  std::string name = run.substr(run.find_last_of('/') == std::string::npos ? 0 : run.find_last_of('/') + 1);
  if (const auto dot = name.find_last_of('.'); dot != std::string::npos && dot > 0) name.erase(dot);
  for (char& c : name) {
    const bool ok =
        (c >= 'A' && c <= 'Z') || (c >= 'a' && c <= 'z') || (c >= '0' && c <= '9') || c == '_' || c == '.' || c == '-';
    if (!ok) c = '_';
  }
  if (!name.empty() && name.front() == '.') name.front() = '_';
  return name.empty() ? "run" : name;
}

std::string diagnosis_candidates_markdown(const analysis::DiagnosisResult& r) {
  std::ostringstream md;
  md << "# Diagnosis: candidate effects\n\n"
     << "Misfit J in units of the noise variance (J ≈ 1: explained to the noise); residual = model − "
        "measured. score = hold-out misfit + penalty × parameters; gain = current hold-out misfit − "
        "score. Candidates best first.\n\n";
  md << cell(verdict_sentence(r)) << "\n\n";
  md << "| signal | final RMS | error scale | of which reproduction | tolerance | RMS / scale | within |\n"
     << "|---|---|---|---|---|---|---|\n";
  for (const auto& c : r.channels)
    md << "| " << c.signal << " | " << fixed(c.final_rms) << " | " << fixed(c.error_scale) << " | "
       << fixed(c.reproduction) << " | " << fixed(c.tolerance) << " | " << fixed(std::sqrt(c.final_misfit)) << " | "
       << (c.within ? "yes" : "no") << " |\n";
  md << "\n";
  const std::string holdout = holdout_text(r.holdout);
  if (!holdout.empty()) md << "Hold-out: " << cell(holdout) << ".\n\n";
  md << "Baseline hold-out misfit: " << fixed(r.baseline_holdout_misfit) << "; final: " << fixed(r.final_holdout_misfit)
     << ".\n\n";
  for (std::size_t k = 0; k < r.steps.size(); ++k) {
    const auto& st = r.steps[k];
    md << "## Step " << k + 1 << ": added " << effects_label(st.effect, st.joint_with) << "\n\n";
    md << "Parameters (refitted on all runs): " << parameters_text(st.parameters) << ". Hold-out misfit "
       << fixed(st.holdout_misfit_before) << " → " << fixed(st.holdout_misfit_after) << "; torque RMS "
       << fixed(st.misfit.torque_rms_Nm) << " N m, temp RMS " << fixed(st.misfit.temp_rms_C) << " °C (all runs).\n\n";
    md << "Why: " << cell(step_reason(st)) << "\n\n";
    candidate_table(md, st.candidates);
  }
  if (!r.withdrawn.empty() || !r.indistinguishable.empty()) {
    md << "## Backward check\n\n"
       << "Each added effect taken out in turn, the others refitted on the fit set; an effect whose removal costs "
          "less held-out misfit than it would need to be added is withdrawn, unless the tie rule keeps it.\n\n";
    for (const auto& f : r.withdrawn) md << "* Withdrawn: " << cell(backward_finding_text(f)) << "\n";
    for (const auto& f : r.indistinguishable) md << "* Kept, not separable: " << cell(backward_finding_text(f)) << "\n";
    md << "\n";
  }
  md << "## Last round (stopped the search)\n\n";
  if (r.last_round.empty())
    md << "No round without an addition (every signal within noise, or the effect limit reached).\n\n";
  else
    md << "No candidate lowered the hold-out misfit by enough to be added.\n\n";
  candidate_table(md, r.last_round);
  return md.str();
}

/// The channels' fit as a table for index.html (the candidates.md table's columns).
HtmlTable channel_table(const analysis::DiagnosisResult& r) {
  HtmlTable t;
  t.caption = "Signals";
  t.header = {"signal", "comparison", "baseline RMS", "final RMS", "error scale", "RMS / scale", "within"};
  for (const auto& c : r.channels)
    t.rows.push_back({c.signal, c.comparison, fixed(c.baseline_rms), fixed(c.final_rms), fixed(c.error_scale),
                      fixed(std::sqrt(c.final_misfit)), c.within ? "yes" : "no"});
  return t;
}

Report write_diagnosis_report(const std::string& dir, const analysis::DiagnosisResult& r,
                              const std::string& summary_text, const std::vector<std::string>& data_files) {
  make_report_dir(dir);
  Report report;
  const auto path = [&](const std::string& f) { return (fs::path(dir) / f).string(); };
  io::write_text_file_atomically(path("summary.txt"), summary_text);
  report.files.push_back(path("summary.txt"));
  io::write_text_file_atomically(path("candidates.md"), diagnosis_candidates_markdown(r));
  report.files.push_back(path("candidates.md"));

  const bool gnuplot = gnuplot_on_path();
  std::set<std::string> used;
  for (const auto& tr : r.traces) {
    std::string stem = diagnosis_run_stem(tr.run);
    for (int k = 2; used.count(stem); ++k) stem = diagnosis_run_stem(tr.run) + "_" + std::to_string(k);
    used.insert(stem);
    const std::string files = stem + "_{torque,temp,residuals}.png";
    if (!gnuplot) {
      report.skipped.push_back(files + ": " + kGnuplotMissing);
      continue;
    }
    if (tr.time_s.empty()) {
      report.skipped.push_back(files + ": the run '" + tr.run + "' has no trace samples");
      continue;
    }
    const MultiPlot plots[] = {
        single_panel(
            signal_plot(tr, "torque", "torque [N m]", tr.torque_measured, tr.torque_baseline, tr.torque_final)),
        single_panel(signal_plot(tr, "temp_C", "temperature [°C]", tr.temp_measured, tr.temp_baseline, tr.temp_final)),
        residual_plot(tr)};
    const char* suffixes[] = {"_torque.png", "_temp.png", "_residuals.png"};
    for (std::size_t i = 0; i < 3; ++i) {
      const std::string file = stem + suffixes[i];
      if (plots[i].rows.empty() || plots[i].rows.front().front().series.empty()) {
        report.skipped.push_back(file + ": no column matches the run's " + std::to_string(tr.time_s.size()) +
                                 " time samples");
        continue;
      }
      add_report_plot(report, dir, file, plots[i]);
    }
  }
  ReportIndex index;
  index.title = "shudder diagnose";
  index.verdict = verdict_sentence(r);
  index.verdict_class = r.verdict == analysis::DiagnosisVerdict::kExplained ? "none" : "shudder";
  index.summary = summary_text;
  index.tables.push_back(channel_table(r));
  index.data_files = data_files;
  write_report_index(dir, index, report);
  return report;
}

}  // namespace shudder::report
