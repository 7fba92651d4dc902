#include "rig_models/driveline_expansion.hpp"

#include <algorithm>
#include <array>
#include <cmath>

namespace shudder::rig_models {

// The expansion writes in the network description's own vocabulary (components/network_spec.hpp).
using namespace components;

namespace {

Signal schedule_signal(const components::PiecewiseLinear& f) { return Signal::table(f.times_s(), f.values(), true); }

}  // namespace

NetworkSpec expand_driveline(const DrivelineParams& p, const clutch::WetClutchParams& pack, const clutch::Fluid& fluid,
                             const DrivelineInputs& in, const DrivelineSettings& cfg) {
  const clutch::WetClutch clutch(pack, fluid);
  const HaldexDriveline dl(p, clutch, in);  // validates, and gives the turn's geometry
  using D = HaldexDriveline;
  const double r = p.wheel_radius_m;
  const double w_vehicle = in.start_speed_km_h / 3.6 / r;
  const Eigen::VectorXd w = dl.rolling_speed_ratios() * w_vehicle;
  NetworkSpec s;

  // Bodies in the driveline's node order (the vehicle is a node of its own kind, last).
  const std::array<std::pair<const char*, double>, D::kNodes> bodies{{{"engine", p.engine_inertia_kg_m2},
                                                                      {"front_diff", p.front_diff_inertia_kg_m2},
                                                                      {"front_side_left", p.side_gear_inertia_kg_m2},
                                                                      {"front_side_right", p.side_gear_inertia_kg_m2},
                                                                      {"wheel_fl", p.wheel_inertia_kg_m2},
                                                                      {"wheel_fr", p.wheel_inertia_kg_m2},
                                                                      {"vehicle", 0.0},
                                                                      {"ptu", p.ptu_inertia_kg_m2},
                                                                      {"coupling_in", p.coupling_half_inertia_kg_m2},
                                                                      {"coupling_out", p.coupling_half_inertia_kg_m2},
                                                                      {"rear_diff", p.rear_diff_inertia_kg_m2},
                                                                      {"rear_side_left", p.side_gear_inertia_kg_m2},
                                                                      {"rear_side_right", p.side_gear_inertia_kg_m2},
                                                                      {"wheel_rl", p.wheel_inertia_kg_m2},
                                                                      {"wheel_rr", p.wheel_inertia_kg_m2}}};
  for (int i = 0; i < D::kNodes; ++i)
    if (i != D::kVehicle)
      s.inertias.push_back(
          {bodies[static_cast<std::size_t>(i)].first, bodies[static_cast<std::size_t>(i)].second, w[i]});

  const double theta = std::atan(in.grade_percent / 100.0);
  const double weight_N = p.vehicle_mass_kg * D::kGravity_m_s2;
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

  const std::array<const char*, 4> tyres{"tyre_fl", "tyre_fr", "tyre_rl", "tyre_rr"};
  const std::array<const char*, 4> wheels{"wheel_fl", "wheel_fr", "wheel_rl", "wheel_rr"};
  for (int i = 0; i < 4; ++i) {
    TyreSpec t;
    t.name = tyres[static_cast<std::size_t>(i)];
    t.wheel = wheels[static_cast<std::size_t>(i)];
    t.vehicle = "vehicle";
    t.params = dl.tyre(i).params();
    t.path_ratio = dl.path_ratios()[static_cast<std::size_t>(i)];
    s.tyres.push_back(t);
  }
  if (p.engine_pulsation.amplitude_Nm > 0)
    s.firing_pulsations.push_back(
        {"firing", "engine", p.engine_pulsation, p.engine.stall_speed_rpm, p.engine.idle_speed_rpm});

  // The engine: its map with the throttle, or the raw torque schedule; the pedal the control
  // unit reads is the throttle, or the raw torque over the full-load curve's peak.
  Signal pedal = Signal::constant(0.0);
  if (in.throttle) {
    EngineSpec e;
    e.name = "engine_map";
    e.node = "engine";
    e.params = p.engine;
    e.throttle = schedule_signal(*in.throttle);
    s.engines.push_back(e);
    pedal = e.throttle;
  } else {
    s.torque_sources.push_back({"engine_torque", "engine", schedule_signal(in.engine_torque_Nm)});
    const auto& full = p.engine.full_load_torque_Nm.values();
    const double peak = *std::max_element(full.begin(), full.end());
    std::vector<double> u;
    for (double t : in.engine_torque_Nm.values()) u.push_back(peak > 0 ? t / peak : 0.0);
    pedal = Signal::table(in.engine_torque_Nm.times_s(), u, true);
  }

  ClutchSpec c;
  c.name = "haldex";
  c.a = "coupling_in";
  c.b = "coupling_out";
  c.law = ClutchSpec::Law::kHaldex;
  c.wet.fluid = fluid;
  c.wet.clutch = pack;  // the pack's oil already applied by the scenario (apply_pack_oil)
  c.wet.oil_volume_given = c.wet.oil_flow_given = true;
  c.wet.stick_time = p.stick_time;
  HaldexSpec& h = c.haldex;
  h.hydraulics = p.hydraulics;
  h.controller = p.controller;
  h.nominal_friction = p.nominal_friction;
  h.front_axle = "front_diff";
  h.rear_axle = "rear_diff";
  const auto& rho = dl.path_ratios();
  h.front_path_ratio = 0.5 * (rho[D::kFL] + rho[D::kFR]);
  h.rear_path_ratio = 0.5 * (rho[D::kRL] + rho[D::kRR]);
  h.wheel_radius_m = r;
  h.pedal = pedal;
  if (in.valve_opening) h.valve_opening = schedule_signal(*in.valve_opening);
  if (in.valve_pressure_bar) h.valve_pressure_bar = schedule_signal(*in.valve_pressure_bar);
  s.clutches.push_back(c);

  s.settings.duration_s = cfg.duration_s;
  s.settings.sample_rate_Hz = cfg.sample_rate_Hz;
  s.settings.thermal_step_s = cfg.slow_step_s;
  s.settings.integrator = p.integrator;
  return s;
}

}  // namespace shudder::rig_models
