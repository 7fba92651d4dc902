#include "report/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <variant>

#include "dynamics/signal_names.hpp"
#include "components/friction_range_block.hpp"
#include "studies/run_verdict.hpp"
#include "core/nan.hpp"

namespace shudder::report {

double signal_at(const dynamics::Recording& rec, std::string_view name, double t) {
  const auto* time = rec.find(dynamics::signal_names::kTime);
  const auto* sig = rec.find(name);
  if (!time || !sig || time->values.empty()) return std::numeric_limits<double>::quiet_NaN();
  const auto& ts = time->values;
  const auto& v = sig->values;
  if (t <= ts.front()) return v.front();
  if (t >= ts.back()) return v.back();
  const auto it = std::upper_bound(ts.begin(), ts.end(), t);
  const std::size_t i = static_cast<std::size_t>(it - ts.begin());
  const double w = (t - ts[i - 1]) / (ts[i] - ts[i - 1]);
  return (1 - w) * v[i - 1] + w * v[i];
}

namespace {

namespace sn = dynamics::signal_names;

double scalar(const dynamics::Recording& rec, const char* name) {
  const auto* s = rec.find_scalar(name);
  return s ? s->value : kNaN;
}

// min / mean / max and the RMS about the mean of a signal over the samples in [from, to] (to
// included only for the run's last interval, so each sample counts once); NaN if absent.
struct Stats {
  double min = kNaN, mean = kNaN, max = kNaN, rms_dev = kNaN;
};

Stats interval_stats(const dynamics::Recording& rec, std::string_view name, double from_s, double to_s, bool last) {
  const auto* time = rec.find(sn::kTime);
  const auto* sig = rec.find(name);
  Stats st;
  if (!time || !sig) return st;
  const auto inside = [&](double t) { return t >= from_s && (t < to_s || (last && t <= to_s)); };
  double sum = 0;
  std::size_t n = 0;
  for (std::size_t i = 0; i < time->values.size(); ++i)
    if (inside(time->values[i])) {
      const double v = sig->values[i];
      st.min = n == 0 ? v : std::min(st.min, v);
      st.max = n == 0 ? v : std::max(st.max, v);
      sum += v;
      ++n;
    }
  if (n == 0) return st;
  st.mean = sum / static_cast<double>(n);
  double sq = 0;
  for (std::size_t i = 0; i < time->values.size(); ++i)
    if (inside(time->values[i])) sq += (sig->values[i] - st.mean) * (sig->values[i] - st.mean);
  st.rms_dev = std::sqrt(sq / static_cast<double>(n));
  return st;
}

// The table runs over fifths of the run: statistics over every sample, not samples at a few
// instants (a 378 Hz oscillation sampled every T/5 prints as unrelated values).
constexpr int kIntervals = 5;
constexpr const char* kIntervalNote =
    "Per fifth of the run, over every sample: min / mean / max; rms dev = RMS about the mean, trend "
    "included (an oscillation of amplitude A alone gives A/sqrt(2))\n";

// A driveline run: the car, the coupling and its hydraulics over each fifth of the run.
void print_section(std::ostream& os, const rig_models::DrivelineModel& model, const dynamics::Recording& rec) {
  const double end = model.settings.duration_s;
  char line[512];
  os << kIntervalNote;
  os << "                 car [km/h]  engine [rpm]  engine [Nm]  coupling slip [rpm]        coupling [Nm]"
        "                rear axle [Nm]  pressure [bar]  interface max [C]\n"
        "   interval [s]        mean          mean         mean       min       max      min     mean      max"
        "  rms dev            mean            mean                max\n";
  for (int k = 0; k < kIntervals; ++k) {
    const double a = end * k / kIntervals, b = end * (k + 1) / kIntervals;
    const bool last = k + 1 == kIntervals;
    const auto st = [&](std::string_view name) { return interval_stats(rec, name, a, b, last); };
    const Stats slip = st(sn::kCouplingSlip), coupling = st(sn::kCouplingTorque);
    std::snprintf(line, sizeof line,
                  "%7.2f-%-7.2f %10.2f  %12.1f  %11.1f  %8.3f  %8.3f %8.1f %8.1f %8.1f %8.1f  %14.1f  %14.2f  %17.2f\n",
                  a, b, st(sn::kVehicleSpeed).mean, st(sn::kEngineSpeed).mean, st(sn::kEngineTorque).mean, slip.min,
                  slip.max, coupling.min, coupling.mean, coupling.max, coupling.rms_dev, st(sn::kRearAxleTorque).mean,
                  st(sn::kPressure).mean, st(sn::kInterfaceMaxTemp).max);
    os << line;
  }
  std::snprintf(line, sizeof line,
                "\nCoupling: heat %.1f J, peak interface %.2f C; %.0f stick and %.0f breakaway events\n"
                "Driveline: locked shuffle mode %.2f Hz (damping ratio %.3f) at the run's mean operating point "
                "(`shudder modes SCENARIO --run RUN.h5`); mechanical energy error "
                "%.2e (relative); %.0f integrator steps\n",
                scalar(rec, "heat_generated_J"), scalar(rec, "peak_interface_temp_C"), scalar(rec, "stick_events"),
                scalar(rec, "breakaway_events"), scalar(rec, "shuffle_frequency_Hz"),
                scalar(rec, "shuffle_damping_ratio"), scalar(rec, "mechanical_energy_relative_error"),
                scalar(rec, "integrator_steps"));
  os << line;
  // The coupling's stability maps (docs/driveline_stability.md): unstable cells and the worst one.
  for (const auto& m : rec.maps) {
    if (m.name.rfind("coupling_stability_map_", 0) != 0) continue;
    const auto* growth = m.find("growth_per_s");
    const auto* freq = m.find("frequency_Hz");
    const auto* force = m.find_scalar("normal_force_N");
    if (!growth || !freq || !force) continue;
    Eigen::Index i = 0, j = 0;
    const double worst = growth->values.maxCoeff(&i, &j);
    const long unstable = (growth->values.array() > 0).count();
    std::snprintf(line, sizeof line,
                  "Coupling stability map at %.0f N: %ld of %ld cells unstable; least damped %+.3g 1/s at %.1f Hz "
                  "(slip %.1f rpm, %.1f C)\n",
                  force->value, unstable, static_cast<long>(growth->values.size()), worst, freq->values(i, j),
                  m.x[static_cast<std::size_t>(i)], m.y[static_cast<std::size_t>(j)]);
    os << line;
  }
}

// The rig and prescribed slip: the drive over each fifth of the run, temperatures and the heat
// account.
void print_drive_cycle_section(std::ostream& os, double end, const dynamics::Recording& rec) {
  char line[512];
  os << kIntervalNote;
  os << "                   speed [rpm]   force [kN]                torque [Nm]              max temperature [C]\n"
        "   interval [s]     min     max        mean      min     mean      max  rms dev   thermocouple      IR    "
        "sump\n";
  for (int k = 0; k < kIntervals; ++k) {
    const double a = end * k / kIntervals, b = end * (k + 1) / kIntervals;
    const bool last = k + 1 == kIntervals;
    const auto st = [&](std::string_view name) { return interval_stats(rec, name, a, b, last); };
    const Stats speed = st(sn::kSpeed), torque = st(sn::kTorque);
    std::snprintf(line, sizeof line, "%7.2f-%-7.2f %7.2f %7.2f  %10.2f %8.2f %8.2f %8.2f %8.2f  %13.2f %7.2f %7.2f\n",
                  a, b, speed.min, speed.max, st(sn::kNormalForce).mean / 1e3, torque.min, torque.mean, torque.max,
                  torque.rms_dev, st(sn::kTemp).max, st(sn::kIrTemp).max, st(sn::kSumpTemp).max);
    os << line;
  }
  std::snprintf(line, sizeof line,
                "\nFinal temperatures: thermocouple %.2f C, IR %.2f C, interface max %.2f C, "
                "sump %.2f C (peak interface %.2f C)\n",
                signal_at(rec, sn::kTemp, end), signal_at(rec, sn::kIrTemp, end),
                signal_at(rec, sn::kInterfaceMaxTemp, end), signal_at(rec, sn::kSumpTemp, end),
                scalar(rec, "peak_interface_temp_C"));
  os << line;
  std::snprintf(line, sizeof line,
                "Energy: generated %.1f J = stored in discs %.1f J + to sump %.1f J + to rig %.1f J; "
                "balance error %.2e (relative)\n",
                scalar(rec, "heat_generated_J"), scalar(rec, "heat_stored_in_discs_J"), scalar(rec, "heat_to_sump_J"),
                scalar(rec, "heat_to_rig_J"), scalar(rec, "energy_balance_relative_error"));
  os << line;
}

void print_section(std::ostream& os, const rig_models::PrescribedSlipModel& model, const dynamics::Recording& rec) {
  print_drive_cycle_section(os, model.settings.duration_s, rec);
}

void print_section(std::ostream& os, const rig_models::RigModel& model, const dynamics::Recording& rec) {
  print_drive_cycle_section(os, model.settings.duration_s, rec);
  char line[512];
  std::snprintf(line, sizeof line,
                "Rig: torsion bar %.4g N m/rad, clutch-side mode %.2f Hz; mechanical energy error "
                "%.2e (relative)\n"
                "Integrator: %.0f steps, %.0f rhs evaluations; events: %.0f stick, %.0f breakaway, "
                "%.0f reversal\n",
                scalar(rec, "bar_stiffness_Nm_per_rad"), scalar(rec, "clutch_side_frequency_Hz"),
                scalar(rec, "mechanical_energy_relative_error"), scalar(rec, "integrator_steps"),
                scalar(rec, "rhs_evaluations"), scalar(rec, "stick_events"), scalar(rec, "breakaway_events"),
                scalar(rec, "reversal_events"));
  os << line;
}

// A clamp force swinging by this fraction of its mean or more with an oscillation: the control
// loop carries it. Friction-induced judder (tens of Hz) rides on a clamp force that the
// hydraulics' millisecond-to-tens-of-milliseconds time constants keep within a few per cent;
// the control loop's hunting swings it by half or more (docs/driveline.md).
constexpr double kControlLoopSwing = 0.2;
// A run whose friction law is outside its data for more than this share of the run gets the
// warning at the top of its summary (outside_data_fraction in the verdict block).
constexpr double kMostlyOutsideData = 0.5;

// The verdict block (studies/run_verdict.hpp) in three lines: what the run shows, the
// operating point it was judged at, and what linear theory predicted there; a fourth for
// stick-slip, which that theory cannot predict.
void print_verdict(std::ostream& os, const char* label, const dynamics::Recording& rec) {
  const auto* b = rec.find_block(studies::kVerdictBlock);
  if (!b) {
    os << label << ": not judged (no verdict in the recording)\n";
    return;
  }
  const auto text = [&](const char* name) {
    const auto* t = b->find_text(name);
    return t ? t->value : std::string();
  };
  const auto value = [&](const char* name) {
    const auto* s = b->find_scalar(name);
    return s ? s->value : kNaN;
  };
  char line[768];
  const std::string verdict = text("verdict");
  if (verdict == "not_judged") {
    os << label << ": not judged (" << text("reason") << ")\n";
    return;
  }
  if (verdict == "none" && value("amplitude_Nm") >= value("threshold_Nm"))
    // Above the threshold yet none: the sustained-oscillation rule (keep_if_repeated) set it aside.
    std::snprintf(
        line, sizeof line,
        "%s: none (an oscillation of %.3g N m at %.2f Hz that dies away or does not repeat: not sustained; judged "
        "on %s)\n",
        label, value("amplitude_Nm"), value("peak_frequency_Hz"), text("judged_signals").c_str());
  else if (verdict == "none")
    std::snprintf(line, sizeof line,
                  "%s: none (largest oscillation %.3g N m, under the threshold %.3g N m; judged on %s)\n", label,
                  value("amplitude_Nm"), value("threshold_Nm"), text("judged_signals").c_str());
  else
    std::snprintf(line, sizeof line, "%s: %s at %.2f Hz, amplitude %.3g N m, onset %.3f s (judged on %s)\n", label,
                  verdict.c_str(), value("frequency_Hz"), value("amplitude_Nm"), value("onset_time_s"),
                  text("judged_signals").c_str());
  os << line;
  std::snprintf(line, sizeof line,
                "Operating point (mean over the %s, %.3f-%.3f s): slip %.2f rpm, interface %.2f C, normal force "
                "%.3g kN\n",
                text("operating_window").c_str(), value("window_from_s"), value("window_to_s"), value("slip_rpm"),
                value("interface_temp_C"), value("normal_force_N") / 1e3);
  os << line;
  const double margin = value("predicted_margin_per_s");
  if (std::isfinite(margin))
    std::snprintf(line, sizeof line,
                  "Predicted there: %s, margin %+.3g 1/s; least damped oscillatory mode %.2f Hz (margin %+.3g 1/s)\n",
                  margin > 0 ? "unstable" : "stable", margin, value("predicted_frequency_Hz"),
                  value("predicted_oscillatory_margin_per_s"));
  else
    std::snprintf(line, sizeof line, "Predicted there: %s\n", text("prediction").c_str());
  os << line;
  // A coupling whose clamp force is a state (the driveline's hydraulics): whether the clamp
  // force swings with the oscillation (rig_models/model.cpp, clamp_force_swing).
  const double swing = value("clamp_force_swing");
  if (std::isfinite(swing)) {
    if (swing >= kControlLoopSwing)
      std::snprintf(line, sizeof line,
                    "Clamp force over the oscillation: +/-%.0f %%: the coupling's control loop carries it (valve and "
                    "pressure hunting with the wheel slip), not friction-induced judder\n",
                    100 * swing);
    else
      std::snprintf(line, sizeof line,
                    "Clamp force over the oscillation: +/-%.0f %% (steady: the oscillation is the friction's, not the "
                    "control loop's)\n",
                    100 * swing);
    os << line;
  }
  if (verdict == "stick_slip") os << kStickSlipNote;
}

}  // namespace

void print_run_summary(std::ostream& os, const io::Scenario& sc, const dynamics::Recording& rec) {
  const double end = rig_models::duration_s(sc.model);
  char line[512];
  std::snprintf(line, sizeof line, "Scenario  %s (%s), fluid %s, %.3g s simulated\n", sc.name.c_str(),
                std::string(model_kind_name(sc.kind())).c_str(), sc.fluid.name.c_str(), end);
  os << line;
  os << "Effects on:";
  for (const auto& e : sc.enabled_effects) os << " " << e;
  os << "\n\n";
  // A friction law used outside its data for most of the run: said before anything else, since
  // every verdict below is then an extrapolation of the law.
  if (const auto* b = rec.find_block(components::kFrictionRangeBlock))
    if (const auto* f = b->find_scalar("fraction_outside"); f && f->value > kMostlyOutsideData) {
      std::snprintf(
          line, sizeof line,
          "WARNING: the friction law is used outside its data for %.0f %% of the run: the verdict below is an "
          "extrapolation of the law (see \"Friction data\")\n\n",
          100 * f->value);
      os << line;
    }
  // The verdict first: whether it shuddered is what a reader looks for.
  print_verdict(os, sc.kind() == ModelKind::kDriveline ? "Coupling judder" : "Shudder", rec);
  // Friction outside its data (components/friction_range_block.hpp): said once, every kind.
  if (const auto* b = rec.find_block(components::kFrictionRangeBlock))
    if (const auto* t = b->find_text("summary")) os << "Friction data: " << t->value << "\n";
  os << "\n";
  // Each kind's own section: one print_section overload per kind above (no fallback, so a new
  // kind without its section does not compile).
  std::visit([&](const auto& m) { print_section(os, m, rec); }, sc.model);
}

}  // namespace shudder::report
