#pragma once
// Tiny friction laws for the dynamics tests: just enough of a ContactLaw to have closed forms.
#include <cstddef>
#include <utility>
#include <vector>

#include "dynamics/contact_law.hpp"

namespace shudder::dynamics::testing {

/// Coulomb contact: constant kinetic torque T_k while slipping, static capacity T_s when stuck.
///   T_k = n r F mu_k,  T_s = n r F mu_s   (n friction faces, effective radius r, clamp force F)
class CoulombLaw : public ContactLaw {
 public:
  CoulombLaw(double kinetic_Nm, double static_Nm) : kinetic_(kinetic_Nm), static_(static_Nm) {}
  static CoulombLaw from_clamp(double faces, double radius_m, double force_N, double mu_static, double mu_kinetic) {
    return {faces * radius_m * force_N * mu_kinetic, faces * radius_m * force_N * mu_static};
  }
  double kinetic_torque_Nm(double, double, const double*) const override { return kinetic_; }
  double static_capacity_Nm(double, double, const double*) const override { return static_; }
  double kinetic_torque_slope_Nms(double, double, const double*) const override { return 0.0; }

 private:
  double kinetic_, static_;
};

/// Coulomb contact whose static capacity grows with the time stuck: T_s(τ) = T_s0 + β τ.
class AgeingCoulombLaw : public ContactLaw {
 public:
  AgeingCoulombLaw(double kinetic_Nm, double static_Nm, double growth_Nm_per_s)
      : kinetic_(kinetic_Nm), static_(static_Nm), growth_(growth_Nm_per_s) {}
  double kinetic_torque_Nm(double, double, const double*) const override { return kinetic_; }
  double static_capacity_Nm(double, double stick_time_s, const double*) const override {
    return static_ + growth_ * stick_time_s;
  }
  double kinetic_torque_slope_Nms(double, double, const double*) const override { return 0.0; }

 private:
  double kinetic_, static_, growth_;
};

/// Viscous-like contact: T = T_0 + c |Δω| while slipping, so dT/d|Δω| = c; static capacity T_s.
/// Optionally splits the whole dissipated power T |Δω| into channels by fixed fractions.
class LinearSlopeLaw : public ContactLaw {
 public:
  LinearSlopeLaw(double offset_Nm, double slope_Nms, double static_Nm, std::vector<double> channel_fractions = {})
      : offset_(offset_Nm), slope_(slope_Nms), static_(static_Nm), fractions_(std::move(channel_fractions)) {}
  double kinetic_torque_Nm(double w, double, const double*) const override { return offset_ + slope_ * w; }
  double static_capacity_Nm(double, double, const double*) const override { return static_; }
  double kinetic_torque_slope_Nms(double, double, const double*) const override { return slope_; }
  int heat_channels() const override { return static_cast<int>(fractions_.size()); }
  void channel_heat_W(double w, double t, const double* z, double* out) const override {
    for (std::size_t i = 0; i < fractions_.size(); ++i) out[i] = fractions_[i] * kinetic_torque_Nm(w, t, z) * w;
  }

 private:
  double offset_, slope_, static_;
  std::vector<double> fractions_;
};

}  // namespace shudder::dynamics::testing
