// The first-generation Haldex hydraulics and controller through the CLI: a sweep over a driveline
// key equals the single runs it stands for, and the new keys' bad inputs exit 2 with one line.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdio>
#include <numeric>
#include <string>

#include "io/hdf5_run.hpp"
#include "io/hdf5_sweep.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/recording.hpp"

namespace shudder {
namespace {

using test::expect_rejected;
using test::replace;
using test::run_cli;

// The split-μ launch (controller on), shortened to 1 s: the coupling takes up in the first second.
std::string short_launch() {
  return replace(test::shipped_scenario_text("driveline_split_mu_launch.toml"), "duration_s = 3.0", "duration_s = 1.0");
}

// A sweep over the pump's displacement: each case's kept coupling signals and verdict equal a
// single `shudder run` of the scenario with that value written in its own [driveline.hydraulics]
// table (an independent path to the same model: the sweep rewrites the key with --set).
TEST(CliDrivelineHaldex, SweepOverADrivelineKeyEqualsTheSingleRuns) {
  const auto dir = test::scratch_dir("cli_driveline_sweep");
  test::write_file(dir / "s.toml", short_launch());
  const auto r = run_cli(
      "sweep s.toml --set driveline.hydraulics.pump_displacement_cm3_per_rev=1.5,2.5,3.5 "
      "--jobs 2 --keep-parts -o sw.h5",
      dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const io::SweepTable t = io::read_sweep_table((dir / "sw.h5").string());
  ASSERT_EQ(t.text_column.size(), 3u);
  std::vector<double> take_up_torques;
  const char* values[] = {"1.5", "2.5", "3.5"};
  for (std::size_t k = 0; k < 3; ++k) {
    const std::string name = "single_" + std::to_string(k);
    test::write_file(dir / (name + ".toml"),
                     short_launch() + "\n[driveline.hydraulics]\npump_displacement_cm3_per_rev = " + values[k] + "\n");
    const auto single = run_cli("run " + name + ".toml -o " + name + ".h5", dir);
    ASSERT_EQ(single.exit_code, 0) << single.err;
    const auto run = io::read_run_hdf5((dir / (name + ".h5")).string());
    char part[32];
    std::snprintf(part, sizeof part, "case_%05zu.h5", k);
    const auto kept = io::read_run_hdf5((dir / "sw.h5.parts" / part).string());
    for (const char* signal : {"time_s", "coupling_slip_rpm", "coupling_torque_Nm", "interface_mean_temp_C"})
      EXPECT_EQ(test::signal(kept, signal), test::signal(run, signal)) << signal << " case " << k;  // bit-identical
    const double code = test::scalar(run, "coupling_verdict_code");
    EXPECT_EQ(t.text_column[k], code == 0 ? "none" : code == 1 ? "vibration" : "stick_slip") << k;
    // The mean coupling torque over the first 0.4 s (1000 S/s): the take-up.
    const auto& torque = test::signal(run, "coupling_torque_Nm");
    take_up_torques.push_back(std::accumulate(torque.begin(), torque.begin() + 400, 0.0) / 400);
  }
  // The key reaches the model: a bigger pump builds the pressure sooner and takes up more torque.
  EXPECT_LT(take_up_torques[0], take_up_torques[1]);
  EXPECT_LT(take_up_torques[1], take_up_torques[2]);
}

TEST(CliDrivelineHaldex, RejectsBadValveAndHydraulicsInput) {
  const std::string launch = short_launch();
  // A raw opening outside [0, 1].
  expect_rejected(test::run_scenario_in("cli_haldex_opening",
                                        replace(launch, "engine_torque_Nm", "valve_opening = 1.5\nengine_torque_Nm")),
                  {"s.toml", "valve_opening", "[0, 1]"});
  // A raw schedule and the controller both.
  expect_rejected(test::run_scenario_in("cli_haldex_both",
                                        replace(launch, "engine_torque_Nm", "valve_opening = 0.5\nengine_torque_Nm") +
                                            "\n[driveline.controller]\nlock_slip_rpm = 30.0\n"),
                  {"s.toml", "valve_opening", "either the schedule or the controller"});
  // A pressure setting beyond a lowered relief valve.
  expect_rejected(
      test::run_scenario_in("cli_haldex_relief",
                            replace(launch, "engine_torque_Nm", "valve_pressure_bar = 25.0\nengine_torque_Nm") +
                                "\n[driveline.hydraulics]\nrelief_pressure_bar = 20.0\n"),
      {"s.toml", "valve_pressure_bar", "[0, 20]"});
  // The generation-mixing model's keys point to what replaced them.
  expect_rejected(
      test::run_scenario_in("cli_haldex_old", launch + "\n[driveline.hydraulics]\ntorque_per_bar_Nm = 59.0\n"),
      {"s.toml", "torque_per_bar_Nm", "piston_area_cm2"});
  expect_rejected(
      test::run_scenario_in("cli_haldex_leak", launch + "\n[driveline.hydraulics]\nleak_time_constant_s = 0.5\n"),
      {"s.toml", "leak_time_constant_s", "valve_area_mm2"});
  // Controller thresholds that contradict each other, and a non-positive pack oil volume.
  expect_rejected(
      test::run_scenario_in("cli_haldex_speeds", launch + "\n[driveline.controller]\nfast_speed_km_h = 100.0\n"
                                                          "top_speed_km_h = 90.0\n"),
      {"s.toml", "top_speed_km_h"});
  expect_rejected(test::run_scenario_in("cli_haldex_oil", launch + "\n[driveline]\npack_oil_volume_ml = 0.0\n"),
                  {"s.toml", "pack_oil_volume_ml"});
}

}  // namespace
}  // namespace shudder
