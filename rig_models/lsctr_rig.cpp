#include "components/friction_range_block.hpp"
#include "rig_models/lsctr_rig.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "components/channel_recorder.hpp"
#include "components/energy_scalars.hpp"
#include "components/network_stepper.hpp"

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
      clutch_(&clutch),
      contact_(clutch, params.bearing_drag, params.stick_time),
      cycle_(cycle),
      force_N_(cycle.normal_force_N) {
  require(p_.drive_inertia_kg_m2 > 0, "rig drive inertia must be > 0 kg m^2");
  require(p_.housing_inertia_kg_m2 > 0, "rig housing inertia must be > 0 kg m^2");
  require(p_.bar_stiffness_Nm_per_rad > 0 || p_.bar_natural_frequency_Hz > 0,
          "torsion bar needs a natural frequency > 0 Hz or a stiffness > 0 N m/rad");
  require(p_.bar_damping_ratio >= 0, "torsion bar damping ratio must be >= 0");
  require(p_.speed_loop_bandwidth_Hz > 0, "speed loop bandwidth must be > 0 Hz");
  require(p_.motor_torque_limit_Nm > 0, "motor torque limit must be > 0 N m");
  require(cycle.normal_force_N.max_value() > 0,
          "the drive cycle's normal force is 0 N throughout, so the clutch never loads; give a normal force > 0 N");

  const SpeedLoopGains gains = speed_loop_gains(p_);
  kp_ = gains.kp_Nms_per_rad;
  ki_ = gains.ki_Nm_per_rad;
  const auto damping = [&](double k_bar) {
    return 2.0 * p_.bar_damping_ratio * std::sqrt(k_bar * p_.housing_inertia_kg_m2);
  };

  if (p_.bar_stiffness_Nm_per_rad > 0) {
    k_bar_ = k_network_ = p_.bar_stiffness_Nm_per_rad;
    c_bar_ = damping(k_bar_);
    build_with_bar(k_bar_, c_bar_, components::NetworkChecks::kAll);  // validates the network
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
    // The first build checks the network; the others change only the bar's stiffness.
    const auto checks = iter == 0 ? components::NetworkChecks::kAll : components::NetworkChecks::kSkipTopology;
    const auto m = build_with_bar(k_bar_, c_bar_, checks).network().modes();
    const double f = m.frequencies_Hz[clutch_side_mode(m)];
    clutch_side_Hz_ = f;
    if (std::abs(f / target - 1.0) < 1e-10) break;
    k_bar_ *= std::pow(target / f, 2);
  }
}

components::NetworkSpec LsctrRig::spec_with_bar(double k_bar, double c_bar, const RigSettings& cfg,
                                                bool share_clutch) const {
  using namespace components;
  NetworkSpec s;
  // The start: steady sliding at the cycle's first speed, every ring at the clutch's start
  // temperature, the friction torque carried by the bar and supplied by the loop's integrator
  // (so the record starts without a spurious transient); or everything at rest.
  double w0 = 0, torque0_Nm = 0;
  if (!p_.start_at_rest) {
    w0 = units::rpm_to_rad_s(cycle_.slip_speed_rpm(0.0));
    ClutchContext context(start_inputs());
    torque0_Nm = contact_.kinetic_torque_Nm(context, std::abs(w0), 0.0) * (w0 >= 0 ? 1.0 : -1.0);
  }
  s.inertias.push_back({"drive", p_.drive_inertia_kg_m2, w0, 0.0});
  s.inertias.push_back({"housing", p_.housing_inertia_kg_m2, 0.0, torque0_Nm / k_bar});

  MotorSpec m;
  m.name = "motor";
  m.node = "drive";
  m.speed_rpm = Signal::table(cycle_.slip_speed_rpm.times_s(), cycle_.slip_speed_rpm.values(), true);
  m.kp_Nms_per_rad = kp_;
  m.ki_Nm_per_rad = ki_;
  m.torque_limit_Nm = p_.motor_torque_limit_Nm;
  m.start_torque_Nm = torque0_Nm;
  m.ripple = p_.motor_ripple;
  s.motors.push_back(m);

  ClutchSpec c;
  c.name = "clutch";
  c.a = "drive";
  c.b = "housing";
  c.law = ClutchSpec::Law::kWet;
  c.max_force_N = cycle_.normal_force_N.max_value();
  std::vector<double> u;
  for (double f : cycle_.normal_force_N.values()) u.push_back(c.max_force_N > 0 ? f / c.max_force_N : 0.0);
  c.force_signal = Signal::table(cycle_.normal_force_N.times_s(), u, true);
  c.wet.fluid = clutch_->fluid();
  c.wet.clutch = clutch_->params();
  c.wet.oil_volume_given = c.wet.oil_flow_given = true;
  c.wet.bearing_drag = p_.bearing_drag;
  c.wet.stick_time = p_.stick_time;
  if (share_clutch) c.wet.prebuilt = std::shared_ptr<const clutch::WetClutch>(std::shared_ptr<void>(), clutch_);
  c.judged_on = "torsion_bar";
  s.clutches.push_back(c);
  s.shafts.push_back({"torsion_bar", "housing", kGroundNode, k_bar, c_bar, 0.0});

  s.settings.duration_s = cfg.duration_s;
  s.settings.sample_rate_Hz = cfg.sample_rate_Hz;
  s.settings.thermal_step_s = cfg.thermal_step_s;
  s.settings.integrator = p_.integrator;
  return s;
}

