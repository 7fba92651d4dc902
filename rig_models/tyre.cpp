#include "rig_models/tyre.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::rig_models {

namespace {
bool positive(double v) { return std::isfinite(v) && v > 0; }
}  // namespace

BrushTyre::BrushTyre(const TyreParams& p) : p_(p) {
  if (!positive(p.slip_stiffness_N) || !positive(p.relaxation_length_m) || !positive(p.vertical_load_N) ||
      !positive(p.road_friction) || !positive(p.radius_m))
    throw std::invalid_argument("tyre: slip stiffness, relaxation length, vertical load, road friction and "
                                "radius must be finite values > 0");
  full_slide_slip_ = 3.0 * p.road_friction * p.vertical_load_N / p.slip_stiffness_N;
}

double BrushTyre::force_N(double slip) const {
  const double limit = p_.road_friction * p_.vertical_load_N;
  const double a = std::abs(slip) / full_slide_slip_;
  const double f = a < 1.0 ? limit * (1.0 - (1.0 - a) * (1.0 - a) * (1.0 - a)) : limit;
  return std::copysign(f, slip);
}

dynamics::ForceLaw::Output BrushTyre::evaluate(double omega_wheel, double omega_ground, const double* z,
                                               double* dzdt) const {
  const double r = p_.radius_m, sigma = p_.relaxation_length_m;
  const double v_wheel = omega_wheel * r, v_ground = omega_ground * r;
  const double v_transport = std::max(std::abs(v_ground), std::abs(v_wheel));
  const double slip = z[0] / sigma;
  dzdt[0] = (v_wheel - v_ground) - v_transport * slip;
  const double force = force_N(slip);
  return {r * force, force * v_transport * slip};
}

double BrushTyre::stored_energy_J(const double* z) const {
  // σ ∫₀^κ' F dκ: with a = |κ'|/κ_sl, ∫ (1 − (1 − a)³) da = a + ((1 − a)⁴ − 1)/4 below full sliding.
  const double a = std::abs(z[0] / p_.relaxation_length_m) / full_slide_slip_;
  const double b = 1.0 - std::min(a, 1.0);
  const double integral = a < 1.0 ? a + (b * b * b * b - 1.0) / 4.0 : 0.75 + (a - 1.0);
  return p_.relaxation_length_m * p_.road_friction * p_.vertical_load_N * full_slide_slip_ * integral;
}

double BrushTyre::modal_stiffness_Nm_per_rad() const {
  // dT/dθ_w at rest: r · (C_κ/σ) · r (the deflection u moves by r per radian of the wheel).
  return p_.slip_stiffness_N / p_.relaxation_length_m * p_.radius_m * p_.radius_m;
}

RoadLoad::RoadLoad(const RoadLoadParams& p) : p_(p) {
  if (!(std::isfinite(p.rolling_resistance_N) && p.rolling_resistance_N >= 0) ||
      !(std::isfinite(p.drag_coefficient_area_m2) && p.drag_coefficient_area_m2 >= 0) ||
      !(std::isfinite(p.air_density_kg_m3) && p.air_density_kg_m3 >= 0) || !positive(p.radius_m) ||
      !positive(p.smoothing_speed_m_s))
    throw std::invalid_argument("road load: resistances must be >= 0, radius and smoothing speed > 0");
}

double RoadLoad::force_N(double v) const {
  return p_.rolling_resistance_N * std::tanh(v / p_.smoothing_speed_m_s) +
         0.5 * p_.air_density_kg_m3 * p_.drag_coefficient_area_m2 * v * std::abs(v);
}

dynamics::ForceLaw::Output RoadLoad::evaluate(double omega_vehicle, double, const double*, double*) const {
  const double torque = p_.radius_m * force_N(omega_vehicle * p_.radius_m);
  return {torque, torque * omega_vehicle};
}

}  // namespace shudder::rig_models
