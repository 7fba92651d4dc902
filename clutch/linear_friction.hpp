#pragma once
// Linear friction–temperature law per sliding speed (Papers B, C, E):
//
//     mu_k(T) = alpha_k * T + beta_k          at tabulated speed v_k (T in °C)
//
// Between tabulated speeds mu is interpolated linearly in ln(v) (boundary friction is close to
// log-linear in speed over 1–100 rpm, cf. Paper G eq. 1); outside the tabulated range it is held
// at the end value, so dmu/dv is zero there. The law is tabulated at one load (Paper E: 20 kN)
// and does not depend on load.

#include <vector>

#include "clutch/friction_law.hpp"

namespace shudder::clutch {

struct LinearTemperaturePoint {
  double speed_mm_s = 0.0;   // local sliding speed of this line
  double alpha_per_C = 0.0;  // slope d(mu)/dT, 1/°C
  double beta = 0.0;         // mu at 0 °C
};

class LinearTemperatureFriction final : public FrictionLaw {
 public:
  /// Points must have strictly increasing positive speeds and finite coefficients
  /// (std::invalid_argument otherwise).
  explicit LinearTemperatureFriction(std::vector<LinearTemperaturePoint> points);

  double mu(double speed_mm_s, double temp_C, double load_N) const override;
  double dmu_dv_per_mm_s(double speed_mm_s, double temp_C, double load_N) const override;
  double min_speed_mm_s() const override { return points_.front().speed_mm_s; }
  double max_speed_mm_s() const override { return points_.back().speed_mm_s; }

  const std::vector<LinearTemperaturePoint>& points() const { return points_; }

 private:
  std::vector<LinearTemperaturePoint> points_;
};

}  // namespace shudder::clutch
