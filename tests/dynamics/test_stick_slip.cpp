// Stick–slip of friction contacts in Simulation against hand-derived closed forms: the
// belt-driven oscillator, two contacts in series that stick together and break away one after
// the other, two contacts in parallel (dependent constraints), and event-location accuracy.
//
// Integrator: dopri5 at abs = rel = 1e-12 (see tight()). Between events the motions are
// harmonic arcs or polynomials, integrated to ~1e-11; events are located by bisection to
// event_time_tol_s = 1e-12 s. Hence event instants are checked to ±1e-9 s (the brief's
// "event_time_tol_s scale", 1000x the bracket for the trajectory error), speeds and torques to
// 1e-6, torques of a stuck contact (which follow from the KKT solve, not from integration) tighter.
#include <gtest/gtest.h>

#include <algorithm>
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

IntegratorSettings tight(double max_step_s = 1e-4) {
  IntegratorSettings s;
  s.abs_tol = 1e-12;
  s.rel_tol = 1e-12;
  s.max_step_s = max_step_s;
  return s;
}

// =============================================================================================
// Belt-driven oscillator (textbook stick–slip)
//
//     V = const ──▶ [ D ] ══ contact ══ [ M ] ──/\/\/\── | ground
//     speed source         (a = D, b = M)  J       k
//
// Contact: n = 2 faces, r = 0.05 m, F = 1000 N, mu_s = 0.15, mu_k = 0.10
//     T_s = n r F mu_s = 15 N m,  T_k = n r F mu_k = 10 N m;  J = 0.02 kg m², k = 500 N m/rad,
//     V = 1 rad/s, ω_n = sqrt(k/J) = 158.11 rad/s.  Δω = V − ω_M, θ = angle of M.
//
// Stuck (ω_M = V): θ grows at V; the contact holds λ = k θ (torque on M) until k θ_s = T_s.
// Slipping (ω_M < V): J θ'' = T_k − k θ, a harmonic arc about θ_k = T_k/k. In x = θ − θ_k it
// starts at x0 = (T_s − T_k)/k with speed V. On the phase circle (x, v/ω_n) it runs clockwise
// from angle α = atan(V/(ω_n x0)) = atan(V k / (ω_n (T_s − T_k))) to the next point where
// v = +V, which is the mirror image x = −x0 at angle π − α: swept angle π + 2α, so
//
//     t_slip  = (π + 2 atan(V k / (ω_n (T_s − T_k)))) / ω_n            (= 27.0 ms)
//     θ_r     = θ_k − x0 = (2 T_k − T_s)/k                (re-stick; holds since |kθ_r| < T_s)
//     t_stick = (θ_s − θ_r)/V = 2 (T_s − T_k)/(k V)                    (= 20.0 ms)
//     period  = t_stick + t_slip;   spring-torque jump k(θ_s − θ_r) = 2 (T_s − T_k) = 10 N m
//
// Re-stick is transversal: J dω_M/dt = T_k − k θ_r = T_s − T_k > 0 there.
// =============================================================================================
constexpr double kFaces = 2, kRadius = 0.05, kForce = 1000, kMuS = 0.15, kMuK = 0.10;
constexpr double kJm = 0.02, kK = 500.0, kV = 1.0;
constexpr double kTs = kFaces * kRadius * kForce * kMuS, kTk = kFaces * kRadius * kForce * kMuK;

struct Belt {
  TorsionalNetwork net;
  int d = 0, m = 0;
  Belt() {
    d = net.add_inertia({"belt", 1.0});
    m = net.add_inertia({"mass", kJm});
    net.add_speed_source({"drive", d, [](double) { return kV; }, [](double) { return 0.0; }});
    net.add_shaft({"spring", m, kGround, kK, 0.0});
    net.add_contact(
        {"contact", d, m, std::make_shared<CoulombLaw>(CoulombLaw::from_clamp(kFaces, kRadius, kForce, kMuS, kMuK))});
  }
};

double omega_n() { return std::sqrt(kK / kJm); }
double t_slip() { return (std::numbers::pi + 2 * std::atan(kV * kK / (omega_n() * (kTs - kTk)))) / omega_n(); }
double t_stick() { return 2 * (kTs - kTk) / (kK * kV); }
double theta_r() { return (2 * kTk - kTs) / kK; }

