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
// Sliding only: the fixed-step rig has no stick/slip event handling (the adaptive run locates
// those events to 1e-10 s). A step across Δω = 0 throws std::runtime_error naming the time.

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

  /// Builds the rig (bar stiffness, speed-loop gains) and starts in steady sliding at the
  /// cycle's first speed, as run_rig does. Throws std::invalid_argument for invalid inputs,
  /// including a start at rest (not supported in the fixed-step mode).
  RealtimeRig(const RigParams& params, const clutch::WetClutch& clutch, const DriveCycle& cycle,
              const RealtimeSettings& settings);

  /// One RK4 step. Allocates nothing.
  void step();

  double time_s() const { return t_s_; }
  const State& state() const { return x_; }
  long steps() const { return steps_; }
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

  LsctrRig rig_;
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
