#pragma once
// Stability of steady sliding on the Limited Slip Clutch Test Rig (analysis/stability.hpp on
// the LsctrRig network, docs/physics.md §6):
//
//   drive J_d ─┤clutch, slope s├─ housing J_h ─ bar k_bar, c_bar ─ ground
//     ▲ PI loop: spring K_i, damper K_p to ground
//
//   J_d δθ̈_d + (K_p + s) δθ̇_d + K_i δθ_d − s δθ̇_h = 0
//   J_h δθ̈_h + (c_bar + s) δθ̇_h + k_bar δθ_h − s δθ̇_d = 0
//
// with s = dM/d|Δω| of the clutch law (n F r² dmu/dv plus the viscous shear's slope) at the
// steady slip, the clamp force and UNIFORM ring temperatures (the interface temperature of the
// operating point, held: the isothermal slope). The drive loop (~20 Hz) and the housing on the
// bar (100–500 Hz) are far apart, so the clutch-side mode is nearly that of the housing alone,
// σ ≈ −(c_bar + s)/(2 J_h); its coupling to the drive shifts the damping by
// −s² (K_p + s)/|Z_d(iω_h)|², Z_d(λ) = J_d λ + K_p + s + K_i/λ (~1e-4 N m s/rad on the rig).
//
// The linearisation assumes the motor holds the speed: a steady clutch torque above the motor's
// limit (no steady sliding) is an error for one point and NaN in a map.

#include <Eigen/Dense>
#include <vector>

#include "analysis/stability.hpp"
#include "clutch/wet_clutch.hpp"
#include "rig_models/lsctr_rig.hpp"

namespace shudder::studies {

using analysis::StabilityPoint;

/// Linearises `rig` about steady sliding at `slip_rpm` (0: clutch stuck) with the clutch at the
/// operating point `clutch_inputs` (ring temperatures, clamp force), the laws evaluated at `t_s`.
/// Throws std::invalid_argument if the steady clutch torque exceeds the motor's torque limit.
StabilityPoint rig_stability(const rig_models::LsctrRig& rig, const components::ClutchHeldInputs& clutch_inputs,
                             double slip_rpm, double t_s = 0.0);

/// Builds the rig with a constant-force, constant-speed cycle and linearises at `slip_rpm` with
/// every ring of the clutch at `interface_temp_C`. Throws std::invalid_argument for a force
/// <= 0, non-finite inputs, invalid rig parameters or a saturated motor.
StabilityPoint rig_stability(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                             double slip_rpm, double interface_temp_C);

struct StabilityMap {
  double force_N = 0.0;
  std::vector<double> speeds_rpm;  // (n_s) slip speeds
  std::vector<double> temps_C;     // (n_T) interface temperatures
  Eigen::MatrixXd margin_per_s;    // (n_s x n_T) largest real part; NaN: motor saturated
  Eigen::MatrixXd frequency_Hz;    // (n_s x n_T) frequency of that mode (0 if not oscillatory)
  // (n_s x n_T) the oscillatory mode with the largest real part (on the rig: the clutch-side
  // mode at the bar's frequency, while the drive loop's slow real mode may lead the margin).
  Eigen::MatrixXd oscillatory_margin_per_s;
  Eigen::MatrixXd oscillatory_frequency_Hz;
};

/// Margin and frequency over slip speed x interface temperature at one force, on one rig (the
/// network does not depend on the operating point; only the law's temperatures and the slip
/// do). Same input errors as rig_stability.
StabilityMap stability_map(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                           const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C);

/// Smallest bar damping ratio ζ that makes the operating point stable (margin <= 0), by
/// bisection on the margin over ζ in [0, max_ratio] to 1e-12 absolute: the bar stiffness is
/// held (that of `params`), c_bar = 2 ζ √(k_bar J_h); one rig, only its bar damper changes. Returns 0 if the point is
/// stable without bar damping and +infinity if it is still unstable at max_ratio (e.g. the drive loop itself is
/// unstable). Decoupled estimate: ζ_crit ≈ −s / (2 √(k_bar J_h)).
double critical_bar_damping_ratio(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                                  double slip_rpm, double interface_temp_C, double max_ratio = 1.0);

struct CriticalBar {
  double frequency_Hz = 0.0;          // clutch-side natural frequency of the bar at the onset
  double stiffness_Nm_per_rad = 0.0;  // bar stiffness at the onset
};

/// Bar frequency (and stiffness) at which the operating point turns stable or unstable, at the
/// damping ratio of `params`: bisection on the margin over the bar frequency in
/// [lo_Hz, hi_Hz] (default 20–5000 Hz: the rig's bars are 175 and 378 Hz) to 1e-10 relative.
/// With c_bar = 2 ζ √(k J_h) the housing mode's σ ≈ −ζ ω_bar − s/(2 J_h) falls with the bar
/// frequency, so stiffer bars are the stable side: onset at ω ≈ −s/(2 ζ J_h). Returns NaN in
/// both fields if the margin has the same sign at both ends of the bracket. Each step builds
/// the rig anew (its bar stiffness comes from the modal tuning); the clutch's operating point
/// is shared by all of them.
CriticalBar critical_bar(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                         double slip_rpm, double interface_temp_C, double lo_Hz = 20.0, double hi_Hz = 5000.0);

}  // namespace shudder::studies
