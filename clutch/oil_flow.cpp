#include "clutch/oil_flow.hpp"

#include <algorithm>
#include <cmath>

namespace shudder::clutch {

double OilFlowLaw::fraction(double slip_rad_s, double mean_temp_C) const {
  const double t_K = std::max(mean_temp_C + 273.15, 1.0);
  const double f = a * std::pow(std::abs(slip_rad_s) + 1.0, b) + c * std::pow(t_K, d) + e;
  return std::max(f, 0.0);
}

}  // namespace shudder::clutch
