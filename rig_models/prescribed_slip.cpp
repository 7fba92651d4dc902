#include "rig_models/friction_range_block.hpp"
#include "rig_models/prescribed_slip.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "rig_models/channel_recorder.hpp"
#include "rig_models/energy_scalars.hpp"

namespace shudder::rig_models {

namespace {

// Everything recorded at one instant; samples between thermal steps interpolate two of these.
struct Probe {
  double slip_rpm, force_N, torque_Nm, clutch_torque_Nm, tc_C, ir_C, sump_C,
      interface_mean_C, interface_max_C, field_max_C, mean_mu, heat_W, flow_ml_min, rig_C;
};

// `heat` gets the ring heat powers at t with the state's temperatures: exactly what the next
// thermal step's Simpson rule needs at its start, so the step reuses them. The ring torques are
// evaluated once for the torque and the heat (WetClutch::torque_Nm and ring_heat_W would each
// evaluate them, with the same numbers).
Probe measure(const clutch::WetClutch& clutch, const clutch::ThermalState& s,
              const DriveCycle& cycle, const BearingDrag& drag, const TorqueCell& cell,
              const LoadCell& load_cell, double drift, double t, Eigen::VectorXd& heat,
              clutch::WetClutch::RingScratch& scratch) {
  const auto& th = clutch.thermal();
  const double slip_rpm = cycle.slip_speed_rpm(t);
  const double slip = units::rpm_to_rad_s(slip_rpm);
  const double force = cycle.normal_force_N(t);
  const Eigen::VectorXd ring_T = th.interface_temps_C(s);
  clutch.ring_torque_Nm(slip, force, ring_T, heat, &scratch);
  heat *= drift;
  const double m = std::copysign(clutch.params().sliding_interfaces * heat.sum(), slip);
  heat *= std::abs(slip);
  const double drag_Nm = drag.enabled ? std::copysign(drag.equivalent_mu * force * drag.radius_m, slip) : 0.0;
  const double n = clutch.params().sliding_interfaces;
  const double denom = n * force * clutch.mean_radius_m();
  return Probe{slip_rpm,
               load_cell.reading_N(force),
               cell.reading_Nm(m + drag_Nm),
               m,
               s.sensor_temp_C,
               th.ir_C(s),
               s.sump_temp_C,
               th.mean_interface_temp_C(s),
               ring_T.maxCoeff(),
               th.max_temp_C(s),
               denom > 0.0 ? std::abs(m) / denom : 0.0,
               n * heat.sum(),
               units::m3_s_to_ml_min(th.interface_flow_m3_s(slip, th.mean_interface_temp_C(s))),
               s.rig_temp_C};
}

}  // namespace

dynamics::Recording run_prescribed_slip(const clutch::WetClutch& clutch, const DriveCycle& cycle,
                                        const PrescribedSlipSettings& cfg) {
  if (!(cfg.duration_s > 0.0)) throw std::invalid_argument("duration must be > 0");
  if (!(cfg.thermal_step_s > 0.0)) throw std::invalid_argument("thermal step must be > 0");
  if (!(cfg.sample_rate_Hz > 0.0)) throw std::invalid_argument("sample rate must be > 0");
  const auto& th = clutch.thermal();

  // Every channel but the time is evaluated at the thermal steps' ends (a Probe) and
  // interpolated to the samples in between (channel_recorder.hpp).
  namespace sn = dynamics::signal_names;
  using Recorder = ChannelRecorder<double, Probe>;
  const auto probed = [](std::string_view name, std::string_view units, double Probe::*field) {
    return Recorder::interpolated(name, units, [field](const Probe& p) { return p.*field; });
  };
  dynamics::Recording rec;
  Recorder recorder(rec, {
      Recorder::sampled(sn::kTime, "s", [](double t_s) { return t_s; }),
      probed(sn::kSpeed, "rpm", &Probe::slip_rpm),
      probed(sn::kNormalForce, "N", &Probe::force_N),
      probed(sn::kTorque, "N m", &Probe::torque_Nm),
      probed(sn::kTemp, "degC", &Probe::tc_C),
      probed(sn::kIrTemp, "degC", &Probe::ir_C),
      probed(sn::kSumpTemp, "degC", &Probe::sump_C),
      probed(sn::kClutchTorque, "N m", &Probe::clutch_torque_Nm),
      probed(sn::kInterfaceMeanTemp, "degC", &Probe::interface_mean_C),
      probed(sn::kInterfaceMaxTemp, "degC", &Probe::interface_max_C),
      probed(sn::kMaxTemp, "degC", &Probe::field_max_C),
      probed(sn::kFrictionCoefficient, "1", &Probe::mean_mu),
      probed(sn::kHeatPower, "W", &Probe::heat_W),
      probed(sn::kInterfaceOilFlow, "ml/min", &Probe::flow_ml_min),
      probed(sn::kRigTemp, "degC", &Probe::rig_C),
  });

  clutch::ThermalState state = clutch.initial_state();
  clutch::ThermalWorkspace workspace(th);
  const long n_samples = static_cast<long>(std::floor(cfg.duration_s * cfg.sample_rate_Hz + 1e-9)) + 1;
  long next_sample = 0;
  recorder.sample(0.0);
  Eigen::VectorXd h0, hm, h1;  // ring heat at a step's start, middle and end
  // Sliding distance at the mean radius (friction_drift), by the same Simpson rule as the heat.
  const double r_m = clutch.mean_radius_m();
  const auto sliding_speed = [&](double t) { return r_m * std::abs(units::rpm_to_rad_s(cycle.slip_speed_rpm(t))); };
  double sliding_m = 0.0;
  // A step's end is evaluated twice at the same slip (old temperatures for the step's heat,
  // new ones for the probe): the friction law's speed-only work is kept between the two.
  clutch::WetClutch::RingScratch scratch;
  recorder.start(measure(clutch, state, cycle, cfg.bearing_drag, cfg.torque_cell, cfg.load_cell,
                         cfg.friction_drift.factor(sliding_m), 0.0, h0, scratch));
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

  clutch::FrictionDataRange data_range(*clutch.fluid().friction);
  double peak_interface_C = th.interface_temps_C(state).maxCoeff();
  while (state.time_s < cfg.duration_s - 1e-12) {
    const double t0 = state.time_s;
    const double dt = std::min(cfg.thermal_step_s, cfg.duration_s - t0);
    const double tm = t0 + 0.5 * dt, t1 = t0 + dt;
    // Ring heat over the step with temperatures held at t0 (Simpson's rule).
    const Eigen::VectorXd ring_T = th.interface_temps_C(state);
    const auto heat_at = [&](double t, Eigen::VectorXd& h) {
      clutch.ring_heat_W(units::rpm_to_rad_s(cycle.slip_speed_rpm(t)), cycle.normal_force_N(t), ring_T, h, &scratch);
    };
    // h0 (at t0 with the temperatures at t0) is the previous measure()'s.
    heat_at(tm, hm);
    heat_at(t1, h1);
    const double v0 = sliding_speed(t0), vm = sliding_speed(tm), v1 = sliding_speed(t1);
    hm *= cfg.friction_drift.factor(sliding_m + 0.25 * dt * (v0 + vm));
    sliding_m += dt * (v0 + 4.0 * vm + v1) / 6.0;
    h1 *= cfg.friction_drift.factor(sliding_m);
    const Eigen::VectorXd mean_heat = (h0 + 4.0 * hm + h1) / 6.0;
    th.step(state, workspace, dt, mean_heat, units::rpm_to_rad_s(cycle.slip_speed_rpm(tm)));
    data_range.add(dt, units::rpm_to_rad_s(cycle.slip_speed_rpm(tm)), th.ring_radius_m(), ring_T, cycle.normal_force_N(tm));
    state.time_s = t1;  // exact end time, free of accumulated round-off

    const Probe after = measure(clutch, state, cycle, cfg.bearing_drag, cfg.torque_cell, cfg.load_cell,
                                cfg.friction_drift.factor(sliding_m), t1, h0, scratch);
    while (next_sample < n_samples) {
      const double ts = static_cast<double>(next_sample) / cfg.sample_rate_Hz;
      if (ts > t1 + 1e-12) break;
      recorder.sample(ts);
      ++next_sample;
    }
    recorder.step(after, t0, t1);
    peak_interface_C = std::max(peak_interface_C, after.interface_max_C);
    take_snapshots(t1, dt);
  }

  // Grid for the snapshots.
  for (int i = 0; i < th.radial_cells(); ++i) rec.grid_r_m.push_back(th.ring_radius_m()[i]);
  for (int j = 0; j < th.nodes_per_ring(); ++j) rec.grid_z_m.push_back(th.node_z_m()[j]);

  // Summary scalars: energy in the whole clutch (all interfaces).
  rec.scalars = heat_account_scalars(clutch, state);
  rec.scalars.push_back({"peak_interface_temp_C", "degC", peak_interface_C});
  rec.scalars.push_back({"final_max_temp_C", "degC", th.max_temp_C(state)});
  rec.scalars.push_back({"thermal_steps", "1", std::ceil(cfg.duration_s / cfg.thermal_step_s - 1e-9)});
  rec.blocks.push_back(friction_range_block(data_range));
  return rec;
}

}  // namespace shudder::rig_models
