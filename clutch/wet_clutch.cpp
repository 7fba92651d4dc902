#include "clutch/wet_clutch.hpp"

#include <cmath>
#include <stdexcept>

namespace shudder::clutch {

WetClutch::WetClutch(WetClutchParams params, Fluid fluid)
    : p_(std::move(params)),
      fluid_(std::move(fluid)),
      thermal_(p_.thermal),
      viscosity_(fluid_.nu40_cSt, fluid_.nu100_cSt) {
  if (!fluid_.friction) throw std::invalid_argument("clutch fluid has no friction law");
  if (p_.sliding_interfaces < 1 || p_.sliding_interfaces > 64)
    throw std::invalid_argument("sliding interfaces must be in [1, 64]");
  if (!(p_.reference_load_N > 0.0)) throw std::invalid_argument("reference load must be > 0");
  if (!(p_.viscous_gap_m > 0.0)) throw std::invalid_argument("viscous gap must be > 0");
}

ThermalState WetClutch::initial_state() const {
  return thermal_.initial_state(p_.start_temp_C, p_.start_temp_C, p_.sump_start_temp_C);
}

double WetClutch::mean_radius_m() const {
  return thermal_.ring_radius_m().dot(thermal_.ring_area_m2()) / thermal_.contact_area_m2();
}

void WetClutch::ring_mu(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C,
                        Eigen::VectorXd& mu) const {
  const auto& r = thermal_.ring_radius_m();
  const double load = p_.load_dependent_friction ? force_N : p_.reference_load_N;
  mu.resize(r.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    const double temp = p_.temperature_dependent_friction ? ring_temp_C[i] : p_.start_temp_C;
    mu[i] = fluid_.friction->mu(r[i] * std::abs(slip_rad_s) * 1e3, temp, load);
  }
}

void WetClutch::ring_torque_Nm(double slip_rad_s, double force_N,
                               const Eigen::VectorXd& ring_temp_C, Eigen::VectorXd& torque) const {
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  ring_mu(slip_rad_s, force_N, ring_temp_C, torque);
  torque = torque.cwiseProduct(r).cwiseProduct(a) * pressure_Pa(force_N);
  if (p_.viscous_shear) {
    const double w = std::abs(slip_rad_s);
    for (Eigen::Index i = 0; i < r.size(); ++i) {
      const double eta_Pa_s = fluid_.density_kg_m3 * viscosity_.kinematic_cSt(ring_temp_C[i]) * 1e-6;
      torque[i] += eta_Pa_s * r[i] * w / p_.viscous_gap_m * r[i] * a[i];
    }
  }
}

double WetClutch::torque_Nm(double slip_rad_s, double force_N,
                            const Eigen::VectorXd& ring_temp_C) const {
  Eigen::VectorXd t;
  ring_torque_Nm(slip_rad_s, force_N, ring_temp_C, t);
  return std::copysign(p_.sliding_interfaces * t.sum(), slip_rad_s);
}

void WetClutch::ring_heat_W(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C,
                            Eigen::VectorXd& heat) const {
  ring_torque_Nm(slip_rad_s, force_N, ring_temp_C, heat);
  heat *= std::abs(slip_rad_s);
}

}  // namespace shudder::clutch
