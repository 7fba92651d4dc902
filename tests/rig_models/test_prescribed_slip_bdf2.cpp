// The prescribed-slip runner with `[solver] thermal_scheme = "bdf2"` (rig_models/prescribed_slip.hpp)
// on the shipped Paper G Case 1 scenario (25.3 kN, slip 1 → 100 rpm in 10 s), against the limit
// dt → 0 of backward Euler, which is first order: L = 2 x(2.5 ms) − x(5 ms) (Richardson; its own
// error is O(dt²), 6e-6 °C here against BDF2 at 1.25 ms). Both schemes discretise the same
// semi-discrete equations, so BDF2 must converge to that same limit, at second order.
//
// What the shipped scenario claims (its [solver] comment, docs/thermal_model.md): BDF2 at 40 ms
// is more accurate, over every sample of the run, than backward Euler at the former default of
// 10 ms — for the thermocouple, the IR pyrometer, the hottest interface ring and the torque.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include "io/scenario.hpp"
#include "components/drive_cycle.hpp"
#include "rig_models/model.hpp"

namespace shudder {
namespace {

using rig_models::ThermalScheme;

const std::string kCase1 = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/paper_g_case1_25kN.toml";

struct Runs {
  io::Scenario sc = io::load_scenario(kCase1);
  clutch::WetClutch clutch = sc.make_clutch();
  dynamics::Recording run(ThermalScheme scheme, double step_s) const {
    rig_models::PrescribedSlipModel m = std::get<rig_models::PrescribedSlipModel>(sc.model);
    m.settings.thermal_scheme = scheme;
    m.settings.thermal_step_s = step_s;
    return rig_models::simulate(m, clutch);
  }
};

const std::vector<double>& values(const dynamics::Recording& r, const char* name) {
  const dynamics::Signal* s = r.find(name);
  if (s == nullptr) throw std::runtime_error(std::string("no signal ") + name);
  return s->values;
}

// max over samples with t >= from_s of |run − limit|.
double max_error(const dynamics::Recording& run, const std::vector<double>& limit, const char* name,
                 double from_s = 0.0) {
  const auto& x = values(run, name);
  const auto& t = values(run, "time_s");
  double e = 0.0;
  for (std::size_t k = 0; k < x.size(); ++k)
    if (t[k] >= from_s) e = std::max(e, std::abs(x[k] - limit[k]));
  return e;
}

TEST(PrescribedSlipBdf2, ShippedCase1IsMoreAccurateThanBackwardEulerAtTenMilliseconds) {
  const Runs runs;
  const auto& shipped = std::get<rig_models::PrescribedSlipModel>(runs.sc.model).settings;
  ASSERT_EQ(shipped.thermal_scheme, ThermalScheme::kBdf2);
  const double shipped_step_s = shipped.thermal_step_s;
  EXPECT_GE(shipped_step_s, 0.04);  // the speed it was chosen for (docs/performance.md)

  const auto be5 = runs.run(ThermalScheme::kBackwardEuler, 0.005);
  const auto be2 = runs.run(ThermalScheme::kBackwardEuler, 0.0025);
  const auto be10 = runs.run(ThermalScheme::kBackwardEuler, 0.01);
  const auto bdf = runs.run(ThermalScheme::kBdf2, shipped_step_s);
  for (const char* name : {"temp_C", "ir_temp_C", "interface_max_temp_C", "torque_Nm", "heat_power_W"}) {
    const auto& a = values(be2, name);
    const auto& b = values(be5, name);
    std::vector<double> limit(a.size());
    for (std::size_t k = 0; k < a.size(); ++k) limit[k] = 2.0 * a[k] - b[k];
    const double e_be = max_error(be10, limit, name), e_bdf = max_error(bdf, limit, name);
    EXPECT_LT(e_bdf, e_be) << name;
    EXPECT_GT(e_be, 0.0) << name;  // not trivially equal
  }
  // The heat account (its trapezoidal sum) too.
  const auto heat = [](const dynamics::Recording& r) { return r.find_scalar("heat_generated_J")->value; };
  const double heat_limit = 2.0 * heat(be2) - heat(be5);
  EXPECT_LT(std::abs(heat(bdf) - heat_limit), std::abs(heat(be10) - heat_limit));
}

// Second order on the real run: the errors at 40 and 20 ms against the backward Euler limit
// fall by 4 (observed order in [1.6, 2.4]) for the temperatures and the torque — after the
// first 0.3 s, where the start (one backward Euler step, the film's √t rise interpolated between
// step ends) dominates at these steps. A first-order slip anywhere in the coupling (the heat
// taken at the step's start, an unextrapolated ring temperature, the flow's temperature lagging)
// gives order 1.
TEST(PrescribedSlipBdf2, Case1ConvergesAtSecondOrderToTheBackwardEulerLimit) {
  const Runs runs;
  const auto be5 = runs.run(ThermalScheme::kBackwardEuler, 0.005);
  const auto be2 = runs.run(ThermalScheme::kBackwardEuler, 0.0025);
  const auto coarse = runs.run(ThermalScheme::kBdf2, 0.04);
  const auto fine = runs.run(ThermalScheme::kBdf2, 0.02);
  for (const char* name : {"temp_C", "ir_temp_C", "torque_Nm"}) {
    const auto& a = values(be2, name);
    const auto& b = values(be5, name);
    std::vector<double> limit(a.size());
    for (std::size_t k = 0; k < a.size(); ++k) limit[k] = 2.0 * a[k] - b[k];
    const double p = std::log2(max_error(coarse, limit, name, 0.3) / max_error(fine, limit, name, 0.3));
    EXPECT_GE(p, 1.6) << name;
    EXPECT_LE(p, 2.4) << name;
  }
}

// Samples between thermal steps: the slip, force and friction channels are evaluated at the
// sample's own time (channel_recorder.hpp, refined). A drive cycle with a kink at 0.015 s and
// 40 ms steps: every speed sample equals the cycle exactly, and the torque samples inside the
// first steps — where the friction bends most with the slip (1–3 rpm) — agree with a 1.25 ms
// run to 0.02 N m (a straight line between the step ends, as before, misses by 5.4 N m here
// and the speed samples by up to 0.8 rpm: both assertions fail without the refinement).
TEST(PrescribedSlipBdf2, SamplesInsideAStepFollowTheCycleAndTheFriction) {
  Runs runs;
  auto& m = std::get<rig_models::PrescribedSlipModel>(runs.sc.model);
  m.settings.duration_s = 0.5;
  m.cycle.slip_speed_rpm = components::PiecewiseLinear({0.0, 0.015, 0.5}, {1.0, 3.0, 5.0});
  const auto coarse = runs.run(ThermalScheme::kBdf2, 0.04);
  const auto fine = runs.run(ThermalScheme::kBdf2, 0.00125);
  const auto& t = values(coarse, "time_s");
  const auto& speed = values(coarse, "speed_rpm");
  for (std::size_t k = 0; k < t.size(); ++k) EXPECT_DOUBLE_EQ(speed[k], m.cycle.slip_speed_rpm(t[k])) << t[k];
  EXPECT_LT(max_error(coarse, values(fine, "torque_Nm"), "torque_Nm"), 0.02);
}

// An abrupt cycle: slip 60 rpm at 2 kN, the force applied in 5 ms at 1 s (→ 25.3 kN), the slip
// dropped to 5 rpm in 2 ms at 3 s, 6 s in all. Ramps shorter than a step break BDF2's smoothness
// assumption; its steps therefore end on the cycle's knots (thermal_step_plan.hpp). Against
// backward Euler at 0.5 ms (its own error, ~1/20 of the 10 ms one's, is inside the margins
// below), BDF2 at 40 ms stays within backward Euler's error at 10 ms on every temperature and
// the torque (measured: temp_C 0.052 against 0.059 °C, IR 0.047 against 0.12 °C, torque 0.014
// against 0.034 N m). Without the knot-aligned steps BDF2 at 40 ms was 0.45 °C off.
TEST(PrescribedSlipBdf2, AbruptCycleStaysWithinBackwardEulerAtTenMilliseconds) {
  Runs runs;
  auto& m = std::get<rig_models::PrescribedSlipModel>(runs.sc.model);
  m.settings.duration_s = 6.0;
  m.settings.snapshot_times_s.clear();
  m.cycle.slip_speed_rpm = components::PiecewiseLinear({0.0, 3.0, 3.002, 6.0}, {60.0, 60.0, 5.0, 5.0});
  m.cycle.normal_force_N = components::PiecewiseLinear({0.0, 1.0, 1.005, 6.0}, {2000.0, 2000.0, 25300.0, 25300.0});
  const auto ref = runs.run(ThermalScheme::kBackwardEuler, 0.0005);
  const auto be10 = runs.run(ThermalScheme::kBackwardEuler, 0.01);
  const auto bdf = runs.run(ThermalScheme::kBdf2, 0.04);
  for (const char* name : {"temp_C", "ir_temp_C", "interface_max_temp_C", "torque_Nm"}) {
    const auto& limit = values(ref, name);
    EXPECT_LT(max_error(bdf, limit, name), max_error(be10, limit, name)) << name;
  }
  // The steps landed on the knots: more steps than the 150 of a plain 40 ms grid, and the ledger closes.
  EXPECT_GT(bdf.find_scalar("thermal_steps")->value, 150.0);
  EXPECT_LT(bdf.find_scalar("energy_balance_relative_error")->value, 1e-12);
}

}  // namespace
}  // namespace shudder
