#pragma once
// A tyre's longitudinal force with its relaxation length, a road friction and a vertical load
// that may follow the car's longitudinal load transfer (a dynamics::ForceLaw between a wheel node
// and the car's node, the ratio ρ being the wheel's path ratio in a turn).
//
// Transient slip (Pacejka, Tyre and Vehicle Dynamics, 3rd ed. 2012, §7.2, the single-contact-point
// transient model): the contact point's longitudinal deflection u (m) lags the slip speed,
//     du/dt = (ω_w r − V_x) − V_t u / σ,      V_x = ρ ω_v r (the wheel's ground speed),
//     κ' = u / σ                                 (the transient slip, ≈ the slip κ in steady state),
// σ the relaxation length. V_t = max(|V_x|, |ω_w r|) is the speed the tread moves through the
// contact patch: κ' then tends to the slip (ω_w r − V_x)/max(|V_x|, |ω_w r|), the bounded slip
// (within ±1: a wheel spinning at standstill has κ' → 1, a locked wheel −1). At standstill
// (V_t = 0) the tyre is a spring of c_x = C_κ/σ (N/m): the force is defined down to rest.
// Relaxation length from the carcass: σ = C_κ / c_x (Pacejka §7.2: the relaxation length is the
// slip stiffness over the carcass's longitudinal stiffness c_x). c_x is a property of the
// carcass, fixed at C_κ(F_z0)/σ0 from the given relaxation length σ0 at the static load F_z0; a
// slip stiffness that follows the load then gives σ = σ0 F_z/F_z0 (Pacejka §7.2: σ grows with
// the load much as C_κ does).
//
// Slip stiffness: C_κ = c_κ F_z, c_κ the load-normalised longitudinal slip stiffness (1).
// c_κ = 19 by default: the slope at zero slip of the Magic Formula's constant-coefficient
// longitudinal curve F_x = F_z D sin(C atan(B κ − E (B κ − atan B κ))) is F_z B C D, and the
// coefficients published for dry tarmac, B = 10, C = 1.9, D = 1 (MathWorks, Simscape Driveline,
// "Tire-Road Interaction (Magic Formula)" block reference, after Pacejka), give B C D = 19. A
// user with a measured
// absolute C_κ (N) gives that instead: it is then independent of the load (σ stays σ0). Giving
// both is an error (TyreParams::static_slip_stiffness_N).
//
// Force: the brush model with a parabolic pressure distribution and one friction coefficient
// (Pacejka §3.2.2, pure longitudinal slip), with a = |κ'| / κ_sl and κ_sl = 3 μ F_z / C_κ:
//     F = sgn(κ') μ F_z (1 − (1 − a)³)   for a < 1,   F = sgn(κ') μ F_z beyond (full sliding),
// slope C_κ at κ' = 0 (independent of speed), saturating at the road friction μ F_z. In the
// deflection, a = |u| c_x / (3 μ F_z): C_κ drops out, the load sets where the force saturates.
//
// Vertical load F_z: the static load F_z0 (the caller's axle statics, grade included), plus,
// with load transfer, ∂F_z/∂a · ā, ā the car's longitudinal acceleration as the wheel loads see
// it (∂F_z/∂a = ± m h / (n L) for a tyre of n on the rear (+) or front (−) axle, m the car's mass,
// h its centre of gravity's height, L the wheelbase: the rigid body's pitch balance, Gillespie,
// Fundamentals of Vehicle Dynamics, 1992, ch. 2, ΔF_z = m a h / L per axle). ā is the car's speed
// v = V_x/ρ_path differentiated through two real lags,
//     dv₁/dt = (v − v₁)/τ₁,  dv₂/dt = (v₁ − v₂)/τ₂,  ā = (v₁ − v₂)/τ₂  (= a in a steady ramp),
// states of this law. Why a filtered acceleration, not the car's acceleration of the same rhs
// evaluation: the acceleration follows from every tyre's force and each force from its load, an
// algebraic loop across force elements that each see only their own two nodes; the wheel loads
// also do follow the demand only through the body's pitch on its suspension. The lags stand for
// that pitch: τ₁ τ₂ = 1/ω_p² and τ₁ + τ₂ = 2ζ/ω_p with a pitch mode of ω_p = 2π · 1.3 Hz
// (estimate: passenger-car body ride frequencies of 1–1.5 Hz) and ζ ≈ 1 (estimate: the real
// body's overshoot is left out, the delay kept; NVIDIA's DriveOS egomotion reference,
// dwEgomotionSuspensionParameters, gives 0.2–0.6 as the pitch damping ratio of passenger cars).
// The rhs stays a pure function of the state. The load is floored at 5 % of F_z0 (a wheel lifting
// off keeps a trace of load, so the force law stays defined; estimate, far from any shipped
// manoeuvre). The exact pitch balance moves h/L × the ground forces, m a + F_drag + m g sin θ
// (the rolling resistance is a ground force like the tyres'); the drag's share h F_drag/L is
// left out (≈ 3 N at 20 km/h, against ≈ 370 N per m/s² of acceleration on the shipped 1.7 t car).
//
// Energy: the force is a function of u and F_z; E(u, F_z) = ∫ F du = 3 μ² F_z² / c_x · I(a) is
// stored (I below), and
//     T (ω_w − ρ ω_v) = r F (ω_w − ρ ω_v) = F du/dt + F V_t u/σ = dE/dt − ∂E/∂F_z dF_z/dt + F V_t κ',
// so the law reports P = F V_t κ' − ∂E/∂F_z dF_z/dt as dissipated: the friction's loss (>= 0) less
// the work the changing load does on the stored deflection energy (the unmodelled pitch's
// exchange with the tyre; 0 without load transfer and at small slip, where E = c_x u²/2).
//
// Units: C_κ N (per unit slip), c_κ 1, σ m, F_z N, r m, ∂F_z/∂a kg; the torque on the wheel
// T = r F (N m). States: u (m); with load transfer also v₁, v₂ (m/s).

