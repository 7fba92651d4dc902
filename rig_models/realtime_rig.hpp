#pragma once
// The LSCTR rig (rig_models/lsctr_rig.hpp) in the fixed-step real-time mode (docs/realtime.md):
// the same network and parameters, integrated with classical RK4 at a fixed step h.
//
//   J_d ω̇_d = T_m + T_ripple − sign(Δω) M_k(|Δω|, F(t))        Δω = ω_d − ω_h
//   J_h ω̇_h = sign(Δω) M_k − (k_bar θ_h + c_bar ω_h)
//   T_m = clamp(K_p e + K_i I, ±T_max),  e = ω_ref(t) − ω_d,
//   İ = e + (T_m − K_p e − K_i I)/(0.9 K_p)                     (dynamics/network.hpp's motor)
//   Ė_i = M_i(|Δω|) |Δω|   ring heat of one interface, integrated with the same RK4 weights
//
// Why RK4 at h = 0.1 ms: the fastest mode is the housing on the torsion bar (100–500 Hz with
// the clutch slipping, rig_models/rig_stability.hpp); at 378 Hz, ωh = 0.24 (500 Hz: 0.31), well
// inside RK4's stability region (|λh| < 2.8 on both axes). Its numerical damping per step is
// (ωh)^6/144 = 1.2e-6, a decay rate of 0.012 1/s against the bar's physical ζω = 24 1/s, and
// its phase error (ωh)^5/120 = 6e-6 rad per step. The friction slope adds s/J_h ≈ 1e3 1/s
// (|λh| ≈ 0.1). Nothing is stiff at this step, so an explicit method of high order is cheaper
// and more accurate than a semi-implicit one (first order in phase).
//
// Stick and slip: while stuck the two inertias move as one, (J_d + J_h) ω̇ = T_m + T_r − T_bar,
// and the clutch carries λ = T_m + T_r − J_d ω̇ until |λ| exceeds the static capacity
// (rig_models::ClutchContact, stick-time growth included): breakaway in the direction of λ.
// A step in which Δω reaches zero ends with both sides merged at their common momentum speed
// if the clutch can hold them (the kinetic energy lost counts as friction work), otherwise the
// slip reverses. Events are located to the step h (the adaptive run locates them to 1e-10 s):
// an O(h) error in their times.

#include <Eigen/Dense>

#include "rig_models/lsctr_rig.hpp"
#include "rig_models/motor_ripple.hpp"
#include "rig_models/realtime_clutch.hpp"

namespace shudder::rig_models {

class RealtimeRig {
 public:
  // θ_d, θ_h, ω_d, ω_h, I, then the energy account's integrals (J): work of the motor and its
  // ripple, friction work of the clutch (drag included), the bar damper's loss.
  using State = Eigen::Matrix<double, 8, 1>;
  static constexpr int kThetaD = 0, kThetaH = 1, kOmegaD = 2, kOmegaH = 3, kIntegral = 4, kSourceWork = 5,
                       kFrictionWork = 6, kDamperLoss = 7;

  /// Builds the rig (bar stiffness, speed-loop gains) and starts as run_rig does: in steady
  /// sliding at the cycle's first speed, or at rest and stuck (`start_at_rest`, or a first
  /// speed of 0). Throws std::invalid_argument for invalid inputs.
  RealtimeRig(const RigParams& params, const clutch::WetClutch& clutch, const DriveCycle& cycle,
              const RealtimeSettings& settings);

  /// One RK4 step. Allocates nothing.
  void step();

  double time_s() const { return t_s_; }
  const State& state() const { return x_; }
  long steps() const { return steps_; }
  bool stuck() const { return stuck_; }
  long stick_events() const { return sticks_; }
  long breakaway_events() const { return breakaways_; }
  long reversal_events() const { return reversals_; }
  /// |source work − Δkinetic − Δelastic − friction work − damper loss| / |source work| (0 if
  /// no work was done): the mechanical energy balance of the integration.
  double energy_relative_error() const;
  double motor_torque_Nm() const { return motor_Nm_; }
  double clutch_torque_Nm() const { return clutch_Nm_; }  // transmitted drive → housing
  double bar_torque_Nm() const { return rig_.bar_stiffness_Nm_per_rad() * x_[kThetaH] + rig_.bar_damping_Nms_per_rad() * x_[kOmegaH]; }
  const ThermalOutputs& thermal() const { return clutch_.thermal(); }
  RealtimeClutch& clutch() { return clutch_; }
  const LsctrRig& rig() const { return rig_; }

 private:
  // dx/dt at (x, t); the per-ring heat power of one interface into `heat_W`.
  State derivative(const State& x, double t, Eigen::VectorXd& heat_W, double& motor_Nm, double& clutch_Nm);
  // Stick, breakaway or reversal at the end of a step (may change `next` and the mode).
  void update_modes(State& next, double t_end);
  double static_capacity_Nm(double t);

  LsctrRig rig_;
  ClutchContext context_;  // held ring temperatures and clamp force for the static capacity
  double capacity_temps_time_s_ = 0.0;
  bool stuck_ = false;
  double direction_ = 1.0;  // slip direction while Δω = 0 exactly (breakaway)
  double stick_start_s_ = 0.0;
  long sticks_ = 0, breakaways_ = 0, reversals_ = 0;
  DriveCycle cycle_;
  MotorRippleTorque ripple_;
  RealtimeClutch clutch_;
  double j_d_, j_h_, t_max_;
  double initial_energy_J_ = 0.0;  // kinetic + elastic at the start
  State x_, d1_;  // the state and its derivative at t_s_ (the next step's first stage)
  double t_s_ = 0.0, motor_Nm_ = 0.0, clutch_Nm_ = 0.0;
  long steps_ = 0;
  Eigen::VectorXd k1_, k2_, k3_, k4_, heat_J_;  // (n_r) stage heats and the step's heat
};

}  // namespace shudder::rig_models