// A sampled run of 10 cycles from the re-stick point: stuck samples have exactly zero slip, slip
// samples the kinetic torque, one stick and one breakaway per cycle, period within 1 %.
TEST(DynamicsStickSlip, BeltDrivenOscillatorLimitCycle) {
  Belt b;
  Simulation sim(b.net, tight());
  sim.initialize(0.0, Eigen::Vector2d(0.0, theta_r()), Eigen::Vector2d(kV, kV));
  ASSERT_EQ(sim.mode(0), ContactMode::kStuck);

  const double period = t_stick() + t_slip();
  const int cycles = 10;
  std::vector<double> times;
  for (int i = 1; i * 1e-4 < cycles * period; ++i) times.push_back(i * 1e-4);
  std::vector<double> breakaways;  // first slipping sample after a stuck one
  bool was_stuck = true;
  int stuck_samples = 0, slip_samples = 0;
  sim.advance(cycles * period - 1e-3, times, [&](const Sample& s) {
    const bool stuck = s.modes[0] == ContactMode::kStuck;
    if (stuck) {
      ++stuck_samples;
      EXPECT_EQ(s.contact_slip_rad_s[0], 0.0) << "t = " << s.t_s;  // bitwise, not just small
      // Holding torque = spring torque (M moves at constant speed), within capacity.
      EXPECT_NEAR(s.contact_torque_Nm[0], kK * s.theta_rad[b.m], 1e-9 * kTs);
      EXPECT_LE(s.contact_torque_Nm[0], kTs * (1 + 1e-12));
      EXPECT_NEAR(s.omega_rad_s[b.m], kV, 1e-12);
    } else {
      ++slip_samples;
      EXPECT_GT(s.contact_slip_rad_s[0], 0.0) << "t = " << s.t_s;
      EXPECT_EQ(s.modes[0], ContactMode::kSlipPositive);
      EXPECT_EQ(s.contact_torque_Nm[0], kTk);  // s · T_k with s = +1, exactly
      // Slip phase stays on the harmonic arc: |θ − θ_k| <= A = hypot(x0, V/ω_n).
      const double amp = std::hypot((kTs - kTk) / kK, kV / omega_n());
      EXPECT_LE(std::abs(s.theta_rad[b.m] - kTk / kK), amp * (1 + 1e-9));
    }
    if (was_stuck && !stuck) breakaways.push_back(s.t_s);
    was_stuck = stuck;
  });
  EXPECT_GT(stuck_samples, 1000);
  EXPECT_GT(slip_samples, 1000);
  ASSERT_EQ(breakaways.size(), static_cast<std::size_t>(cycles));
  // Each transition is seen within one sample spacing (1e-4 s): the mean period over 9 cycles
  // is known to 2e-4 s / 9 = 2.3e-5 s, i.e. 5e-4 of the period; the brief asks 1 %.
  const double measured = (breakaways.back() - breakaways.front()) / (cycles - 1);
  EXPECT_NEAR(measured / period, 1.0, 0.01);
  EXPECT_NEAR(measured / period, 1.0, 1e-3);
  // One breakaway and one re-stick per cycle; the run ends in the 10th slip phase, before the
  // 10th re-stick.
  EXPECT_EQ(sim.counters().breakaway_events, cycles);
  EXPECT_EQ(sim.counters().stick_events, cycles - 1);
  EXPECT_EQ(sim.counters().reversal_events, 0);
  // The constraint system depends only on the stuck set: its two sets (stuck, slipping) are
  // factorised once each per run, however many right-hand sides and events (the counters restart
  // after initialize, which met the stuck set: one factorisation after it).
  EXPECT_GT(sim.counters().rhs_calls, 1000);
  EXPECT_EQ(sim.counters().constraint_factorisations, 1);
}

