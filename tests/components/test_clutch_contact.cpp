// The clutch contact law (components/clutch_contact) of a real WetClutch against the closed
// forms of its header, with a friction law whose mu is known in closed form: the same linear
// temperature line at every speed, mu_k(T) = beta + alpha T, and mu_s = ratio · mu_k.
//
//   kinetic torque  M_k = n Σ_i r_i p mu_k(T_i) A_i + M_drag,      p = F / A
//   static capacity M_s = n Σ_i r_i p mu_s(T_i) A_i · g(t_st) + M_drag
//   g = 1 + Δ_s (1 − exp(−t_st/τ_s)),  M_drag = mu_b F r_b,  heat q_i = |Δω| r_i p mu_k A_i
//
// With uniform temperatures the ring sum is that of the annulus, Σ r_i A_i → (2π/3)(R_o³ − R_i³)
// (midpoint rings fall short by Σ π Δr³/6: 3e-5 relative on the default 20-ring grid; tolerance
// 1e-4). Ring by ring (the grid's r_i, A_i) the law must agree to round-off: 1e-12 relative.
#include <gtest/gtest.h>

#include <array>
#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <vector>

#include "clutch/linear_friction.hpp"
#include "clutch/wet_clutch.hpp"
#include "components/clutch_contact.hpp"

