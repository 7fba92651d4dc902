#pragma once
// An all-wheel-drive car with a Haldex limited-slip coupling (thesis Introduction; docs/physics.md §8)
// as a torsional network, per wheel (left and right on each axle, open differentials):
//
//   engine ═(i_g·i_f)═ front_diff ⟨open diff⟩ front_side_l/r ─half-shaft─ wheel_fl/fr ~tyre(ρ_fl/fr)~ vehicle
//                          ║ (i_ptu)                                                                    │
//                         ptu ─propeller shaft─ coupling_in ┤Haldex├ coupling_out                         │
//                                                                ║ (i_r)                                  │
//                                               rear_diff ⟨open diff⟩ rear_side_l/r ─half-shaft─ wheel_rl/rr
//                                               ~tyre(ρ_rl/rr)~┘
//   vehicle ~road load~ ground;  grade: a constant torque −m g sin θ r on the vehicle.
//
//   ═(r)═ a gear: ω_a = r ω_b;  ─ a shaft (spring k and damper c);  ┤├ the clutch;
//   ⟨open diff⟩ ω_l + ω_r = 2 ω_carrier (dynamics::Differential; equal torques left and right);
//   ~tyre(ρ)~ components/tyre.hpp: the brush tyre with its relaxation length and the wheel's road
//     friction, between the wheel and the vehicle seen through ρ.
//   vehicle: the car's mass as an inertia m r_w² turning at v / r_w, v the rear axle centre's speed.
//   ρ_i: wheel i's path over the rear axle centre's in a steady turn (kinematic, no side slip):
//     rear wheels (R ∓ w/2)/R, front wheels √(L² + (R ∓ w/2)²)/R for a left turn of radius R
//     (rear axle centre), wheelbase L, track w. With the coupling locked, the front axle's longer
//     path winds the driveline up through the tyres' slip: the tight-turn case. (A legacy
//     `turn_ratio` ρ puts both front wheels on ρ and both rear on 1.)
//   Vertical loads (components/tyre.hpp): each axle's static load on the grade θ (uphill > 0),
//     F_z,front = m g (s_f cos θ − (h/L) sin θ),  F_z,rear = m g ((1 − s_f) cos θ + (h/L) sin θ),
//   split equally between its two tyres (s_f the front axle's share on the level, h the centre of
//   gravity's height, L the wheelbase), plus the dynamic transfer ∓ m h ā / (2 L) per tyre of the
//   car's filtered acceleration ā; each tyre's slip stiffness C_κ = c_κ F_z follows its load
//   (or an absolute C_κ when tyre_slip_stiffness_N is given). cg_height_m = 0: no transfer.
//   the coupling: the wet clutch of clutch/ clamped by F = F_preload + A p from HaldexHydraulics
//     (a Gen I coupling: pump ∝ |Δω|, throttle valve on the return, relief valve, oil and pack
//     compliance), one contact law with the pressure and the valve's opening as its states,
//     integrated with the motion (components/haldex_coupling_law.hpp); the valve commanded by
//     HaldexController every control period from sampled, filtered axle speeds
//     (components/haldex_controller.hpp), or by a raw schedule. The thermal step sets only the
//     disc temperatures' update. The pack's own oil (volume, cooling flow) replaces the rig's sump
//     and forced flow (components/pack_oil.hpp).
//
// The car is written as network components (spec(); rig_models/driveline_expansion.hpp names
// them), assembled by components/network_builder.hpp and run by components/network_stepper.hpp
// with the coupling's control unit, the same code as any network scenario; what is the car's own
// is its parameters, what is derived from them (tyres, loads, the turn's path ratios), the
// operating points its stability studies linearise about and the channels it records.
//
// Parameters are not in the thesis: every default below is an ESTIMATE for a mid-size AWD car of
// the thesis' era (1.7 t, 1st gear; wheelbase and track of a VW Golf IV 4motion, the first
// Haldex car), named and overridable. Together they put the first driveline (shuffle) mode at a
// few Hz, in docs/physics.md's 2–10 Hz.

#include <array>
#include <memory>
#include <optional>

