// Signals, the plain friction law, the freewheel's holding rule and the lash shaft against their
// definitions (components/signal.hpp, plain_friction.hpp, one_way_clutch.hpp, lash_shaft.hpp).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "components/lash_shaft.hpp"
#include "components/one_way_clutch.hpp"
#include "components/plain_friction.hpp"
#include "components/signal.hpp"
#include "core/units.hpp"

namespace shudder::components {
namespace {

TEST(Signal, EachKindFollowsItsDefinition) {
  const auto table = Signal::table({0.0, 1.0, 3.0}, {0.0, 2.0, -2.0}, true);
  EXPECT_DOUBLE_EQ(table(0.5), 1.0);
  EXPECT_DOUBLE_EQ(table(2.0), 0.0);
  EXPECT_DOUBLE_EQ(table(-1.0), 0.0);  // the first value before the first time
  EXPECT_DOUBLE_EQ(table(9.0), -2.0);  // the last after the last
  EXPECT_DOUBLE_EQ(table.derivative(2.0), -2.0);
  const auto held = Signal::table({0.0, 1.0, 3.0}, {0.0, 2.0, -2.0}, false);
  EXPECT_DOUBLE_EQ(held(2.9), 2.0);
  EXPECT_DOUBLE_EQ(held(3.0), -2.0);
  const auto step = Signal::step(0.5, 1.0, 3.0);
  EXPECT_DOUBLE_EQ(step(0.4999), 1.0);
  EXPECT_DOUBLE_EQ(step(0.5), 3.0);
  const auto sine = Signal::sine(1.0, 2.0, 5.0, std::numbers::pi / 2, 0.1);
  EXPECT_DOUBLE_EQ(sine(0.05), 1.0);    // the offset before start_s
  EXPECT_NEAR(sine(0.1), 3.0, 1e-12);   // phase 90 deg at start_s
  EXPECT_NEAR(sine(0.2), -1.0, 1e-12);  // half a period (0.1 s) later
  EXPECT_NEAR(sine(0.3), 3.0, 1e-12);   // a whole period (0.2 s) later
  EXPECT_NEAR(sine.derivative(0.15),
              2.0 * 2 * std::numbers::pi * 5.0 * std::cos(2 * std::numbers::pi * 5.0 * 0.05 + std::numbers::pi / 2),
              1e-9);
  const auto pulse = Signal::pulse(0.0, 1.0, 0.5, 0.2, 1.0);
  EXPECT_DOUBLE_EQ(pulse(0.9), 0.0);
  EXPECT_DOUBLE_EQ(pulse(1.1), 1.0);
  EXPECT_DOUBLE_EQ(pulse(1.3), 0.0);
  EXPECT_DOUBLE_EQ(pulse(1.55), 1.0);
  const auto ramp = Signal::ramp(2.0, 4.0, 1.0, 2.0);
  EXPECT_DOUBLE_EQ(ramp(0.0), 2.0);
  EXPECT_DOUBLE_EQ(ramp(2.0), 3.0);
  EXPECT_DOUBLE_EQ(ramp(5.0), 4.0);
  EXPECT_DOUBLE_EQ(ramp.derivative(2.0), 1.0);
  const auto product = Signal::product(ramp, step);
  EXPECT_DOUBLE_EQ(product(2.0), 9.0);
  EXPECT_DOUBLE_EQ(product.derivative(2.0), 3.0);  // (f g)' = f' g + f g' with g' = 0
}

TEST(Signal, KnotsAndExtremesOverAnInterval) {
  const auto pulse = Signal::pulse(-1.0, 2.0, 1.0, 0.25, 0.0);
  const auto k = pulse.knots(0.0, 2.1);
  ASSERT_GE(k.size(), 4u);
  EXPECT_DOUBLE_EQ(k[0], 0.25);
  EXPECT_DOUBLE_EQ(k[1], 1.0);
  EXPECT_DOUBLE_EQ(pulse.max_over(0.0, 2.0), 2.0);
  EXPECT_DOUBLE_EQ(pulse.min_over(0.0, 2.0), -1.0);
  const auto late = Signal::step(5.0, 0.0, 1.0);
  EXPECT_DOUBLE_EQ(late.max_over(0.0, 4.0), 0.0);  // a clutch stepped on after the run never loads
  EXPECT_DOUBLE_EQ(Signal::sine(0.0, 1.0, 1.0, 0.0, 0.0).max_over(0.0, 1.0), 1.0);
  EXPECT_THROW(Signal::table({0.0, 0.0}, {1.0, 2.0}, true), std::invalid_argument);
  EXPECT_THROW(Signal::pulse(0.0, 1.0, 0.1, 0.2, 0.0), std::invalid_argument);
}

// T_k = mu(|dn|) R F, T_s = peak mu(0) R F, F = F_max max(u, 0); slope = dmu/dw R F.
TEST(PlainFriction, TorqueCapacityAndSlopeFromTheTable) {
  PlainFrictionParams p;
  p.slip_rpm = {0.0, 100.0};
  p.mu = {0.15, 0.10};
  p.peak_ratio = 1.2;
  p.geometry_factor_m = 0.2;
  p.max_force_N = 1000.0;
  const PlainFrictionLaw law(p, Signal::ramp(-0.5, 1.0, 0.0, 1.5));  // u < 0 until 0.5 s: open
  EXPECT_DOUBLE_EQ(law.normal_force_N(0.25), 0.0);
  EXPECT_DOUBLE_EQ(law.normal_force_N(1.5), 1000.0);
  const double w50 = units::rpm_to_rad_s(50.0);
  EXPECT_NEAR(law.kinetic_torque_Nm(w50, 1.5, nullptr), 0.125 * 0.2 * 1000.0, 1e-12);
  EXPECT_NEAR(law.kinetic_torque_Nm(units::rpm_to_rad_s(500.0), 1.5, nullptr), 0.10 * 200.0, 1e-12);  // held beyond
  EXPECT_NEAR(law.static_capacity_Nm(1.5, 0.0, nullptr), 1.2 * 0.15 * 200.0, 1e-12);
  EXPECT_NEAR(law.kinetic_torque_slope_Nms(w50, 1.5, nullptr), -0.05 / units::rpm_to_rad_s(100.0) * 200.0, 1e-12);
  EXPECT_DOUBLE_EQ(law.kinetic_torque_Nm(w50, 0.25, nullptr), 0.0);
  p.mu = {0.15, -0.1};
  EXPECT_THROW(PlainFrictionLaw(p, Signal::constant(1.0)), std::invalid_argument);
}

TEST(OneWayClutch, HoldsOneDirectionOnly) {
  const OneWayClutchLaw law(0.5);
  EXPECT_GE(law.holding_capacity_Nm(0.0, 0.0, 1e6, nullptr), 1e12);    // driving: any torque
  EXPECT_LT(law.holding_capacity_Nm(0.0, 0.0, -1e-6, nullptr), 1e-6);  // reversed: releases
  EXPECT_DOUBLE_EQ(law.kinetic_torque_Nm(10.0, 0.0, nullptr), 0.5);    // overrunning drag
}

// Lash: no torque inside the gap; beyond it k d + c w, never pulling; P_diss >= 0 and
// T w = dE/dt + P_diss with dE/dt = k d w.
TEST(LashShaft, DeadZoneSpringThatNeverPulls) {
  const LashShaft s(1000.0, 2.0, 0.1);  // half gap 0.05 rad
  double dz = 0.0;
  double z = 0.04;
  EXPECT_DOUBLE_EQ(s.evaluate(3.0, 1.0, &z, &dz).torque_Nm, 0.0);
  EXPECT_DOUBLE_EQ(dz, 2.0);
  z = 0.06;
  const auto in = s.evaluate(3.0, 1.0, &z, &dz);
  EXPECT_NEAR(in.torque_Nm, 1000.0 * 0.01 + 2.0 * 2.0, 1e-12);
  EXPECT_NEAR(in.dissipated_W, 2.0 * 2.0 * 2.0, 1e-12);  // c w^2
  const auto out = s.evaluate(1.0, 10.0, &z, &dz);       // separating fast: the damper would pull
  EXPECT_DOUBLE_EQ(out.torque_Nm, 0.0);
  EXPECT_GE(out.dissipated_W, 0.0);
  EXPECT_NEAR(out.torque_Nm * (1.0 - 10.0), 1000.0 * 0.01 * (1.0 - 10.0) + out.dissipated_W, 1e-12);
  EXPECT_NEAR(s.stored_energy_J(&z), 0.5 * 1000.0 * 0.01 * 0.01, 1e-15);
}

}  // namespace
}  // namespace shudder::components
