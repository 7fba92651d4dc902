#include "components/friction_range_block.hpp"
#include "rig_models/lsctr_rig.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "components/channel_recorder.hpp"
#include "components/energy_scalars.hpp"
#include "components/multirate_clutch.hpp"

namespace shudder::rig_models {

namespace {

// Index of the mode in which the housing moves most relative to the drive.
Eigen::Index clutch_side_mode(const dynamics::Modes& m) {
  Eigen::Index best = 0;
  double best_share = -1.0;
  for (Eigen::Index j = 0; j < m.shapes.cols(); ++j) {
    const double h = std::abs(m.shapes(LsctrRig::kHousing, j));
    const double share = h / (h + std::abs(m.shapes(LsctrRig::kDrive, j)));
    if (share > best_share) {
      best_share = share;
      best = j;
    }
  }
  return best;
}

void require(bool ok, const char* what) {
  if (!ok) throw std::invalid_argument(what);
}

}  // namespace

SpeedLoopGains speed_loop_gains(const RigParams& p) {
  const double wc = units::kTwoPi * p.speed_loop_bandwidth_Hz;
  const double kp = p.drive_inertia_kg_m2 * wc;
  return {kp, kp * wc / 4.0};
}

LsctrRig::LsctrRig(const RigParams& params, const clutch::WetClutch& clutch, const components::DriveCycle& cycle)
    : p_(params),
      contact_(clutch, params.bearing_drag, params.stick_time),
      speed_rpm_(cycle.slip_speed_rpm),
      force_N_(cycle.normal_force_N) {
  require(p_.drive_inertia_kg_m2 > 0, "rig drive inertia must be > 0 kg m^2");
  require(p_.housing_inertia_kg_m2 > 0, "rig housing inertia must be > 0 kg m^2");
  require(p_.bar_stiffness_Nm_per_rad > 0 || p_.bar_natural_frequency_Hz > 0,
          "torsion bar needs a natural frequency > 0 Hz or a stiffness > 0 N m/rad");
  require(p_.bar_damping_ratio >= 0, "torsion bar damping ratio must be >= 0");
  require(p_.speed_loop_bandwidth_Hz > 0, "speed loop bandwidth must be > 0 Hz");
  require(p_.motor_torque_limit_Nm > 0, "motor torque limit must be > 0 N m");

  const SpeedLoopGains gains = speed_loop_gains(p_);
  kp_ = gains.kp_Nms_per_rad;
  ki_ = gains.ki_Nm_per_rad;
  // The tuning's modal analysis does not evaluate the clutch law; any context serves.
  const auto law = std::make_shared<components::ClutchContactLaw>(
      contact_, std::make_shared<components::ClutchContext>(start_inputs()));
  const auto damping = [&](double k_bar) {
    return 2.0 * p_.bar_damping_ratio * std::sqrt(k_bar * p_.housing_inertia_kg_m2);
  };

  if (p_.bar_stiffness_Nm_per_rad > 0) {
    k_bar_ = k_network_ = p_.bar_stiffness_Nm_per_rad;
    c_bar_ = damping(k_bar_);
    build(k_bar_, c_bar_, law);  // validates the network
    return;
  }
  // Start from the isolated housing on the bar, then correct on the full modal analysis (the
  // loop converges in one pass while the housing is decoupled by the slipping clutch, and keeps
  // the frequency right if elements are added around it).
  const double target = p_.bar_natural_frequency_Hz;
  k_bar_ = p_.housing_inertia_kg_m2 * std::pow(units::kTwoPi * target, 2);
  for (int iter = 0; iter < 8; ++iter) {
    k_network_ = k_bar_;
    c_bar_ = damping(k_bar_);
    const auto m = build(k_bar_, c_bar_, law).modes();
    const double f = m.frequencies_Hz[clutch_side_mode(m)];
    clutch_side_Hz_ = f;
    if (std::abs(f / target - 1.0) < 1e-10) break;
    k_bar_ *= std::pow(target / f, 2);
  }
}

dynamics::TorsionalNetwork LsctrRig::build(double k_bar, double c_bar,
                                           std::shared_ptr<const dynamics::ContactLaw> law) const {
  const components::PiecewiseLinear speed = speed_rpm_;
  dynamics::TorsionalNetwork n;
  n.add_inertia({"drive", p_.drive_inertia_kg_m2});
  n.add_inertia({"housing", p_.housing_inertia_kg_m2});
  n.add_motor({"motor", kDrive, [speed](double t) { return units::rpm_to_rad_s(speed(t)); }, kp_, ki_,
               p_.motor_torque_limit_Nm});
  if (p_.motor_ripple.amplitude_Nm > 0)
    n.add_torque_source({"motor_ripple", kDrive, components::MotorRippleTorque(p_.motor_ripple, speed_rpm_)});
  n.add_contact({"clutch", kDrive, kHousing, std::move(law)});
  n.add_shaft({"torsion_bar", kHousing, dynamics::kGround, k_bar, c_bar});
  n.validate();
  return n;
}

dynamics::TorsionalNetwork LsctrRig::network(std::shared_ptr<components::ClutchContext> clutch_context) const {
  return build(k_network_, c_bar_, std::make_shared<components::ClutchContactLaw>(contact_, std::move(clutch_context)));
}

dynamics::TorsionalNetwork LsctrRig::network(std::shared_ptr<components::ClutchContext> clutch_context,
                                             double bar_damping_ratio) const {
  const double c_bar = 2.0 * bar_damping_ratio * std::sqrt(k_network_ * p_.housing_inertia_kg_m2);
  return build(k_network_, c_bar, std::make_shared<components::ClutchContactLaw>(contact_, std::move(clutch_context)));
}

dynamics::TorsionalNetwork LsctrRig::network() const {
  return network(std::make_shared<components::ClutchContext>(start_inputs()));
}

double LsctrRig::clutch_side_frequency_Hz() const {
  if (clutch_side_Hz_ >= 0) return clutch_side_Hz_;
  const auto m = network().modes();
  return m.frequencies_Hz[clutch_side_mode(m)];
}

dynamics::Recording run_rig(const RigParams& params, const clutch::WetClutch& clutch,
                            const components::DriveCycle& cycle, const RigSettings& cfg) {
  if (!(cfg.duration_s > 0) || !(cfg.thermal_step_s > 0) || !(cfg.sample_rate_Hz > 0))
    throw std::invalid_argument("duration, thermal step and sample rate must be > 0");
  const LsctrRig rig(params, clutch, cycle);
  const auto& th = clutch.thermal();
  clutch::ThermalState ts = clutch.initial_state();
  const auto clutch_context = std::make_shared<components::ClutchContext>(
      components::ClutchHeldInputs{th.interface_temps_C(ts), cycle.normal_force_N});
  const auto& law = rig.clutch_contact();
  const dynamics::TorsionalNetwork network = rig.network(clutch_context);

  // Start in steady sliding (the bar already carries the friction torque and the speed loop's
  // integrator supplies it, so the record starts without a spurious transient), or at rest.
  dynamics::Simulation sim(network, params.integrator);
  Eigen::VectorXd theta = Eigen::VectorXd::Zero(2), omega = Eigen::VectorXd::Zero(2),
                  integral = Eigen::VectorXd::Zero(1);
  if (!params.start_at_rest) {
    const double w0 = units::rpm_to_rad_s(cycle.slip_speed_rpm(0.0));
    const double t0_Nm = law.kinetic_torque_Nm(*clutch_context, std::abs(w0), 0.0) * (w0 >= 0 ? 1.0 : -1.0);
    theta[LsctrRig::kHousing] = t0_Nm / rig.bar_stiffness_Nm_per_rad();
    omega[LsctrRig::kDrive] = w0;
    integral[0] = t0_Nm / rig.motor_ki();
  }
  sim.initialize(0.0, theta, omega, integral);

  // Channels: mechanical ones come from dynamics samples, thermal ones from the thermal state,
  // interpolated across each thermal step (channel_recorder.hpp).
  namespace sn = dynamics::signal_names;
  using Recorder = components::ChannelRecorder<dynamics::Sample, clutch::ThermalState>;
  using clutch::ThermalState;
  using dynamics::Sample;
  const double n_if = clutch.params().sliding_interfaces;
  const double r_eff = clutch.mean_radius_m();
  dynamics::Recording rec;
  Recorder recorder(
      rec,
      {
          Recorder::sampled(sn::kTime, "s", [](const Sample& s) { return s.t_s; }),
          Recorder::sampled(sn::kSpeed, "rpm",
                            [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[LsctrRig::kDrive]); }),
          Recorder::sampled(sn::kNormalForce, "N",
                            [&](const Sample& s) { return params.load_cell.reading_N(cycle.normal_force_N(s.t_s)); }),
          Recorder::sampled(sn::kTorque, "N m", [](const Sample& s) { return s.shaft_torque_Nm[LsctrRig::kBar]; }),
          Recorder::interpolated(sn::kTemp, "degC", [](const ThermalState& state) { return state.sensor_temp_C; }),
          Recorder::interpolated(sn::kIrTemp, "degC", [&](const ThermalState& state) { return th.ir_C(state); }),
          Recorder::interpolated(sn::kSumpTemp, "degC", [](const ThermalState& state) { return state.sump_temp_C; }),
          Recorder::sampled(
              sn::kSlip, "rpm",
              [](const Sample& s) { return units::rad_s_to_rpm(s.contact_slip_rad_s[LsctrRig::kClutch]); }),
          Recorder::sampled(sn::kClutchTorque, "N m",
                            [](const Sample& s) { return s.contact_torque_Nm[LsctrRig::kClutch]; }),
          Recorder::sampled(sn::kMotorTorque, "N m", [](const Sample& s) { return s.motor_torque_Nm[0]; }),
          Recorder::sampled(sn::kHousingSpeed, "rpm",
                            [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[LsctrRig::kHousing]); }),
          Recorder::sampled(sn::kStuck, "1",
                            [](const Sample& s) {
                              return static_cast<double>(s.modes[LsctrRig::kClutch] == dynamics::ContactMode::kStuck);
                            }),
          Recorder::interpolated(sn::kInterfaceMeanTemp, "degC",
                                 [&](const ThermalState& state) { return th.mean_interface_temp_C(state); }),
          Recorder::interpolated(sn::kInterfaceMaxTemp, "degC",
                                 [&](const ThermalState& state) { return th.interface_temps_C(state).maxCoeff(); }),
          Recorder::sampled(sn::kFrictionCoefficient, "1",
                            [&](const Sample& s) {
                              const double force = cycle.normal_force_N(s.t_s);
                              return force > 0
                                         ? std::abs(s.contact_torque_Nm[LsctrRig::kClutch]) / (n_if * force * r_eff)
                                         : 0.0;
                            }),
      });

  double peak_interface_C = th.interface_temps_C(ts).maxCoeff();
  recorder.sample(sim.sample());
  recorder.start(ts);

  std::vector<double> snaps = cfg.snapshot_times_s;
  std::sort(snaps.begin(), snaps.end());
  std::size_t next_snap = 0;
  clutch::FrictionDataRange data_range(*clutch.fluid().friction);
  components::run_multirate(
      sim, *clutch_context, clutch, ts, LsctrRig::kClutch, cfg.duration_s, cfg.thermal_step_s, cfg.sample_rate_Hz,
      [&](const dynamics::Sample& s) { recorder.sample(s); },
      [&](const components::SlowStep& step) {
        peak_interface_C = std::max(peak_interface_C, th.interface_temps_C(ts).maxCoeff());
        recorder.step(ts, step.ta_s, step.tb_s);
        const double dt = step.tb_s - step.ta_s;
        while (next_snap < snaps.size() && snaps[next_snap] <= step.tb_s + 0.5 * dt) {
          rec.snapshots.push_back({step.tb_s, th.field_C(ts)});
          ++next_snap;
        }
      },
      &data_range);
  rec.blocks.push_back(components::friction_range_block(data_range));

  const int nr = th.radial_cells();
  for (int i = 0; i < nr; ++i) rec.grid_r_m.push_back(th.ring_radius_m()[i]);
  for (int j = 0; j < th.nodes_per_ring(); ++j) rec.grid_z_m.push_back(th.node_z_m()[j]);
  const auto me = sim.energy();
  const auto& cnt = sim.counters();
  rec.scalars = components::heat_account_scalars(clutch, ts);
  const std::vector<dynamics::Scalar> more = {
      {"mechanical_energy_relative_error", "1",
       components::mechanical_energy_relative_error(me, components::MechanicalEnergyScale::kSourceWork)},
      {"friction_work_J", "J", me.friction_heat_J},
      {"peak_interface_temp_C", "degC", peak_interface_C},
      {"final_max_temp_C", "degC", th.max_temp_C(ts)},
      {"bar_stiffness_Nm_per_rad", "N m/rad", rig.bar_stiffness_Nm_per_rad()},
      {"bar_damping_Nms_per_rad", "N m s/rad", rig.bar_damping_Nms_per_rad()},
      {"clutch_side_frequency_Hz", "Hz", rig.clutch_side_frequency_Hz()},
      {"integrator_steps", "1", static_cast<double>(cnt.steps)},
      {"rhs_evaluations", "1", static_cast<double>(cnt.rhs_calls)},
      {"stick_events", "1", static_cast<double>(cnt.stick_events)},
      {"breakaway_events", "1", static_cast<double>(cnt.breakaway_events)},
      {"reversal_events", "1", static_cast<double>(cnt.reversal_events)},
  };
  rec.scalars.insert(rec.scalars.end(), more.begin(), more.end());
  return rec;
}

}  // namespace shudder::rig_models
