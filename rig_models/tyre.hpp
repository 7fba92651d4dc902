#pragma once
// A tyre's longitudinal force with its relaxation length and a road friction (a dynamics::ForceLaw
// between a wheel node and the car's node, the ratio ρ being the wheel's path ratio in a turn).
//
// Transient slip (Pacejka, Tyre and Vehicle Dynamics, 3rd ed. 2012, §7.2, the single-contact-point
// transient model): the contact point's longitudinal deflection u (m) lags the slip speed,
//     du/dt = (ω_w r − V_x) − V_t u / σ,      V_x = ρ ω_v r (the wheel's ground speed),
//     κ' = u / σ                                 (the transient slip, ≈ the slip κ in steady state),
// σ the relaxation length. V_t = max(|V_x|, |ω_w r|) is the speed the tread moves through the
// contact patch: κ' then tends to the slip (ω_w r − V_x)/max(|V_x|, |ω_w r|), the bounded slip
// (within ±1: a wheel spinning at standstill has κ' → 1, a locked wheel −1). At standstill
// (V_t = 0) the tyre is a spring of C_κ/σ (N/m): the force is defined down to rest.
// Relaxation length from the carcass: σ = C_κ / c_x (Pacejka §7.2: the relaxation length is the
// slip stiffness over the carcass's longitudinal stiffness c_x).
//
// Force: the brush model with a parabolic pressure distribution and one friction coefficient
// (Pacejka §3.2.2, pure longitudinal slip), with a = |κ'| / κ_sl and κ_sl = 3 μ F_z / C_κ:
//     F = sgn(κ') μ F_z (1 − (1 − a)³)   for a < 1,   F = sgn(κ') μ F_z beyond (full sliding),
// slope C_κ at κ' = 0 (independent of speed), saturating at the road friction μ F_z.
// Energy: the force is a function of u, so E(u) = ∫ F du is stored (in closed form below), and
//     T (ω_w − ρ ω_v) = r F (ω_w − ρ ω_v) = F du/dt + F V_t u/σ = dE/dt + P_diss,  P_diss = F V_t κ' >= 0.
//
// Units: C_κ N (per unit slip), σ m, F_z N, r m; the torque on the wheel T = r F (N m).

#include "dynamics/network.hpp"

namespace shudder::rig_models {

struct TyreParams {
  double slip_stiffness_N = 1.5e5;  // C_κ
  double relaxation_length_m = 0.3;  // σ
  double vertical_load_N = 4000.0;   // F_z
  double road_friction = 1.0;        // μ
  double radius_m = 0.32;            // r
};

class BrushTyre final : public dynamics::ForceLaw {
 public:
  /// Throws std::invalid_argument unless every parameter is finite and > 0.
  explicit BrushTyre(const TyreParams& p);
  int states() const override { return 1; }
  Output evaluate(double omega_wheel, double omega_ground_at_wheel, const double* z, double* dzdt) const override;
  double stored_energy_J(const double* z) const override;
  double modal_stiffness_Nm_per_rad() const override;
  /// The steady force at a slip κ (N), the brush curve above.
  double force_N(double slip) const;
  const TyreParams& params() const { return p_; }

 private:
  TyreParams p_;
  double full_slide_slip_ = 0;  // κ_sl
};

/// The road load on the car, as a ForceLaw from the car's node to ground (ratio 1):
///   F = F_rr tanh(v / v_rr) + ½ ρ_air c_d A v |v|,   v = ω_v r,  T = r F,  P_diss = T ω_v >= 0.
/// F_rr = f_r m g cos θ the rolling resistance (coefficient f_r; Gillespie, Fundamentals of Vehicle
/// Dynamics, 1992, ch. 4: 0.01–0.015 for passenger tyres on asphalt), smoothed below v_rr (so the
/// force is continuous through standstill; the car creeps at v_rr-scale speeds on a grade it would
/// hold); c_d A the drag area (Gillespie ch. 4: c_d 0.3–0.4 for cars of the era, A ≈ 2 m²).
struct RoadLoadParams {
  double rolling_resistance_N = 200.0;  // F_rr
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

}  // namespace shudder::rig_models
