#pragma once
// The engine's torque at its crankshaft from a throttle map, with closed-throttle losses and an
// idle governor (the driveline's engine when a scenario gives `throttle` instead of a raw
// `engine_torque_Nm` schedule):
//
//   T(ω, u) = T_comb − T_loss,
//   T_comb  = clamp(u T_full(n) + K_gov max(ω_idle − ω, 0), 0, T_full(n))   combustion torque
//   T_loss  = (T_loss,idle + (T_loss,max − T_loss,idle) n / n_max) tanh(ω / 10 rad/s)   friction and pumping
//
// u the throttle (0–1), n = ω in rpm, T_full the full-load curve (piecewise linear over n, zero
// at and below the stall speed: below it the engine cannot fire), K_gov the idle governor's
// proportional gain (it opens the throttle as far as full load allows when the speed sags below
// idle). The tanh lets the losses pass through standstill continuously.
// Stall: the speed falling below the stall speed while the map drives the engine (the run
// records when). The torque–speed slope dT/dω (N m s/rad) at an operating point enters the
// driveline's modes as a damper −dT/dω on the engine (docs/physics.md §6: a falling torque with speed
// damps, a rising one feeds oscillations).
//
// Defaults are ESTIMATES for a 2-litre petrol engine of the thesis' era (VW 2.0 8v class: public
// figures ~170 N m at 2400 rpm, 85 kW at 5200 rpm); losses of 15–35 N m from the usual friction
// mean effective pressure of 1–2 bar over 2 l (Heywood, Internal Combustion Engine
// Fundamentals, 1988, ch. 13: fmep ≈ 1–2.5 bar over the speed range).

#include "components/drive_cycle.hpp"

namespace shudder::components {

struct EngineParams {
  PiecewiseLinear full_load_torque_Nm{{0.0, 400.0, 1000.0, 2400.0, 4000.0, 5200.0, 6200.0},
                                      {0.0, 0.0, 130.0, 170.0, 160.0, 150.0, 120.0}};  // over rpm
  double idle_speed_rpm = 800.0;
  double stall_speed_rpm = 400.0;
  double idle_governor_gain_Nms_per_rad = 3.0;  // estimate: ~50 rpm droop at idle losses
  double loss_torque_idle_Nm = 15.0;
  double loss_torque_max_Nm = 35.0;  // at max_speed_rpm
  double max_speed_rpm = 6200.0;
};

class Engine {
 public:
  /// Throws std::invalid_argument for a negative full-load torque, idle at or below stall,
  /// or non-positive gains, losses or speeds.
  explicit Engine(const EngineParams& p);
  double torque_Nm(double omega_rad_s, double throttle) const;
  /// dT/dω by central difference (N m s/rad).
  double torque_speed_slope_Nms_per_rad(double omega_rad_s, double throttle) const;
  double stall_speed_rad_s() const;
  const EngineParams& params() const { return p_; }

 private:
  EngineParams p_;
};

}  // namespace shudder::components
