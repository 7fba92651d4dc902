#include "components/friction_range_block.hpp"
#include "rig_models/haldex_driveline.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "clutch/fluid.hpp"
#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "components/channel_recorder.hpp"
#include "components/energy_scalars.hpp"
#include "components/network_stepper.hpp"

namespace shudder::rig_models {

namespace {

void require_positive_parameter(double v, const char* what) {
  if (!std::isfinite(v) || !(v > 0))
    throw std::invalid_argument(std::string("driveline: ") + what + " must be a finite value > 0");
}

double pack_torque_per_newton(const DrivelineParams& p, const clutch::WetClutch& clutch) {
  return clutch.params().sliding_interfaces * p.nominal_friction * clutch.mean_radius_m();
}

// ρ of each wheel (FL, FR, RL, RR) for the turn of the inputs or the legacy axle ratio.
std::array<double, 4> wheel_path_ratios(const DrivelineParams& p, const DrivelineInputs& in) {
  const double rho = p.turn_ratio;
  if (in.turn_radius_m == 0.0) return {rho, rho, 1.0, 1.0};
  if (rho != 1.0) throw std::invalid_argument("driveline: turn_ratio and turn_radius_m are alternatives; give one");
  const double r = in.turn_radius_m, half = 0.5 * p.track_width_m, l = p.wheelbase_m;
  if (!std::isfinite(r) || !(r > half))
    throw std::invalid_argument("driveline: turn radius " + std::to_string(r) + " m must exceed half the track (" +
                                std::to_string(half) + " m): the inner rear wheel would stand or run backwards");
  return {std::hypot(l, r - half) / r, std::hypot(l, r + half) / r, (r - half) / r, (r + half) / r};
}

}  // namespace

std::array<double, 2> static_axle_loads_N(const DrivelineParams& p, double grade_percent) {
  const double theta = std::atan(grade_percent / 100.0);
  const double weight_N = p.vehicle_mass_kg * HaldexDriveline::kGravity_m_s2;
  const double pitch = p.cg_height_m / p.wheelbase_m * std::sin(theta);
  return {weight_N * (p.front_axle_load_share * std::cos(theta) - pitch),
          weight_N * ((1.0 - p.front_axle_load_share) * std::cos(theta) + pitch)};
}

HaldexDriveline::HaldexDriveline(const DrivelineParams& params, const clutch::WetClutch& clutch,
                                 const DrivelineInputs& inputs)
    : p_(params),
      clutch_(&clutch),
      inputs_(inputs),
      hydraulics_(params.hydraulics, pack_torque_per_newton(params, clutch)),
      valve_opening_(inputs.valve_opening),
      valve_pressure_bar_(inputs.valve_pressure_bar),
      contact_(clutch, components::BearingDrag{}, params.stick_time),
      engine_torque_Nm_(inputs.engine_torque_Nm),
      throttle_(inputs.throttle),
      engine_(params.engine) {
  for (const auto& [v, what] : std::initializer_list<std::pair<double, const char*>>{
           {p_.engine_inertia_kg_m2, "engine_inertia_kg_m2"},
           {p_.gear_ratio, "gear_ratio"},
           {p_.final_drive_ratio, "final_drive_ratio"},
           {p_.front_diff_inertia_kg_m2, "front_diff_inertia_kg_m2"},
           {p_.halfshaft_stiffness_Nm_per_rad, "halfshaft_stiffness_Nm_per_rad"},
           {p_.side_gear_inertia_kg_m2, "side_gear_inertia_kg_m2"},
           {p_.wheel_inertia_kg_m2, "wheel_inertia_kg_m2"},
           {p_.tyre_stiffness_Nm_per_rad, "tyre_stiffness_Nm_per_rad"},
           {p_.wheelbase_m, "wheelbase_m"},
           {p_.track_width_m, "track_width_m"},
           {p_.vehicle_mass_kg, "vehicle_mass_kg"},
           {p_.wheel_radius_m, "wheel_radius_m"},
           {p_.ptu_ratio, "ptu_ratio"},
           {p_.ptu_inertia_kg_m2, "ptu_inertia_kg_m2"},
           {p_.propshaft_stiffness_Nm_per_rad, "propshaft_stiffness_Nm_per_rad"},
           {p_.coupling_half_inertia_kg_m2, "coupling_half_inertia_kg_m2"},
           {p_.rear_diff_ratio, "rear_diff_ratio"},
           {p_.rear_diff_inertia_kg_m2, "rear_diff_inertia_kg_m2"},
           {p_.turn_ratio, "turn_ratio"},
           {p_.nominal_friction, "nominal_friction"},
           {p_.front_axle_load_share, "front_axle_load_share"}})
    require_positive_parameter(v, what);
  if (!(p_.front_axle_load_share < 1))
    throw std::invalid_argument("driveline: front_axle_load_share must be in (0, 1)");
  for (const auto& [v, what] : std::initializer_list<std::pair<double, const char*>>{
           {p_.halfshaft_damping_Nms_per_rad, "halfshaft_damping_Nms_per_rad"},
           {p_.propshaft_damping_Nms_per_rad, "propshaft_damping_Nms_per_rad"},
           {p_.rolling_resistance_coefficient, "rolling_resistance_coefficient"},
           {p_.drag_coefficient_area_m2, "drag_coefficient_area_m2"},
           {p_.air_density_kg_m3, "air_density_kg_m3"},
           {p_.cg_height_m, "cg_height_m"}})
    if (!std::isfinite(v) || v < 0) throw std::invalid_argument(std::string("driveline: ") + what + " must be >= 0");
  for (double mu : inputs.road_friction)
    if (!std::isfinite(mu) || !(mu > 0))
      throw std::invalid_argument("driveline: road friction must be a finite value > 0 at every wheel");
  if (!std::isfinite(inputs.grade_percent) || std::abs(inputs.grade_percent) > 100)
    throw std::invalid_argument("driveline: grade must be within ±100 %");

  if (valve_opening_)
    for (double u : valve_opening_->values())
      if (!std::isfinite(u) || u < 0 || u > 1)
        throw std::invalid_argument("driveline: valve_opening must be within [0, 1] (0 shut, 1 open)");
  if (valve_pressure_bar_)
    for (double v : valve_pressure_bar_->values())
      if (!std::isfinite(v) || v < 0 || v > p_.hydraulics.relief_pressure_bar)
        throw std::invalid_argument("driveline: valve_pressure_bar must be within [0, relief_pressure_bar]");
  path_ratios_ = wheel_path_ratios(p_, inputs);
  for (const auto& [v, what] : std::initializer_list<std::pair<std::optional<double>, const char*>>{
           {p_.tyre_slip_stiffness_N, "tyre_slip_stiffness_N"},
           {p_.tyre_slip_stiffness_per_load, "tyre_slip_stiffness_per_load"}})
    if (v) require_positive_parameter(*v, what);
  if (p_.tyre_slip_stiffness_N && p_.tyre_slip_stiffness_per_load)
    throw std::invalid_argument(
        "driveline: tyre_slip_stiffness_N and tyre_slip_stiffness_per_load are alternatives; "
        "give one (an absolute C_kappa, or C_kappa / F_z)");
  const double theta = std::atan(inputs.grade_percent / 100.0);
  const double weight_N = p_.vehicle_mass_kg * kGravity_m_s2;
  const double r = p_.wheel_radius_m;
  const std::array<double, 2> axle_N = static_axle_loads_N(p_, inputs.grade_percent);
  if (!(axle_N[0] > 0) || !(axle_N[1] > 0))
    throw std::invalid_argument("driveline: on a grade of " + std::to_string(inputs.grade_percent) + " % the " +
                                (axle_N[0] > 0 ? "rear" : "front") +
                                " axle would lift (cg_height_m / wheelbase_m too large for the grade)");
  const double transfer_kg = p_.vehicle_mass_kg * p_.cg_height_m / (2.0 * p_.wheelbase_m);
  for (int w = 0; w < 4; ++w) {
    const bool front = w < 2;
    components::TyreParams t;
    t.slip_stiffness_N = p_.tyre_slip_stiffness_N;
    t.slip_stiffness_per_load = p_.tyre_slip_stiffness_per_load;
    t.vertical_load_N = 0.5 * axle_N[front ? 0 : 1];
    t.relaxation_length_m = t.static_slip_stiffness_N() * r * r / p_.tyre_stiffness_Nm_per_rad;
    t.road_friction = inputs.road_friction[static_cast<std::size_t>(w)];
    t.radius_m = r;
    t.load_transfer.load_per_acceleration_kg = front ? -transfer_kg : transfer_kg;
    t.load_transfer.path_ratio = path_ratios_[static_cast<std::size_t>(w)];
    tyres_[static_cast<std::size_t>(w)] = std::make_shared<const components::BrushTyre>(t);
  }
  components::RoadLoadParams rl;
  rl.rolling_resistance_N = p_.rolling_resistance_coefficient * weight_N * std::cos(theta);
  rl.drag_coefficient_area_m2 = p_.drag_coefficient_area_m2;
  rl.air_density_kg_m3 = p_.air_density_kg_m3;
  rl.radius_m = r;
  road_load_ = std::make_shared<const components::RoadLoad>(rl);
  grade_torque_Nm_ = -weight_N * std::sin(theta) * r;

  // Builds the network once with every check; runs and analyses build their own.
  checked_.emplace(build(components::NetworkChecks::kAll));
  control_unit_ = std::make_unique<components::HaldexControlUnit>(checked_->built().clutches.front());
}

components::HaldexCommand HaldexDriveline::start_command() const {
  components::HaldexCommand c;
  c.setting_bar = p_.hydraulics.relief_pressure_bar;
  c.setting_schedule_bar = valve_pressure_bar_;
  if (valve_pressure_bar_) c.opening = 0.0;
  return c;
}

Eigen::VectorXd HaldexDriveline::coupling_states(double clamp_force_N, double opening) const {
  Eigen::VectorXd z(2);
  z[components::HaldexCouplingLaw::kPressure] = hydraulics_.pressure_for_force_bar(clamp_force_N);
  z[components::HaldexCouplingLaw::kOpening] = opening;
  return z;
}

components::ClutchHeldInputs HaldexDriveline::start_inputs() const {
  return contact_.start_inputs(components::PiecewiseLinear({0.0}, {hydraulics_.clamp_force_N(0.0)}));
}

namespace {

components::Signal schedule_signal(const components::PiecewiseLinear& f) {
  return components::Signal::table(f.times_s(), f.values(), true);
}

}  // namespace

components::NetworkSpec HaldexDriveline::spec(const DrivelineSettings& cfg, bool share_clutch) const {
  using namespace components;
  const DrivelineParams& p = p_;
  const DrivelineInputs& in = inputs_;
  const double r = p.wheel_radius_m;
  const double w_vehicle = in.start_speed_km_h / 3.6 / r;
  const Eigen::VectorXd w = rolling_speed_ratios() * w_vehicle;
  NetworkSpec s;

  // Bodies in the node order (the vehicle is a node of its own kind, last).
  const std::array<std::pair<const char*, double>, kVehicle> bodies{{{"engine", p.engine_inertia_kg_m2},
                                                                     {"front_diff", p.front_diff_inertia_kg_m2},
                                                                     {"front_side_left", p.side_gear_inertia_kg_m2},
                                                                     {"front_side_right", p.side_gear_inertia_kg_m2},
                                                                     {"wheel_fl", p.wheel_inertia_kg_m2},
                                                                     {"wheel_fr", p.wheel_inertia_kg_m2},
                                                                     {"ptu", p.ptu_inertia_kg_m2},
                                                                     {"coupling_in", p.coupling_half_inertia_kg_m2},
                                                                     {"coupling_out", p.coupling_half_inertia_kg_m2},
                                                                     {"rear_diff", p.rear_diff_inertia_kg_m2},
                                                                     {"rear_side_left", p.side_gear_inertia_kg_m2},
                                                                     {"rear_side_right", p.side_gear_inertia_kg_m2},
                                                                     {"wheel_rl", p.wheel_inertia_kg_m2},
                                                                     {"wheel_rr", p.wheel_inertia_kg_m2}}};
  for (int i = 0; i < kVehicle; ++i)
    s.inertias.push_back({bodies[static_cast<std::size_t>(i)].first, bodies[static_cast<std::size_t>(i)].second, w[i]});

  const double theta = std::atan(in.grade_percent / 100.0);
  const double weight_N = p.vehicle_mass_kg * kGravity_m_s2;
  VehicleSpec v;
  v.name = "vehicle";
  v.mass_kg = p.vehicle_mass_kg;
  v.wheel_radius_m = r;
  v.speed_m_s = in.start_speed_km_h / 3.6;
  v.grade_percent = in.grade_percent;
  v.road.rolling_resistance_N = p.rolling_resistance_coefficient * weight_N * std::cos(theta);
  v.road.drag_coefficient_area_m2 = p.drag_coefficient_area_m2;
  v.road.air_density_kg_m3 = p.air_density_kg_m3;
  s.vehicles.push_back(v);

  const double k_h = p.halfshaft_stiffness_Nm_per_rad, c_h = p.halfshaft_damping_Nms_per_rad;
  s.shafts = {
      {"front_left_halfshaft", "front_side_left", "wheel_fl", k_h, c_h, 0.0},
      {"front_right_halfshaft", "front_side_right", "wheel_fr", k_h, c_h, 0.0},
      {"propshaft", "ptu", "coupling_in", p.propshaft_stiffness_Nm_per_rad, p.propshaft_damping_Nms_per_rad, 0.0},
      {"rear_left_halfshaft", "rear_side_left", "wheel_rl", k_h, c_h, 0.0},
      {"rear_right_halfshaft", "rear_side_right", "wheel_rr", k_h, c_h, 0.0}};
  s.gears = {{"gearbox_and_final_drive", "engine", "front_diff", p.gear_ratio * p.final_drive_ratio},
             {"power_take_off", "ptu", "front_diff", p.ptu_ratio},
             {"rear_final_drive", "coupling_out", "rear_diff", p.rear_diff_ratio}};
  s.differentials = {{"front_differential", "front_diff", "front_side_left", "front_side_right"},
                     {"rear_differential", "rear_diff", "rear_side_left", "rear_side_right"}};

  const std::array<const char*, 4> tyre_names{"tyre_fl", "tyre_fr", "tyre_rl", "tyre_rr"};
  const std::array<const char*, 4> wheels{"wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr"};
  for (int i = 0; i < 4; ++i) {
    TyreSpec t;
    t.name = tyre_names[static_cast<std::size_t>(i)];
    t.wheel = wheels[static_cast<std::size_t>(i)];
    t.vehicle = "vehicle";
    t.params = tyre(i).params();
    t.path_ratio = path_ratios_[static_cast<std::size_t>(i)];
    s.tyres.push_back(t);
  }
  if (p.engine_pulsation.amplitude_Nm > 0)
    s.firing_pulsations.push_back(
        {"firing", "engine", p.engine_pulsation, p.engine.stall_speed_rpm, p.engine.idle_speed_rpm});

  // The engine: its map with the throttle, or the raw torque schedule; the pedal the control
  // unit reads is the throttle, or the raw torque over the full-load curve's peak.
  Signal pedal_signal = Signal::constant(0.0);
  if (in.throttle) {
    EngineSpec e;
    e.name = "engine_map";
    e.node = "engine";
    e.params = p.engine;
    e.throttle = schedule_signal(*in.throttle);
    s.engines.push_back(e);
    pedal_signal = e.throttle;
  } else {
    s.torque_sources.push_back({"engine_torque", "engine", schedule_signal(in.engine_torque_Nm)});
    const auto& full = p.engine.full_load_torque_Nm.values();
    const double peak = *std::max_element(full.begin(), full.end());
    std::vector<double> u;
    for (double t : in.engine_torque_Nm.values()) u.push_back(peak > 0 ? t / peak : 0.0);
    pedal_signal = Signal::table(in.engine_torque_Nm.times_s(), u, true);
  }

  ClutchSpec c;
  c.name = "haldex";
  c.a = "coupling_in";
  c.b = "coupling_out";
  c.law = ClutchSpec::Law::kHaldex;
  c.wet.fluid = clutch_->fluid();
  c.wet.clutch = clutch_->params();  // the pack's oil already applied by the scenario (apply_pack_oil)
  c.wet.oil_volume_given = c.wet.oil_flow_given = true;
  c.wet.stick_time = p.stick_time;
  if (share_clutch) c.wet.prebuilt = std::shared_ptr<const clutch::WetClutch>(std::shared_ptr<void>(), clutch_);
  HaldexSpec& h = c.haldex;
  h.hydraulics = p.hydraulics;
  h.controller = p.controller;
  h.nominal_friction = p.nominal_friction;
  h.front_axle = "front_diff";
  h.rear_axle = "rear_diff";
  h.front_path_ratio = 0.5 * (path_ratios_[kFL] + path_ratios_[kFR]);
  h.rear_path_ratio = 0.5 * (path_ratios_[kRL] + path_ratios_[kRR]);
  h.wheel_radius_m = r;
  h.pedal = pedal_signal;
  if (in.valve_opening) h.valve_opening = schedule_signal(*in.valve_opening);
  if (in.valve_pressure_bar) h.valve_pressure_bar = schedule_signal(*in.valve_pressure_bar);
  s.clutches.push_back(c);

  s.settings.duration_s = cfg.duration_s;
  s.settings.sample_rate_Hz = cfg.sample_rate_Hz;
  s.settings.thermal_step_s = cfg.slow_step_s;
  s.settings.integrator = p.integrator;
  return s;
}

components::OwnedNetwork HaldexDriveline::build(components::NetworkChecks checks) const {
  components::OwnedNetwork b(spec(DrivelineSettings{}, true), checks);
  b.clutch_context() = components::ClutchContext(start_inputs());
  b.command() = start_command();
  return b;
}

double HaldexDriveline::engine_torque_Nm(double t, double w) const {
  return throttle_ ? engine_.torque_Nm(w, (*throttle_)(t)) : engine_torque_Nm_(t);
}

double HaldexDriveline::valve_opening(const dynamics::Sample& s) const {
  return control_unit_->commanded_opening(s.t_s, s.omega_rad_s[kFrontDiff], s.omega_rad_s[kRearDiff]);
}

double HaldexDriveline::valve_setting_bar(double t) const {
  return valve_pressure_bar_ ? (*valve_pressure_bar_)(t) : p_.hydraulics.relief_pressure_bar;
}

double HaldexDriveline::engine_slope_Nms_per_rad(double t, double w) const {
  return throttle_ ? engine_.torque_speed_slope_Nms_per_rad(w, (*throttle_)(t)) : 0.0;
}

Eigen::VectorXd HaldexDriveline::rolling_speed_ratios() const {
  // Rolling without tyre slip or twist: each wheel and its side gear follow the wheel's path
  // (ρ_i ω_v), each carrier the mean of its two; the coupling's two sides then differ.
  Eigen::VectorXd s(kNodes);
  s[kVehicle] = 1.0;
  s[kFrontSideLeft] = s[kFrontLeftWheel] = path_ratios_[kFL];
  s[kFrontSideRight] = s[kFrontRightWheel] = path_ratios_[kFR];
  s[kRearSideLeft] = s[kRearLeftWheel] = path_ratios_[kRL];
  s[kRearSideRight] = s[kRearRightWheel] = path_ratios_[kRR];
  s[kFrontDiff] = 0.5 * (path_ratios_[kFL] + path_ratios_[kFR]);
  s[kRearDiff] = 0.5 * (path_ratios_[kRL] + path_ratios_[kRR]);
  s[kEngine] = p_.gear_ratio * p_.final_drive_ratio * s[kFrontDiff];
  s[kPtu] = s[kCouplingIn] = p_.ptu_ratio * s[kFrontDiff];
  s[kCouplingOut] = p_.rear_diff_ratio * s[kRearDiff];
  return s;
}

namespace {

using DrivelineRecorder = components::ChannelRecorder<dynamics::Sample, clutch::ThermalState>;

// The run's channels: mechanical ones and the coupling's pressure and valve (its contact law's
// states, from index z_coupling) at every sample, the interface temperatures from the thermal
// state, interpolated across each slow step.
std::vector<DrivelineRecorder::Channel> driveline_channels(
    const HaldexDriveline& dl, const DrivelineParams& params, const clutch::ThermalModel& th, int z_coupling,
    const std::function<double(const dynamics::Sample&)>& clamp_force_N) {
  namespace sn = dynamics::signal_names;
  using Recorder = DrivelineRecorder;
  using clutch::ThermalState;
  using dynamics::Sample;
  using D = HaldexDriveline;
  const auto pressure_bar = [z_coupling](const Sample& s) {
    return s.contact_states[z_coupling + components::HaldexCouplingLaw::kPressure];
  };
  return {
      Recorder::sampled(sn::kTime, "s", [](const Sample& s) { return s.t_s; }),
      Recorder::sampled(sn::kEngineSpeed, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kEngine]); }),
      Recorder::sampled(sn::kVehicleSpeed, "km/h",
                        [r = params.wheel_radius_m](const Sample& s) { return s.omega_rad_s[D::kVehicle] * r * 3.6; }),
      // An axle's wheel speed: the mean of its two wheels, the carrier's speed.
      Recorder::sampled(sn::kFrontWheelSpeed, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kFrontDiff]); }),
      Recorder::sampled(sn::kRearWheelSpeed, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kRearDiff]); }),
      Recorder::sampled(sn::kCouplingSlip, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.contact_slip_rad_s[D::kCoupling]); }),
      Recorder::sampled(sn::kCouplingTorque, "N m", [](const Sample& s) { return s.contact_torque_Nm[D::kCoupling]; }),
      Recorder::sampled(sn::kFrontAxleTorque, "N m",
                        [](const Sample& s) {
                          return s.shaft_torque_Nm[D::kFrontLeftHalfshaft] + s.shaft_torque_Nm[D::kFrontRightHalfshaft];
                        }),
      Recorder::sampled(sn::kRearAxleTorque, "N m",
                        [](const Sample& s) {
                          return s.shaft_torque_Nm[D::kRearLeftHalfshaft] + s.shaft_torque_Nm[D::kRearRightHalfshaft];
                        }),
      Recorder::sampled(sn::kEngineTorque, "N m",
                        [&dl](const Sample& s) { return dl.engine_torque_Nm(s.t_s, s.omega_rad_s[D::kEngine]); }),
      Recorder::sampled(
          sn::kStuck, "1",
          [](const Sample& s) { return static_cast<double>(s.modes[D::kCoupling] == dynamics::ContactMode::kStuck); }),
      Recorder::sampled(sn::kPressure, "bar", pressure_bar),
      Recorder::sampled(sn::kValveOpening, "1",
                        [z_coupling](const Sample& s) {
                          return s.contact_states[z_coupling + components::HaldexCouplingLaw::kOpening];
                        }),
      Recorder::sampled(sn::kClampForce, "N", clamp_force_N),
      Recorder::sampled(sn::kWheelSpeedFL, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kFrontLeftWheel]); }),
      Recorder::sampled(sn::kWheelSpeedFR, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kFrontRightWheel]); }),
      Recorder::sampled(sn::kWheelSpeedRL, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kRearLeftWheel]); }),
      Recorder::sampled(sn::kWheelSpeedRR, "rpm",
                        [](const Sample& s) { return units::rad_s_to_rpm(s.omega_rad_s[D::kRearRightWheel]); }),
      Recorder::sampled(sn::kTyreForceFL, "N",
                        [r = params.wheel_radius_m](const Sample& s) { return s.element_torque_Nm[D::kFL] / r; }),
      Recorder::sampled(sn::kTyreForceFR, "N",
                        [r = params.wheel_radius_m](const Sample& s) { return s.element_torque_Nm[D::kFR] / r; }),
      Recorder::sampled(sn::kTyreForceRL, "N",
                        [r = params.wheel_radius_m](const Sample& s) { return s.element_torque_Nm[D::kRL] / r; }),
      Recorder::sampled(sn::kTyreForceRR, "N",
                        [r = params.wheel_radius_m](const Sample& s) { return s.element_torque_Nm[D::kRR] / r; }),
      Recorder::sampled(
          sn::kRoadLoad, "N",
          [r = params.wheel_radius_m](const Sample& s) { return s.element_torque_Nm[D::kRoadLoadElement] / r; }),
      Recorder::interpolated(sn::kInterfaceMeanTemp, "degC",
                             [&th](const ThermalState& state) { return th.mean_interface_temp_C(state); }),
      Recorder::interpolated(sn::kInterfaceMaxTemp, "degC",
                             [&th](const ThermalState& state) { return th.interface_temps_C(state).maxCoeff(); }),
      // What an instrumented coupling's sensors read (a measured vehicle run, coupling_measurement.hpp).
      Recorder::interpolated(sn::kCouplingTemp, "degC", [](const ThermalState& state) { return state.sensor_temp_C; }),
      Recorder::interpolated(sn::kCouplingOilTemp, "degC", [](const ThermalState& state) { return state.sump_temp_C; }),
  };
}

}  // namespace

