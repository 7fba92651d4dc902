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
// Model and run are kept apart (as a System and its Context):
//   ClutchContact     the const model: the clutch, bearing drag and stick-time growth.
//   ClutchContext     what a run changes: the HELD inputs (ring temperatures T_i, clamp force
//                     F(t)) and the frozen-friction cache built from them. Owned by the run.
//   ClutchContactLaw  a ClutchContact bound to one ClutchContext: what the integrator calls.
// Ring temperatures between thermal steps (docs/architecture.md multi-rate coupling): either held
// (set_ring_temperatures: linearisation, real-time mode) or on a first-order hold across the slow
// step (set_ring_temperature_ramp: the multi-rate runs, components/multirate_clutch.hpp). On the
// hold each ring's friction moves linearly in time between its values at the two end
// temperatures, T_i(t) = T_i0 + s (T_i1 − T_i0), s = (t − t0)/(t1 − t0) clamped to [0, 1]:
//   M_i(|Δω|, t) = (1 − s) M_i(|Δω|, T_i0) + s M_i(|Δω|, T_i1)   (kinetic; mu_s alike)
// This equals friction at the linearly moving temperature to second order, ½ ∂²M/∂T² ΔT² s(1−s)
// with ΔT the ring's change over one step (< 1 K on the shipped scenarios); it is continuous in
// time, so the torque has no step at the slow-step boundaries. Energy is unaffected: the heat
// channels are this same M_i |Δω|, integrated alongside the motion.
// The stick-time growth law (saturating, Δ_s and τ_s) is an estimate after Paper A's review
// (static friction grows with time at rest, Gao et al.); defaults in StickTimeFriction.

#include <Eigen/Dense>
#include <memory>

#include "clutch/wet_clutch.hpp"
#include "dynamics/contact_law.hpp"
#include "components/drive_cycle.hpp"
#include "components/clutch_faults.hpp"

namespace shudder::components {

struct StickTimeFriction {
  bool enabled = false;
  double max_increase = 0.15;    // Δ_s: fractional rise of mu_s after a long stick (estimate)
  double time_constant_s = 1.0;  // τ_s (estimate)
};

/// The inputs a run holds between slow steps: an operating point of the contact.
struct ClutchHeldInputs {
  Eigen::VectorXd ring_temp_C;     // (n_r) interface temperature of each ring
  PiecewiseLinear normal_force_N;  // clamp force over time
};

/// A run's state of one clutch contact: its held inputs and the cache derived from them.
/// Setting an input drops the cache.
class ClutchContext {
 public:
  explicit ClutchContext(ClutchHeldInputs held) : held_(std::move(held)) {}

  /// Holds every ring at `ring_temp_C` (no ramp).
  void set_ring_temperatures(const Eigen::VectorXd& ring_temp_C);
  /// Friction moves linearly in time from its value at `start_C` (time t0_s) to its value at
  /// `end_C` (t1_s > t0_s); before t0 and after t1 the nearer end holds. held().ring_temp_C is
  /// `start_C`. A ramp that starts where the previous one ended reuses its frozen friction.
  void set_ring_temperature_ramp(const Eigen::VectorXd& start_C, const Eigen::VectorXd& end_C, double t0_s,
                                 double t1_s);
  /// Replaces the clamp force schedule (an FMU's input between communication steps).
  void set_normal_force(PiecewiseLinear normal_force_N);
  const ClutchHeldInputs& held() const { return held_; }

