#include "rig_models/prescribed_slip.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shudder::rig_models {

namespace {

constexpr double kRadPerSPerRpm = 2.0 * std::numbers::pi / 60.0;

// Everything recorded at one instant; samples between thermal steps interpolate two of these.
struct Probe {
  double time_s, slip_rpm, force_N, torque_Nm, clutch_torque_Nm, tc_C, ir_C, sump_C,
      interface_mean_C, interface_max_C, field_max_C, mean_mu, heat_W, flow_ml_min, rig_C;
};

Probe measure(const clutch::WetClutch& clutch, const clutch::ThermalState& s,
              const DriveCycle& cycle, const BearingDrag& drag, double t) {
  const auto& th = clutch.thermal();
  const double slip_rpm = cycle.slip_speed_rpm(t);
  const double slip = slip_rpm * kRadPerSPerRpm;
  const double force = cycle.normal_force_N(t);
  const Eigen::VectorXd ring_T = th.interface_temps_C(s);
  const double m = clutch.torque_Nm(slip, force, ring_T);
  const double drag_Nm = drag.enabled ? std::copysign(drag.equivalent_mu * force * drag.radius_m, slip) : 0.0;
  Eigen::VectorXd heat;
  clutch.ring_heat_W(slip, force, ring_T, heat);
  const double n = clutch.params().sliding_interfaces;
  const double denom = n * force * clutch.mean_radius_m();
  return Probe{t,
               slip_rpm,
               force,
               m + drag_Nm,
               m,
               s.sensor_temp_C,
               th.ir_C(s),
               s.sump_temp_C,
               th.mean_interface_temp_C(s),
               ring_T.maxCoeff(),
               th.max_temp_C(s),
               denom > 0.0 ? std::abs(m) / denom : 0.0,
               n * heat.sum(),
               th.interface_flow_m3_s(slip, th.mean_interface_temp_C(s)) * 6e7,
               s.rig_temp_C};
}

}  // namespace