namespace {

using shudder::clutch::WetClutch;
using shudder::components::BearingDrag;
using shudder::components::ClutchContact;
using shudder::components::ClutchContext;
using shudder::components::PiecewiseLinear;
using shudder::components::StickTimeFriction;

constexpr double kAlpha = -5e-4, kBeta = 0.13, kRatio = 1.3;
constexpr int kInterfaces = 3;
double mu_k(double temp_C) { return kBeta + kAlpha * temp_C; }

WetClutch clutch(bool temperature_dependent = true) {
  shudder::clutch::Fluid fluid;
  fluid.name = "linear";
  fluid.friction = std::make_shared<shudder::clutch::LinearTemperatureFriction>(
      std::vector<shudder::clutch::LinearTemperaturePoint>{{1.0, kAlpha, kBeta}, {1000.0, kAlpha, kBeta}});
  fluid.breakaway_ratio = kRatio;
  shudder::clutch::WetClutchParams p;
  p.sliding_interfaces = kInterfaces;
  p.start_temp_C = 40.0;
  p.temperature_dependent_friction = temperature_dependent;
  return WetClutch(p, fluid);
}

// Force ramp 0 → 20 kN over 1 s: at t = 0.6 s, F = 12 kN.
const PiecewiseLinear kForce({0.0, 1.0}, {0.0, 20000.0});
constexpr double kT = 0.6, kF = 12000.0;

TEST(ClutchContact, KineticTorqueAtAUniformTemperatureIsThatOfTheAnnulus) {
  const WetClutch c = clutch();
  const ClutchContact law(c, BearingDrag{}, StickTimeFriction{});
  ClutchContext ctx({Eigen::VectorXd::Constant(c.thermal().radial_cells(), 60.0), kForce});
  const double ri = c.thermal().params().inner_radius_m, ro = c.thermal().params().outer_radius_m;
  const double area = std::numbers::pi * (ro * ro - ri * ri);
  const double expected =
      kInterfaces * (kF / area) * mu_k(60.0) * (2.0 * std::numbers::pi / 3.0) * (ro * ro * ro - ri * ri * ri);
  EXPECT_NEAR(law.kinetic_torque_Nm(ctx, 2.0, kT) / expected, 1.0, 1e-4);
  EXPECT_NEAR(law.static_capacity_Nm(ctx, kT, 0.0) / (kRatio * expected), 1.0, 1e-4);
}

TEST(ClutchContact, RingByRingTorquesCapacityAndHeatFollowTheClosedForms) {
  const WetClutch c = clutch();
  const auto& th = c.thermal();
  const int n = th.radial_cells();
  Eigen::VectorXd temps(n);
  for (int i = 0; i < n; ++i) temps[i] = 30.0 + 3.0 * i;  // hotter outwards
  const BearingDrag drag{true, 0.005, 0.047};
  const StickTimeFriction stick{true, 0.15, 1.0};
  const ClutchContact law(c, drag, stick);
  ClutchContext ctx({temps, kForce});

  const double p = kF / th.ring_area_m2().sum();
  double sum_k = 0.0;
  for (int i = 0; i < n; ++i) sum_k += th.ring_radius_m()[i] * p * mu_k(temps[i]) * th.ring_area_m2()[i];
  const double m_drag = drag.equivalent_mu * kF * drag.radius_m;
  const double slip = 1.5;  // rad/s: r_i |Δω| ≈ 60–85 mm/s, inside the law's 1–1000 mm/s
  EXPECT_NEAR(law.kinetic_torque_Nm(ctx, slip, kT), kInterfaces * sum_k + m_drag, 1e-12 * kInterfaces * sum_k);
  EXPECT_NEAR(law.drag_torque_Nm(ctx, kT), m_drag, 1e-15 * m_drag);

  const double t_stick = 0.7, growth = 1.0 + 0.15 * (1.0 - std::exp(-t_stick / 1.0));
  EXPECT_NEAR(law.static_capacity_Nm(ctx, kT, t_stick), kInterfaces * kRatio * sum_k * growth + m_drag,
              1e-12 * kInterfaces * sum_k);

  // Heat per ring of ONE interface; the drag heats no disc.
  std::vector<double> q(static_cast<std::size_t>(n));
  law.channel_heat_W(ctx, slip, kT, q.data());
  for (int i = 0; i < n; ++i) {
    const double expected = slip * th.ring_radius_m()[i] * p * mu_k(temps[i]) * th.ring_area_m2()[i];
    EXPECT_NEAR(q[static_cast<std::size_t>(i)], expected, 1e-12 * expected) << "ring " << i;
  }
  // The mu line does not depend on speed, so neither does the torque: zero slope.
  EXPECT_NEAR(law.kinetic_torque_slope_Nms(ctx, slip, kT), 0.0, 1e-9 * kInterfaces * sum_k);
}

TEST(ClutchContact, NewHeldTemperaturesAndTheTemperatureSwitchReachTheTorque) {
  // The context's held temperatures are what the law evaluates: changing them changes the torque
  // by the closed form; with temperature_dependent_friction off every ring uses the clutch's
  // start temperature (40 °C) whatever is held.
  const WetClutch c = clutch();
  const ClutchContact law(c, BearingDrag{}, StickTimeFriction{});
  const int n = c.thermal().radial_cells();
  ClutchContext ctx({Eigen::VectorXd::Constant(n, 40.0), kForce});
  const double at40 = law.kinetic_torque_Nm(ctx, 1.0, kT);
  ctx.set_ring_temperatures(Eigen::VectorXd::Constant(n, 100.0));
  EXPECT_NEAR(law.kinetic_torque_Nm(ctx, 1.0, kT) / at40, mu_k(100.0) / mu_k(40.0), 1e-12);

  const WetClutch off = clutch(false);
  const ClutchContact law_off(off, BearingDrag{}, StickTimeFriction{});
  ClutchContext hot({Eigen::VectorXd::Constant(n, 100.0), kForce});
  EXPECT_NEAR(law_off.kinetic_torque_Nm(hot, 1.0, kT) / at40, 1.0, 1e-12);
  EXPECT_NEAR(law_off.static_capacity_Nm(hot, kT, 0.0) / (kRatio * at40), 1.0, 1e-12);
}

// The first-order hold across a thermal step (ClutchContext::set_ring_temperature_ramp, used by
// components/multirate_clutch): each ring's friction moves linearly in time between its values
// at the ramp's two end temperatures. With this law mu_k is linear in T, so the blend is exactly
// friction at the linearly moving temperature: at the ramp's middle the torque, capacity and
// heat are those at the mean temperature (1e-12); before t0 / after t1 the nearer end holds.
// The next ramp starts where this one ended, so the torque has no step at the boundary (what
// removed the thermal step's staircase).
TEST(ClutchContact, TemperatureRampBlendsFrictionLinearlyInTimeAndIsContinuousAtItsEnds) {
  const WetClutch c = clutch();
  const ClutchContact law(c, BearingDrag{}, StickTimeFriction{true, 0.15, 1.0});
  const int n = c.thermal().radial_cells();
  Eigen::VectorXd start(n), end(n), mid(n);
  for (int i = 0; i < n; ++i) {
    start[i] = 40.0 + i;
    end[i] = 100.0 - 2.0 * i;
  }
  mid = 0.5 * (start + end);
  const auto held_at = [&](const Eigen::VectorXd& temps, double t) {
    ClutchContext h({temps, kForce});
    return std::array<double, 2>{law.kinetic_torque_Nm(h, 1.0, t), law.static_capacity_Nm(h, t, 0.3)};
  };
  const double t0 = 0.55, t1 = 0.65;  // kT = 0.6 is the middle
  ClutchContext ramp({start, kForce});
  ramp.set_ring_temperature_ramp(start, end, t0, t1);
  const auto at_mid = held_at(mid, kT);
  EXPECT_NEAR(law.kinetic_torque_Nm(ramp, 1.0, kT), at_mid[0], 1e-12 * at_mid[0]);
  EXPECT_NEAR(law.static_capacity_Nm(ramp, kT, 0.3), at_mid[1], 1e-12 * at_mid[1]);
  std::vector<double> q(static_cast<std::size_t>(n)), q_mid(static_cast<std::size_t>(n));
  law.channel_heat_W(ramp, 1.0, kT, q.data());
  ClutchContext h_mid({mid, kForce});
  law.channel_heat_W(h_mid, 1.0, kT, q_mid.data());
  for (std::size_t i = 0; i < q.size(); ++i) EXPECT_NEAR(q[i], q_mid[i], 1e-12 * q_mid[i]) << "ring " << i;
  // Outside the ramp the nearer end holds (force at 0.5 / 0.7 s differs: compare at equal t).
  EXPECT_NEAR(law.kinetic_torque_Nm(ramp, 1.0, 0.5), held_at(start, 0.5)[0], 1e-12 * held_at(start, 0.5)[0]);
  EXPECT_NEAR(law.kinetic_torque_Nm(ramp, 1.0, 0.7), held_at(end, 0.7)[0], 1e-12 * held_at(end, 0.7)[0]);
  // The next ramp starts at this one's end: equal torque at the boundary t1 from both sides.
  const double before = law.kinetic_torque_Nm(ramp, 1.0, t1);
  ramp.set_ring_temperature_ramp(end, end + (end - start), t1, t1 + (t1 - t0));
  EXPECT_NEAR(law.kinetic_torque_Nm(ramp, 1.0, t1), before, 1e-12 * before);
  // A held setting cancels the ramp.
  ramp.set_ring_temperatures(mid);
  EXPECT_NEAR(law.kinetic_torque_Nm(ramp, 1.0, kT), at_mid[0], 1e-12 * at_mid[0]);
  EXPECT_THROW(ramp.set_ring_temperature_ramp(start, end, 0.6, 0.6), std::invalid_argument);
}

}  // namespace
