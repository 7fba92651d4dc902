#pragma once
// The clutch (or coupling pack) as a real-time element with prescribed slip: the FMU's model
// (docs/fmu.md) and `shudder run --fixed-step` for a prescribed-slip scenario (docs/realtime.md).
//
// Inputs per fixed step h, held over the step (zero-order hold, as a co-simulation master gives
// them): slip speed Δω (rad/s) and clamp force F (N). With the ring temperatures T_i latched
// from the thermal task (rig_models/realtime_clutch.hpp):
//
//   M      = sign(Δω) · (n Σ_i M_i(|Δω|, F, T_i) + M_drag)     torque the torque cell reads, N m
//   E_i   += M_i |Δω| h                                         heat of ring i (one interface), J
//
// There is no mechanical state: the torque is algebraic in the inputs, the only integration is
// the rectangle rule of the ring heat (exact for inputs held over the step).

#include "rig_models/realtime_clutch.hpp"

namespace shudder::rig_models {

class RealtimeCoupling {
 public:
  /// `clutch` must outlive this object; `force_N` is the clamp force at t = 0 (the first
  /// frozen friction). Throws std::invalid_argument for invalid settings.
  RealtimeCoupling(const clutch::WetClutch& clutch, const components::BearingDrag& drag,
                   const RealtimeSettings& settings, double force_N);

  /// Advances one fixed step with Δω (rad/s) and F (N) held over it. Allocates nothing.
  /// `fraction` (0, 1] shortens the step to fraction × the fixed step (a co-simulation master's
  /// step that is not a whole multiple, docs/fmu.md); the heat is integrated over that length.
  /// A caller taking shorter steps must not cross a thermal window's end within one step
  /// (clutch().window_steps_left()).
  void step(double slip_rad_s, double force_N, double fraction = 1.0);

  double time_s() const { return t_s_; }
  /// Over the last step: torque with bearing drag (the torque cell), without it (the clutch),
  /// and the friction heat power of all interfaces.
  double torque_Nm() const { return torque_Nm_; }
  double clutch_torque_Nm() const { return clutch_torque_Nm_; }
  double heat_W() const { return heat_W_; }
  const ThermalOutputs& thermal() const { return clutch_.thermal(); }
  RealtimeClutch& clutch() { return clutch_; }
  void reset(double force_N);

 private:
  RealtimeClutch clutch_;
  components::BearingDrag drag_;
  Eigen::VectorXd heat_J_;  // (n_r) scratch
  double steps_ = 0.0;      // fixed steps taken (an exact integer while all steps are whole)
  double t_s_ = 0.0, torque_Nm_ = 0.0, clutch_torque_Nm_ = 0.0, heat_W_ = 0.0;
};

}  // namespace shudder::rig_models
