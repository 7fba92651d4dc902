#include "clutch/wet_clutch.hpp"

#include <algorithm>
#include <cmath>
#include <span>
#include <stdexcept>

#include "clutch/friction_radius.hpp"

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
  // A law fitted from torque at another friction radius is read at this clutch's
  // (clutch/friction_radius.hpp): the torque it was fitted on is reproduced.
  fluid_ = with_friction_radius(std::move(fluid_), mean_radius_m() * 1e3);
}

ThermalState WetClutch::initial_state() const {
  return thermal_.initial_state(p_.start_temp_C, p_.start_temp_C, p_.sump_start_temp_C);
}

double WetClutch::mean_radius_m() const { return model_friction_radius_m(thermal_); }

void WetClutch::ring_mu(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C,
                        Eigen::VectorXd& mu, RingScratch* scratch) const {
  const auto& r = thermal_.ring_radius_m();
  const double load = friction_load_N(force_N);
  mu.resize(r.size());
  if (!scratch) {  // point by point: allocates nothing (the real-time step relies on that)
    for (Eigen::Index i = 0; i < r.size(); ++i)
      mu[i] = fluid_.friction->mu(r[i] * std::abs(slip_rad_s) * 1e3, friction_temp_C(ring_temp_C[i]), load);
    return;
  }
  RingScratch& w = *scratch;
  const auto n = static_cast<std::size_t>(r.size());
  w.speed_mm_s.resize(n);
  w.temp_C.resize(n);
  for (std::size_t i = 0; i < n; ++i) {
    const auto k = static_cast<Eigen::Index>(i);
    w.speed_mm_s[i] = r[k] * std::abs(slip_rad_s) * 1e3;
    w.temp_C[i] = friction_temp_C(ring_temp_C[k]);
  }
  fluid_.friction->mu_at_load(w.speed_mm_s, w.temp_C, load, std::span<double>(mu.data(), n), w.terms);
}

void WetClutch::ring_torque_Nm(double slip_rad_s, double force_N,
                               const Eigen::VectorXd& ring_temp_C, Eigen::VectorXd& torque,
                               RingScratch* scratch) const {
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  ring_mu(slip_rad_s, force_N, ring_temp_C, torque, scratch);
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
                            Eigen::VectorXd& heat, RingScratch* scratch) const {
  ring_torque_Nm(slip_rad_s, force_N, ring_temp_C, heat, scratch);
  heat *= std::abs(slip_rad_s);
}

FrozenFriction WetClutch::freeze(const Eigen::VectorXd& ring_temp_C, double force_N) const {
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  FrozenFriction f;
  f.ring_temp_C = ring_temp_C;
  f.load_N = friction_load_N(force_N);
  f.viscous_Nms = Eigen::VectorXd::Zero(r.size());
  f.radius_pow = (r * 1e3).array().pow(0.1);
  f.curves.resize(static_cast<std::size_t>(r.size()));
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    if (!fluid_.friction->speed_curve(friction_temp_C(ring_temp_C[i]), f.load_N,
                                      f.curves[static_cast<std::size_t>(i)])) {
      f.curves.clear();
      break;
    }
  }
  if (p_.viscous_shear)
    for (Eigen::Index i = 0; i < r.size(); ++i)
      f.viscous_Nms[i] = fluid_.density_kg_m3 * viscosity_.kinematic_cSt(ring_temp_C[i]) * 1e-6 *
                         r[i] * r[i] * a[i] / p_.viscous_gap_m;
  return f;
}