// The event instants themselves, checked by stopping ±δ around the analytic times, and the
// spring-torque jump between breakaway and re-stick.
TEST(DynamicsStickSlip, BreakawayAndRestickAtTheAnalyticInstants) {
  Belt b;
  Simulation sim(b.net, tight());
  sim.initialize(0.0, Eigen::Vector2d(0.0, theta_r()), Eigen::Vector2d(kV, kV));
  const double period = t_stick() + t_slip(), delta = 1e-9;
  for (int n = 0; n < 5; ++n) {
    const double tb = t_stick() + n * period, tr = tb + t_slip();
    sim.advance(tb - delta);
    ASSERT_EQ(sim.mode(0), ContactMode::kStuck) << "cycle " << n;
    // Stuck: spring torque k θ = T_s − k V δ just before breakaway.
    const double before = sim.sample().shaft_torque_Nm[0];
    EXPECT_NEAR(before, kTs - kK * kV * delta, 1e-9 * kTs);
    sim.advance(tb + delta);
    ASSERT_EQ(sim.mode(0), ContactMode::kSlipPositive) << "cycle " << n;
    EXPECT_EQ(sim.counters().breakaway_events, n + 1);

    sim.advance(tr - delta);
    ASSERT_EQ(sim.mode(0), ContactMode::kSlipPositive) << "cycle " << n;
    EXPECT_EQ(sim.counters().stick_events, n);
    sim.advance(tr + delta);
    ASSERT_EQ(sim.mode(0), ContactMode::kStuck) << "cycle " << n;
    EXPECT_EQ(sim.counters().stick_events, n + 1);
    // Just after re-stick: k θ = k θ_r + k V δ.
    const double after = sim.sample().shaft_torque_Nm[0];
    EXPECT_NEAR(after, kK * theta_r() + kK * kV * delta, 1e-9 * kTs);
    // Jump 2 (T_s − T_k), corrected for the ±δ offsets; 1e-6 relative as asked.
    const double jump = (before + kK * kV * delta) - (after - kK * kV * delta);
    EXPECT_NEAR(jump / (2 * (kTs - kTk)), 1.0, 1e-6);
  }
  EXPECT_EQ(sim.counters().reversal_events, 0);
}

