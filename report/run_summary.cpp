#include "report/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <set>
#include <string>
#include <variant>

#include "analysis/shudder_detection.hpp"
#include "dynamics/signal_names.hpp"

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
  return s ? s->value : std::numeric_limits<double>::quiet_NaN();
}

// A driveline run: the car, the coupling and its hydraulics at key times.
void print_section(std::ostream& os, const rig_models::DrivelineModel& model, const dynamics::Recording& rec) {
  const double end = model.settings.duration_s;
  char line[512];
  std::set<double> times{0.0, end};
  for (double t : model.manoeuvre.engine_torque_Nm.times_s()) if (t > 0 && t < end) times.insert(t);
  for (int k = 1; k < 5; ++k) times.insert(end * k / 5.0);
  os << "   t [s]  car [km/h]  engine [rpm]  engine [Nm]  coupling slip [rpm]  coupling [Nm]  rear axle [Nm]"
        "  pressure [bar]  interface max [C]\n";
  for (double t : times) {
    std::snprintf(line, sizeof line, "%8.2f  %10.2f  %12.1f  %11.1f  %19.3f  %13.1f  %14.1f  %14.2f  %17.2f\n", t,
                  signal_at(rec, sn::kVehicleSpeed, t), signal_at(rec, sn::kEngineSpeed, t),
                  signal_at(rec, sn::kEngineTorque, t), signal_at(rec, sn::kCouplingSlip, t),
                  signal_at(rec, sn::kCouplingTorque, t), signal_at(rec, sn::kRearAxleTorque, t),
                  signal_at(rec, sn::kPressure, t), signal_at(rec, sn::kInterfaceMaxTemp, t));
    os << line;
  }
  const double code = scalar(rec, "coupling_verdict_code");
  const bool oscillates = code == 1 || code == 2;
  const std::string verdict(
      analysis::to_string(oscillates ? analysis::kVerdicts[static_cast<std::size_t>(code)] : analysis::Verdict::kNone));
  std::snprintf(line, sizeof line, "\nCoupling judder: %s", verdict.c_str());
  os << line;
  if (oscillates) {
    std::snprintf(line, sizeof line, " at %.2f Hz, amplitude %.1f N m (FFT of the coupling torque)",
                  scalar(rec, "coupling_oscillation_frequency_Hz"), scalar(rec, "coupling_oscillation_amplitude_Nm"));
    os << line;
  }
  std::snprintf(line, sizeof line,
                "\nCoupling: heat %.1f J, peak interface %.2f C; %.0f stick and %.0f breakaway events\n"
                "Driveline: locked shuffle mode %.2f Hz (damping ratio %.3f); mechanical energy error "
                "%.2e (relative); %.0f integrator steps\n",
                scalar(rec, "heat_generated_J"), scalar(rec, "peak_interface_temp_C"), scalar(rec, "stick_events"),
                scalar(rec, "breakaway_events"), scalar(rec, "shuffle_frequency_Hz"),
                scalar(rec, "shuffle_damping_ratio"), scalar(rec, "mechanical_energy_relative_error"),
                scalar(rec, "integrator_steps"));
  os << line;
}

// The rig and prescribed slip: the drive cycle's key times, temperatures and the heat account.
void print_drive_cycle_section(std::ostream& os, const rig_models::DriveCycle& cycle, double end,
                               const dynamics::Recording& rec) {
  char line[512];
  // Key times: every drive breakpoint inside the run, five even splits, and the end.
  std::set<double> times{0.0, end};
  for (double t : cycle.slip_speed_rpm.times_s()) if (t > 0 && t < end) times.insert(t);
  for (int k = 1; k < 5; ++k) times.insert(end * k / 5.0);
  os << "   t [s]  speed [rpm]  force [kN]  torque [Nm]  thermocouple [C]  IR [C]  sump [C]\n";
  for (double t : times) {
    std::snprintf(line, sizeof line, "%8.2f  %11.2f  %10.2f  %11.2f  %16.2f  %7.2f  %8.2f\n", t,
                  signal_at(rec, sn::kSpeed, t), signal_at(rec, sn::kNormalForce, t) / 1e3,
                  signal_at(rec, sn::kTorque, t), signal_at(rec, sn::kTemp, t),
                  signal_at(rec, sn::kIrTemp, t), signal_at(rec, sn::kSumpTemp, t));
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
                scalar(rec, "heat_generated_J"), scalar(rec, "heat_stored_in_discs_J"),
                scalar(rec, "heat_to_sump_J"), scalar(rec, "heat_to_rig_J"),
                scalar(rec, "energy_balance_relative_error"));
  os << line;
}

void print_section(std::ostream& os, const rig_models::PrescribedSlipModel& model, const dynamics::Recording& rec) {
  print_drive_cycle_section(os, model.cycle, model.settings.duration_s, rec);
}

void print_section(std::ostream& os, const rig_models::RigModel& model, const dynamics::Recording& rec) {
  print_drive_cycle_section(os, model.cycle, model.settings.duration_s, rec);
  char line[512];
  std::snprintf(line, sizeof line,
                "Rig: torsion bar %.4g N m/rad, clutch-side mode %.2f Hz; mechanical energy error "
                "%.2e (relative)\n"
                "Integrator: %.0f steps, %.0f rhs evaluations; events: %.0f stick, %.0f breakaway, "
                "%.0f reversal\n",
                scalar(rec, "bar_stiffness_Nm_per_rad"), scalar(rec, "clutch_side_frequency_Hz"),
                scalar(rec, "mechanical_energy_relative_error"), scalar(rec, "integrator_steps"),
                scalar(rec, "rhs_evaluations"), scalar(rec, "stick_events"),
                scalar(rec, "breakaway_events"), scalar(rec, "reversal_events"));
  os << line;
}

}  // namespace

void print_run_summary(std::ostream& os, const io::Scenario& sc, const dynamics::Recording& rec) {
  const double end = rig_models::duration_s(sc.model);
  char line[512];
  std::snprintf(line, sizeof line, "Scenario  %s (%s), fluid %s, %.3g s simulated\n",
                sc.name.c_str(), std::string(model_kind_name(sc.kind())).c_str(), sc.fluid.name.c_str(), end);
  os << line;
  os << "Effects on:";
  for (const auto& e : sc.enabled_effects) os << " " << e;
  os << "\n\n";
  // Each kind's own section: one print_section overload per kind above (no fallback, so a new
  // kind without its section does not compile).
  std::visit([&](const auto& m) { print_section(os, m, rec); }, sc.model);
}

}  // namespace shudder::report