#include "clutch/wet_clutch.hpp"
#include "dynamics/network.hpp"
#include "dynamics/recording.hpp"
#include "dynamics/simulation.hpp"
#include "components/clutch_contact.hpp"
#include "components/drive_cycle.hpp"
#include "components/engine.hpp"
#include "components/engine_pulsation.hpp"
#include "components/haldex_control.hpp"
#include "components/haldex_controller.hpp"
#include "components/haldex_coupling_law.hpp"
#include "components/haldex_hydraulics.hpp"
#include "components/network_builder.hpp"
#include "components/network_spec.hpp"
#include "components/tyre.hpp"

namespace shudder::rig_models {

struct DrivelineParams {
  double engine_inertia_kg_m2 = 0.25;              // estimate: 2-litre engine, flywheel and clutch
  double gear_ratio = 3.5;                         // estimate: 1st gear
  double final_drive_ratio = 4.0;                  // estimate
  double front_diff_inertia_kg_m2 = 0.05;          // estimate: gearbox output, differential
  double halfshaft_stiffness_Nm_per_rad = 6000.0;  // estimate, per shaft (×2 per axle)
  double halfshaft_damping_Nms_per_rad = 5.0;      // estimate, per shaft
  double side_gear_inertia_kg_m2 = 0.005;          // estimate, per differential side gear
  double wheel_inertia_kg_m2 = 1.0;                // estimate, per wheel with tyre and brake disc
  // Carcass: c_x r², c_x ≈ 5e5 N/m (estimate; Pacejka §7.2 gives 3–10e5 N/m for car tyres); the
  // relaxation length is σ = C_κ r² / (c_x r²) = 0.31 m with the slip stiffness below (Pacejka:
  // σ ≈ 0.1–0.5 m, about a tyre radius).
  // The relaxation length then follows the load: σ = C_κ r² / k_tyre (0.19 m front, 0.13 m rear
  // on the level with c_κ = 19).
  double tyre_stiffness_Nm_per_rad = 50000.0;
  // Slip stiffness: c_κ = C_κ/F_z (default components::kDefaultSlipStiffnessPerLoad, the Magic
  // Formula's dry-tarmac B C D = 19, tyre.hpp), or an absolute C_κ per tyre (N) independent of the
  // load; at most one of the two.
  std::optional<double> tyre_slip_stiffness_per_load;
  std::optional<double> tyre_slip_stiffness_N;
  double cg_height_m = 0.55;                      // h (estimate: a compact hatchback's laden CG, 0.5–0.6 m)
  double vehicle_mass_kg = 1700.0;                // estimate
  double wheelbase_m = 2.51;                      // VW Golf IV (public data)
  double track_width_m = 1.51;                    // VW Golf IV, mean of front and rear (public data)
  double front_axle_load_share = 0.6;             // estimate: front-engined car
  double rolling_resistance_coefficient = 0.012;  // f_r (Gillespie ch. 4: 0.01–0.015)
  double drag_coefficient_area_m2 = 0.67;         // c_d A: Golf IV c_d 0.32 × A 2.1 m² (public, rounded)
  double air_density_kg_m3 = 1.2;
  double wheel_radius_m = 0.32;                     // estimate: 205/55 R16 rolling radius
  double ptu_ratio = 2.6;                           // estimate: power take-off, front diff → propshaft
  double ptu_inertia_kg_m2 = 0.01;                  // estimate
  double propshaft_stiffness_Nm_per_rad = 25000.0;  // estimate
  double propshaft_damping_Nms_per_rad = 5.0;       // estimate
  double coupling_half_inertia_kg_m2 = 0.02;        // estimate, each side of the disc pack
  double rear_diff_ratio = 2.6;                     // estimate; = ptu_ratio: front and rear axles match
  double rear_diff_inertia_kg_m2 = 0.03;            // estimate
  double turn_ratio = 1.0;                          // legacy ρ of the front axle, see header
  double nominal_friction = 0.12;                   // μ_nom for the preload's force (estimate: wet clutch)
  // The coupling's own oil (estimates: a Gen I unit holds ~0.6 l; the pack is splash- and
  // pump-washed, no forced cooling circuit): shared by the pack's interfaces (components/pack_oil.hpp).
  double pack_oil_volume_ml = 600.0;
  double pack_cooling_flow_ml_min = 300.0;
  components::HaldexHydraulicsParams hydraulics;
  components::HaldexControllerParams controller;  // used unless the manoeuvre gives a raw valve schedule
  components::EngineParams engine;                // used when the manoeuvre gives a throttle
  components::StickTimeFriction stick_time;       // the `stick_time_static_friction` effect
  components::EnginePulsation engine_pulsation;   // firing-order torque pulsation (engine_pulsation.hpp); 0 N m: none
  // Tolerances as for the rig: speeds of ~1–100 rad/s, twists of ~1e-2 rad.
  dynamics::IntegratorSettings integrator{1e-6, 1e-6, 1e-3, 1e-6, 1e-10};
};

struct DrivelineInputs {
  components::PiecewiseLinear engine_torque_Nm{{0.0}, {0.0}};  // raw schedule, used without a throttle
  std::optional<components::PiecewiseLinear> throttle;         // 0–1: the engine map of components/engine.hpp
  // The throttle valve: a raw opening schedule (0 shut – 1 open) and/or a raw pressure setting
  // (an ideal cap, the valve shut below it); neither: the controller model decides.
  std::optional<components::PiecewiseLinear> valve_opening;
  std::optional<components::PiecewiseLinear> valve_pressure_bar;
  double start_speed_km_h = 0.0;                            // vehicle speed at t = 0, every part rolling with it
  double turn_radius_m = 0.0;                               // R of the rear axle centre, left turn; 0 = straight
  std::array<double, 4> road_friction{1.0, 1.0, 1.0, 1.0};  // μ per wheel: FL, FR, RL, RR (dry asphalt ≈ 1)
  double grade_percent = 0.0;                               // road gradient, uphill > 0 (100 tan θ)
};

struct DrivelineSettings {
  double duration_s = 5.0;
  double slow_step_s = 0.01;  // thermal step (the hydraulics are integrated with the motion)
  double sample_rate_Hz = 1000.0;
};

/// The car's parameters and what is derived from them (tyres, road load, the turn's path
/// ratios), and the car as network components (spec()). A const
/// model: a run or an analysis builds its own network from it (build()).
class HaldexDriveline {
 public:
  /// Throws std::invalid_argument for invalid parameters. `clutch` must outlive the driveline.
  HaldexDriveline(const DrivelineParams& params, const clutch::WetClutch& clutch, const DrivelineInputs& inputs);

