// The Haldex coupling's hydraulics (rig_models/haldex_hydraulics) against closed forms of
//   dp/dt = (p_relief/φ_full)|Δω| − p/τ,  0 <= p <= p_valve,  F = F_pre + A p:
//   * no leakage: the pressure reaches p_relief after exactly φ_full of relative rotation;
//   * constant |Δω|: p(t) = p_ss (1 − e^(−t/τ)), p_ss = (p_relief/φ_full)|Δω|τ, at any step size
//     (the update is exact for a constant rate);
//   * no rotation: p(t) = p0 e^(−t/τ); the valve caps the pressure;
//   * the pack's torque n μ r_eff F is the public 59 N m/bar plus the preload torque.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "rig_models/haldex_hydraulics.hpp"

namespace shudder::rig_models {
namespace {

constexpr double kPackNmPerN = 16 * 0.12 * 0.046;  // n μ r_eff of a 16-interface pack

TEST(HaldexHydraulics, FullPressureAfterNinetyDegreesWithoutLeakage) {
  HaldexHydraulicsParams p;
  p.leak_time_constant_s = 1e12;
  const HaldexHydraulics h(p, kPackNmPerN);
  const double slip_rad_s = 2.0, step_s = 1e-3;
  double pressure = 0, rotation = 0;
  while (pressure < p.relief_pressure_bar && rotation < 2.0) {
    pressure = h.step_pressure_bar(pressure, slip_rad_s * step_s, step_s, 100.0);
    rotation += slip_rad_s * step_s;
  }
  // 1e-3 rad steps: the relief is reached within one step of 90°.
  EXPECT_NEAR(rotation, std::numbers::pi / 2, slip_rad_s * step_s);
  EXPECT_DOUBLE_EQ(pressure, p.relief_pressure_bar);  // capped by the relief valve
}

TEST(HaldexHydraulics, ConstantSlipApproachesTheLeakageBalanceExactlyAtAnyStep) {
  const HaldexHydraulicsParams p;
  const HaldexHydraulics h(p, kPackNmPerN);
  const double slip_rad_s = 0.05;  // slow: the balance stays below the relief
  const double steady = p.relief_pressure_bar / p.full_pressure_rotation_rad * slip_rad_s * p.leak_time_constant_s;
  ASSERT_LT(steady, p.relief_pressure_bar);
  for (double step_s : {1e-3, 0.01, 0.1}) {
    double pressure = 0;
    const int n = static_cast<int>(std::lround(1.0 / step_s));
    for (int k = 0; k < n; ++k) pressure = h.step_pressure_bar(pressure, slip_rad_s * step_s, step_s, 30.0);
    EXPECT_NEAR(pressure, steady * (1 - std::exp(-1.0 / p.leak_time_constant_s)), 1e-12 * steady) << step_s;
  }
}

TEST(HaldexHydraulics, DecaysWithoutRotationAndObeysTheValve) {
  const HaldexHydraulicsParams p;
  const HaldexHydraulics h(p, kPackNmPerN);
  EXPECT_NEAR(h.step_pressure_bar(20.0, 0.0, 0.25, 30.0), 20.0 * std::exp(-0.25 / p.leak_time_constant_s), 1e-12);
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(0.0, 10.0, 0.01, 12.0), 12.0);   // the valve's setting
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(0.0, 10.0, 0.01, 80.0), 30.0);   // never above the relief
  EXPECT_DOUBLE_EQ(h.step_pressure_bar(5.0, 0.0, 0.01, -1.0), 0.0);     // valve shut: no pressure
}

TEST(HaldexHydraulics, PackTorqueIsFiftyNineNewtonMetresPerBarPlusPreload) {
  const HaldexHydraulicsParams p;
  const HaldexHydraulics h(p, kPackNmPerN);
  EXPECT_NEAR(kPackNmPerN * h.clamp_force_N(17.0), 59.0 * 17.0 + p.preload_torque_Nm, 1e-9);
  EXPECT_NEAR(kPackNmPerN * h.clamp_force_N(0.0), p.preload_torque_Nm, 1e-12);
}

TEST(HaldexHydraulics, RejectsNonPhysicalParameters) {
  HaldexHydraulicsParams p;
  p.leak_time_constant_s = 0;
  EXPECT_THROW(HaldexHydraulics(p, kPackNmPerN), std::invalid_argument);
  p = {};
  p.preload_torque_Nm = -1;
  EXPECT_THROW(HaldexHydraulics(p, kPackNmPerN), std::invalid_argument);
  EXPECT_THROW(HaldexHydraulics({}, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace shudder::rig_models
