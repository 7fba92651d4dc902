// Network components against closed forms. Each case states its derivation; tolerances are the
// integrator's (rel_tol 1e-6 per step: speeds to ~1e-6 relative), or one sample interval where a
// time is read off the sampled record.
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "components/network_builder.hpp"
#include "core/units.hpp"
#include "tests/components/network_helpers.hpp"

namespace shudder::components {
namespace {

using test::channel;
using test::first_change_s;
using test::inertia;
using test::plain_clutch;
using test::scalar;

double rpm(double rad_s) { return units::rad_s_to_rpm(rad_s); }

NetworkSettings settings(double duration_s, double rate_Hz) {
  NetworkSettings s;
  s.duration_s = duration_s;
  s.sample_rate_Hz = rate_Hz;
  s.integrator.abs_tol = 1e-10;
  s.integrator.rel_tol = 1e-9;
  return s;
}

// Two inertias, constant-mu clutch of kinetic torque T from t = 0 (peak ratio 1):
//   slipping: J1 dw1/dt = -T, J2 dw2/dt = +T, so d(dw)/dt = -T (1/J1 + 1/J2) = -T / J_eff;
//   lock-up at t_L = dw0 J_eff / T, at the common speed w_f = (J1 w1 + J2 w2) / (J1 + J2);
//   heat = the kinetic energy lost = 1/2 J_eff dw0^2.
TEST(NetworkClosedForm, TwoInertiasLockUpTimeSpeedAndHeat) {
  const double j1 = 0.5, j2 = 1.5, w1 = 200.0, w2 = 20.0, T = 60.0;
  NetworkSpec spec;
  spec.inertias = {inertia("a", j1, w1), inertia("b", j2, w2)};
  spec.clutches = {plain_clutch("c", "a", "b", T)};
  spec.settings = settings(2.0, 10000.0);
  const auto run = studies::run_network(spec);
  const double j_eff = j1 * j2 / (j1 + j2), dw0 = w1 - w2;
  const double t_lock = dw0 * j_eff / T, w_f = (j1 * w1 + j2 * w2) / (j1 + j2);
  EXPECT_NEAR(first_change_s(run.recording, "c.stuck"), t_lock, 1e-4);  // one sample
  EXPECT_NEAR(channel(run.recording, "a.speed_rpm").back(), rpm(w_f), 1e-6 * rpm(w_f));
  EXPECT_NEAR(channel(run.recording, "b.speed_rpm").back(), rpm(w_f), 1e-6 * rpm(w_f));
  EXPECT_NEAR(scalar(run.recording, "c.friction_work_J"), 0.5 * j_eff * dw0 * dw0, 1e-6 * 0.5 * j_eff * dw0 * dw0);
  // Before lock-up the clutch carries exactly its kinetic torque.
  EXPECT_NEAR(channel(run.recording, "c.torque_Nm")[100], T, 1e-9 * T);
  EXPECT_LT(std::abs(scalar(run.recording, "mechanical_energy_relative_error")), 1e-8);
}

// A brake (clutch to ground) on inertia J, static capacity T_s = peak * T_k, and a torque ramp
// T(t) = a t on J: the brake holds while a t < T_s and breaks away at t_b = T_s / a; then
//   J dw/dt = a t - T_k, w(t) = (a/2 (t^2 - t_b^2) - T_k (t - t_b)) / J.
TEST(NetworkClosedForm, BrakeBreaksAwayWhenTheTorqueExceedsItsPeak) {
  const double J = 0.2, Tk = 40.0, peak = 1.5, a = 100.0;
  NetworkSpec spec;
  spec.inertias = {inertia("drum", J)};
  spec.clutches = {plain_clutch("brake", "drum", kGroundNode, Tk, peak)};
  spec.torque_sources = {{"load", "drum", Signal::ramp(0.0, a * 2.0, 0.0, 2.0)}};
  spec.settings = settings(1.0, 10000.0);
  const auto run = studies::run_network(spec);
  const double t_b = peak * Tk / a;
  EXPECT_NEAR(first_change_s(run.recording, "brake.stuck"), t_b, 1e-4);
  const double t = 1.0;
  const double w = (0.5 * a * (t * t - t_b * t_b) - Tk * (t - t_b)) / J;
  EXPECT_NEAR(channel(run.recording, "drum.speed_rpm").back(), rpm(w), 1e-6 * rpm(w));
}

// A freewheel transmits torque one way only. Driving inertia J1 with a torque T(t) = T0 sin(2 pi t):
// while T > 0 the freewheel locks and both turn together, w' = T / (J1 + J2); when T turns
// negative it releases at once (t = 0.5 s), the driven side keeps its speed (no torque on it),
// the driving side slows alone.
// Speeds at t = 0.5: w = T0 (1 - cos(pi)) / (2 pi (J1 + J2)) = T0 / (pi (J1 + J2)).
TEST(NetworkClosedForm, FreewheelDrivesOneWayOnly) {
  const double j1 = 0.1, j2 = 0.3, T0 = 10.0;
  NetworkSpec spec;
  spec.inertias = {inertia("driving", j1), inertia("driven", j2)};
  spec.freewheels = {{"sprag", "driving", "driven", 0.0}};
  spec.torque_sources = {{"crank", "driving", Signal::sine(0.0, T0, 1.0, 0.0, 0.0)}};
  spec.settings = settings(0.75, 10000.0);
  const auto run = studies::run_network(spec);
  const auto& t = channel(run.recording, "time_s");
  const auto& w1 = channel(run.recording, "driving.speed_rpm");
  const auto& w2 = channel(run.recording, "driven.speed_rpm");
  const auto& locked = channel(run.recording, "sprag.locked");
  const double w_half = T0 / (std::numbers::pi * (j1 + j2));
  for (std::size_t i = 0; i < t.size(); i += 250) {
    if (t[i] <= 0.5 - 1e-9) {
      const double w = T0 * (1 - std::cos(2 * std::numbers::pi * t[i])) / (2 * std::numbers::pi * (j1 + j2));
      EXPECT_NEAR(w1[i], rpm(w), 1e-6 * rpm(w_half)) << t[i];
      EXPECT_NEAR(w2[i], rpm(w), 1e-6 * rpm(w_half)) << t[i];
      if (t[i] > 0.0 && t[i] < 0.5 - 1e-3) {
        EXPECT_EQ(locked[i], 1.0) << t[i];
      }
    } else if (t[i] > 0.5 + 1e-3) {
      // From 0.5 s the driving side alone: J1 w1' = T0 sin(2 pi t),
      // w1 = w_half - T0 / (2 pi J1) (1 + cos(2 pi t)).
      const double w = w_half - T0 / (2 * std::numbers::pi * j1) * (1 + std::cos(2 * std::numbers::pi * t[i]));
      EXPECT_NEAR(w1[i], rpm(w), 1e-6 * rpm(w_half)) << t[i];
      EXPECT_NEAR(w2[i], rpm(w_half), 1e-6 * rpm(w_half)) << t[i];
      EXPECT_EQ(locked[i], 0.0) << t[i];
    }
  }
}

// Backlash: two inertias with relative speed dw0 and a shaft of total lash b, starting centred in
// the gap: no torque until the flanks meet at t_c = (b/2) / dw0 (free flight, the speeds
// constant). With no damping the contact is an elastic impact: the relative speed reverses to
// -dw0 and the gap is crossed in b / dw0 before the other flanks meet.
TEST(NetworkClosedForm, BacklashFreeFlightAcrossTheGap) {
  const double dw0 = 10.0, lash = 0.2, k = 1e4;
  NetworkSpec spec;
  spec.inertias = {inertia("a", 0.05, dw0), inertia("b", 0.05, 0.0)};
  spec.shafts = {{"shaft", "a", "b", k, 0.0, lash}};
  spec.torque_sources = {{"none", "a", Signal::constant(0.0)}};
  spec.settings = settings(0.06, 100000.0);
  const auto run = studies::run_network(spec);
  const auto& t = channel(run.recording, "time_s");
  const auto& tq = channel(run.recording, "shaft.torque_Nm");
  double first = NAN, release = NAN, second = NAN;
  for (std::size_t i = 1; i < t.size(); ++i) {
    if (std::isnan(first) && tq[i] != 0.0)
      first = t[i];
    else if (!std::isnan(first) && std::isnan(release) && tq[i] == 0.0)
      release = t[i];
    else if (!std::isnan(release) && std::isnan(second) && tq[i] != 0.0)
      second = t[i];
  }
  EXPECT_NEAR(first, 0.5 * lash / dw0, 1e-5);
  // Contact lasts half a period of the pair, pi / sqrt(k / J_eff); then the gap b at dw0.
  const double j_eff = 0.025, contact = std::numbers::pi / std::sqrt(k / j_eff);
  EXPECT_NEAR(release, first + contact, 2e-5);
  EXPECT_NEAR(second, release + lash / dw0, 2e-5);
  EXPECT_LT(std::abs(scalar(run.recording, "mechanical_energy_relative_error")), 1e-7);
}

// A gear pair: input J1 driven by a constant T, output J2, w_in = r w_out. The output reflects
// to the input as J2 / r^2: w_in(t) = T t / (J1 + J2 / r^2).
TEST(NetworkClosedForm, GearReflectsTheOutputInertia) {
  const double j1 = 0.1, j2 = 4.0, r = 5.0, T = 30.0, t_end = 0.5;
  NetworkSpec spec;
  spec.inertias = {inertia("in", j1), inertia("out", j2)};
  spec.gears = {{"pair", "in", "out", r}};
  spec.torque_sources = {{"drive", "in", Signal::constant(T)}};
  spec.settings = settings(t_end, 1000.0);
  const auto run = studies::run_network(spec);
  const double w = T * t_end / (j1 + j2 / (r * r));
  EXPECT_NEAR(channel(run.recording, "in.speed_rpm").back(), rpm(w), 1e-8 * rpm(w));
  EXPECT_NEAR(channel(run.recording, "out.speed_rpm").back(), rpm(w / r), 1e-8 * rpm(w));
}

// Two contacts sticking and slipping in one network, events by hand. J1 = J2 = J3 = 1 kg m^2,
// w1 = 100 rad/s, w2 = w3 = 0; c1 (1-2) kinetic 20 N m, c2 (2-3) 5 N m, peak ratio 1.
//   t = 0: c2 has no slip; stuck it would carry 20 * J3/(J2 + J3) = 10 N m > 5: it slips.
//   phase 1: w1' = -20, w2' = 20 - 5 = 15, w3' = 5; c1 locks when 100 - 20 t = 15 t: t1 = 20/7 s,
//            at w = 300/7; w3(t1) = 100/7.
//   phase 2: J1 + J2 locked, w' = -5/2 (c1 holds 2.5 N m < 20); w3' = 5; c2 locks when
//            300/7 - 2.5 s = 100/7 + 5 s: s = 80/21, t2 = t1 + 80/21 = 20/3 s, at 100/3 rad/s.
//   heat = 1/2 * 100^2 - 1/2 * 3 * (100/3)^2 = 10000/3 J.
TEST(NetworkClosedForm, TwoContactsStickAtTheHandDerivedTimes) {
  NetworkSpec spec;
  spec.inertias = {inertia("one", 1.0, 100.0), inertia("two", 1.0), inertia("three", 1.0)};
  spec.clutches = {plain_clutch("c1", "one", "two", 20.0), plain_clutch("c2", "two", "three", 5.0)};
  spec.settings = settings(8.0, 1000.0);
  const auto run = studies::run_network(spec);
  const auto& t = channel(run.recording, "time_s");
  const auto& w1 = channel(run.recording, "one.speed_rpm");
  const auto& w2 = channel(run.recording, "two.speed_rpm");
  const auto& w3 = channel(run.recording, "three.speed_rpm");
  const double t1 = 20.0 / 7.0, t2 = 20.0 / 3.0;
  const auto expect = [&](double time) {
    struct W {
      double a, b, c;
    };
    if (time <= t1) return W{100 - 20 * time, 15 * time, 5 * time};
    if (time <= t2) {
      const double s = time - t1, w = 300.0 / 7.0 - 2.5 * s;
      return W{w, w, 100.0 / 7.0 + 5 * s};
    }
    return W{100.0 / 3, 100.0 / 3, 100.0 / 3};
  };
  for (std::size_t i = 0; i < t.size(); i += 7) {
    const auto e = expect(t[i]);
    EXPECT_NEAR(w1[i], rpm(e.a), 1e-5) << t[i];
    EXPECT_NEAR(w2[i], rpm(e.b), 1e-5) << t[i];
    EXPECT_NEAR(w3[i], rpm(e.c), 1e-5) << t[i];
  }
  EXPECT_NEAR(first_change_s(run.recording, "c1.stuck"), t1, 1e-3);
  EXPECT_NEAR(first_change_s(run.recording, "c2.stuck"), t2, 1e-3);
  EXPECT_EQ(scalar(run.recording, "stick_events"), 2.0);
  EXPECT_NEAR(scalar(run.recording, "friction_heat_J"), 10000.0 / 3.0, 1e-6 * 10000.0 / 3.0);
}

}  // namespace
}  // namespace shudder::components
