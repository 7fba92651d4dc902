#pragma once
// Unit conversions used at the edges (SI inside, rpm / ml/min / mm/s in files and friction
// laws). One definition so that every conversion in the project is the same floating-point
// operation: rpm_to_rad_s multiplies, rad_s_to_rpm divides, as the code always did, so results
// stay bit-identical where these replace local constants.
#include <numbers>

namespace shudder::units {

inline constexpr double kTwoPi = 2.0 * std::numbers::pi;
/// 1 rpm = 2π/60 rad/s.
inline constexpr double kRadPerSPerRpm = kTwoPi / 60.0;
/// 1 m³/s = 6e7 ml/min.
inline constexpr double kMlPerMinPerM3PerS = 6e7;

constexpr double rpm_to_rad_s(double speed_rpm) { return speed_rpm * kRadPerSPerRpm; }
constexpr double rad_s_to_rpm(double speed_rad_s) { return speed_rad_s / kRadPerSPerRpm; }
/// Sliding speed at radius r: v [mm/s] = ω [rad/s] · r [mm].
constexpr double mm_s_per_rpm(double radius_mm) { return kRadPerSPerRpm * radius_mm; }
constexpr double ml_min_to_m3_s(double flow_ml_min) { return flow_ml_min / kMlPerMinPerM3PerS; }
constexpr double m3_s_to_ml_min(double flow_m3_s) { return flow_m3_s * kMlPerMinPerM3PerS; }

}  // namespace shudder::units
