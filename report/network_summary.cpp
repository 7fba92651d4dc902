#include "report/network_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>

#include "report/run_summary.hpp"

namespace shudder::report {

namespace {

std::string format(const char* fmt, double a, double b = 0, double c = 0) {
  char buf[256];
  std::snprintf(buf, sizeof buf, fmt, a, b, c);
  return buf;
}

std::string verdict_line(const studies::RunVerdict& v) {
  const auto& r = v.judged;
  const std::string name(analysis::to_string(r.verdict));
  if (r.verdict == analysis::Verdict::kNone)
    return "none (largest oscillation " + format("%.3g N m at %.3g Hz", r.amplitude_Nm, r.peak_frequency_Hz) + ")";
  // An oscillation already there in the first frames of the judged window has no onset of its
  // own: the window's start is all that can be said (analysis/shudder_detection.hpp, threshold-crossing onset).
  std::string onset;
  if (std::isfinite(r.onset_time_s))
    onset = r.growth_observed ? format(", onset %.3g s", r.onset_time_s)
                              : format(", present from the judged window's start (%.3g s)", r.onset_time_s);
  return name + format(" at %.3g Hz, amplitude %.3g N m", r.frequency_Hz, r.amplitude_Nm) + onset;
}

// Linear theory about the judged window (studies/clutch_prediction.hpp), in one line.
std::string prediction_line(const studies::Prediction& p) {
  if (!p.made) return p.method;  // "not predicted: <why>"
  // A zero margin is a mode that neither grows nor decays (a free rotation the constraints leave).
  std::string s = p.margin_per_s > 0 ? "predicted: UNSTABLE"
                                     : (p.margin_per_s < 0 ? "predicted: stable" : "predicted: neutrally stable");
  s += format(" (margin %.3g 1/s", p.margin_per_s);
  if (std::isfinite(p.frequency_Hz))
    s += format("; least damped oscillation %.4g Hz at %.3g 1/s", p.frequency_Hz, p.oscillatory_margin_per_s);
  return s + ")";
}

// The time from which the clutch stays stuck to the end, NaN if it slips at the end.
double locked_from_s(const dynamics::Recording& rec, const std::string& clutch) {
  const auto* t = rec.find("time_s");
  const auto* stuck = rec.find(clutch + ".stuck");
  if (!t || !stuck || stuck->values.empty() || stuck->values.back() < 0.5) return std::nan("");
  std::size_t i = stuck->values.size();
  while (i > 0 && stuck->values[i - 1] > 0.5) --i;
  return t->values[i == 0 ? 0 : i];
}

double scalar(const dynamics::Recording& rec, const std::string& name) {
  const auto* s = rec.find_scalar(name);
  return s ? s->value : std::nan("");
}

}  // namespace

void print_network_summary(std::ostream& os, const io::NetworkScenario& sc, const studies::NetworkRun& run) {
  const auto& spec = sc.spec;
  const auto& rec = run.recording;
  os << "Scenario: " << sc.name << " (network)";
  if (!sc.description.empty()) os << " - " << sc.description;
  os << "\n";
  os << "  " << spec.inertias.size() + spec.vehicles.size() << " nodes, " << spec.shafts.size() << " shafts, "
     << spec.gears.size() << " gears, " << spec.differentials.size() << " differentials, " << spec.clutches.size()
     << " clutches/brakes, " << spec.freewheels.size() << " freewheels; "
     << format("%.4g s at %.4g samples/s", spec.settings.duration_s, spec.settings.sample_rate_Hz) << "\n";
  if (run.worst >= 0) {
    const auto& w = run.verdicts[static_cast<std::size_t>(run.worst)];
    // The clutch the verdict names used its friction law outside its data for most of the run:
    // said first, as for the model kinds (docs/formats/run_output.md, outside_data_fraction).
    if (const auto* b = rec.find_block("verdict"))
      if (const auto* f = b->find_scalar("outside_data_fraction"); f && f->value > 0.5)
        os << "WARNING: clutch '" << w.clutch << "' uses its friction law outside its data for "
           << format("%.0f %% of the run", 100.0 * f->value)
           << ": the verdict below is an extrapolation of the law (see its \"friction data\" line)\n";
    os << "Verdict: " << verdict_line(w.verdict) << " - clutch '" << w.clutch << "'\n";
  } else {
    os << "Verdict: not judged (" << (spec.clutches.empty() ? "no clutch in the network" : run.verdicts.front().reason)
       << ")\n";
  }
  for (std::size_t c = 0; c < spec.clutches.size(); ++c) {
    const auto& k = spec.clutches[c];
    const auto& v = run.verdicts[c];
    using Law = components::ClutchSpec::Law;
    os << "  " << k.name << " ("
       << (k.law == Law::kWet      ? "wet"
           : k.law == Law::kHaldex ? "Haldex coupling"
                                   : "plain")
       << ", " << k.a << " -> " << k.b << "): ";
    os << (v.judged ? verdict_line(v.verdict) : "not judged: " + v.reason);
    if (!k.judged_on.empty()) os << " [judged on " << k.judged_on << ".torque_Nm]";
    os << "\n";
    if (v.judged) os << "    " << prediction_line(v.verdict.prediction) << "\n";
    if (v.judged && v.verdict.judged.verdict == analysis::Verdict::kStickSlip) os << "    " << kStickSlipNote;
    const double locked = locked_from_s(rec, k.name);
    os << "    "
       << (std::isfinite(locked) ? format("locked from %.4g s to the end", locked) : std::string("slipping at the end"))
       << format("; friction heat %.4g kJ", scalar(rec, k.name + ".friction_work_J") * 1e-3);
    if (k.law != Law::kPlain) {
      os << format("; peak interface temperature %.4g degC", scalar(rec, k.name + ".peak_interface_temp_C"));
      if (k.law == Law::kHaldex) {
        const auto* p = rec.find(k.name + ".pressure_bar");
        if (p && !p->values.empty())
          os << format("; pressure %.3g-%.3g bar", *std::min_element(p->values.begin(), p->values.end()),
                       *std::max_element(p->values.begin(), p->values.end()));
      }
      os << "\n    fluid " << k.wet.fluid.name << ", effects on:";
      for (const auto& e : k.wet.enabled_effects) os << " " << e;
      if (const auto* range = rec.find_block("friction_data_range." + k.name))
        if (const auto* t = range->find_text("summary")) os << "\n    friction data: " << t->value;
    }
    os << "\n";
  }
  os << format("Energy: source work %.6g kJ = kinetic change %.6g kJ", scalar(rec, "source_work_J") * 1e-3,
               scalar(rec, "kinetic_energy_change_J") * 1e-3)
     << format(" + elastic change %.4g kJ + friction heat %.6g kJ", scalar(rec, "elastic_energy_change_J") * 1e-3,
               scalar(rec, "friction_heat_J") * 1e-3)
     << format(" + damper losses %.4g kJ (relative error %.2g)\n", scalar(rec, "damper_loss_J") * 1e-3,
               scalar(rec, "mechanical_energy_relative_error"));
  for (const auto& w : sc.warnings) os << "Note: " << w << "\n";
}

}  // namespace shudder::report
