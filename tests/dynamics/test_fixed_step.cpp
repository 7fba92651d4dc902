// The fixed-step mode of Simulation (dynamics/simulation.hpp, "Fixed-step mode": classical RK4 at
// a step h, events handled at the step ends) against closed forms.
//
// Lock-up of two inertias through a Coulomb contact (constant kinetic torque T):
//   J1 ω̇1 = −T,  J2 ω̇2 = +T  while Δω = ω1 − ω2 > 0, so Δω(t) = Δω0 − T (1/J1 + 1/J2) t and
//   t* = Δω0 / (T (1/J1 + 1/J2)).  After the stick the pair turns at the momentum speed
//   ω_c = (J1 ω1 + J2 ω2)/(J1 + J2), and the heat is the kinetic energy lost,
//   Q = ½ J_eff Δω0² with J_eff = J1 J2/(J1 + J2).
// RK4 is exact on these linear motions, so between events the fixed-step run is exact to
// round-off; the stick is taken at the first step end past t* (within one step), where the
// projection onto ω1 = ω2 conserves momentum and books the kinetic energy it removes as the
// contact's heat: speeds and heat match the closed forms to round-off, whatever h.
//
// The belt-driven oscillator of test_stick_slip.cpp (speed source V, contact, mass on a spring):
//   t_stick = 2 (T_s − T_k)/(k V),  t_slip = (π + 2 atan(V k/(ω_n (T_s − T_k))))/ω_n.
// Breakaway is taken at the first step end past the capacity, up to h late; the spring is then
// up to V h further wound, which shortens the slip arc by |dt_slip/dx0| V h = 0.57 h (x0 the
// arc's start offset; dt_slip/dx0 = −2 (V/ω_n)/(ω_n (x0² + (V/ω_n)²)) = −0.57 s/rad here). One
// cycle's period thus differs from the closed form by at most h (late breakaway) + 0.57 h:
// checked against 2 h.
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <vector>

#include "dynamics/network.hpp"
#include "dynamics/simulation.hpp"
#include "tests/dynamics/test_laws.hpp"

namespace {

using namespace shudder::dynamics;
using shudder::dynamics::testing::CoulombLaw;

IntegratorSettings fixed(double h) {
  IntegratorSettings s;
  s.fixed_step_s = h;
  return s;
}

constexpr double kJ1 = 0.3, kJ2 = 0.1, kW1 = 40.0, kW2 = 10.0, kT = 12.0;

TEST(FixedStep, TwoInertiasLockAtTheMomentumSpeedWithTheClosedFormHeat) {
  const double t_lock = (kW1 - kW2) / (kT * (1 / kJ1 + 1 / kJ2));  // 0.5625 s
  const double w_c = (kJ1 * kW1 + kJ2 * kW2) / (kJ1 + kJ2);
  const double heat = 0.5 * kJ1 * kJ2 / (kJ1 + kJ2) * (kW1 - kW2) * (kW1 - kW2);
  for (const double h : {1e-3, 3e-4, 7e-5}) {
    TorsionalNetwork net;
    const int a = net.add_inertia({"a", kJ1});
    const int b = net.add_inertia({"b", kJ2});
    net.add_contact({"clutch", a, b, std::make_shared<CoulombLaw>(kT, 1.5 * kT)});
    Simulation sim(net, fixed(h));
    sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(kW1, kW2));
    double t_stuck = -1.0;
    std::vector<double> samples;
    for (int k = 1; k <= 1000; ++k) samples.push_back(k * 1e-3);
    sim.advance(1.0, samples, [&](const Sample& s) {
      if (t_stuck < 0 && s.modes[0] == ContactMode::kStuck) t_stuck = s.t_s;
    });
    const Sample end = sim.sample();
    EXPECT_EQ(sim.mode(0), ContactMode::kStuck) << "h = " << h;
    // Stuck within one step after t*, so seen by the first sample at or after t* + h.
    EXPECT_GE(t_stuck, t_lock - 1e-12);
    EXPECT_LE(t_stuck, std::ceil((t_lock + h) / 1e-3) * 1e-3 + 1e-12) << "h = " << h;
    EXPECT_NEAR(end.omega_rad_s[0], w_c, 1e-12 * w_c) << "h = " << h;
    EXPECT_EQ(end.omega_rad_s[0], end.omega_rad_s[1]);
    EXPECT_NEAR(sim.friction_work_J(0), heat, 1e-10 * heat) << "h = " << h;
    EXPECT_NEAR(sim.energy().imbalance_J(), 0.0, 1e-10 * heat) << "h = " << h;
    // The span cut into equal steps no longer than h: ceil(1/h) of them.
    EXPECT_EQ(sim.counters().steps, static_cast<long>(std::ceil(1.0 / h - 1e-9)));
  }
}

