// `shudder diagnose` on a network scenario: a measured run of one wet clutch of the network
// (`run --measurement` writes RUN.CLUTCH.csv, metadata `rig: network_clutch`, `clutch: NAME`)
// replayed through that clutch alone, its slip and clamp force imposed sample by sample
// (studies/clutch_replay.hpp).
//
// The network: a speed-controlled motor turns a drive at 120 rpm; the wet clutch `pack` (fluid
// C, 16 interfaces) joins it to a housing on a 378 Hz torsion bar, its force ramped 0 → 10 kN
// over 1 s and held; a second wet clutch, `brake`, holds a second motor's shaft at 3 kN. The
// pack slips 120 rpm throughout at up to ~700 N m and its thermocouple warms some kelvin in 4 s.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <iostream>

#include "analysis/diagnosis.hpp"
#include "studies/clutch_replay.hpp"
#include "io/diagnosis_inputs.hpp"
#include "io/measured_run.hpp"
#include "io/network_scenario.hpp"
#include "studies/replay.hpp"
#include "tests/support/cli.hpp"

namespace shudder {
namespace {

using test::run_cli;
using test::scratch_dir;
using test::source_path;
using test::write_file;

std::string network_text(const std::string& pack_effects = "") {
  const std::string fluid = source_path("scenarios/fluids/lsc_fluid_c.toml");
  return "[scenario]\ntype = \"network\"\nduration_s = 4.0\n[output]\nsample_rate_Hz = 1000\n"
         "[network.drive]\ntype = \"inertia\"\ninertia_kg_m2 = 0.6\nspeed_rpm = 120\n"
         "[network.motor]\ntype = \"motor\"\nnode = \"drive\"\nspeed_rpm = 120\nkp_Nms_per_rad = 75.4\n"
         "ki_Nm_per_rad = 2370\ntorque_limit_Nm = 1000\n"
         "[network.pack]\ntype = \"clutch\"\nlaw = \"wet\"\nfrom = \"drive\"\nto = \"housing\"\nmax_force_N = 10000\n"
         "normal_force = { kind = \"ramp\", from = 0.0, to = 1.0, duration_s = 1.0 }\n"
         "[network.pack.clutch]\nfluid = \"" +
         fluid + "\"\nsliding_interfaces = 16\nstart_temp_C = 40.0\n" + pack_effects +
         "[network.housing]\ntype = \"inertia\"\ninertia_kg_m2 = 0.02\n"
         "[network.bar]\ntype = \"shaft\"\nfrom = \"housing\"\nto = \"ground\"\nstiffness_Nm_per_rad = 1.128e5\n"
         "damping_Nms_per_rad = 0.95\n"
         "[network.aux]\ntype = \"inertia\"\ninertia_kg_m2 = 0.3\nspeed_rpm = 20\n"
         "[network.aux_motor]\ntype = \"motor\"\nnode = \"aux\"\nspeed_rpm = 20\nkp_Nms_per_rad = 40\n"
         "ki_Nm_per_rad = 1000\ntorque_limit_Nm = 1000\n"
         "[network.brake]\ntype = \"brake\"\nlaw = \"wet\"\nnode = \"aux\"\nmax_force_N = 3000\n"
         "[network.brake.clutch]\nfluid = \"" +
         fluid + "\"\nstart_temp_C = 40.0\n";
}

// `shudder run --measurement` of the network with the pack's `effects` hidden in it (truth.toml);
// the baseline without them is net.toml. Returns the directory.
std::filesystem::path measured(const std::string& name, const std::string& effects, const std::string& noise) {
  const auto dir = scratch_dir("diag_network_" + name);
  write_file(dir / "truth.toml", network_text(effects));
  write_file(dir / "net.toml", network_text());
  const auto out = run_cli("run truth.toml -o truth.h5 --measurement run.csv " + noise, dir);
  EXPECT_EQ(out.exit_code, 0) << out.err;
  return dir;
}

TEST(DiagnoseNetwork, MeasuredRunNamesItsClutch) {
  const auto dir = measured("meta", "", "--sample-rate 200");
  const auto run = io::read_measured_run((dir / "run.pack.csv").string());
  EXPECT_EQ(run.meta("rig").value_or(""), "network_clutch");
  EXPECT_EQ(run.meta("clutch").value_or(""), "pack");
  EXPECT_EQ(io::read_measured_run((dir / "run.brake.csv").string()).meta("clutch").value_or(""), "brake");
  EXPECT_EQ(run.rows(), 801u);  // 4 s at 200 Hz
}

// The replay through the pack alone reproduces the network's pack: noise-free, torque within
// 1e-4 of its peak RMS (what separates the two is the replay's 1 ms pack steps against the
// network's 10 ms thermal steps with their first-order hold, and the linear join of the 1 kHz
// samples; the driveline's coupling replays to 7e-5 of its 280 N m the same way), and the
// thermocouple within 1 % of its rise: a 10 ms backward-Euler thermal step lags a ~4 K/s rise by
// a few hundredths of a kelvin, which the network's first-order hold carries on (measured
// 0.064 K RMS of a 15.9 K rise, 0.4 %).
TEST(DiagnoseNetwork, ReplayOfAClutchReproducesItsTorqueAndTemperature) {
  const auto dir = measured("clean", "", "");
  const auto run = io::read_measured_run((dir / "run.pack.csv").string());
  const auto sc = io::load_network_scenario((dir / "net.toml").string());
  const auto model = studies::clutch_replay_model(sc.spec, "pack");
  const auto data = io::diagnosis_data({run}, model);
  EXPECT_TRUE(data.warnings.empty());
  const auto out = studies::replay(model, data.inputs.front());
  const auto& torque = *run.column("torque_Nm");
  const auto& temp = *run.column("temp_C");
  double torque_ss = 0, temp_ss = 0;
  for (std::size_t i = 0; i < torque.size(); ++i) {
    torque_ss += std::pow(out.torque_Nm[i] - torque[i], 2);
    temp_ss += std::pow(out.temp_C[i] - temp[i], 2);
  }
  const double n = static_cast<double>(torque.size());
  std::cout << "network clutch replay: torque RMS " << std::sqrt(torque_ss / n) << " N m, temp RMS "
            << std::sqrt(temp_ss / n) << " C, torque peak " << *std::max_element(torque.begin(), torque.end())
            << " N m, warming " << temp.back() - temp.front() << " K\n";
  EXPECT_LT(std::sqrt(torque_ss / n), 1e-4 * *std::max_element(torque.begin(), torque.end()));
  EXPECT_GT(temp.back() - temp.front(), 5.0);  // it warms: the thermal effects can show
  EXPECT_LT(std::sqrt(temp_ss / n), 0.01 * (temp.back() - temp.front()));
}

TEST(DiagnoseNetwork, CliNamesNothingForTheTrueModelAndWritesAModelThatRuns) {
  const auto dir = measured("true", "", "--noise --seed 3");
  const auto r = run_cli("diagnose net.toml run.pack.csv --jobs 1 --write-model fixed.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, ::testing::HasSubstr("(network clutch 'pack')"));
  EXPECT_THAT(r.out, ::testing::Not(::testing::HasSubstr("Added:")));
  const auto again = run_cli("run fixed.toml -o fixed.h5", dir);
  EXPECT_EQ(again.exit_code, 0) << again.err;
}

TEST(DiagnoseNetwork, HiddenSensorLagIsNamedAndWrittenIntoTheClutch) {
  const auto dir =
      measured("hidden", "[network.pack.effects.temperature_sensor_lag]\nenabled = true\ntime_constant_s = 2.0\n",
               "--noise --seed 2");
  const auto r = run_cli("diagnose net.toml run.pack.csv --jobs 1 --write-model fixed.toml", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  std::cout << r.out;
  EXPECT_THAT(r.out, ::testing::HasSubstr("temperature_sensor_lag"));
  const auto fixed = io::load_network_scenario((dir / "fixed.toml").string());
  const components::ClutchSpec* pack = nullptr;
  for (const auto& c : fixed.spec.clutches)
    if (c.name == "pack") pack = &c;
  ASSERT_NE(pack, nullptr);
  EXPECT_THAT(pack->wet.enabled_effects, ::testing::Contains("temperature_sensor_lag"));
  EXPECT_NEAR(pack->wet.clutch.thermal.sensor_time_constant_s, 2.0, 0.4);  // 20 %, as for the driveline
}

TEST(DiagnoseNetwork, ClutchChoiceErrorsNameTheFix) {
  const auto dir = measured("choice", "", "--sample-rate 200");
  // The runs' metadata names the brake; --clutch may name it too, a misspelling gets the nearest.
  const auto typo = run_cli("diagnose net.toml run.pack.csv --clutch pakc", dir);
  EXPECT_EQ(typo.exit_code, 2);
  EXPECT_THAT(typo.err, ::testing::HasSubstr("component 'pakc': is no clutch of the network; did you mean 'pack'?"));
  const auto mixed = run_cli("diagnose net.toml run.pack.csv run.brake.csv", dir);
  EXPECT_EQ(mixed.exit_code, 2);
  EXPECT_THAT(mixed.err, ::testing::HasSubstr("diagnose one clutch's runs at a time, or name it with --clutch"));
  write_file(dir / "anonymous.csv", test::replace(test::slurp(dir / "run.pack.csv"), "# clutch: pack\n", ""));
  const auto unnamed = run_cli("diagnose net.toml anonymous.csv", dir);
  EXPECT_EQ(unnamed.exit_code, 2);
  EXPECT_THAT(unnamed.err, ::testing::HasSubstr("the network has 2 wet clutches and the runs do not say which they are "
                                                "of; name one with --clutch (brake, pack)"));
}

}  // namespace
}  // namespace shudder