void WetClutch::ring_torque_Nm(const FrozenFriction& f, double abs_slip, double force_N,
                               Eigen::VectorXd& torque) const {
  if (f.curves.empty()) {  // law without a SpeedCurve form: evaluate it directly
    ring_torque_Nm(abs_slip, force_N, f.ring_temp_C, torque);
    return;
  }
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  const double p = pressure_Pa(force_N);
  // One pow per call: v_i^0.1 = (r_i [mm])^0.1 · |Δω|^0.1 wherever v_i is not clamped.
  const double slip_pow = std::pow(abs_slip, 0.1);
  torque.resize(r.size());
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    const SpeedCurve& c = f.curves[static_cast<std::size_t>(i)];
    const double v_raw = r[i] * abs_slip * 1e3;
    const double v = std::clamp(v_raw, c.min_speed_mm_s, c.max_speed_mm_s);
    const double v_pow = v == v_raw ? f.radius_pow[i] * slip_pow : std::pow(v, 0.1);
    double mu = c.power_weight * v_pow + c.offset;
    for (std::size_t j = 0; j < c.tanh_rate.size(); ++j) mu += c.tanh_weight[j] * std::tanh(c.tanh_rate[j] * v);
    torque[i] = r[i] * a[i] * p * mu + f.viscous_Nms[i] * abs_slip;
  }
}

void WetClutch::ring_torque_pair_Nm(const FrozenFriction& fa, const FrozenFriction& fb, double abs_slip,
                                    double force_N, Eigen::VectorXd& torque_a, Eigen::VectorXd& torque_b) const {
  if (fa.curves.empty() || fb.curves.empty()) {
    ring_torque_Nm(fa, abs_slip, force_N, torque_a);
    ring_torque_Nm(fb, abs_slip, force_N, torque_b);
    return;
  }
  const auto& r = thermal_.ring_radius_m();
  const auto& a = thermal_.ring_area_m2();
  const double p = pressure_Pa(force_N);
  const double slip_pow = std::pow(abs_slip, 0.1);
  torque_a.resize(r.size());
  torque_b.resize(r.size());
  // The expressions are ring_torque_Nm's, term by term in the same order: the same numbers.
  constexpr std::size_t kKept = 8;  // tanh values kept per ring (the Mäki matrix gives <= 4 rates)
  double kept[kKept];
  for (Eigen::Index i = 0; i < r.size(); ++i) {
    const SpeedCurve& ca = fa.curves[static_cast<std::size_t>(i)];
    const SpeedCurve& cb = fb.curves[static_cast<std::size_t>(i)];
    const double v_raw = r[i] * abs_slip * 1e3;
    const double va = std::clamp(v_raw, ca.min_speed_mm_s, ca.max_speed_mm_s);
    const double va_pow = va == v_raw ? fa.radius_pow[i] * slip_pow : std::pow(va, 0.1);
    const double vb = std::clamp(v_raw, cb.min_speed_mm_s, cb.max_speed_mm_s);
    const double vb_pow = vb == v_raw ? fb.radius_pow[i] * slip_pow : vb == va ? va_pow : std::pow(vb, 0.1);
    double mu_a = ca.power_weight * va_pow + ca.offset;
    double mu_b = cb.power_weight * vb_pow + cb.offset;
    const std::size_t na = ca.tanh_rate.size(), nb = cb.tanh_rate.size();
    if (vb == va && na == nb && ca.tanh_rate == cb.tanh_rate) {
      // The common case: both ends in one bracket of the matrix, the same rates in the same order.
      for (std::size_t j = 0; j < na; ++j) {
        const double t = std::tanh(ca.tanh_rate[j] * va);
        mu_a += ca.tanh_weight[j] * t;
        mu_b += cb.tanh_weight[j] * t;
      }
    } else {
      for (std::size_t j = 0; j < na; ++j) {
        const double t = std::tanh(ca.tanh_rate[j] * va);
        if (j < kKept) kept[j] = t;
        mu_a += ca.tanh_weight[j] * t;
      }
      const std::size_t shared = vb == va ? std::min(na, kKept) : 0;
      for (std::size_t j = 0; j < nb; ++j) {
        const double rate = cb.tanh_rate[j];
        std::size_t k = 0;
        while (k < shared && ca.tanh_rate[k] != rate) ++k;
        mu_b += cb.tanh_weight[j] * (k < shared ? kept[k] : std::tanh(rate * vb));
      }
    }
    torque_a[i] = r[i] * a[i] * p * mu_a + fa.viscous_Nms[i] * abs_slip;
    torque_b[i] = r[i] * a[i] * p * mu_b + fb.viscous_Nms[i] * abs_slip;
  }
}

}  // namespace shudder::clutch
