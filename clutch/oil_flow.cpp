#include "clutch/oil_flow.hpp"

#include <algorithm>
#include <cmath>

namespace shudder::clutch {

double OilFlowLaw::fraction(double slip_rad_s, double mean_temp_C) const {
  const double t_K = std::max(mean_temp_C + 273.15, 1.0);
  // A zero weight skips its pow (the calibrated default has a = c = 0): the same sum, since
  // 0 * pow(...) is an exact zero for the finite, positive bases here.
  const double speed_term = a == 0.0 ? 0.0 : a * std::pow(std::abs(slip_rad_s) + 1.0, b);
  const double temp_term = c == 0.0 ? 0.0 : c * std::pow(t_K, d);
  const double f = speed_term + temp_term + e;
  return std::max(f, 0.0);
}

}  // namespace shudder::clutch
