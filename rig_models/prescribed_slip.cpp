#include "components/friction_range_block.hpp"
#include "rig_models/prescribed_slip.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string_view>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "components/channel_recorder.hpp"
#include "rig_models/thermal_step_plan.hpp"
#include "components/energy_scalars.hpp"

namespace shudder::rig_models {

namespace {

// Everything recorded at one instant; samples between thermal steps interpolate two of these.
struct Probe {
  double slip_rpm, force_N, torque_Nm, clutch_torque_Nm, tc_C, ir_C, sump_C, interface_mean_C, interface_max_C,
      field_max_C, mean_mu, heat_W, flow_ml_min, rig_C;
};

// The friction side of a Probe at time t with the ring temperatures ring_T (and the film's mean
// mean_interface_C for the oil flow): slip, force, torques, friction coefficient, heat, flow.
// `heat` gets the ring heat powers.
void measure_friction(Probe& p, const clutch::WetClutch& clutch, const components::DriveCycle& cycle,
                      const components::BearingDrag& drag, const components::TorqueCell& cell,
                      const components::LoadCell& load_cell, double drift, double t, const Eigen::VectorXd& ring_T,
                      double mean_interface_C, Eigen::VectorXd& heat, clutch::WetClutch::RingScratch& scratch) {
  const auto& th = clutch.thermal();
  const double slip_rpm = cycle.slip_speed_rpm(t);
  const double slip = units::rpm_to_rad_s(slip_rpm);
  const double force = cycle.normal_force_N(t);
  clutch.ring_torque_Nm(slip, force, ring_T, heat, &scratch);
  heat *= drift;
  const double m = std::copysign(clutch.params().sliding_interfaces * heat.sum(), slip);
  heat *= std::abs(slip);
  const double drag_Nm = drag.enabled ? std::copysign(drag.equivalent_mu * force * drag.radius_m, slip) : 0.0;
  const double n = clutch.params().sliding_interfaces;
  const double denom = n * force * clutch.mean_radius_m();
  p.slip_rpm = slip_rpm;
  p.force_N = load_cell.reading_N(force);
  p.torque_Nm = cell.reading_Nm(m + drag_Nm);
  p.clutch_torque_Nm = m;
  p.mean_mu = denom > 0.0 ? std::abs(m) / denom : 0.0;
  p.heat_W = n * heat.sum();
  p.flow_ml_min = units::m3_s_to_ml_min(th.interface_flow_m3_s(slip, mean_interface_C));
}

// Everything at t with the state's temperatures. `heat` gets the ring heat powers there: exactly
// what the next backward Euler step's Simpson rule needs at its start, so the step reuses them.
// The ring torques are evaluated once for the torque and the heat (WetClutch::torque_Nm and
// ring_heat_W would each evaluate them, with the same numbers).
Probe measure(const clutch::WetClutch& clutch, const clutch::ThermalState& s, const components::DriveCycle& cycle,
              const components::BearingDrag& drag, const components::TorqueCell& cell,
              const components::LoadCell& load_cell, double drift, double t, Eigen::VectorXd& heat,
              clutch::WetClutch::RingScratch& scratch) {
  const auto& th = clutch.thermal();
  const Eigen::VectorXd ring_T = th.interface_temps_C(s);
  Probe p{};
  measure_friction(p, clutch, cycle, drag, cell, load_cell, drift, t, ring_T, th.mean_interface_temp_C(s), heat,
                   scratch);
  p.tc_C = s.sensor_temp_C;
  p.ir_C = th.ir_C(s);
  p.sump_C = s.sump_temp_C;
  p.interface_mean_C = th.mean_interface_temp_C(s);
  p.interface_max_C = ring_T.maxCoeff();
  p.field_max_C = th.max_temp_C(s);
  p.rig_C = s.rig_temp_C;
  return p;
}

}  // namespace

dynamics::Recording run_prescribed_slip(const clutch::WetClutch& clutch, const components::DriveCycle& cycle,
                                        const PrescribedSlipSettings& cfg) {
  if (!(cfg.duration_s > 0.0)) throw std::invalid_argument("duration must be > 0");
  if (!(cfg.thermal_step_s > 0.0)) throw std::invalid_argument("thermal step must be > 0");
  if (!(cfg.sample_rate_Hz > 0.0)) throw std::invalid_argument("sample rate must be > 0");
  const auto& th = clutch.thermal();

  // Every channel but the time is evaluated at the thermal steps' ends (a Probe) and
  // interpolated to the samples in between (channel_recorder.hpp).
  namespace sn = dynamics::signal_names;
  using Recorder = components::ChannelRecorder<double, Probe>;
  const auto probed = [](std::string_view name, std::string_view units, double Probe::*field) {
    return Recorder::interpolated(name, units, [field](const Probe& p) { return p.*field; });
  };
  // The drive cycle's and the friction's channels, evaluated afresh at samples inside a thermal
  // step (the slip and the force may bend there, the friction bends with them); the temperatures
  // are interpolated, as they change smoothly (channel_recorder.hpp).
  const auto refined = [](std::string_view name, std::string_view units, double Probe::*field) {
    return Recorder::refined(name, units, [field](const Probe& p) { return p.*field; });
  };
  dynamics::Recording rec;
  Recorder recorder(rec, {
                             Recorder::sampled(sn::kTime, "s", [](double t_s) { return t_s; }),
                             refined(sn::kSpeed, "rpm", &Probe::slip_rpm),
                             refined(sn::kNormalForce, "N", &Probe::force_N),
                             refined(sn::kTorque, "N m", &Probe::torque_Nm),
                             probed(sn::kTemp, "degC", &Probe::tc_C),
                             probed(sn::kIrTemp, "degC", &Probe::ir_C),
                             probed(sn::kSumpTemp, "degC", &Probe::sump_C),
                             refined(sn::kClutchTorque, "N m", &Probe::clutch_torque_Nm),
                             probed(sn::kInterfaceMeanTemp, "degC", &Probe::interface_mean_C),
                             probed(sn::kInterfaceMaxTemp, "degC", &Probe::interface_max_C),
                             probed(sn::kMaxTemp, "degC", &Probe::field_max_C),
                             refined(sn::kFrictionCoefficient, "1", &Probe::mean_mu),
                             refined(sn::kHeatPower, "W", &Probe::heat_W),
                             refined(sn::kInterfaceOilFlow, "ml/min", &Probe::flow_ml_min),
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
  // The distance slid over [ta, ta + h], Simpson's rule (exact for the piecewise-linear cycle
  // within a segment).
  const auto slid_m = [&](double ta, double h) {
    return h * (sliding_speed(ta) + 4.0 * sliding_speed(ta + 0.5 * h) + sliding_speed(ta + h)) / 6.0;
  };
  double sliding_m = 0.0;
  // A step's end is evaluated twice at the same slip (old temperatures for the step's heat,
  // new ones for the probe): the friction law's speed-only work is kept between the two.
  clutch::WetClutch::RingScratch scratch;
  const Probe recorder_start = measure(clutch, state, cycle, cfg.bearing_drag, cfg.torque_cell, cfg.load_cell,
                                       cfg.friction_drift.factor(sliding_m), 0.0, h0, scratch);
  recorder.start(recorder_start);
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
  Eigen::VectorXd predicted_T;  // BDF2: the film temperatures extrapolated to the step's end
  // For samples inside a step: the film temperatures at its two ends and between them, the
  // probe at its start, the sliding distance there, and a heat scratch of their own.
  Eigen::VectorXd film_start_C = th.interface_temps_C(state), film_end_C, film_between_C, heat_inside;
  Probe before = recorder_start;
  // BDF2's steps end on the cycles' breakpoints and grow by at most 2x (thermal_step_plan.hpp);
  // backward Euler keeps its fixed grid.
  std::vector<double> knots_s = cycle.slip_speed_rpm.times_s();
  knots_s.insert(knots_s.end(), cycle.normal_force_N.times_s().begin(), cycle.normal_force_N.times_s().end());
  const ThermalStepPlan plan(std::move(knots_s), cfg.thermal_step_s, cfg.duration_s);
  const bool bdf2 = cfg.thermal_scheme == ThermalScheme::kBdf2;
  double previous_dt = 0.0;
  long thermal_steps = 0;
  while (state.time_s < cfg.duration_s - 1e-12) {
    const double t0 = state.time_s;
    const double dt = bdf2 ? plan.next_step_s(t0, previous_dt) : std::min(cfg.thermal_step_s, cfg.duration_s - t0);
    previous_dt = dt;
    ++thermal_steps;
    const double tm = t0 + 0.5 * dt, t1 = t0 + dt;
    const double sliding_start_m = sliding_m;
    if (bdf2) {
      // Heat at the step's end with the film temperatures extrapolated there (second order
      // without iterating); the sliding distance still by Simpson's rule.
      th.predicted_interface_temps_C(state, dt, predicted_T);
      const double slip1 = units::rpm_to_rad_s(cycle.slip_speed_rpm(t1));
      clutch.ring_heat_W(slip1, cycle.normal_force_N(t1), predicted_T, h1, &scratch);
      sliding_m += slid_m(t0, dt);
      h1 *= cfg.friction_drift.factor(sliding_m);
      // The data range takes each step at its middle, as under backward Euler (film
      // temperatures half way to the predicted ones), before the step moves the field.
      film_between_C = 0.5 * (film_start_C + predicted_T);
      data_range.add(dt, units::rpm_to_rad_s(cycle.slip_speed_rpm(tm)), th.ring_radius_m(), film_between_C,
                     cycle.normal_force_N(tm));
      th.step_bdf2(state, workspace, dt, h1, slip1);
    } else {
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
      data_range.add(dt, units::rpm_to_rad_s(cycle.slip_speed_rpm(tm)), th.ring_radius_m(), ring_T,
                     cycle.normal_force_N(tm));
    }
    state.time_s = t1;  // exact end time, free of accumulated round-off

    const Probe after = measure(clutch, state, cycle, cfg.bearing_drag, cfg.torque_cell, cfg.load_cell,
                                cfg.friction_drift.factor(sliding_m), t1, h0, scratch);
    while (next_sample < n_samples) {
      const double ts = static_cast<double>(next_sample) / cfg.sample_rate_Hz;
      if (ts > t1 + 1e-12) break;
      recorder.sample(ts);
      ++next_sample;
    }
    film_end_C = th.interface_temps_C(state);
    // A sample inside the step: the friction at its own slip and force, with the film
    // temperatures (and their mean, for the oil flow) linear in time between the step's ends.
    const auto inside = [&](double t, double w) {
      film_between_C = (1.0 - w) * film_start_C + w * film_end_C;
      const double mean_C = (1.0 - w) * before.interface_mean_C + w * after.interface_mean_C;
      Probe p{};
      measure_friction(p, clutch, cycle, cfg.bearing_drag, cfg.torque_cell, cfg.load_cell,
                       cfg.friction_drift.factor(sliding_start_m + slid_m(t0, t - t0)), t, film_between_C, mean_C,
                       heat_inside, scratch);
      return p;
    };
    recorder.step(after, t0, t1, inside);
    film_start_C.swap(film_end_C);
    before = after;
    peak_interface_C = std::max(peak_interface_C, after.interface_max_C);
    take_snapshots(t1, dt);
  }

  // Grid for the snapshots.
  for (int i = 0; i < th.radial_cells(); ++i) rec.grid_r_m.push_back(th.ring_radius_m()[i]);
  for (int j = 0; j < th.nodes_per_ring(); ++j) rec.grid_z_m.push_back(th.node_z_m()[j]);

  // Summary scalars: energy in the whole clutch (all interfaces).
  rec.scalars = components::heat_account_scalars(clutch, state);
  rec.scalars.push_back({"peak_interface_temp_C", "degC", peak_interface_C});
  rec.scalars.push_back({"final_max_temp_C", "degC", th.max_temp_C(state)});
  rec.scalars.push_back({"thermal_steps", "1", static_cast<double>(thermal_steps)});
  rec.blocks.push_back(components::friction_range_block(data_range));
  return rec;
}

}  // namespace shudder::rig_models