 private:
  friend class ClutchContact;
  ClutchHeldInputs held_;
  // Ring torques at the last (|Δω|, t) asked: the integrator asks for the torque and then the
  // channel heats at the same arguments. Frozen friction is rebuilt with new temperatures or
  // when the friction load moved by more than 1e-4 relative (a force ramp; mu changes by
  // < 1e-6 over such a step).
  clutch::FrozenFriction frozen_;
  bool frozen_valid_ = false;
  double cached_slip_ = -1.0, cached_t_ = 0.0, cached_force_ = 0.0;
  Eigen::VectorXd ring_torque_;  // (n_r) per interface at the cached arguments
  // The ramp's far end (set_ring_temperature_ramp): temperatures, times, frozen friction there.
  bool ramp_ = false;
  Eigen::VectorXd ring_temp_end_C_;
  double ramp_t0_s_ = 0.0, ramp_t1_s_ = 0.0;
  clutch::FrozenFriction frozen_end_;
  bool frozen_end_valid_ = false;
  Eigen::VectorXd ring_torque_end_;  // (n_r) at the far end, cached arguments
  // Σ r_i A_i mu_s,i at the hold's two ends and at static_load_N_: the static capacity is asked
  // at every sample and event check, its sums change only with the temperatures or the load.
  mutable bool static_valid_ = false;
  mutable double static_load_N_ = 0.0, static_sum_start_ = 0.0, static_sum_end_ = 0.0;
  /// Weight s of the far end at time t (0 without a ramp).
  double ramp_weight(double t_s) const;
};

/// The contact's model: every evaluation reads the held inputs from a context.
class ClutchContact {
 public:
  ClutchContact(const clutch::WetClutch& clutch, BearingDrag drag, StickTimeFriction stick_time)
      : clutch_(&clutch), drag_(drag), stick_(stick_time) {}

  /// Held inputs with every ring at the clutch's start temperature.
  ClutchHeldInputs start_inputs(PiecewiseLinear normal_force_N) const;

  // At the context's held clamp force F(t):
  double kinetic_torque_Nm(ClutchContext& c, double abs_slip_rad_s, double t_s) const;
  double static_capacity_Nm(const ClutchContext& c, double t_s, double stick_time_s) const;
  double kinetic_torque_slope_Nms(ClutchContext& c, double abs_slip_rad_s, double t_s) const;
  int heat_channels() const { return clutch_->thermal().radial_cells(); }
  void channel_heat_W(ClutchContext& c, double abs_slip_rad_s, double t_s, double* out) const;
  double drag_torque_Nm(const ClutchContext& c, double t_s) const;
  // At a clamp force given by the caller (a force that is a state of the run, e.g. an actuator's
  // pressure integrated with the motion); the ring temperatures still come from the context.
  double kinetic_torque_at_force_Nm(ClutchContext& c, double abs_slip_rad_s, double t_s, double force_N) const;
  double static_capacity_at_force_Nm(const ClutchContext& c, double t_s, double stick_time_s, double force_N) const;
  double kinetic_torque_slope_at_force_Nms(ClutchContext& c, double abs_slip_rad_s, double t_s, double force_N) const;
  void channel_heat_at_force_W(ClutchContext& c, double abs_slip_rad_s, double t_s, double force_N, double* out) const;
  double drag_torque_at_force_Nm(double force_N) const;

 private:
  void update(ClutchContext& c, double abs_slip_rad_s, double t_s, double force_N) const;
  const clutch::WetClutch* clutch_;
  BearingDrag drag_;
  StickTimeFriction stick_;
};

/// A ClutchContact bound to a run's context (shared with the run, which updates it between
/// slow steps): the law the torsional network's contact calls with (|Δω|, t).
class ClutchContactLaw final : public dynamics::ContactLaw {
 public:
  ClutchContactLaw(ClutchContact model, std::shared_ptr<ClutchContext> context)
      : model_(model), context_(std::move(context)) {}

  double kinetic_torque_Nm(double abs_slip_rad_s, double t_s, const double* /*z*/) const override {
    return model_.kinetic_torque_Nm(*context_, abs_slip_rad_s, t_s);
  }
  double static_capacity_Nm(double t_s, double stick_time_s, const double* /*z*/) const override {
    return model_.static_capacity_Nm(*context_, t_s, stick_time_s);
  }
  double kinetic_torque_slope_Nms(double abs_slip_rad_s, double t_s, const double* /*z*/) const override {
    return model_.kinetic_torque_slope_Nms(*context_, abs_slip_rad_s, t_s);
  }
  int heat_channels() const override { return model_.heat_channels(); }
  void channel_heat_W(double abs_slip_rad_s, double t_s, const double* /*z*/, double* out) const override {
    model_.channel_heat_W(*context_, abs_slip_rad_s, t_s, out);
  }
  double drag_torque_Nm(double t_s) const { return model_.drag_torque_Nm(*context_, t_s); }

 private:
  ClutchContact model_;
  std::shared_ptr<ClutchContext> context_;
};

}  // namespace shudder::components