  /// Every ring at the clutch's start temperature, the clamp force of the unpressurised pump.
  components::ClutchHeldInputs start_inputs() const;
  /// The command at the start: the valve open, the raw pressure setting if one is given.
  components::HaldexCommand start_command() const;
  /// The car as network components (rig_models/driveline_expansion.hpp), run with `settings`. The
  /// spec holds copies of the pack's parameters and fluid and stands alone; with `share_clutch`
  /// its networks take this car's clutch itself instead of building their own (which must then
  /// outlive them).
  components::NetworkSpec spec(const DrivelineSettings& settings, bool share_clutch = false) const;
  /// The network of spec(DrivelineSettings{}): what a run integrates and an analysis linearises,
  /// in this class' node, shaft, contact and force-element order. Its coupling (clutch 0) holds
  /// start_inputs() and its command start_command(). The constructor has built it with every
  /// check; later builds skip the topology's by default.
  components::OwnedNetwork build(components::NetworkChecks checks = components::NetworkChecks::kSkipTopology) const;
  /// The coupling law's states [p, u] for a clamp force and valve opening (operating points).
  Eigen::VectorXd coupling_states(double clamp_force_N, double opening) const;
  const components::HaldexHydraulics& hydraulics() const { return hydraulics_; }
  /// The valve opening the run's control unit (components/haldex_control.hpp) commands for the
  /// axles' speeds of a steady state `s` (the controller's, or the raw schedule's; shut under a
  /// raw pressure setting), and the pressure setting (the relief pressure unless a raw one is
  /// given).
  double valve_opening(const dynamics::Sample& s) const;
  double valve_setting_bar(double t_s) const;
  const DrivelineParams& params() const { return p_; }
  /// Speed of every node per unit vehicle speed (rad/s per rad/s) when all rolls together.
  Eigen::VectorXd rolling_speed_ratios() const;
  /// ρ of each wheel (FL, FR, RL, RR), see the header.
  const std::array<double, 4>& path_ratios() const { return path_ratios_; }
  /// The tyre of wheel i (FL, FR, RL, RR).
  const components::BrushTyre& tyre(int wheel) const { return *tyres_[static_cast<std::size_t>(wheel)]; }
  const components::RoadLoad& road_load() const { return *road_load_; }
  /// The engine's torque at a time and crankshaft speed: the map with the throttle, or the schedule.
  double engine_torque_Nm(double t_s, double omega_rad_s) const;
  /// dT/dω of the engine there (0 for a raw schedule), N m s/rad.
  double engine_slope_Nms_per_rad(double t_s, double omega_rad_s) const;
  bool engine_mapped() const { return throttle_.has_value(); }
  const components::Engine& engine() const { return engine_; }
  /// The grade's torque on the vehicle node, −m g sin θ r_w (N m).
  double grade_torque_Nm() const { return grade_torque_Nm_; }

