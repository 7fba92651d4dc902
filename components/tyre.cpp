#include "components/tyre.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::components {

namespace {
bool positive(double v) { return std::isfinite(v) && v > 0; }
constexpr double kLoadFloor = 0.05;  // F_z >= 5 % of F_z0 (see the header)

// ∫₀^a (1 − (1 − s)³) ds and its derivative, the brush curve's shape (a = |u| c_x / (3 μ F_z)).
double shape_integral(double a) {
  if (a >= 1.0) return 0.75 + (a - 1.0);
  const double b = 1.0 - a;
  return a + (b * b * b * b - 1.0) / 4.0;
}
double shape(double a) {
  if (a >= 1.0) return 1.0;
  const double b = 1.0 - a;
  return 1.0 - b * b * b;
}
}  // namespace

double TyreParams::static_slip_stiffness_N() const {
  if (slip_stiffness_N && slip_stiffness_per_load)
    throw std::invalid_argument(
        "tyre: slip_stiffness_N and slip_stiffness_per_load are alternatives; give one "
        "(an absolute C_kappa, or C_kappa / F_z)");
  if (slip_stiffness_N) return *slip_stiffness_N;
  return slip_stiffness_per_load.value_or(kDefaultSlipStiffnessPerLoad) * vertical_load_N;
}

BrushTyre::BrushTyre(const TyreParams& p) : p_(p) {
  if ((p.slip_stiffness_N && !positive(*p.slip_stiffness_N)) ||
      (p.slip_stiffness_per_load && !positive(*p.slip_stiffness_per_load)))
    throw std::invalid_argument("tyre: slip_stiffness_N and slip_stiffness_per_load must be finite values > 0");
  if (!positive(p.relaxation_length_m) || !positive(p.vertical_load_N) || !positive(p.road_friction) ||
      !positive(p.radius_m))
    throw std::invalid_argument(
        "tyre: relaxation length, vertical load, road friction and radius must be finite "
        "values > 0");
  const auto& lt = p.load_transfer;
  if (!std::isfinite(lt.load_per_acceleration_kg) || !positive(lt.first_lag_s) || !positive(lt.second_lag_s) ||
      !positive(lt.path_ratio))
    throw std::invalid_argument("tyre: the load transfer's dF_z/da must be finite, its lags and path ratio > 0");
  static_slip_stiffness_N_ = p.static_slip_stiffness_N();
  carcass_N_per_m_ = static_slip_stiffness_N_ / p.relaxation_length_m;
}

double BrushTyre::slip_stiffness_N(double fz) const {
  return p_.slip_stiffness_follows_load() ? static_slip_stiffness_N_ * fz / p_.vertical_load_N
                                          : static_slip_stiffness_N_;
}

double BrushTyre::relaxation_length_m(double fz) const { return slip_stiffness_N(fz) / carcass_N_per_m_; }

double BrushTyre::vertical_load_N(const double* z) const {
  if (!transfers_load()) return p_.vertical_load_N;
  const auto& lt = p_.load_transfer;
  const double acceleration = (z[1] - z[2]) / lt.second_lag_s;
  return std::max(p_.vertical_load_N + lt.load_per_acceleration_kg * acceleration, kLoadFloor * p_.vertical_load_N);
}

double BrushTyre::force_at_N(double u, double fz) const {
  const double limit = p_.road_friction * fz;
  return std::copysign(limit * shape(std::abs(u) * carcass_N_per_m_ / (3.0 * limit)), u);
}

double BrushTyre::force_N(double slip) const { return force_at_N(slip * p_.relaxation_length_m, p_.vertical_load_N); }

double BrushTyre::stored_energy_J(double u, double fz) const {
  const double limit = p_.road_friction * fz;
  return 3.0 * limit * limit / carcass_N_per_m_ * shape_integral(std::abs(u) * carcass_N_per_m_ / (3.0 * limit));
}

double BrushTyre::energy_load_slope_J_per_N(double u, double fz) const {
  // E = 3 μ² F_z² I(a)/c_x with a ∝ 1/F_z: ∂E/∂F_z = 3 μ² F_z (2 I(a) − a I'(a)) / c_x.
  const double mu = p_.road_friction;
  const double a = std::abs(u) * carcass_N_per_m_ / (3.0 * mu * fz);
  return 3.0 * mu * mu * fz * (2.0 * shape_integral(a) - a * shape(a)) / carcass_N_per_m_;
}

dynamics::ForceLaw::Output BrushTyre::evaluate(double omega_wheel, double omega_ground, const double* z,
                                               double* dzdt) const {
  const double r = p_.radius_m;
  const double fz = vertical_load_N(z);
  const double sigma = relaxation_length_m(fz);
  const double v_wheel = omega_wheel * r, v_ground = omega_ground * r;
  const double v_transport = std::max(std::abs(v_ground), std::abs(v_wheel));
  const double slip = z[0] / sigma;
  dzdt[0] = (v_wheel - v_ground) - v_transport * slip;
  const double force = force_at_N(z[0], fz);
  double dissipated = force * v_transport * slip;
  if (transfers_load()) {
    // The car's speed through the two lags; the load's rate from the filtered acceleration's.
    const auto& lt = p_.load_transfer;
    dzdt[1] = (v_ground / lt.path_ratio - z[1]) / lt.first_lag_s;
    dzdt[2] = (z[1] - z[2]) / lt.second_lag_s;
    const double unfloored = p_.vertical_load_N + lt.load_per_acceleration_kg * (z[1] - z[2]) / lt.second_lag_s;
    if (unfloored > kLoadFloor * p_.vertical_load_N) {
      const double load_rate = lt.load_per_acceleration_kg * (dzdt[1] - dzdt[2]) / lt.second_lag_s;
      dissipated -= energy_load_slope_J_per_N(z[0], fz) * load_rate;
    }
  }
  return {r * force, dissipated};
}

double BrushTyre::stored_energy_J(const double* z) const { return stored_energy_J(z[0], vertical_load_N(z)); }

double BrushTyre::modal_stiffness_Nm_per_rad() const {
  // dT/dθ_w at rest: r · c_x · r (the deflection u moves by r per radian of the wheel).
  return carcass_N_per_m_ * p_.radius_m * p_.radius_m;
}

void BrushTyre::initial_states(double, double omega_ground, double* z) const {
  steady_states(0.0, omega_ground * p_.radius_m / p_.load_transfer.path_ratio, 0.0, z);
}

void BrushTyre::steady_states(double u, double v, double a, double* z) const {
  z[0] = u;
  if (!transfers_load()) return;
  z[1] = v - p_.load_transfer.first_lag_s * a;
  z[2] = z[1] - p_.load_transfer.second_lag_s * a;
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

}  // namespace shudder::components
