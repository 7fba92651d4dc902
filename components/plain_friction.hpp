#pragma once
// A dry-style friction clutch or brake as other drivetrain tools describe it (Modelica's
// Rotational.Components.Clutch, Simscape's Disk Friction Clutch): a coefficient of friction, a
// geometry factor and a commanded normal force. No thermal model; heat is only counted.
//
//   F(t)        = F_max · max(u(t), 0)                  u: the normalised force signal (open at u <= 0)
//   slipping:   T_k = μ_k(|Δn|) · R · F(t)              Δn = |Δω| · 60/(2π) rpm
//   stuck:      |T| <= T_s = peak_ratio · μ_k(0) · R · F(t)
//   R           = geometry factor (m): n r_m for n friction interfaces at a mean radius r_m, or
//                 n · (2/3)(r_o³ − r_i³)/(r_o² − r_i²) for uniform pressure on an annulus
//   μ_k(Δn)     = constant, or linear in a table over slip speed (held beyond its ends)
//
// Units: F in N, R in m, T in N m, slip in rad/s (the table's abscissa in rpm, as engineers
// tabulate it). Source: the Coulomb law with a static peak, as in Modelica Standard Library 4,
// Modelica.Mechanics.Rotational.Components.Clutch (fn = fn_max · f_normalized, peak ≥ 1).

#include <vector>

#include "components/signal.hpp"
#include "dynamics/contact_law.hpp"

namespace shudder::components {

struct PlainFrictionParams {
  std::vector<double> slip_rpm;    // μ table abscissa, ascending from >= 0; one point: constant
  std::vector<double> mu;          // μ_k at those slips, each > 0
  double peak_ratio = 1.0;         // μ_s / μ_k(0), >= 1
  double geometry_factor_m = 0.0;  // R
  double max_force_N = 0.0;        // F_max
};

class PlainFrictionLaw final : public dynamics::ContactLaw {
 public:
  /// Throws std::invalid_argument for an empty or unsorted table, μ <= 0, peak_ratio < 1, R <= 0
  /// or F_max < 0.
  PlainFrictionLaw(PlainFrictionParams p, Signal force_signal);
  double kinetic_torque_Nm(double abs_slip_rad_s, double t_s, const double* z) const override;
  double static_capacity_Nm(double t_s, double stick_time_s, const double* z) const override;
  double kinetic_torque_slope_Nms(double abs_slip_rad_s, double t_s, const double* z) const override;
  double normal_force_N(double t_s) const;
  double mu(double abs_slip_rad_s) const;

 private:
  PlainFrictionParams p_;
  Signal force_;
};

}  // namespace shudder::components
