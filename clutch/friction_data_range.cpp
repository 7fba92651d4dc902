#include "clutch/friction_data_range.hpp"

#include <algorithm>
#include <cmath>

namespace shudder::clutch {

FrictionDataRange::FrictionDataRange(const FrictionLaw& law)
    : speed_lo_mm_s(law.min_speed_mm_s()),
      speed_hi_mm_s(law.max_speed_mm_s()),
      temp_lo_C(law.temp_range_C().first),
      temp_hi_C(law.temp_range_C().second),
      load_lo_N(law.load_range_N().first),
      load_hi_N(law.load_range_N().second) {}

void FrictionDataRange::add(double dt_s, double slip_rad_s, const Eigen::VectorXd& ring_radius_m,
                            const Eigen::VectorXd& ring_temp_C, double load_N) {
  total_s += dt_s;
  bool out = false;
  const auto count = [&](bool cond, double& time) {
    if (cond) {
      time += dt_s;
      out = true;
    }
  };
  const double w = std::abs(slip_rad_s);
  const double v_lo = w * ring_radius_m.minCoeff() * 1000.0, v_hi = w * ring_radius_m.maxCoeff() * 1000.0;
  // Sliding only above 0.01 mm/s: below, a step's mean slip is a stuck contact's creep (the
  // integrator's stick band) or a reversal, where kinetic friction is not what acts.
  if (v_lo > kSlidingThreshold_mm_s) {
    min_speed_mm_s = std::min(min_speed_mm_s, v_lo);
    max_speed_mm_s = std::max(max_speed_mm_s, v_hi);
    count(v_lo < speed_lo_mm_s, speed_below_s);
    count(v_hi > speed_hi_mm_s, speed_above_s);
  }
  const double t_lo = ring_temp_C.minCoeff(), t_hi = ring_temp_C.maxCoeff();
  min_temp_C = std::min(min_temp_C, t_lo);
  max_temp_C = std::max(max_temp_C, t_hi);
  count(t_lo < temp_lo_C, temp_below_s);
  count(t_hi > temp_hi_C, temp_above_s);
  min_load_N = std::min(min_load_N, load_N);
  max_load_N = std::max(max_load_N, load_N);
  count(load_N < load_lo_N, load_below_s);
  count(load_N > load_hi_N, load_above_s);
  if (out) outside_s += dt_s;
}

}  // namespace shudder::clutch