  enum Node {
    kEngine,
    kFrontDiff,
    kFrontSideLeft,
    kFrontSideRight,
    kFrontLeftWheel,
    kFrontRightWheel,
    kPtu,
    kCouplingIn,
    kCouplingOut,
    kRearDiff,
    kRearSideLeft,
    kRearSideRight,
    kRearLeftWheel,
    kRearRightWheel,
    kVehicle,  // the car's mass, last: a network builds its vehicles after its inertias
    kNodes
  };
  enum ShaftIndex { kFrontLeftHalfshaft, kFrontRightHalfshaft, kPropshaft, kRearLeftHalfshaft, kRearRightHalfshaft };
  enum Wheel { kFL, kFR, kRL, kRR };
  static constexpr int kCoupling = 0;
  static constexpr int kRoadLoadElement = 4;  // force elements: the four tyres (Wheel order), then the road load
  static constexpr double kGravity_m_s2 = 9.80665;

 private:
  DrivelineParams p_;
  const clutch::WetClutch* clutch_;
  DrivelineInputs inputs_;
  components::HaldexHydraulics hydraulics_;
  std::optional<components::PiecewiseLinear> valve_opening_, valve_pressure_bar_;
  components::ClutchContact contact_;
  components::PiecewiseLinear engine_torque_Nm_;
  std::optional<components::PiecewiseLinear> throttle_;
  components::Engine engine_;
  std::array<double, 4> path_ratios_{};
  std::array<std::shared_ptr<const components::BrushTyre>, 4> tyres_;
  std::shared_ptr<const components::RoadLoad> road_load_;
  double grade_torque_Nm_ = 0;
  // The network built with every check, and a control unit on its coupling: what valve_opening
  // asks (the run's own control logic, not a copy of it).
  std::optional<components::OwnedNetwork> checked_;
  std::unique_ptr<components::HaldexControlUnit> control_unit_;
};

/// The static axle loads (front, rear; N) on a grade (%, uphill > 0): the car's weight split by
/// front_axle_load_share on the level, moved rearwards by m g (h/L) sin θ uphill (see the header).
std::array<double, 2> static_axle_loads_N(const DrivelineParams& params, double grade_percent);

/// Simulates the driveline: its network (spec()) run by components::NetworkStepper, the
/// coupling's thermal model coupled multi-rate, its hydraulics integrated with the motion and its
/// control unit sampled at its period; records speeds, torques, pressure and temperatures
/// (docs/formats/run_output.md). Judging the coupling is a study of the recording
/// (studies/driveline_judgement.hpp).
dynamics::Recording run_driveline(const DrivelineParams& params, const clutch::WetClutch& clutch,
                                  const DrivelineInputs& inputs, const DrivelineSettings& settings);

}  // namespace shudder::rig_models
