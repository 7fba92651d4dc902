#pragma once
// A transmission fluid as the clutch model sees it: its boundary-friction law, its static
// (breakaway) friction and its kinematic viscosity.
//
// Static friction: mu_s(T, F) = breakaway_ratio * mu_k(v_min, T, F), where v_min is the law's
// lowest tabulated speed. The Mäki model has no static term (docs/physics.md §1); the ratio is a
// per-fluid datum (estimate unless the fluid file cites a measurement). Growth with stick time
// is the `stick_time_static_friction` effect, applied by the dynamics, not here.
//
// Viscosity: Walther / ASTM D341, log10(log10(nu + 0.7)) = A - B*log10(T_K), with A and B
// through (40 °C, nu40) and (100 °C, nu100); nu in cSt (mm²/s).

#include <memory>
#include <string>

#include "clutch/friction_law.hpp"

namespace shudder::clutch {

class WaltherViscosity {
 public:
  /// Throws std::invalid_argument unless nu40 > nu100 > 0.
  WaltherViscosity(double nu40_cSt, double nu100_cSt);
  double kinematic_cSt(double temp_C) const;
  double a() const { return a_; }
  double b() const { return b_; }

 private:
  double a_ = 0.0;
  double b_ = 0.0;
};

struct Fluid {
  std::string name;
  std::shared_ptr<const FrictionLaw> friction;  // immutable, shared by every clutch using it
  double breakaway_ratio = 1.0;                 // mu_s / mu_k(v_min); >= 1 for stick-slip
  double nu40_cSt = 35.0;                       // Paper E Table 1, fluid C
  double nu100_cSt = 6.7;                       // Paper E Table 1, fluid C
  double density_kg_m3 = 868.0;                 // Paper G Table 1 (at 40 °C)
  // The friction radius the law was fitted at from torque (clutch/friction_radius.hpp), mm, and
  // its convention ("uniform_pressure", "uniform_wear"); 0 and "": the law's mu is a local
  // coefficient (Paper G's matrix) and no model converts it.
  double friction_radius_mm = 0.0;
  std::string friction_radius_convention;

  double mu_static(double temp_C, double load_N) const {
    return breakaway_ratio * friction->mu(friction->min_speed_mm_s(), temp_C, load_N);
  }
};

}  // namespace shudder::clutch
