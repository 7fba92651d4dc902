// ThermalModel::step_bdf2 (variable-step BDF2, clutch/thermal_model.hpp) against closed forms
// and against backward Euler:
//
//   1. second order in time, with constant and with alternating step sizes
//   2. the heat account's trapezoidal sum, exactly as its closed form for a quadratic heat
//   3. the ledger closes to round-off with every effect on, random steps; its scheme term
//      shrinks with the step
//   4. the steady state is backward Euler's (both solve K T = q there)
//   5. history: the first step and any after a backward Euler step are backward Euler; the
//      film temperatures extrapolated linearly
//
// Each case builds ThermalParams directly and switches off the effects it does not test.
#include <gtest/gtest.h>

#include <cmath>
#include <functional>
#include <random>
#include <vector>

#include "clutch/thermal_model.hpp"

namespace {

using shudder::clutch::OilFlowLaw;
using shudder::clutch::ThermalModel;
using shudder::clutch::ThermalParams;
using shudder::clutch::ThermalState;
using shudder::clutch::ThermalWorkspace;

// Paper G geometry and materials with the interface oil cooling on (its flow depends on the
// slip and the film temperature, which BDF2 extrapolates); sump and rig mass off: their
// explicit one-step lag is first order under either scheme.
ThermalParams cooled_params() {
  ThermalParams p;
  p.interface_oil_cooling = true;
  p.oil_flow = OilFlowLaw{.a = 0.02, .b = 0.5, .c = 2e-5, .d = 1.0, .e = 0.005};
  p.sump_heating = false;
  p.rig_heat_capacity = false;
  p.temperature_sensor_lag = false;
  return p;
}

double order(double err_coarse, double err_fine) { return std::log2(err_coarse / err_fine); }

// Ring heat at time t: 60 kW/m² rising by half over a 0.3 s period, smooth (so the scheme's
// order shows), with a slip that moves the oil flow.
Eigen::VectorXd heat_at(const ThermalModel& m, double t) {
  return 6e4 * (1.0 + 0.5 * std::sin(2.0 * M_PI * t / 0.3)) * m.ring_area_m2();
}
double slip_at(double t) { return 5.0 + 3.0 * std::cos(2.0 * M_PI * t / 0.7); }

// The field after 1 s of BDF2 with the steps `pattern` repeated (their sum divides 1 s).
Eigen::VectorXd bdf2_field(const std::vector<double>& pattern) {
  const ThermalModel model(cooled_params());
  ThermalWorkspace ws(model);
  ThermalState s = model.initial_state(60.0, 60.0, 60.0);
  double period = 0.0;
  for (double h : pattern) period += h;
  const long repeats = std::lround(1.0 / period);
  for (long r = 0; r < repeats; ++r)
    for (double h : pattern) {
      const double t1 = s.time_s + h;
      model.step_bdf2(s, ws, h, heat_at(model, t1), slip_at(t1));
    }
  return s.temp_C;
}

// 1. Error = max nodal difference to a dt = 1e-4 s BDF2 reference on the same grid (the spatial
// error cancels). BDF2's global error is C dt² (its one backward Euler start step adds O(dt²)
// too), so halving the step divides it by 4: observed order 2. The reference's own error is
// (1e-4 / 2.5e-3)² = 0.2 % of the finest error. Band [1.7, 2.3]: backward Euler (order 1) or a
// first-order slip in the heat timing or the extrapolation would fail it.
TEST(ThermalBdf2, ConvergesAtSecondOrderInTime) {
  const Eigen::VectorXd ref = bdf2_field({1e-4});
  std::vector<double> err;
  for (const double dt : {0.02, 0.01, 0.005, 0.0025}) err.push_back((bdf2_field({dt}) - ref).cwiseAbs().maxCoeff());
  for (std::size_t k = 0; k + 1 < err.size(); ++k) {
    const double p = order(err[k], err[k + 1]);
    EXPECT_GE(p, 1.7) << "halving " << k << ": errors " << err[k] << ", " << err[k + 1];
    EXPECT_LE(p, 2.3) << "halving " << k;
  }
}

// Steps alternating 0.6 u and 1.4 u (step ratios w = 7/3 and 3/7): the variable-step
// coefficients keep the order 2 (with constant-step coefficients the scheme would be first
// order or worse at these ratios).
TEST(ThermalBdf2, ConvergesAtSecondOrderWithAlternatingSteps) {
  const Eigen::VectorXd ref = bdf2_field({1e-4});
  std::vector<double> err;
  for (const double u : {0.02, 0.01, 0.005, 0.0025})
    err.push_back((bdf2_field({0.6 * u, 1.4 * u}) - ref).cwiseAbs().maxCoeff());
  for (std::size_t k = 0; k + 1 < err.size(); ++k) {
    const double p = order(err[k], err[k + 1]);
    EXPECT_GE(p, 1.7) << "halving " << k << ": errors " << err[k] << ", " << err[k + 1];
    EXPECT_LE(p, 2.3) << "halving " << k;
  }
}

// 2. The heat generated is booked by the trapezoidal rule over each step's ends, the first
// (backward Euler) step as dt·q(dt). For q(t) = Q (1 + t²) on [0, 1] with N steps of dt:
//   exact integral                      Q (1 + 1/3)
//   trapezoid error (exact for q'' = 2Q) + (1 − 0) dt² q'' / 12 = Q dt² / 6
//   first step dt q(dt) − dt (q(0) + q(dt)) / 2 = dt (q(dt) − q(0)) / 2 = Q dt³ / 2
// so generated = Q (4/3 + dt²/6 + dt³/2) to round-off. (Booking dt·q(t1), as the BDF2 solve
// does, would be off by dt (q(1) − q(0)) / 2 = Q dt / 2.)
TEST(ThermalBdf2, GeneratedHeatIsTheTrapezoidalSumInClosedForm) {
  const ThermalModel model(cooled_params());
  for (const int n : {10, 40, 250}) {
    ThermalWorkspace ws(model);
    ThermalState s = model.initial_state(60.0, 60.0, 60.0);
    const double dt = 1.0 / n;
    const Eigen::VectorXd base = 2e4 * model.ring_area_m2();
    const double Q = base.sum();
    for (int k = 1; k <= n; ++k) {
      const double t1 = k * dt;
      model.step_bdf2(s, ws, dt, base * (1.0 + t1 * t1), 5.0);
    }
    const double expected = Q * (4.0 / 3.0 + dt * dt / 6.0 + dt * dt * dt / 2.0);
    EXPECT_NEAR(s.energy.generated_J, expected, 1e-12 * expected) << n << " steps";
  }
}

// 3. Every thermal effect on (sump heating and rig mass too), random ring heats, random steps
// between 2 and 30 ms (step ratios up to 15), oscillating slip. The ledger
//   generated − (stored − stored0) − scheme_storage − to_sump − to_rig
// computes the scheme term from the fields and rates alone (thermal_model.hpp), so it closes
// only if the solve satisfied the BDF2 balance: round-off, ~1e-12 relative after 600 steps;
// tolerance 1e-9.
TEST(ThermalBdf2, LedgerClosesToRoundOffWithEveryEffectOnAndRandomSteps) {
  ThermalParams p = cooled_params();
  p.sump_heating = true;
  p.rig_heat_capacity = true;
  p.temperature_sensor_lag = true;
  const ThermalModel model(p);
  ThermalWorkspace ws(model);
  ThermalState s = model.initial_state(50.0, 50.0, 50.0);
  std::mt19937 rng(20261124);
  std::uniform_real_distribution<double> ring_heat(0.0, 60.0), step(0.002, 0.03);
  Eigen::VectorXd heat(model.radial_cells());
  for (int n = 0; n < 600; ++n) {
    for (int i = 0; i < heat.size(); ++i) heat[i] = ring_heat(rng);
    model.step_bdf2(s, ws, step(rng), heat, 20.0 * std::sin(0.7 * s.time_s) + 3.0 * (n % 7));
  }
  const auto& e = s.energy;
  EXPECT_GT(e.generated_J, 3e3);  // ~5.6 kJ: every path carried heat, the balance is not trivial
  EXPECT_GT(e.to_sump_J, 1e-3 * e.generated_J);
  EXPECT_GT(e.to_rig_J, 1e-4 * e.generated_J);
  EXPECT_NE(e.scheme_storage_J, 0.0);
  EXPECT_LT(std::abs(model.energy_imbalance_J(s)) / e.generated_J, 1e-9)
      << "imbalance " << model.energy_imbalance_J(s) << " J";
  // The sump took exactly its ledger energy (explicit, as under backward Euler).
  EXPECT_NEAR(s.sump_temp_C - 50.0, e.to_sump_J / model.sump_heat_capacity_J_per_K(), 1e-9);
}

// The scheme term is the difference between what BDF2 balances and the trapezoidal account; it
// telescopes to the first and last steps' terms, which nearly cancel against the trapezoid's end
// corrections (C ΔT_last ≈ dt (q − out) at the end): it shrinks like dt² (measured: 1.04, 0.233,
// 0.047 J for 40, 20, 10 ms of a 665 J run) instead of growing with the run. Bound: a factor
// 0.36 = 2^-1.5 per halving, which a term of first order (0.5) or a drifting one would break.
TEST(ThermalBdf2, SchemeStorageTermShrinksWithTheStep) {
  const ThermalModel model(cooled_params());
  std::vector<double> scheme;
  for (const double dt : {0.04, 0.02, 0.01}) {
    ThermalWorkspace ws(model);
    ThermalState s = model.initial_state(60.0, 60.0, 60.0);
    const long n = std::lround(2.0 / dt);
    for (long k = 1; k <= n; ++k) model.step_bdf2(s, ws, dt, heat_at(model, k * dt), slip_at(k * dt));
    scheme.push_back(std::abs(s.energy.scheme_storage_J));
  }
  EXPECT_LT(scheme[1], 0.36 * scheme[0]);
  EXPECT_LT(scheme[2], 0.36 * scheme[1]);
}

// 4. Constant heat and slip: both schemes' fixed points solve K T = q + boundary terms (BDF2's
// storage term a T − b T + c T vanishes for a steady field since a − b + c = 0). After 600 s of
// 0.5 s steps the slowest mode (radial conduction across the disc, τ ≈ 25 s) has decayed by
// e^-24 ≈ 4e-11; tolerance 1e-6 K.
TEST(ThermalBdf2, SteadyStateIsBackwardEulers) {
  const ThermalModel model(cooled_params());
  const Eigen::VectorXd heat = 3e4 * model.ring_area_m2();
  ThermalWorkspace ws_be(model), ws_bdf(model);
  ThermalState be = model.initial_state(60.0, 60.0, 60.0), bdf = be;
  for (int n = 0; n < 1200; ++n) {
    model.step(be, ws_be, 0.5, heat, 5.0);
    model.step_bdf2(bdf, ws_bdf, 0.5, heat, 5.0);
  }
  EXPECT_GT(be.temp_C.maxCoeff() - 60.0, 1.0);  // it did heat up
  EXPECT_LT((be.temp_C - bdf.temp_C).cwiseAbs().maxCoeff(), 1e-6);
}

// 5. The first BDF2 step is backward Euler (bit for bit, with the same heat), and a backward
// Euler step in between drops the history, so the next BDF2 step is backward Euler again.
TEST(ThermalBdf2, StartsAndRestartsWithABackwardEulerStep) {
  const ThermalModel model(cooled_params());
  const Eigen::VectorXd heat = 4e4 * model.ring_area_m2();
  ThermalWorkspace ws_a(model), ws_b(model);
  ThermalState a = model.initial_state(60.0, 60.0, 60.0), b = a;
  model.step_bdf2(a, ws_a, 0.01, heat, 5.0);
  model.step(b, ws_b, 0.01, heat, 5.0);
  EXPECT_EQ(a.temp_C, b.temp_C);
  EXPECT_EQ(a.history.step_s, 0.01);
  model.step_bdf2(a, ws_a, 0.01, heat, 5.0);  // a real BDF2 step: differs from backward Euler
  model.step(b, ws_b, 0.01, heat, 5.0);
  EXPECT_GT((a.temp_C - b.temp_C).cwiseAbs().maxCoeff(), 1e-6);
  model.step(a, ws_a, 0.01, heat, 5.0);
  EXPECT_EQ(a.history.step_s, 0.0);
  ThermalState c = a;
  ThermalWorkspace ws_c(model);
  model.step_bdf2(a, ws_a, 0.01, heat, 5.0);
  model.step(c, ws_c, 0.01, heat, 5.0);
  EXPECT_EQ(a.temp_C, c.temp_C);
}

// The film temperatures extrapolated to t + dt lie on the line through the last two fields:
// T0 + (dt / dt_prev)(T0 − T−1); without history they are the current ones.
TEST(ThermalBdf2, PredictedFilmTemperaturesExtrapolateLinearly) {
  const ThermalModel model(cooled_params());
  const Eigen::VectorXd heat = 4e4 * model.ring_area_m2();
  ThermalWorkspace ws(model);
  ThermalState s = model.initial_state(60.0, 60.0, 60.0);
  Eigen::VectorXd predicted;
  model.predicted_interface_temps_C(s, 0.02, predicted);
  EXPECT_EQ(predicted, model.interface_temps_C(s));
  model.step_bdf2(s, ws, 0.01, heat, 5.0);
  model.step_bdf2(s, ws, 0.01, heat, 5.0);
  const Eigen::VectorXd before = [&] {
    ThermalState h = s;
    h.temp_C = s.history.temp_C;
    return model.interface_temps_C(h);
  }();
  const Eigen::VectorXd now = model.interface_temps_C(s);
  model.predicted_interface_temps_C(s, 0.03, predicted);  // w = 3
  for (int i = 0; i < now.size(); ++i) EXPECT_NEAR(predicted[i], now[i] + 3.0 * (now[i] - before[i]), 1e-12 * now[i]);
  EXPECT_GT((predicted - now).cwiseAbs().minCoeff(), 1e-3);  // the film is still heating
}

}  // namespace