components::NetworkSpec LsctrRig::spec(const RigSettings& settings, bool share_clutch) const {
  return spec_with_bar(k_network_, c_bar_, settings, share_clutch);
}

components::OwnedNetwork LsctrRig::build_with_bar(double k_bar, double c_bar, components::NetworkChecks checks) const {
  components::OwnedNetwork b(spec_with_bar(k_bar, c_bar, RigSettings{}, true), checks);
  b.clutch_context() = components::ClutchContext(start_inputs());
  return b;
}

components::OwnedNetwork LsctrRig::build(std::optional<double> bar_damping_ratio) const {
  if (!bar_damping_ratio) return build_with_bar(k_network_, c_bar_);
  return build_with_bar(k_network_, 2.0 * *bar_damping_ratio * std::sqrt(k_network_ * p_.housing_inertia_kg_m2));
}

double LsctrRig::clutch_side_frequency_Hz() const {
  if (clutch_side_Hz_ >= 0) return clutch_side_Hz_;
  const auto m = build().network().modes();
  return m.frequencies_Hz[clutch_side_mode(m)];
}

dynamics::Recording run_rig(const RigParams& params, const clutch::WetClutch& clutch,
                            const components::DriveCycle& cycle, const RigSettings& cfg) {
  if (!(cfg.duration_s > 0) || !(cfg.thermal_step_s > 0) || !(cfg.sample_rate_Hz > 0))
    throw std::invalid_argument("duration, thermal step and sample rate must be > 0");
  const LsctrRig rig(params, clutch, cycle);
  const components::NetworkSpec spec = rig.spec(cfg, true);
  components::NetworkStepper stepper(spec, cfg.duration_s);
  const auto& th = clutch.thermal();
  const clutch::ThermalState& ts = stepper.thermal()[0];
  const dynamics::Simulation& sim = stepper.simulation();

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
  stepper.advance_to(
      cfg.duration_s, [&](const dynamics::Sample& s) { recorder.sample(s); },
      [&](const components::SlowStep& step) {
        peak_interface_C = std::max(peak_interface_C, th.interface_temps_C(ts).maxCoeff());
        recorder.step(ts, step.ta_s, step.tb_s);
        const double dt = step.tb_s - step.ta_s;
        while (next_snap < snaps.size() && snaps[next_snap] <= step.tb_s + 0.5 * dt) {
          rec.snapshots.push_back({step.tb_s, th.field_C(ts)});
          ++next_snap;
        }
      });
  rec.blocks.push_back(components::friction_range_block(stepper.data_ranges().front()));

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
