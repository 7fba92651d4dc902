#include "components/plain_friction.hpp"

#include <algorithm>
#include <stdexcept>

#include "core/units.hpp"

namespace shudder::components {

PlainFrictionLaw::PlainFrictionLaw(PlainFrictionParams p, Signal force_signal)
    : p_(std::move(p)), force_(std::move(force_signal)) {
  if (p_.mu.empty() || p_.mu.size() != p_.slip_rpm.size())
    throw std::invalid_argument("a friction table needs one mu per slip speed and at least one point");
  for (std::size_t i = 0; i < p_.mu.size(); ++i) {
    if (!(p_.mu[i] > 0)) throw std::invalid_argument("every mu must be > 0");
    if (!(p_.slip_rpm[i] >= 0) || (i > 0 && !(p_.slip_rpm[i] > p_.slip_rpm[i - 1])))
      throw std::invalid_argument("slip_rpm must start at >= 0 and strictly increase");
  }
  if (!(p_.peak_ratio >= 1)) throw std::invalid_argument("peak_ratio must be >= 1");
  if (!(p_.geometry_factor_m > 0)) throw std::invalid_argument("the geometry factor must be > 0");
  if (!(p_.max_force_N >= 0)) throw std::invalid_argument("max_force_N must be >= 0");
}

double PlainFrictionLaw::normal_force_N(double t) const { return p_.max_force_N * std::max(force_(t), 0.0); }

double PlainFrictionLaw::mu(double abs_slip_rad_s) const {
  const double n = units::rad_s_to_rpm(abs_slip_rad_s);
  const auto& x = p_.slip_rpm;
  if (n <= x.front()) return p_.mu.front();
  if (n >= x.back()) return p_.mu.back();
  const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), n) - x.begin());
  const double w = (n - x[hi - 1]) / (x[hi] - x[hi - 1]);
  return p_.mu[hi - 1] + w * (p_.mu[hi] - p_.mu[hi - 1]);
}

double PlainFrictionLaw::kinetic_torque_Nm(double abs_slip, double t, const double*) const {
  return mu(abs_slip) * p_.geometry_factor_m * normal_force_N(t);
}

double PlainFrictionLaw::static_capacity_Nm(double t, double, const double*) const {
  return p_.peak_ratio * p_.mu.front() * p_.geometry_factor_m * normal_force_N(t);
}

double PlainFrictionLaw::kinetic_torque_slope_Nms(double abs_slip, double t, const double*) const {
  const double n = units::rad_s_to_rpm(abs_slip);
  const auto& x = p_.slip_rpm;
  if (x.size() < 2 || n < x.front() || n >= x.back()) return 0.0;
  const auto hi = static_cast<std::size_t>(std::upper_bound(x.begin(), x.end(), n) - x.begin());
  const double dmu_drpm = (p_.mu[hi] - p_.mu[hi - 1]) / (x[hi] - x[hi - 1]);
  return dmu_drpm * units::rad_s_to_rpm(1.0) * p_.geometry_factor_m * normal_force_N(t);
}

}  // namespace shudder::components
