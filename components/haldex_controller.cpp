#include "components/haldex_controller.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shudder::components {

namespace {

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument("Haldex controller: " + what);
}

}  // namespace

HaldexController::HaldexController(const HaldexControllerParams& p) : p_(p) {
  require(std::isfinite(p.lock_slip_rpm) && p.lock_slip_rpm > 0, "lock_slip_rpm must be a finite value > 0");
  require(std::isfinite(p.pedal_gain) && p.pedal_gain >= 0 && p.pedal_gain <= 1, "pedal_gain must be in [0, 1]");
  require(std::isfinite(p.parking_speed_km_h) && p.parking_speed_km_h >= 0, "parking_speed_km_h must be >= 0");
  require(std::isfinite(p.parking_turn_ratio) && p.parking_turn_ratio > 0, "parking_turn_ratio must be > 0");
  require(std::isfinite(p.fast_speed_km_h) && std::isfinite(p.top_speed_km_h) && p.fast_speed_km_h >= 0 &&
              p.top_speed_km_h > p.fast_speed_km_h,
          "top_speed_km_h must exceed fast_speed_km_h (both >= 0)");
  require(std::isfinite(p.fast_demand) && p.fast_demand >= 0 && p.fast_demand <= 1, "fast_demand must be in [0, 1]");
  require(std::isfinite(p.control_period_ms) && p.control_period_ms > 0,
          "control_period_ms must be a finite value > 0");
  require(std::isfinite(p.speed_filter_time_constant_ms) && p.speed_filter_time_constant_ms >= 0,
          "speed_filter_time_constant_ms must be a finite value >= 0");
}

double HaldexController::excess_slip_rpm(const ControllerReading& r) const {
  return std::abs(r.front_axle_rpm - r.rear_axle_rpm * r.turn_axle_ratio);
}

bool HaldexController::parking(const ControllerReading& r) const {
  return std::abs(r.vehicle_speed_km_h) < p_.parking_speed_km_h && r.turn_axle_ratio - 1.0 > p_.parking_turn_ratio;
}

double HaldexController::valve_opening(const ControllerReading& r) const {
  const double slip_demand = excess_slip_rpm(r) / p_.lock_slip_rpm;
  const double pedal_demand = parking(r) ? 0.0 : p_.pedal_gain * std::clamp(r.pedal, 0.0, 1.0);
  double demand = std::clamp(std::max(slip_demand, pedal_demand), 0.0, 1.0);
  const double fast = std::clamp(
      (std::abs(r.vehicle_speed_km_h) - p_.fast_speed_km_h) / (p_.top_speed_km_h - p_.fast_speed_km_h), 0.0, 1.0);
  demand = std::min(demand, 1.0 - (1.0 - p_.fast_demand) * fast);
  return 1.0 - demand;
}

}  // namespace shudder::components