dynamics::Recording run_driveline(const DrivelineParams& params, const clutch::WetClutch& clutch,
                                  const DrivelineInputs& inputs, const DrivelineSettings& cfg) {
  if (!(cfg.duration_s > 0) || !(cfg.slow_step_s > 0) || !(cfg.sample_rate_Hz > 0))
    throw std::invalid_argument("driveline: duration, slow step and sample rate must be > 0");
  if (!std::isfinite(inputs.start_speed_km_h) || inputs.start_speed_km_h < 0)
    throw std::invalid_argument("driveline: start speed must be a finite value >= 0 km/h");
  const HaldexDriveline dl(params, clutch, inputs);
  using D = HaldexDriveline;
  const components::NetworkSpec spec = dl.spec(cfg, true);
  components::NetworkStepper stepper(spec, cfg.duration_s);
  const components::BuiltClutch& coupling = stepper.built().clutches[D::kCoupling];
  const auto& th = clutch.thermal();
  const clutch::ThermalState& ts = stepper.thermal()[0];
  const dynamics::Simulation& sim = stepper.simulation();
  const int z_coupling = coupling.state_index;
  const auto clamp_force_N = [&coupling](const dynamics::Sample& s) { return coupling.normal_force_N(s); };

  dynamics::Recording rec;
  DrivelineRecorder recorder(rec, driveline_channels(dl, params, th, z_coupling, clamp_force_N));

  // Stall: the mapped engine's speed below its stall speed (the first sample that shows it).
  double stall_time_s = std::numeric_limits<double>::quiet_NaN();
  const auto watch_stall = [&](const dynamics::Sample& s) {
    if (dl.engine_mapped() && std::isnan(stall_time_s) && s.omega_rad_s[D::kEngine] < dl.engine().stall_speed_rad_s())
      stall_time_s = s.t_s;
  };
  watch_stall(sim.sample());
  recorder.sample(sim.sample());
  recorder.start(ts);
  double peak_C = th.interface_temps_C(ts).maxCoeff();
  stepper.advance_to(
      cfg.duration_s,
      [&](const dynamics::Sample& s) {
        watch_stall(s);
        recorder.sample(s);
      },
      [&](const components::SlowStep& step) {
        peak_C = std::max(peak_C, th.interface_temps_C(ts).maxCoeff());
        recorder.step(ts, step.ta_s, step.tb_s);
      });
  rec.blocks.push_back(components::friction_range_block(stepper.data_ranges().front()));

  const double n_if = clutch.params().sliding_interfaces;
  const auto me = sim.energy();
  const auto& cnt = sim.counters();
  // The coupling's verdict and the locked shuffle mode are studies of this recording
  // (studies/driveline_judgement.hpp), added with the run's analysis.
  const dynamics::Sample end = sim.sample();
  const double engine_slope = dl.engine_slope_Nms_per_rad(end.t_s, end.omega_rad_s[D::kEngine]);
  rec.scalars = {
      {"heat_generated_J", "J", n_if * ts.energy.generated_J},
      {"peak_interface_temp_C", "degC", peak_C},
      {"friction_work_J", "J", me.friction_heat_J},
      {"mechanical_energy_relative_error", "1",
       components::mechanical_energy_relative_error(me, components::MechanicalEnergyScale::kLargestEnergyInPlay)},
      {"piston_area_m2", "m^2", dl.hydraulics().piston_area_m2()},
      {"engine_torque_speed_slope_Nms_per_rad", "N m s/rad", engine_slope},
      {"engine_stall_time_s", "s", stall_time_s},
      {"integrator_steps", "1", static_cast<double>(cnt.steps)},
      {"stick_events", "1", static_cast<double>(cnt.stick_events)},
      {"breakaway_events", "1", static_cast<double>(cnt.breakaway_events)},
  };
  return rec;
}

}  // namespace shudder::rig_models
