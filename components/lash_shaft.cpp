#include "components/lash_shaft.hpp"

#include <algorithm>
#include <stdexcept>

namespace shudder::components {

LashShaft::LashShaft(double k, double c, double lash) : k_(k), c_(c), half_gap_(0.5 * lash) {
  if (!(k > 0) || !(c >= 0) || !(lash > 0))
    throw std::invalid_argument("a shaft with lash needs stiffness > 0, damping >= 0 and lash > 0");
}

double LashShaft::deflection_rad(double z) const {
  if (z > half_gap_) return z - half_gap_;
  if (z < -half_gap_) return z + half_gap_;
  return 0.0;
}

dynamics::ForceLaw::Output LashShaft::evaluate(double omega_a, double omega_b, const double* z, double* dzdt) const {
  const double rate = omega_a - omega_b;
  dzdt[0] = rate;
  const double d = deflection_rad(z[0]);
  Output out;
  if (d == 0.0) return out;
  const double raw = k_ * d + c_ * rate;
  out.torque_Nm = d > 0 ? std::max(raw, 0.0) : std::min(raw, 0.0);
  out.dissipated_W = (out.torque_Nm - k_ * d) * rate;
  return out;
}

double LashShaft::stored_energy_J(const double* z) const {
  const double d = deflection_rad(z[0]);
  return 0.5 * k_ * d * d;
}

}  // namespace shudder::components
