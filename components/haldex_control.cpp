#include "components/haldex_control.hpp"

#include <algorithm>
#include <cmath>

#include "core/units.hpp"

namespace shudder::components {

HaldexControlUnit::HaldexControlUnit(const BuiltClutch& coupling)
    : c_(coupling),
      h_(coupling.spec->haldex),
      controller_(h_.controller),
      viscosity_(coupling.wet->fluid().nu40_cSt, coupling.wet->fluid().nu100_cSt),
      nu40_cSt_(viscosity_.kinematic_cSt(40.0)),
      period_s_(1e-3 * h_.controller.control_period_ms),
      filter_s_(1e-3 * h_.controller.speed_filter_time_constant_ms) {}

void HaldexControlUnit::start(const Eigen::VectorXd& speed_rad_s, const clutch::ThermalState& pack) {
  front_.start(0.0, speed_rad_s[c_.front_axle_node]);
  rear_.start(0.0, speed_rad_s[c_.rear_axle_node]);
  c_.command->opening = commanded_opening(0.0, front_.value_rad_s(), rear_.value_rad_s());
  update_oil(pack);
  next_ = 1;
}

std::vector<double> HaldexControlUnit::instants(double from_s, double until_s) const {
  std::vector<double> t;
  long k = std::max(1L, static_cast<long>(std::floor((from_s - 1e-12) / period_s_)));
  for (; static_cast<double>(k) * period_s_ < until_s - 1e-12; ++k)
    if (static_cast<double>(k) * period_s_ >= from_s - 1e-12) t.push_back(static_cast<double>(k) * period_s_);
  return t;
}

void HaldexControlUnit::at(double t_s, const dynamics::Sample& s) {
  const double due = static_cast<double>(next_) * period_s_;
  if (std::abs(t_s - due) > 1e-9 * period_s_) return;
  ++next_;
  const double front = front_.update(s.theta_rad[c_.front_axle_node], period_s_, filter_s_);
  const double rear = rear_.update(s.theta_rad[c_.rear_axle_node], period_s_, filter_s_);
  c_.command->opening = commanded_opening(t_s, front, rear);
}

void HaldexControlUnit::update_oil(const clutch::ThermalState& pack) {
  c_.command->leak_scale = nu40_cSt_ / viscosity_.kinematic_cSt(pack.sump_temp_C);
}

components::ControllerReading HaldexControlUnit::reading(double t_s, double front_rad_s, double rear_rad_s) const {
  components::ControllerReading r;
  const double vehicle_rad_s = std::min(front_rad_s / h_.front_path_ratio, rear_rad_s / h_.rear_path_ratio);
  r.vehicle_speed_km_h = vehicle_rad_s * h_.wheel_radius_m * 3.6;
  r.front_axle_rpm = units::rad_s_to_rpm(front_rad_s);
  r.rear_axle_rpm = units::rad_s_to_rpm(rear_rad_s);
  r.turn_axle_ratio = h_.front_path_ratio / h_.rear_path_ratio;
  r.pedal = std::clamp(h_.pedal(t_s), 0.0, 1.0);
  return r;
}

double HaldexControlUnit::commanded_opening(double t_s, double front_rad_s, double rear_rad_s) const {
  if (h_.valve_opening) return std::clamp((*h_.valve_opening)(t_s), 0.0, 1.0);
  if (h_.valve_pressure_bar) return 0.0;  // a raw pressure setting: shut below it
  return controller_.valve_opening(reading(t_s, front_rad_s, rear_rad_s));
}

}  // namespace shudder::components
