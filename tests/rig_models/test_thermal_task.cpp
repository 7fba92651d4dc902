// The thermal task's handover (rig_models/thermal_task.hpp): when the fast side gives the worker
// time (a paced real-time loop), post() and collect() complete without waking or waiting for it
// — no system call on the stepping thread — and the result is the same, bit for bit, as when the
// fast side must wake the worker and wait (steps run back to back). Exact equality is the right
// tolerance: both paths run the same thermal step on the same inputs; only who waits differs.
#include <gtest/gtest.h>

#include <chrono>
#include <stdexcept>
#include <string>
#include <thread>

#include "io/scenario.hpp"
#include "rig_models/thermal_task.hpp"

namespace shudder {
namespace {

const std::string kScenarios = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/";

// Ten 10 ms windows of Case 1 heat (rising, so the oil flow and the factorisation change).
void run_windows(rig_models::ThermalTask& task, int n_r, bool give_worker_time) {
  Eigen::VectorXd heat_J(n_r);
  for (int w = 0; w < 10; ++w) {
    task.collect();
    for (int i = 0; i < n_r; ++i) heat_J[i] = 0.5 + 0.01 * w + 0.02 * i;
    task.post(heat_J, 0.01, 0.01 * (w + 1), 1.0 + 0.5 * w, 25300.0);
    // Two poll intervals (2 ms here) and the solve (~0.1 ms) fit well inside 20 ms, even on a
    // loaded machine; if the worker was starved anyway the test fails on the count, not silently.
    if (give_worker_time) std::this_thread::sleep_for(std::chrono::milliseconds(20));
  }
  task.collect();
}

TEST(ThermalTask, PacedHandoverNeverWaitsAndEqualsTheWaitedOneExactly) {
  const io::Scenario sc = io::load_scenario(kScenarios + "paper_g_case1_25kN.toml");
  const clutch::WetClutch clutch = sc.make_clutch();
  const int n_r = clutch.thermal().radial_cells();
  rig_models::ThermalTask paced(clutch, 25300.0, 1e-3);
  rig_models::ThermalTask back_to_back(clutch, 25300.0, 10.0);  // polls far too rarely: must be woken
  run_windows(paced, n_r, true);
  run_windows(back_to_back, n_r, false);
  EXPECT_EQ(paced.waited_collects(), 0);
  EXPECT_GE(back_to_back.waited_collects(), 1);  // then post() wakes it: later jobs may be done in time
  EXPECT_DOUBLE_EQ(paced.latest().time_s, 0.1);
  EXPECT_GT(paced.latest().interface_max_C, clutch.initial_state().temp_C.maxCoeff());  // heat went in
  EXPECT_EQ(paced.latest().ring_temp_C, back_to_back.latest().ring_temp_C);
  EXPECT_EQ(paced.latest().thermocouple_C, back_to_back.latest().thermocouple_C);
  EXPECT_EQ(paced.state().temp_C, back_to_back.state().temp_C);
  EXPECT_EQ(paced.state().energy.generated_J, back_to_back.state().energy.generated_J);
}

TEST(ThermalTask, ResetAfterAnUncollectedJobStartsAgainFromTheInitialState) {
  const io::Scenario sc = io::load_scenario(kScenarios + "paper_g_case1_25kN.toml");
  const clutch::WetClutch clutch = sc.make_clutch();
  rig_models::ThermalTask task(clutch, 25300.0, 10.0);
  task.post(Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), 5.0), 0.01, 0.01, 2.0, 25300.0);
  task.reset(25300.0);
  EXPECT_FALSE(task.busy());
  EXPECT_EQ(task.state().temp_C, clutch.initial_state().temp_C);
  EXPECT_THROW(rig_models::ThermalTask(clutch, 25300.0, 0.0), std::invalid_argument);
}

}  // namespace
}  // namespace shudder