#include <optional>

#include "dynamics/network.hpp"

namespace shudder::components {

/// c_κ = C_κ/F_z by default (see the header: the Magic Formula's dry-tarmac B C D).
inline constexpr double kDefaultSlipStiffnessPerLoad = 19.0;

struct TyreLoadTransfer {
  double load_per_acceleration_kg = 0.0;  // ∂F_z/∂a: + m h/(n L) rear, − front; 0: a constant load
  double first_lag_s = 0.16;              // τ₁ (estimate, see the header: 1.3 Hz pitch, ζ ≈ 1)
  double second_lag_s = 0.09;             // τ₂
  double path_ratio = 1.0;                // V_x over the car's speed (the wheel's path ratio)
};

struct TyreParams {
  std::optional<double> slip_stiffness_N;         // C_κ absolute (N), independent of the load
  std::optional<double> slip_stiffness_per_load;  // c_κ (1); neither given: kDefaultSlipStiffnessPerLoad
  double relaxation_length_m = 0.3;               // σ0 at the static load
  double vertical_load_N = 4000.0;                // F_z0, the static load
  double road_friction = 1.0;                     // μ
  double radius_m = 0.32;                         // r
  TyreLoadTransfer load_transfer;

  /// C_κ at the static load: the absolute value, or c_κ F_z0. Throws std::invalid_argument if both
  /// are given.
  double static_slip_stiffness_N() const;
  bool slip_stiffness_follows_load() const { return !slip_stiffness_N.has_value(); }
};

class BrushTyre final : public dynamics::ForceLaw {
 public:
  /// Throws std::invalid_argument unless every parameter is finite and > 0 (lags > 0, the load's
  /// derivative finite) and at most one slip stiffness is given.
  explicit BrushTyre(const TyreParams& p);
  int states() const override { return transfers_load() ? 3 : 1; }
  Output evaluate(double omega_wheel, double omega_ground_at_wheel, const double* z, double* dzdt) const override;
  double stored_energy_J(const double* z) const override;
  double modal_stiffness_Nm_per_rad() const override;
  /// u = 0 and, with load transfer, both lags at the car's speed (no acceleration).
  void initial_states(double omega_wheel, double omega_ground_at_wheel, double* z) const override;
  /// The steady force at a slip κ (N) at the static load, the brush curve above.
  double force_N(double slip) const;
  /// The force at a deflection u (m) and load F_z (N).
  double force_at_N(double deflection_m, double vertical_load_N) const;
  /// F_z (N) for the law's states.
  double vertical_load_N(const double* z) const;
  /// C_κ (N) and σ (m) at a load.
  double slip_stiffness_N(double vertical_load_N) const;
  double relaxation_length_m(double vertical_load_N) const;
  /// The states of a steady motion: deflection u, the car's speed v (m/s) and acceleration a (m/s²)
  /// (the lags behind a ramp: v₁ = v − τ₁ a, v₂ = v₁ − τ₂ a). Writes states() values.
  void steady_states(double deflection_m, double vehicle_speed_m_s, double acceleration_m_s2, double* z) const;
  bool transfers_load() const { return p_.load_transfer.load_per_acceleration_kg != 0.0; }
  const TyreParams& params() const { return p_; }
  double carcass_stiffness_N_per_m() const { return carcass_N_per_m_; }

 private:
  double stored_energy_J(double deflection_m, double vertical_load_N) const;
  double energy_load_slope_J_per_N(double deflection_m, double vertical_load_N) const;
  TyreParams p_;
  double static_slip_stiffness_N_ = 0;
  double carcass_N_per_m_ = 0;  // c_x
};

/// The road load on the car, as a ForceLaw from the car's node to ground (ratio 1):
///   F = F_rr tanh(v / v_rr) + ½ ρ_air c_d A v |v|,   v = ω_v r,  T = r F,  P_diss = T ω_v >= 0.
/// F_rr = f_r m g cos θ the rolling resistance (coefficient f_r; Gillespie, Fundamentals of Vehicle
/// Dynamics, 1992, ch. 4: 0.01–0.015 for passenger tyres on asphalt), smoothed below v_rr (so the
/// force is continuous through standstill; the car creeps at v_rr-scale speeds on a grade it would
/// hold); c_d A the drag area (Gillespie ch. 4: c_d 0.3–0.4 for cars of the era, A ≈ 2 m²).
struct RoadLoadParams {
  double rolling_resistance_N = 200.0;    // F_rr
  double drag_coefficient_area_m2 = 0.7;  // c_d A
  double air_density_kg_m3 = 1.2;
  double radius_m = 0.32;
  double smoothing_speed_m_s = 0.05;  // v_rr (estimate: well below any manoeuvre's speed)
};

class RoadLoad final : public dynamics::ForceLaw {
 public:
  /// Throws std::invalid_argument for negative loads or a non-positive radius/smoothing.
  explicit RoadLoad(const RoadLoadParams& p);
  int states() const override { return 0; }
  Output evaluate(double omega_vehicle, double, const double*, double*) const override;
  double stored_energy_J(const double*) const override { return 0.0; }
  double modal_stiffness_Nm_per_rad() const override { return 0.0; }
  double force_N(double speed_m_s) const;

 private:
  RoadLoadParams p_;
};

}  // namespace shudder::components
