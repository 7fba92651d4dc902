#include "rig_models/realtime_run.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <initializer_list>
#include <stdexcept>
#include <string>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "components/energy_scalars.hpp"
#include "rig_models/realtime_coupling.hpp"

namespace shudder::rig_models {

namespace {

namespace sn = dynamics::signal_names;

long whole_steps(double span_s, double step_s, const char* what) {
  const double ratio = span_s / step_s;
  const double n = std::round(ratio);
  if (!(n >= 1.0) || std::abs(ratio - n) > 1e-9 * n) {
    char line[256];
    std::snprintf(line, sizeof line,
                  "--fixed-step %g s: %s (%g s) must be a whole number of fixed steps; choose a step that divides it",
                  step_s, what, span_s);
    throw std::invalid_argument(line);
  }
  return static_cast<long>(n);
}

// Channels filled by a per-sample function, in declaration order.
struct Columns {
  dynamics::Recording& rec;
  std::size_t first;
  void add(std::string_view name, std::string_view units) { rec.add_signal(std::string(name), std::string(units)); }
  /// The channels a measured run carries (docs/formats/measured_run.md), first in both runners' lists, in this order:
  /// time, speed, normal force, torque, thermocouple, IR, sump.
  void add_measured_channels() {
    add(sn::kTime, "s");
    add(sn::kSpeed, "rpm");
    add(sn::kNormalForce, "N");
    add(sn::kTorque, "N m");
    add(sn::kTemp, "degC");
    add(sn::kIrTemp, "degC");
    add(sn::kSumpTemp, "degC");
  }
  void push(std::initializer_list<double> values) {
    std::size_t c = first;
    for (double v : values) rec.signals[c++].values.push_back(v);
  }
};

void finish_recording(dynamics::Recording& rec, RealtimeClutch& clutch, double step_s, long thermal_steps) {
  clutch.finish();
  const auto& th = clutch.clutch().thermal();
  for (int i = 0; i < th.radial_cells(); ++i) rec.grid_r_m.push_back(th.ring_radius_m()[i]);
  for (int j = 0; j < th.nodes_per_ring(); ++j) rec.grid_z_m.push_back(th.node_z_m()[j]);
  rec.scalars = components::heat_account_scalars(clutch.clutch(), clutch.thermal_state());
  rec.scalars.push_back({"final_max_temp_C", "degC", th.max_temp_C(clutch.thermal_state())});
  rec.scalars.push_back({"fixed_step_s", "s", step_s});
  rec.scalars.push_back({"thermal_steps", "1", static_cast<double>(thermal_steps)});
}

}  // namespace

dynamics::Recording run_fixed_step(const PrescribedSlipModel& model, const clutch::WetClutch& clutch, double step_s) {
  const auto& cfg = model.settings;
  const RealtimeSettings rt{step_s, cfg.thermal_step_s};
  const long n_steps = whole_steps(cfg.duration_s, step_s, "scenario.duration_s");
  const long every = whole_steps(1.0 / cfg.sample_rate_Hz, step_s, "the sample interval 1 / output.sample_rate_Hz");
  const auto& cycle = model.cycle;
  RealtimeCoupling coupling(clutch, cfg.bearing_drag, rt, cycle.normal_force_N(0.0));

  dynamics::Recording rec;
  Columns col{rec, 0};
  col.add_measured_channels();
  col.add(sn::kClutchTorque, "N m");
  col.add(sn::kInterfaceMeanTemp, "degC");
  col.add(sn::kInterfaceMaxTemp, "degC");
  col.add(sn::kMaxTemp, "degC");
  col.add(sn::kHeatPower, "W");
  col.add(sn::kRigTemp, "degC");
  const auto record = [&](double t, double slip_rpm, double force) {
    const ThermalOutputs& th = coupling.thermal();
    col.push({t, slip_rpm, force, coupling.torque_Nm(), th.thermocouple_C, th.ir_C, th.sump_C,
              coupling.clutch_torque_Nm(), th.interface_mean_C, th.interface_max_C, th.field_max_C, coupling.heat_W(),
              th.rig_C});
  };
  double peak_C = coupling.thermal().interface_max_C;
  for (long k = 0; k < n_steps; ++k) {
    const double t = static_cast<double>(k) * step_s;
    const double slip_rpm = cycle.slip_speed_rpm(t), force = cycle.normal_force_N(t);
    coupling.step(units::rpm_to_rad_s(slip_rpm), force);
    // The first step's outputs are those at t = 0 (the inputs there, the start temperatures).
    if (k == 0) record(0.0, slip_rpm, force);
    if ((k + 1) % every == 0) {
      const double t1 = coupling.time_s();
      record(t1, cycle.slip_speed_rpm(t1), cycle.normal_force_N(t1));
    }
    peak_C = std::max(peak_C, coupling.thermal().interface_max_C);
  }
  finish_recording(rec, coupling.clutch(), step_s, n_steps / steps_per_thermal_step(rt));
  rec.scalars.push_back({"peak_interface_temp_C", "degC", peak_C});
  return rec;
}

namespace {

// The kinds built on dynamics::Simulation take its fixed-step mode: the adaptive run's own
// network, right-hand side and multi-rate thermal coupling, advanced by RK4 at the step.
template <class KindModel>
dynamics::Recording network_fixed_step(KindModel model, const clutch::WetClutch& clutch, double step_s,
                                       double thermal_step_s) {
  const auto& cfg = model.settings;
  whole_steps(cfg.duration_s, step_s, "scenario.duration_s");
  whole_steps(thermal_step_s, step_s, "the thermal step solver.thermal_step_ms");
  whole_steps(1.0 / cfg.sample_rate_Hz, step_s, "the sample interval 1 / output.sample_rate_Hz");
  model.params.integrator.fixed_step_s = step_s;
  dynamics::Recording rec = simulate(model, clutch);
  rec.scalars.push_back({"fixed_step_s", "s", step_s});
  return rec;
}

}  // namespace

dynamics::Recording run_fixed_step(const RigModel& model, const clutch::WetClutch& clutch, double step_s) {
  return network_fixed_step(model, clutch, step_s, model.settings.thermal_step_s);
}

dynamics::Recording run_fixed_step(const DrivelineModel& model, const clutch::WetClutch& clutch, double step_s) {
  return network_fixed_step(model, clutch, step_s, model.settings.slow_step_s);
}

}  // namespace shudder::rig_models
