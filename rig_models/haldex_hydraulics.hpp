#pragma once
// The Haldex coupling's hydraulics: what clamps the disc pack (PHYSICS.md §8; thesis
// Introduction; public workshop manuals and patents, medium reliability).
//
// A cam on the rear side of the coupling strokes piston pumps whenever the front and rear axles
// turn at different speeds, so the pump delivers in proportion to the relative speed |Δω|; the
// pressure reaches its full value after about 90° of relative rotation. An electronically
// controlled throttle valve sets the pressure the pack gets (and spills above it); oil leaks
// back through the throttle, so the pressure decays once the axles turn together. A spring
// preloads the pack.
//
//   dp/dt = (p_relief / φ_full) |Δω| − p / τ_leak,        0 <= p <= p_valve(t) <= p_relief
//   F_clamp = F_preload + A_piston p
//
//   p_relief   relief pressure, 30 bar (public: "order 10–30 bar"; a Volvo variant 27.5 bar)
//   φ_full     π/2: full pressure after 90° of relative rotation (public)
//   τ_leak     0.5 s (estimate: the coupling lets go within about a second once the slip stops)
//   A_piston   from the public 59 N m/bar (17 bar ≈ 1000 N m): A = 59 N m/bar /
//              (n μ_nom r_eff · 1e5 Pa/bar) for the pack's n interfaces, nominal friction μ_nom
//              and mean radius r_eff — the area that makes the pack's torque per bar right
//   F_preload  the preload torque (public: up to ~80 N m; 50 N m here) over n μ_nom r_eff
//
// Multi-rate (DESIGN.md): the pressure changes over tens of milliseconds, like the disc
// temperatures, so it is advanced once per slow step with the step's relative rotation φ and
// held over the next. For a constant pumping rate over the step h the update is exact:
//   p(t+h) = p_ss + (p(t) − p_ss) e^(−h/τ_leak),  p_ss = (p_relief/φ_full)(φ/h) τ_leak,
// then clamped to [0, p_valve].

namespace shudder::rig_models {

struct HaldexHydraulicsParams {
  double relief_pressure_bar = 30.0;       // public figure, see header
  double full_pressure_rotation_rad = 1.5707963267948966;  // 90°, public
  double leak_time_constant_s = 0.5;       // estimate
  double torque_per_bar_Nm = 59.0;         // public: 17 bar ≈ 1000 N m
  double preload_torque_Nm = 50.0;         // public: up to ~80 N m
};

class HaldexHydraulics {
 public:
  /// `pack_torque_per_newton_m` = n μ_nom r_eff of the disc pack (N m per N of clamp force).
  /// Throws std::invalid_argument for non-positive or non-finite parameters.
  HaldexHydraulics(const HaldexHydraulicsParams& params, double pack_torque_per_newton_m);

  /// Pressure after a slow step of `step_s` in which the coupling turned by `rotation_rad`
  /// (>= 0, the integral of |Δω|), with the valve set to `valve_bar` (clamped to the relief).
  double step_pressure_bar(double pressure_bar, double rotation_rad, double step_s, double valve_bar) const;
  double clamp_force_N(double pressure_bar) const;
  double piston_area_m2() const { return area_m2_; }
  double preload_force_N() const { return preload_N_; }
  const HaldexHydraulicsParams& params() const { return p_; }

 private:
  HaldexHydraulicsParams p_;
  double area_m2_ = 0, preload_N_ = 0;
};

}  // namespace shudder::rig_models
