#pragma once
// An all-wheel-drive car with a Haldex limited-slip coupling (thesis Introduction; PHYSICS.md §8)
// as a torsional network, lumped per axle (the two wheels of an axle, and their half-shafts and
// tyres, act in parallel as one):
//
//   engine ═(i_g·i_f)═ front_diff ─half-shafts─ front_wheels ─k_t─ front_belts ─c_t─ front_road ═(ρ)═ vehicle
//                          ║ (i_ptu)                                                                         │
//                         ptu ─propeller shaft─ coupling_in ┤Haldex├ coupling_out                            │
//                                                                ║ (i_r)                                     │
//                                               rear_diff ─half-shafts─ rear_wheels ─k_t─ rear_belts ─c_t────┘
//
//   ═(r)═ a gear: ω_a = r ω_b;  ─ a shaft (spring k and damper c in parallel);  ┤├ the clutch.
//   vehicle: the car's mass as an inertia m r_w² turning at v / r_w (no road load yet).
//   front_road: where the front tyres meet the road. In a turn the front axle travels a longer
//     path than the rear: ρ = path_front / path_rear (1 straight; ≈ 1.03–1.05 at full lock, from
//     1/cos of the mean steering angle). With the coupling locked, ρ > 1 winds the driveline up:
//     the tight-turn case where a Haldex clutch slips slowly under high torque.
//   the coupling: the wet clutch of clutch/ (WetClutch as a ClutchContactLaw) clamped by
//     F = F_preload + A p from HaldexHydraulics, p advanced per slow step with the coupling's
//     relative rotation and held over the next (as the disc temperatures are).
//
// Tyres: the carcass, a spring k_t from the rim to the belt and tread, in series with the slip,
// a damper c_t = C_κ r_w² / v_ref from the belt to the road (the longitudinal slip stiffness C_κ
// read as a damping at the reference speed v_ref): the linear tyre about an operating point. In
// series, so that a steady slip (a turn) carries a steady torque instead of winding the carcass
// up. It cannot spin a wheel: slip limits are not modelled yet.
//
// Parameters are not in the thesis: every default below is an ESTIMATE for a mid-size AWD car of
// the thesis' era (1.7 t, 1st gear), named and overridable. Together they put the first
// driveline (shuffle) mode at a few Hz, in PHYSICS.md's 2–10 Hz.

#include <memory>

#include "clutch/wet_clutch.hpp"
#include "dynamics/network.hpp"
#include "dynamics/recording.hpp"
#include "dynamics/simulation.hpp"
#include "rig_models/clutch_contact.hpp"
#include "rig_models/drive_cycle.hpp"
#include "rig_models/haldex_hydraulics.hpp"

