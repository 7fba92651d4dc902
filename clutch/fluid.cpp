#include "clutch/fluid.hpp"

#include <cmath>
#include <stdexcept>

namespace shudder::clutch {

namespace {
constexpr double kKelvin = 273.15;
double loglog(double nu_cSt) { return std::log10(std::log10(nu_cSt + 0.7)); }
}  // namespace

WaltherViscosity::WaltherViscosity(double nu40_cSt, double nu100_cSt) {
  if (!(nu100_cSt > 0.0) || !(nu40_cSt > nu100_cSt))
    throw std::invalid_argument("viscosity needs nu40 > nu100 > 0 (cSt)");
  const double x40 = std::log10(40.0 + kKelvin);
  const double x100 = std::log10(100.0 + kKelvin);
  b_ = (loglog(nu40_cSt) - loglog(nu100_cSt)) / (x100 - x40);
  a_ = loglog(nu40_cSt) + b_ * x40;
}

double WaltherViscosity::kinematic_cSt(double temp_C) const {
  const double z = a_ - b_ * std::log10(temp_C + kKelvin);
  return std::pow(10.0, std::pow(10.0, z)) - 0.7;
}

}  // namespace shudder::clutch