dynamics::Recording run_prescribed_slip(const clutch::WetClutch& clutch, const DriveCycle& cycle,
                                        const PrescribedSlipSettings& cfg) {
  if (!(cfg.duration_s > 0.0)) throw std::invalid_argument("duration must be > 0");
  if (!(cfg.thermal_step_s > 0.0)) throw std::invalid_argument("thermal step must be > 0");
  if (!(cfg.sample_rate_Hz > 0.0)) throw std::invalid_argument("sample rate must be > 0");
  const auto& th = clutch.thermal();

  dynamics::Recording rec;
  struct Channel { const char* name; const char* units; double Probe::*field; };
  static constexpr Channel kChannels[] = {
      {"time_s", "s", &Probe::time_s},
      {"speed_rpm", "rpm", &Probe::slip_rpm},
      {"normal_force_N", "N", &Probe::force_N},
      {"torque_Nm", "N m", &Probe::torque_Nm},
      {"temp_C", "degC", &Probe::tc_C},
      {"ir_temp_C", "degC", &Probe::ir_C},
      {"sump_temp_C", "degC", &Probe::sump_C},
      {"clutch_torque_Nm", "N m", &Probe::clutch_torque_Nm},
      {"interface_mean_temp_C", "degC", &Probe::interface_mean_C},
      {"interface_max_temp_C", "degC", &Probe::interface_max_C},
      {"max_temp_C", "degC", &Probe::field_max_C},
      {"friction_coefficient", "1", &Probe::mean_mu},
      {"heat_power_W", "W", &Probe::heat_W},
      {"interface_oil_flow_ml_min", "ml/min", &Probe::flow_ml_min},
      {"rig_temp_C", "degC", &Probe::rig_C},
  };
  for (const auto& c : kChannels) rec.add_signal(c.name, c.units);
  const auto record = [&](const Probe& a, const Probe& b, double t) {
    const double w = b.time_s > a.time_s ? (t - a.time_s) / (b.time_s - a.time_s) : 1.0;
    for (std::size_t k = 0; k < std::size(kChannels); ++k)
      rec.signals[k].values.push_back((1 - w) * a.*kChannels[k].field + w * b.*kChannels[k].field);
    rec.signals[0].values.back() = t;
  };

  clutch::ThermalState state = clutch.initial_state();
  clutch::ThermalWorkspace workspace(th);
  const long n_samples = static_cast<long>(std::floor(cfg.duration_s * cfg.sample_rate_Hz + 1e-9)) + 1;
  long next_sample = 0;
  Probe before = measure(clutch, state, cycle, cfg.bearing_drag, 0.0);
  record(before, before, 0.0);
  next_sample = 1;

  std::vector<double> snaps = cfg.snapshot_times_s;
  std::sort(snaps.begin(), snaps.end());
  std::size_t next_snap = 0;
  const auto take_snapshots = [&](double t_now, double dt) {
    while (next_snap < snaps.size() && snaps[next_snap] <= t_now + 0.5 * dt) {
      rec.snapshots.push_back({state.time_s, th.field_C(state)});
      ++next_snap;
    }
  };
  take_snapshots(0.0, cfg.thermal_step_s);

  const double n_if = clutch.params().sliding_interfaces;
  Eigen::VectorXd h0, hm, h1;
  double peak_interface_C = th.interface_temps_C(state).maxCoeff();
  while (state.time_s < cfg.duration_s - 1e-12) {
    const double t0 = state.time_s;
    const double dt = std::min(cfg.thermal_step_s, cfg.duration_s - t0);
    const double tm = t0 + 0.5 * dt, t1 = t0 + dt;
    // Ring heat over the step with temperatures held at t0 (Simpson's rule).
    const Eigen::VectorXd ring_T = th.interface_temps_C(state);
    const auto heat_at = [&](double t, Eigen::VectorXd& h) {
      clutch.ring_heat_W(cycle.slip_speed_rpm(t) * kRadPerSPerRpm, cycle.normal_force_N(t), ring_T, h);
    };
    heat_at(t0, h0);
    heat_at(tm, hm);
    heat_at(t1, h1);
    const Eigen::VectorXd mean_heat = (h0 + 4.0 * hm + h1) / 6.0;
    th.step(state, workspace, dt, mean_heat, cycle.slip_speed_rpm(tm) * kRadPerSPerRpm);
    state.time_s = t1;  // exact end time, free of accumulated round-off

    const Probe after = measure(clutch, state, cycle, cfg.bearing_drag, t1);
    while (next_sample < n_samples) {
      const double ts = static_cast<double>(next_sample) / cfg.sample_rate_Hz;
      if (ts > t1 + 1e-12) break;
      record(before, after, ts);
      ++next_sample;
    }
    before = after;
    peak_interface_C = std::max(peak_interface_C, after.interface_max_C);
    take_snapshots(t1, dt);
  }

  // Grid for the snapshots.
  for (int i = 0; i < th.radial_cells(); ++i) rec.grid_r_m.push_back(th.ring_radius_m()[i]);
  for (int j = 0; j < th.nodes_per_ring(); ++j) rec.grid_z_m.push_back(th.node_z_m()[j]);

  // Summary scalars: energy in the whole clutch (all interfaces).
  const auto& e = state.energy;
  const double stored = th.stored_energy_J(state) - e.initial_stored_J;
  const double imbalance = th.energy_imbalance_J(state);
  rec.scalars = {
      {"heat_generated_J", "J", n_if * e.generated_J},
      {"heat_stored_in_discs_J", "J", n_if * stored},
      {"heat_to_sump_J", "J", n_if * e.to_sump_J},
      {"heat_to_rig_J", "J", n_if * e.to_rig_J},
      {"energy_balance_relative_error", "1", e.generated_J > 0 ? std::abs(imbalance) / e.generated_J : 0.0},
      {"peak_interface_temp_C", "degC", peak_interface_C},
      {"final_max_temp_C", "degC", th.max_temp_C(state)},
      {"thermal_steps", "1", std::ceil(cfg.duration_s / cfg.thermal_step_s - 1e-9)},
  };
  return rec;
}

}  // namespace shudder::rig_models