namespace shudder::rig_models {

struct DrivelineParams {
  double engine_inertia_kg_m2 = 0.25;       // estimate: 2-litre engine, flywheel and clutch
  double gear_ratio = 3.5;                  // estimate: 1st gear
  double final_drive_ratio = 4.0;           // estimate
  double front_diff_inertia_kg_m2 = 0.05;   // estimate: gearbox output, differential
  double halfshaft_stiffness_Nm_per_rad = 6000.0;  // estimate, per shaft (×2 per axle)
  double halfshaft_damping_Nms_per_rad = 5.0;      // estimate, per shaft
  double wheel_inertia_kg_m2 = 1.0;         // estimate, per wheel with tyre and brake disc
  double belt_share = 0.35;                 // estimate: tread and belt's part of it (~4 kg at 0.3 m)
  double tyre_stiffness_Nm_per_rad = 50000.0;  // estimate, per tyre: ~5e5 N/m at the patch × r²
  double tyre_slip_stiffness_N = 1.5e5;     // C_κ per tyre (estimate: typical passenger tyre)
  double tyre_reference_speed_m_s = 5.0;    // v_ref for the slip damping (estimate: manoeuvring)
  double vehicle_mass_kg = 1700.0;          // estimate
  double wheel_radius_m = 0.32;             // estimate: 205/55 R16 rolling radius
  double ptu_ratio = 2.6;                   // estimate: power take-off, front diff → propshaft
  double ptu_inertia_kg_m2 = 0.01;          // estimate
  double propshaft_stiffness_Nm_per_rad = 25000.0;  // estimate
  double propshaft_damping_Nms_per_rad = 5.0;       // estimate
  double coupling_half_inertia_kg_m2 = 0.02;  // estimate, each side of the disc pack
  double rear_diff_ratio = 2.6;             // estimate; = ptu_ratio: front and rear axles match
  double rear_diff_inertia_kg_m2 = 0.03;    // estimate
  double turn_ratio = 1.0;                  // ρ, see header
  double nominal_friction = 0.12;           // μ_nom for the piston area (estimate: wet clutch)
  HaldexHydraulicsParams hydraulics;
  StickTimeFriction stick_time;             // the `stick_time_static_friction` effect
  // Tolerances as for the rig: speeds of ~1–100 rad/s, twists of ~1e-2 rad.
  dynamics::IntegratorSettings integrator{1e-6, 1e-6, 1e-3, 1e-6, 1e-10};
};

struct DrivelineInputs {
  PiecewiseLinear engine_torque_Nm{{0.0}, {0.0}};
  PiecewiseLinear valve_pressure_bar{{0.0}, {30.0}};  // the controller's setting
  double start_speed_km_h = 0.0;  // vehicle speed at t = 0, every part rolling with it
};

struct DrivelineSettings {
  double duration_s = 5.0;
  double slow_step_s = 0.01;      // thermal and hydraulic step
  double sample_rate_Hz = 1000.0;
};

/// A const model: the coupling's held inputs (ring temperatures, clamp force) live in a
/// ClutchContext owned by the run, to which the network's coupling law is bound.
class HaldexDriveline {
 public:
  /// Throws std::invalid_argument for invalid parameters.
  HaldexDriveline(const DrivelineParams& params, const clutch::WetClutch& clutch, const DrivelineInputs& inputs);

  /// Every ring at the clutch's start temperature, the clamp force of the unpressurised pump.
  ClutchHeldInputs start_inputs() const;
  /// The network with the coupling's law bound to `coupling_context` (the run's held inputs).
  dynamics::TorsionalNetwork network(std::shared_ptr<ClutchContext> coupling_context) const;
  /// The network bound to a fresh context at start_inputs() (for inspection and modes).
  dynamics::TorsionalNetwork network() const;
  const HaldexHydraulics& hydraulics() const { return hydraulics_; }
  const DrivelineParams& params() const { return p_; }
  /// Speed of every node per unit vehicle speed (rad/s per rad/s) when all rolls together.
  Eigen::VectorXd rolling_speed_ratios() const;

  enum Node { kEngine, kFrontDiff, kFrontWheels, kFrontBelts, kFrontRoad, kVehicle, kPtu, kCouplingIn,
              kCouplingOut, kRearDiff, kRearWheels, kRearBelts, kNodes };
  enum ShaftIndex { kFrontHalfshafts, kFrontCarcass, kFrontSlip, kPropshaft, kRearHalfshafts, kRearCarcass,
                    kRearSlip };
  static constexpr int kCoupling = 0;

 private:
  dynamics::TorsionalNetwork build(std::shared_ptr<const dynamics::ContactLaw> coupling_law) const;
  DrivelineParams p_;
  HaldexHydraulics hydraulics_;
  ClutchContact contact_;
  PiecewiseLinear engine_torque_Nm_;
};

/// Simulates the driveline with the coupling's thermal model and hydraulics (multi-rate) and
/// records speeds, torques, pressure and temperatures; judges the coupling's judder from its
/// torque and slip (analysis/shudder_detection.hpp, from 2 Hz), counting only an oscillation
/// that still has half its amplitude at the end of the record (a torque step's ringing of the
/// shuffle mode dies out and is not judder).
dynamics::Recording run_driveline(const DrivelineParams& params, const clutch::WetClutch& clutch,
                                  const DrivelineInputs& inputs, const DrivelineSettings& settings);

}  // namespace shudder::rig_models