// From rest the first stick is a harmonic arc about θ_k from x = −θ_k with zero speed:
//     x = −θ_k cos ω_n t,  v = θ_k ω_n sin ω_n t  →  stick at v = V:
//     t_1 = asin(V/(θ_k ω_n)) / ω_n = 1.999 ms,  θ_1 = θ_k − sqrt(θ_k² − (V/ω_n)²)
// (needs θ_k ω_n = 3.16 rad/s >= V). Then stuck until k θ = T_s: t_b = t_1 + (θ_s − θ_1)/V.
// From the breakaway on, the cycle above: re-stick at t_b + t_slip with k θ = 2 T_k − T_s.
TEST(DynamicsStickSlip, FirstStickFromRestIsLocatedToTheEventTolerance) {
  Belt b;
  Simulation sim(b.net, tight());
  sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(kV, 0.0));
  ASSERT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  const double thk = kTk / kK, wn = omega_n(), delta = 1e-9;
  const double t1 = std::asin(kV / (thk * wn)) / wn;
  const double th1 = thk - std::sqrt(thk * thk - kV * kV / (wn * wn));
  sim.advance(t1 - delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  EXPECT_GT(sim.sample().contact_slip_rad_s[0], 0.0);
  sim.advance(t1 + delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_EQ(sim.counters().stick_events, 1);
  EXPECT_NEAR(sim.sample().theta_rad[b.m], th1 + kV * delta, 1e-11);
  EXPECT_EQ(sim.sample().contact_slip_rad_s[0], 0.0);

  const double tb = t1 + (kTs / kK - th1) / kV;
  sim.advance(tb - delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  sim.advance(tb + delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  const double tr = tb + t_slip();
  sim.advance(tr - delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  sim.advance(tr + delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_NEAR(sim.sample().contact_torque_Nm[0], 2 * kTk - kTs + kK * kV * delta, 1e-9 * kTs);
}

// Event root finding must terminate when the time is so large that adjacent doubles are further
// apart than event_time_tol_s (ulp(3e4 s) = 3.6e-12 s > 1e-12 s). Same cycle, shifted by t0.
TEST(DynamicsStickSlip, EventsAreLocatedAtLargeTimes) {
  Belt b;
  Simulation sim(b.net, tight());
  const double t0 = 3e4, delta = 1e-8;  // δ well above ulp(t0)
  sim.initialize(t0, Eigen::Vector2d(0.0, theta_r()), Eigen::Vector2d(kV, kV));
  sim.advance(t0 + t_stick() - delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  sim.advance(t0 + t_stick() + delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  sim.advance(t0 + t_stick() + t_slip() + delta);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_EQ(sim.counters().stick_events, 1);
  EXPECT_EQ(sim.counters().breakaway_events, 1);
}

// Static capacity growing with the time stuck, T_s(τ) = T_s0 + β τ (β = 100 N m/s), same belt.
// Stuck from θ_r at τ = 0:  k (θ_r + V τ) = T_s0 + β τ  →  τ_b = (T_s0 − k θ_r)/(k V − β) = 25 ms
// (20 ms without ageing). Breakaway torque T_b = T_s0 + β τ_b = 17.5 N m, so the slip arc has
// x0' = (T_b − T_k)/k and re-sticks after t_slip' = (π + 2 atan(V/(ω_n x0')))/ω_n at
// θ_r' = θ_k − x0' (k θ_r' = 2.5 N m). The stick time restarts from zero there:
// τ_b' = (T_s0 − k θ_r')/(k V − β) = 31.25 ms.
TEST(DynamicsStickSlip, CapacityGrowingWithStickTimeDelaysBreakaway) {
  using shudder::dynamics::testing::AgeingCoulombLaw;
  const double beta = 100.0, delta = 1e-9;
  TorsionalNetwork net;
  const int d = net.add_inertia({"belt", 1.0});
  const int m = net.add_inertia({"mass", kJm});
  net.add_speed_source({"drive", d, [](double) { return kV; }, [](double) { return 0.0; }});
  net.add_shaft({"spring", m, kGround, kK, 0.0});
  net.add_contact({"contact", d, m, std::make_shared<AgeingCoulombLaw>(kTk, kTs, beta)});
  Simulation sim(net, tight());
  sim.initialize(0.0, Eigen::Vector2d(0.0, theta_r()), Eigen::Vector2d(kV, kV));

  const double tau_b = (kTs - kK * theta_r()) / (kK * kV - beta);
  const double x0 = (kTs + beta * tau_b - kTk) / kK;
  const double slip = (std::numbers::pi + 2 * std::atan(kV / (omega_n() * x0))) / omega_n();
  const double theta_r2 = kTk / kK - x0;
  const double tau_b2 = (kTs - kK * theta_r2) / (kK * kV - beta);
  EXPECT_NEAR(tau_b, 0.025, 1e-15);
  EXPECT_NEAR(kK * theta_r2, 2.5, 1e-12);

  const double events[3] = {tau_b, tau_b + slip, tau_b + slip + tau_b2};
  const ContactMode before[3] = {ContactMode::kStuck, ContactMode::kSlipPositive, ContactMode::kStuck};
  for (int i = 0; i < 3; ++i) {
    sim.advance(events[i] - delta);
    EXPECT_EQ(sim.mode(0), before[i]) << "event " << i;
    sim.advance(events[i] + delta);
    EXPECT_NE(sim.mode(0), before[i]) << "event " << i;
  }
  EXPECT_EQ(sim.counters().breakaway_events, 2);
  EXPECT_EQ(sim.counters().stick_events, 1);
}

// ---------------------------------------------------------------------------------------------
// A contact that cannot hold when its slip reaches zero slips on the other way (a reversal).
//   T0 = −5 N m ──▶ [ J = 0.5 ] ══ c ══| ground      Coulomb T_k = 2, T_s = 3 N m, ω(0) = 4 rad/s
//   slip +:  J ω' = T0 − T_k = −7  →  ω = 4 − 14 t, zero at t1 = 2/7 s
//   at rest the contact would have to hold |T0| = 5 > T_s  →  slip −:  J ω' = T0 + T_k = −3
//   →  ω = −6 (t − t1);  contact torque (on ground, b) = s T_k: +2 then −2.
// ---------------------------------------------------------------------------------------------
TEST(DynamicsStickSlip, SlipReversesWhenTheContactCannotHold) {
  TorsionalNetwork net;
  const int n = net.add_inertia({"J", 0.5});
  net.add_torque_source({"T0", n, [](double) { return -5.0; }});
  net.add_contact({"c", n, kGround, std::make_shared<CoulombLaw>(2.0, 3.0)});
  Simulation sim(net, tight(1e-3));
  sim.initialize(0.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 4.0));
  const double t1 = 2.0 / 7.0;
  std::vector<double> times;
  for (int i = 1; i < 60; ++i) times.push_back(0.01 * i + 0.0013);
  int n_samples = 0;
  sim.advance(0.6, times, [&](const Sample& s) {
    ++n_samples;
    const bool before = s.t_s < t1;
    EXPECT_EQ(s.modes[0], before ? ContactMode::kSlipPositive : ContactMode::kSlipNegative);
    EXPECT_NEAR(s.omega_rad_s[0], before ? 4 - 14 * s.t_s : -6 * (s.t_s - t1), 1e-9) << "t = " << s.t_s;
    EXPECT_EQ(s.contact_torque_Nm[0], before ? 2.0 : -2.0);
  });
  EXPECT_EQ(n_samples, 59);
  EXPECT_EQ(sim.counters().reversal_events, 1);
  EXPECT_EQ(sim.counters().stick_events, 0);
  EXPECT_EQ(sim.counters().breakaway_events, 0);
}

// =============================================================================================
// Two contacts in series that stick at the same instant and break away one after the other.
//
//   T(t) ──▶ [ J1 ] ══ c1 ══ [ J2 ] ══ c2 ══ [ J3 ]      J1 = 0.1, J2 = 0.2, J3 = 0.3 kg m²
//                  T_k1 = 2, S1 = 8        T_k2 = 1.5, S2 = 3 N m     (Coulomb; J = ΣJ = 0.6)
//   T(t) = ρ (t − t0) for t > t0 = 0.2 s, else 0;  ρ = 10 N m/s.   λ = torque of a contact on b.
//
// Phase 1, both slipping positive (0 < t < t*):
//   J1 ω1' = −T_k1, J2 ω2' = T_k1 − T_k2, J3 ω3' = T_k2  →  ω1' = −20, ω2' = 2.5, ω3' = 5
//   Δω1' = −22.5, Δω2' = −2.5.  Start ω = (12.25, 10, 9.75): Δω1 = 2.25, Δω2 = 0.25
//   → both reach zero at t* = 0.1 s, with ω = 10.25 (= total momentum 6.15 / J).
// Phase 2, all stuck (t* < t < t_b2): one rigid body, ω' = T/J, ω = 10.25 + ρ (t − t0)²₊ / (2J).
//   Free bodies: J1 ω' = T − λ1 → λ1 = T (1 − J1/J) = 5T/6;  J3 ω' = λ2 → λ2 = T J3/J = T/2.
//   λ2 reaches S2 = 3 at T = 6, t_b2 = 0.8 s (λ1 = 5 < 8 then). ω(t_b2) = 13.25.
// Phase 3, c1 stuck, c2 slipping positive (λ2 > 0 was dragging J3 along, so J2 runs ahead):
//   J3 ω3' = T_k2 → ω3 = 13.25 + 5 (t − 0.8)
//   (J1+J2) ω12' = T − T_k2 → ω12 = 13.25 + [5((t − 0.2)² − 0.36) − 1.5 (t − 0.8)] / 0.3
//   λ1 = T − J1 ω12' = (2T + 1.5)/3 (drops from 5 to 4.5 at t_b2), reaches S1 = 8 at T = 11.25,
//   t_b1 = 1.325 s.
// Phase 4, both slipping positive: ω1' = (T − T_k1)/J1, ω2' = (T_k1 − T_k2)/J2 = 2.5, ω3' = 5;
//   Δω2 is still 9.8 rad/s at t_b1 and falls at 2.5 rad/s², so no re-stick before 1.5 s.
// =============================================================================================
struct Chain {
  static constexpr double j1 = 0.1, j2 = 0.2, j3 = 0.3, rho = 10.0, t0 = 0.2;
  static constexpr double tk1 = 2.0, s1 = 8.0, tk2 = 1.5, s2 = 3.0;
  static constexpr double t_star = 0.1, t_b2 = 0.8, t_b1 = 1.325;
  TorsionalNetwork net;
  Chain() {
    const int a = net.add_inertia({"J1", j1});
    const int b = net.add_inertia({"J2", j2});
    const int c = net.add_inertia({"J3", j3});
    net.add_torque_source({"ramp", a, torque});
    net.add_contact({"c1", a, b, std::make_shared<CoulombLaw>(tk1, s1)});
    net.add_contact({"c2", b, c, std::make_shared<CoulombLaw>(tk2, s2)});
  }
  static double torque(double t) { return t > t0 ? rho * (t - t0) : 0.0; }

  struct Expected {
    double w1, w2, w3, l1, l2;
    ContactMode m1, m2;
  };
  static Expected at(double t) {
    const double T = torque(t);
    const auto slip = ContactMode::kSlipPositive, stuck = ContactMode::kStuck;
    if (t < t_star) return {12.25 - 20 * t, 10 + 2.5 * t, 9.75 + 5 * t, tk1, tk2, slip, slip};
    const auto w_rigid = [](double s) {
      return 10.25 + rho * std::pow(std::max(s - t0, 0.0), 2) / (2 * (j1 + j2 + j3));
    };
    if (t < t_b2) {
      const double w = w_rigid(t);
      return {w, w, w, T * (1 - j1 / (j1 + j2 + j3)), T * j3 / (j1 + j2 + j3), stuck, stuck};
    }
    const double w_b2 = w_rigid(t_b2);
    const auto w12 = [&](double s) {
      return w_b2 + (0.5 * rho * (std::pow(s - t0, 2) - std::pow(t_b2 - t0, 2)) - tk2 * (s - t_b2)) / (j1 + j2);
    };
    const double w3 = w_b2 + tk2 / j3 * (t - t_b2);
    if (t < t_b1) return {w12(t), w12(t), w3, (2 * T + 1.5) / 3, tk2, stuck, slip};
    const double w_b1 = w12(t_b1);
    const double w1 = w_b1 + (0.5 * rho * (std::pow(t - t0, 2) - std::pow(t_b1 - t0, 2)) - tk1 * (t - t_b1)) / j1;
    const double w2 = w_b1 + (tk1 - tk2) / j2 * (t - t_b1);
    return {w1, w2, w3, tk1, tk2, slip, slip};
  }
};

// The simulated chain at the hand-derived instants t* = 0.1 s, t_b2 = 0.8 s, t_b1 = 1.325 s:
// just before and after each (δ = 1e-6 s, far above the 1e-12 s event tolerance, far below the
// phases' lengths) the contacts' modes flip as derived, and speeds and contact torques equal
// the phase solutions above (Chain::at) to 1e-6, the integration and KKT accuracy of the file
// comment. The quoted hand numbers hold to their change over δ: ω = 10.25 at t*, ω1 = 13.25
// and λ2 = S2 = 3 N m at t_b2 (rates 10 rad/s² and 5 N m/s: 1e-5), λ1 = S1 = 8 N m at t_b1.
TEST(DynamicsStickSlip, ChainEventsHappenAtTheHandDerivedInstants) {
  Chain ch;
  Simulation sim(ch.net, tight(1e-3));
  sim.initialize(0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(12.25, 10.0, 9.75));
  const double d = 1e-6;
  const auto check = [&](double t, ContactMode m1, ContactMode m2) {
    sim.advance(t);
    const Sample s = sim.sample();
    const auto e = Chain::at(t);
    EXPECT_EQ(e.m1, m1) << "t = " << t;  // the derivation's modes
    EXPECT_EQ(e.m2, m2) << "t = " << t;
    EXPECT_EQ(sim.mode(0), m1) << "t = " << t;
    EXPECT_EQ(sim.mode(1), m2) << "t = " << t;
    EXPECT_NEAR(s.omega_rad_s[0], e.w1, 1e-6) << "t = " << t;
    EXPECT_NEAR(s.omega_rad_s[1], e.w2, 1e-6) << "t = " << t;
    EXPECT_NEAR(s.omega_rad_s[2], e.w3, 1e-6) << "t = " << t;
    EXPECT_NEAR(s.contact_torque_Nm[0], e.l1, 1e-6) << "t = " << t;
    EXPECT_NEAR(s.contact_torque_Nm[1], e.l2, 1e-6) << "t = " << t;
    return s;
  };
  const auto stuck = ContactMode::kStuck, slip = ContactMode::kSlipPositive;
  check(0.1 - d, slip, slip);
  const Sample at_star = check(0.1 + d, stuck, stuck);
  EXPECT_NEAR(at_star.omega_rad_s[0], 10.25, 1e-5);
  const Sample before_b2 = check(0.8 - d, stuck, stuck);
  EXPECT_NEAR(before_b2.omega_rad_s[0], 13.25, 2e-5);
  EXPECT_NEAR(before_b2.contact_torque_Nm[1], 3.0, 2e-5);
  check(0.8 + d, stuck, slip);
  const Sample before_b1 = check(1.325 - d, stuck, slip);
  EXPECT_NEAR(before_b1.contact_torque_Nm[0], 8.0, 2e-5);
  check(1.325 + d, slip, slip);
  EXPECT_EQ(sim.counters().stick_events, 2);
  EXPECT_EQ(sim.counters().breakaway_events, 2);
}

TEST(DynamicsStickSlip, TwoContactsStickTogetherAndBreakAwayInTurn) {
  Chain ch;
  Simulation sim(ch.net, tight(1e-3));
  sim.initialize(0.0, Eigen::Vector3d::Zero(), Eigen::Vector3d(12.25, 10.0, 9.75));
  // Samples on a grid that never coincides with an event (0.0037 + 0.01 i).
  std::vector<double> times;
  for (int i = 0; i < 150; ++i) times.push_back(0.0037 + 0.01 * i);
  int n = 0;
  const auto check = [&](const Sample& s) {
    ++n;
    const auto e = Chain::at(s.t_s);
    EXPECT_EQ(s.modes[0], e.m1) << "t = " << s.t_s;
    EXPECT_EQ(s.modes[1], e.m2) << "t = " << s.t_s;
    EXPECT_NEAR(s.omega_rad_s[0], e.w1, 1e-6) << "t = " << s.t_s;
    EXPECT_NEAR(s.omega_rad_s[1], e.w2, 1e-6) << "t = " << s.t_s;
    EXPECT_NEAR(s.omega_rad_s[2], e.w3, 1e-6) << "t = " << s.t_s;
    EXPECT_NEAR(s.contact_torque_Nm[0], e.l1, 1e-6) << "t = " << s.t_s;
    EXPECT_NEAR(s.contact_torque_Nm[1], e.l2, 1e-6) << "t = " << s.t_s;
    if (e.m1 == ContactMode::kStuck) {
      EXPECT_EQ(s.contact_slip_rad_s[0], 0.0);
    }
    if (e.m2 == ContactMode::kStuck) {
      EXPECT_EQ(s.contact_slip_rad_s[1], 0.0);
    }
  };
  // Stop ±δ around each analytic event to check its instant, sampling in between.
  const double delta = 1e-9;
  sim.advance(Chain::t_star - delta, times, check);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  EXPECT_EQ(sim.mode(1), ContactMode::kSlipPositive);
  sim.advance(Chain::t_star + delta, times, check);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_EQ(sim.mode(1), ContactMode::kStuck);
  EXPECT_EQ(sim.counters().stick_events, 2);  // both in one event

  sim.advance(Chain::t_b2 - delta, times, check);
  EXPECT_EQ(sim.mode(1), ContactMode::kStuck);
  sim.advance(Chain::t_b2 + delta, times, check);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_EQ(sim.mode(1), ContactMode::kSlipPositive);
  EXPECT_EQ(sim.counters().breakaway_events, 1);
  // λ1 dropped from 5 to 4.5 when c2 let go.
  EXPECT_NEAR(sim.sample().contact_torque_Nm[0], 4.5, 1e-6);

  sim.advance(Chain::t_b1 - delta, times, check);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  sim.advance(Chain::t_b1 + delta, times, check);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  EXPECT_EQ(sim.counters().breakaway_events, 2);

  sim.advance(1.5, times, check);
  EXPECT_EQ(n, 150);
  EXPECT_EQ(sim.counters().stick_events, 2);
  EXPECT_EQ(sim.counters().reversal_events, 0);
}

// =============================================================================================
// Two contacts in PARALLEL between the same nodes: their stuck constraints are dependent.
//
//   T0 ──▶ [ J1 ] ══ ca ══ [ J2 ]       J1 = 0.1, J2 = 0.3 kg m², T0 = 3 N m
//                 ══ cb ══               ca: T_k = 1, cb: T_k = 0.5
//
// Start ω = (0, 5): Δω = −5, both slipping negative, so J2 gets −(1 + 0.5) and J1 gets +1.5:
//   ω1' = (3 + 1.5)/0.1 = 45, ω2' = −1.5/0.3 = −5, Δω' = 50  →  stick at t* = 0.1 s, ω = 4.5.
// Then rigid: ω' = T0/(J1+J2) = 7.5; the torque the contacts must hold together (on J2):
//   λa + λb = J2 ω' = 2.25 N m.
// How it is split between dependent constraints is not physics; the sum is.
// =============================================================================================
struct Parallel {
  TorsionalNetwork net;
  explicit Parallel(double capacity_a) {
    const int a = net.add_inertia({"J1", 0.1});
    const int b = net.add_inertia({"J2", 0.3});
    net.add_torque_source({"T0", a, [](double) { return 3.0; }});
    net.add_contact({"ca", a, b, std::make_shared<CoulombLaw>(1.0, capacity_a)});
    net.add_contact({"cb", a, b, std::make_shared<CoulombLaw>(0.5, 2.0)});
  }
};

void expect_parallel_holds(const Simulation& sim) {
  const Sample s = sim.sample();
  for (int i = 0; i < 2; ++i) {
    EXPECT_TRUE(std::isfinite(s.omega_rad_s[i]));
    EXPECT_TRUE(std::isfinite(s.contact_torque_Nm[i]));
    EXPECT_NEAR(s.omega_rad_s[i], 4.5 + 7.5 * (s.t_s - 0.1), 1e-6);
    EXPECT_EQ(s.contact_slip_rad_s[i], 0.0);
  }
  EXPECT_NEAR(s.contact_torque_Nm[0] + s.contact_torque_Nm[1], 2.25, 1e-9);
}

TEST(DynamicsStickSlip, ParallelContactsStickTogether) {
  Parallel p(2.0);
  Simulation sim(p.net, tight(1e-3));
  sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.0, 5.0));
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipNegative);
  sim.advance(0.1 - 1e-9);
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipNegative);
  sim.advance(0.1 + 1e-9);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_EQ(sim.mode(1), ContactMode::kStuck);
  EXPECT_EQ(sim.counters().stick_events, 2);
  expect_parallel_holds(sim);
  sim.advance(0.3);
  EXPECT_EQ(sim.mode(0), ContactMode::kStuck);
  EXPECT_EQ(sim.mode(1), ContactMode::kStuck);
  expect_parallel_holds(sim);
  const Sample s = sim.sample();
  EXPECT_LE(std::abs(s.contact_torque_Nm[0]), 2.0);
  EXPECT_LE(std::abs(s.contact_torque_Nm[1]), 2.0);
}

// ca cannot take its share: it slips on at zero relative speed, carrying its kinetic torque 1 N m
// in the direction of the holding torque, and cb holds the rest, 1.25 N m < 2. Sum unchanged.
TEST(DynamicsStickSlip, ParallelContactsWithAWeakOneStillHoldTheSum) {
  Parallel p(0.9);
  Simulation sim(p.net, tight(1e-3));
  sim.initialize(0.0, Eigen::Vector2d::Zero(), Eigen::Vector2d(0.0, 5.0));
  EXPECT_NO_THROW(sim.advance(0.3));
  EXPECT_EQ(sim.mode(0), ContactMode::kSlipPositive);
  EXPECT_EQ(sim.mode(1), ContactMode::kStuck);
  expect_parallel_holds(sim);
  EXPECT_NEAR(sim.sample().contact_torque_Nm[0], 1.0, 1e-12);
  EXPECT_NEAR(sim.sample().contact_torque_Nm[1], 1.25, 1e-9);
}

}  // namespace
