#pragma once
// The wet clutch in the fixed-step real-time mode (docs/realtime.md): the friction torque per
// ring at the latched ring temperatures, the heat the fast steps put into each ring, and the
// slow thermal update handed to a ThermalTask every `thermal_step_s`.
//
//   M_k(|Δω|, F) = n Σ_i M_i + M_drag,  M_i = r_i p mu_i(r_i|Δω|, T_i, F) A_i (+ viscous shear)
//   heat of ring i over a fast step: E_i = ∫ M_i |Δω| dt (one interface; the caller integrates)
//
// The equations are the clutch's own (clutch::WetClutch): the friction frozen at the latched
// temperatures while the friction load is within 1e-4 of the load it was frozen at (as
// components::ClutchContact does), the direct evaluation otherwise. Both read buffers sized at
// construction, so a step allocates nothing.

#include <Eigen/Dense>

#include "clutch/wet_clutch.hpp"
#include "rig_models/prescribed_slip.hpp"
#include "rig_models/thermal_task.hpp"

namespace shudder::rig_models {

struct RealtimeSettings {
  double step_s = 1e-4;          // the fixed step
  double thermal_step_s = 0.01;  // slow step, a whole multiple of step_s
};

/// thermal_step_s / step_s as an integer; throws std::invalid_argument unless both are > 0,
/// finite and the ratio is a whole number (to 1e-9 relative) of at least 1.
long steps_per_thermal_step(const RealtimeSettings& settings);

class RealtimeClutch {
 public:
  /// `clutch` must outlive this object; `force_N` is the clamp force at the start.
  RealtimeClutch(const clutch::WetClutch& clutch, const components::BearingDrag& drag, const RealtimeSettings& settings,
                 double force_N);

  /// Kinetic torque magnitude of all interfaces plus bearing drag at |Δω| and F, N m; the
  /// per-ring torques of one interface are left in ring_torque_Nm().
  double kinetic_torque_Nm(double abs_slip_rad_s, double force_N);
  const Eigen::VectorXd& ring_torque_Nm() const { return ring_torque_; }

  /// Closes one fixed step ending at `t_end_s`: the heat per ring of one interface over it (J)
  /// and the relative rotation Δθ over it (rad). Every steps_per_thermal_step() steps the
  /// window goes to the thermal task (and the previous window's result is latched).
  /// `fraction` (0, 1] is the step's length in fixed steps: below 1 for the shorter steps a
  /// co-simulation master may ask for (docs/fmu.md). A window then closes once the steps in it
  /// add up to steps_per_thermal_step() within kWindowSlack (the caller must not step across
  /// a window's end: window_steps_left()); the thermal task is given the window's true length.
  /// Whole steps (fraction 1, the default) add exact integers and behave as before.
  void end_step(const Eigen::VectorXd& ring_heat_J, double slip_angle_rad, double t_end_s, double force_N,
                double fraction = 1.0);
  /// Fixed steps left in the open thermal window (a whole number unless shorter steps were taken).
  double window_steps_left() const { return static_cast<double>(steps_per_window_) - steps_in_window_; }
  /// How short of full (in fixed steps) a window may be and still close: the round-off of
  /// adding up fractions of a step (e.g. 0.23 + 0.77), far below any step a master asks for.
  static constexpr double kWindowSlack = 1e-9;

  const ThermalOutputs& thermal() const { return task_.latest(); }
  /// Handovers that found the thermal job unfinished and waited for it (0 in a paced loop).
  long thermal_waits() const { return task_.waited_collects(); }
  /// Waits for an outstanding thermal job and latches it (the end of a run).
  void finish() { task_.collect(); }
  /// The thermal state (energy account); call finish() first.
  const clutch::ThermalState& thermal_state() const { return task_.state(); }
  /// Back to the initial state (FMI reset).
  void reset(double force_N);

  const clutch::WetClutch& clutch() const { return clutch_; }
  const RealtimeSettings& settings() const { return cfg_; }

 private:
  const clutch::WetClutch& clutch_;
  components::BearingDrag drag_;
  RealtimeSettings cfg_;
  long steps_per_window_;
  ThermalTask task_;
  Eigen::VectorXd ring_torque_, mu_;  // (n_r) scratch
  Eigen::VectorXd window_heat_J_;     // (n_r) heat of the open window
  double window_angle_rad_ = 0.0;
  double window_start_s_ = 0.0;
  double steps_in_window_ = 0.0;  // fixed steps in the open window (whole unless shorter steps)
};

}  // namespace shudder::rig_models
