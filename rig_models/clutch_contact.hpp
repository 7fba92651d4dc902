#pragma once
// The wet clutch as a friction contact of the torsional network (dynamics::ContactLaw).
//
//   kinetic torque  M_k(|Δω|, t) = n Σ_i r_i p(t) mu_k(r_i|Δω|, T_i, F(t)) A_i  + M_drag
//   static capacity M_s(t, t_st)  = n Σ_i r_i p(t) mu_s(T_i, F(t)) A_i · g(t_st) + M_drag
//   g(t_st) = 1 + Δ_s (1 − exp(−t_st/τ_s))   `stick_time_static_friction` (else g = 1)
//   M_drag = mu_b F(t) r_b                    `bearing_drag` (rig: mu_b = 0.005, thesis)
//   heat channels: the rings of ONE interface's thermal grid, q_i = |Δω| r_i p mu_k A_i (+ the
//   viscous shear heat when that effect is on); bearing drag heats no disc.
//
// Ring temperatures T_i are HELD between thermal steps (DESIGN.md multi-rate coupling): the rig
// simulation calls set_ring_temperatures() after each thermal step and restarts the stepper.
// The stick-time growth law (saturating, Δ_s and τ_s) is an estimate after Paper A's review
// (static friction grows with time at rest, Gao et al.); defaults in StickTimeFriction.

#include <Eigen/Dense>

#include "clutch/wet_clutch.hpp"
#include "dynamics/contact_law.hpp"
#include "rig_models/drive_cycle.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::rig_models {

struct StickTimeFriction {
  bool enabled = false;
  double max_increase = 0.15;    // Δ_s: fractional rise of mu_s after a long stick (estimate)
  double time_constant_s = 1.0;  // τ_s (estimate)
};

class ClutchContactLaw final : public dynamics::ContactLaw {
 public:
  ClutchContactLaw(const clutch::WetClutch& clutch, PiecewiseLinear normal_force_N,
                   BearingDrag drag, StickTimeFriction stick_time);

  void set_ring_temperatures(const Eigen::VectorXd& ring_temp_C);
  /// Replaces the clamp force (a coupling whose force comes from a slow hydraulic state).
  void set_normal_force(PiecewiseLinear normal_force_N);
  const Eigen::VectorXd& ring_temperatures() const { return ring_temp_C_; }

  double kinetic_torque_Nm(double abs_slip_rad_s, double t_s) const override;
  double static_capacity_Nm(double t_s, double stick_time_s) const override;
  double kinetic_torque_slope_Nms(double abs_slip_rad_s, double t_s) const override;
  int heat_channels() const override { return clutch_.thermal().radial_cells(); }
  void channel_heat_W(double abs_slip_rad_s, double t_s, double* out) const override;

  double drag_torque_Nm(double t_s) const;

 private:
  const clutch::WetClutch& clutch_;
  PiecewiseLinear force_N_;
  BearingDrag drag_;
  StickTimeFriction stick_;
  // Ring torques at the last (|Δω|, t) asked: the integrator asks for the torque and then the
  // channel heats at the same arguments. Frozen friction is rebuilt with new temperatures or
  // when the friction load moved by more than 1e-4 relative (a force ramp; mu changes by
  // < 1e-6 over such a step).
  void update(double abs_slip_rad_s, double t_s) const;
  Eigen::VectorXd ring_temp_C_;            // (n_r) held interface temperatures
  mutable clutch::FrozenFriction frozen_;
  mutable bool frozen_valid_ = false;
  mutable double cached_slip_ = -1.0, cached_t_ = 0.0;
  mutable Eigen::VectorXd ring_torque_;    // (n_r) per interface at the cached arguments
};

}  // namespace shudder::rig_models
