#pragma once
// A shaft with backlash: a spring–damper that acts only once the free play is taken up, as
// Modelica.Mechanics.Rotational.Components.ElastoBacklash. A dynamics::ForceLaw between nodes a
// and b (ratio 1) whose one state is the relative twist z = θ_a − θ_b (rad), starting centred in
// the gap.
//
//   dz/dt = ω_a − ω_b
//   d     = z − b/2 (z > b/2),  z + b/2 (z < −b/2),  0 inside the gap     b: total lash, rad
//   T     = max(k d + c dz/dt, 0) for d > 0,  min(k d + c dz/dt, 0) for d < 0,  0 in the gap
// (the damper cannot pull the flanks together: T never changes the sign of d, as Modelica's
// ElastoBacklash). T acts −T on a, +T on b.
// Energy: E = ½ k d², dE/dt = k d dz/dt, so P_diss = T dz/dt − k d dz/dt: c (dz/dt)² in contact,
// −k d dz/dt >= 0 where the clamp applies (there k d + c dz/dt changed sign, so dz/dt opposes d).
// In the gap the two sides fly freely: relative speed constant without other torques, the gap
// crossed in b / |Δω|.

#include "dynamics/network.hpp"

namespace shudder::components {

class LashShaft final : public dynamics::ForceLaw {
 public:
  /// k > 0 (N m/rad), c >= 0 (N m s/rad), lash > 0 (rad); std::invalid_argument otherwise.
  LashShaft(double stiffness_Nm_per_rad, double damping_Nms_per_rad, double lash_rad);
  int states() const override { return 1; }
  Output evaluate(double omega_a, double omega_b, const double* z, double* dzdt) const override;
  double stored_energy_J(const double* z) const override;
  /// Engaged stiffness: the modes of a shaft whose flanks are in contact.
  double modal_stiffness_Nm_per_rad() const override { return k_; }
  double deflection_rad(double twist_rad) const;

 private:
  double k_, c_, half_gap_;
};

}  // namespace shudder::components