TEST(FixedStep, AReversingContactThatCannotHoldSlipsOnTheOtherWay) {
  // A torque source keeps pushing b past a: the contact (capacity below the push) reaches
  // Δω = 0, cannot hold, and slips on reversed, as the adaptive run would.
  TorsionalNetwork net;
  const int a = net.add_inertia({"a", kJ1});
  const int b = net.add_inertia({"b", kJ2});
  net.add_torque_source({"push", b, [](double) { return 20.0; }});
  net.add_contact({"clutch", a, b, std::make_shared<CoulombLaw>(2.0, 3.0)});
  Simulation sim(net, fixed(1e-4));
  sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(5.0, 0.0));
  sim.advance(1.0);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipNegative);
  EXPECT_EQ(sim.counters().stick_events, 0);
  EXPECT_EQ(sim.counters().reversal_events, 1);
  // After the reversal the slip is b ahead of a: both accelerate, b at (20 − 2)/J2, a at 2/J1.
  const Sample s = sim.sample();
  EXPECT_LT(s.omega_rad_s[0], s.omega_rad_s[1]);
  EXPECT_NEAR(sim.energy().imbalance_J(), 0.0, 1e-9 * sim.energy().source_work_J);
}

// The belt-driven oscillator (test_stick_slip.cpp has its derivation).
constexpr double kTs = 15.0, kTk = 10.0, kJm = 0.02, kK = 500.0, kV = 1.0;

struct Belt {
  TorsionalNetwork net;
  Belt() {
    const int d = net.add_inertia({"belt", 1.0});
    const int m = net.add_inertia({"mass", kJm});
    net.add_speed_source({"drive", d, [](double) { return kV; }, [](double) { return 0.0; }});
    net.add_shaft({"spring", m, kGround, kK, 0.0});
    net.add_contact({"contact", d, m, std::make_shared<CoulombLaw>(kTk, kTs)});
  }
};

TEST(FixedStep, BeltOscillatorPeriodWithinTheStepBound) {
  const double wn = std::sqrt(kK / kJm);
  const double period =
      2 * (kTs - kTk) / (kK * kV) + (std::numbers::pi + 2 * std::atan(kV * kK / (wn * (kTs - kTk)))) / wn;
  for (const double h : {1e-4, 2e-5}) {
    const Belt belt;
    Simulation sim(belt.net, fixed(h));
    sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(kV, kV));
    // Breakaway instants: the first sample of each slip phase, sampled at every step.
    std::vector<double> samples, breakaways;
    const int steps = static_cast<int>(std::lround(0.5 / h));
    for (int k = 1; k <= steps; ++k) samples.push_back(k * h);
    ContactMode last = ContactMode::kStuck;
    sim.advance(0.5, samples, [&](const Sample& s) {
      if (last == ContactMode::kStuck && s.modes[0] != ContactMode::kStuck) breakaways.push_back(s.t_s);
      last = s.modes[0];
    });
    ASSERT_GE(breakaways.size(), 8u) << "h = " << h;
    for (std::size_t i = 1; i < breakaways.size(); ++i)
      EXPECT_NEAR(breakaways[i] - breakaways[i - 1], period, 2 * h) << "cycle " << i << ", h = " << h;
    // Every stuck interval holds the mass at the belt's speed exactly (a stuck group shares one speed).
    EXPECT_GE(sim.counters().stick_events, 8);
    // RK4's energy integrals close the account to its truncation error: (ω_n h)⁵ ≈ 1e-7 per
    // step at h = 1e-4 on an arc of ~300 steps; 1e-6 of the source's work is a bound with room.
    EXPECT_NEAR(sim.energy().imbalance_J(), 0.0, 1e-6 * std::abs(sim.energy().source_work_J)) << "h = " << h;
  }
}

TEST(FixedStep, SamplesBetweenStepEndsDoNotAlterTheTrajectory) {
  const auto run = [](const std::vector<double>& samples) {
    const Belt belt;
    Simulation sim(belt.net, fixed(1e-4));
    sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(kV, kV));
    sim.advance(0.2, samples, [](const Sample&) {});
    return sim.sample();
  };
  const Sample plain = run({});
  const Sample sampled = run({0.01234, 0.05, 0.13333, 0.19999});
  EXPECT_EQ(plain.theta_rad, sampled.theta_rad);
  EXPECT_EQ(plain.omega_rad_s, sampled.omega_rad_s);
}

}  // namespace
