#include "clutch/interface_thermal_impedance.hpp"

#include <cmath>
#include <stdexcept>

namespace shudder::clutch {

namespace {

using cd = std::complex<double>;

// The face impedance of `layer` backed by impedance `behind` (infinite = adiabatic: pass 0 as
// `behind_admittance`). Written with admittances so that the adiabatic back is Y_b = 0.
cd face_admittance(const Layer& layer, double omega, cd behind_admittance) {
  if (!(layer.thickness_m > 0) || !(layer.density_kg_m3 > 0) || !(layer.specific_heat_J_per_kgK > 0) ||
      !(layer.conductivity_W_per_mK > 0))
    throw std::invalid_argument(
        "thermal impedance: every layer needs thickness, density, heat capacity and "
        "conductivity > 0");
  const double alpha = layer.conductivity_W_per_mK / (layer.density_kg_m3 * layer.specific_heat_J_per_kgK);
  const cd gamma = std::sqrt(cd(0.0, omega / alpha));
  const cd yc = layer.conductivity_W_per_mK * gamma;  // 1/Z_c
  const cd t = std::tanh(gamma * layer.thickness_m);
  // Y = Y_c (Y_b + Y_c tanh γL) / (Y_c + Y_b tanh γL): the impedance formula of the header inverted.
  return yc * (behind_admittance + yc * t) / (yc + behind_admittance * t);
}

}  // namespace

std::complex<double> interface_thermal_impedance(const ThermalParams& p, double omega) {
  if (!std::isfinite(omega) || !(omega > 0))
    throw std::invalid_argument("thermal impedance: the frequency must be a finite value > 0");
  const cd y_separator = face_admittance(p.separator, omega, 0.0);
  const cd y_lining = face_admittance(p.lining, omega, face_admittance(p.core, omega, 0.0));
  return 1.0 / (y_separator + y_lining);
}

}  // namespace shudder::clutch
