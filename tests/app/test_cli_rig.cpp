// Rig scenarios through the real CLI: `shudder modes`, `shudder run --measurement`, and
// bad rig input — exit code 2, ONE line on stderr naming the file, the key and what is allowed,
// no output file left behind; a torsion bar outside the rig's 100–500 Hz is only a warning.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cstdlib>
#include <sstream>
#include <string>
#include <vector>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;
using ::testing::Not;
using ::testing::StartsWith;

namespace {

// A valid short rig scenario (50 ms at 10 rpm, 15 kN, 378 Hz bar); each test breaks one thing.
std::string base_rig_scenario() {
  return "[scenario]\n"
         "type = \"rig\"\n"
         "duration_s = 0.05\n"
         "[clutch]\n"
         "fluid = \"" +
         source_path("scenarios/fluids/lsc_fluid_c.toml") +
         "\"\n"
         "start_temp_C = 77.0\n"
         "[drive]\n"
         "time_s = [0.0, 0.05]\n"
         "speed_rpm = [10.0, 10.0]\n"
         "normal_force_N = 15000.0\n"
         "[rig]\n"
         "drive_inertia_kg_m2 = 0.6\n"
         "housing_inertia_kg_m2 = 0.02\n"
         "[rig.torsion_bar]\n"
         "natural_frequency_Hz = 378.0\n";
}

Outcome run_scenario(const std::string& name, const std::string& scenario_text) {
  return run_scenario_in("rig_" + name, scenario_text);
}

std::vector<std::string> split(const std::string& line, char sep) {
  std::vector<std::string> out;
  std::stringstream ss(line);
  for (std::string cell; std::getline(ss, cell, sep);) out.push_back(cell);
  return out;
}

}  // namespace

// The base scenario is valid: each rejection below is caused by the one change it makes.
TEST(CliRig, ValidBaseRigScenarioRuns) {
  const Outcome o = run_scenario("base", base_rig_scenario());
  EXPECT_EQ(o.r.exit_code, 0) << o.r.err;
  EXPECT_TRUE(o.output_exists);
  EXPECT_EQ(o.r.err, "");
}

// `shudder modes` on the 378 Hz Case 1 rig: the clutch-side mode is derived to the target
// (RigBar tests: to 1e-9), so it prints 378.000 Hz at the printed 3 decimals.
TEST(CliRig, ModesPrintsTheClutchSideModeAtTheBarTarget) {
  const auto dir = scratch_dir("rig_modes");
  const auto r = run_cli("modes '" + source_path("scenarios/rig_case1_25kN_378Hz.toml") + "'", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Clutch-side mode (slipping): 378.000 Hz"));
  EXPECT_THAT(r.out, HasSubstr("Clutch slipping:"));
  EXPECT_THAT(r.out, HasSubstr("Clutch stuck:"));
  EXPECT_THAT(r.out, HasSubstr("housing"));
  EXPECT_THAT(r.out, HasSubstr("378.000"));
}

// A prescribed-slip scenario has no torsional network: exit 2, one line naming scenario.type.
TEST(CliRig, ModesOnPrescribedSlipScenarioIsRejectedNamingScenarioType) {
  const auto dir = scratch_dir("rig_modes_ps");
  const auto r = run_cli("modes '" + source_path("scenarios/paper_g_case1_25kN.toml") + "'", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("paper_g_case1_25kN.toml"));
  EXPECT_THAT(r.err, HasSubstr("scenario.type"));
  EXPECT_THAT(r.err, HasSubstr("rig"));
  EXPECT_EQ(r.out, "");
}

// `shudder run RIG --measurement out.csv` writes the docs/formats/measured_run.md measured-run CSV: metadata
// lines starting with '#' (format first), the header with the five required columns first,
// one row per recorded sample (Case 1: 10 s at 1 kHz, 10001 rows). Spot values: the force is
// the scenario's 25300 N; the drive encoder follows the 1 -> 100 rpm ramp (at 5 s, 50.5 rpm,
// within 0.1 % — the loop's lag there is ~2e-4 rad/s, see RigQuasiStatic); the torque is a
// fluid-C friction torque (~116 N m at 5 s, Paper G Figure 12 shape), temperatures rise.
TEST(CliRig, RunWritesTheFormatsMeasurementCsv) {
  const auto dir = scratch_dir("rig_measurement");
  const auto r =
      run_cli("run '" + source_path("scenarios/rig_case1_25kN_378Hz.toml") + "' -o out.h5 --measurement out.csv", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  ASSERT_TRUE(std::filesystem::exists(dir / "out.csv"));
  EXPECT_TRUE(std::filesystem::exists(dir / "out.h5"));

  std::istringstream in(slurp(dir / "out.csv"));
  std::string line;
  std::vector<std::string> meta;
  while (std::getline(in, line) && line.rfind("#", 0) == 0) meta.push_back(line);
  ASSERT_FALSE(meta.empty());
  EXPECT_EQ(meta.front(), "# format: shudder-measurement/1");
  EXPECT_THAT(line, StartsWith("time_s,speed_rpm,normal_force_N,torque_Nm,temp_C"));
  const auto header = split(line, ',');
  const auto column = [&](const std::string& name) {
    return static_cast<std::size_t>(std::find(header.begin(), header.end(), name) - header.begin());
  };
  EXPECT_LT(column("sump_temp_C"), header.size());

  std::vector<std::vector<double>> rows;
  while (std::getline(in, line)) {
    if (line.empty()) continue;
    const auto cells = split(line, ',');
    ASSERT_EQ(cells.size(), header.size()) << line;
    std::vector<double> v;
    for (const auto& c : cells) v.push_back(std::strtod(c.c_str(), nullptr));
    rows.push_back(v);
  }
  ASSERT_EQ(rows.size(), 10001u);
  for (std::size_t k = 1; k < rows.size(); ++k) ASSERT_GT(rows[k][0], rows[k - 1][0]) << "row " << k;
  EXPECT_NEAR(rows.back()[0], 10.0, 1e-9);
  const auto& mid = rows[5000];
  EXPECT_NEAR(mid[0], 5.0, 1e-9);
  EXPECT_NEAR(mid[column("speed_rpm")], 50.5, 0.05);
  EXPECT_NEAR(mid[column("normal_force_N")], 25300.0, 1e-6);
  EXPECT_GT(mid[column("torque_Nm")], 100.0);
  EXPECT_LT(mid[column("torque_Nm")], 130.0);
  EXPECT_GT(rows.back()[column("temp_C")], rows.front()[column("temp_C")] + 10.0);
}

// --- Bad input --------------------------------------------------------------------------------

TEST(CliRig, ZeroHousingInertiaIsRejected) {
  expect_rejected(run_scenario("housing0", replace(base_rig_scenario(), "housing_inertia_kg_m2 = 0.02",
                                                   "housing_inertia_kg_m2 = 0.0")),
                  {"s.toml:", "rig.housing_inertia_kg_m2", "out of range", "> 0"});
}

TEST(CliRig, NegativeDriveInertiaIsRejected) {
  expect_rejected(run_scenario("drive_neg",
                               replace(base_rig_scenario(), "drive_inertia_kg_m2 = 0.6", "drive_inertia_kg_m2 = -1.0")),
                  {"s.toml:", "rig.drive_inertia_kg_m2", "out of range", "> 0"});
}

TEST(CliRig, ZeroBarStiffnessIsRejected) {
  expect_rejected(
      run_scenario("k0", replace(base_rig_scenario(), "natural_frequency_Hz = 378.0", "stiffness_Nm_per_rad = 0.0")),
      {"s.toml:", "rig.torsion_bar.stiffness_Nm_per_rad", "out of range", "> 0"});
}

TEST(CliRig, BarFrequencyBelowOneHertzIsRejected) {
  expect_rejected(
      run_scenario("f_low", replace(base_rig_scenario(), "natural_frequency_Hz = 378.0", "natural_frequency_Hz = 0.5")),
      {"s.toml:", "rig.torsion_bar.natural_frequency_Hz", "out of range", "[1, 10000]"});
}

TEST(CliRig, BarFrequencyAboveTenKilohertzIsRejected) {
  expect_rejected(run_scenario("f_high", replace(base_rig_scenario(), "natural_frequency_Hz = 378.0",
                                                 "natural_frequency_Hz = 20000.0")),
                  {"s.toml:", "rig.torsion_bar.natural_frequency_Hz", "out of range", "[1, 10000]"});
}

TEST(CliRig, BarFrequencyAndStiffnessTogetherAreRejected) {
  expect_rejected(run_scenario("f_and_k", replace(base_rig_scenario(), "natural_frequency_Hz = 378.0",
                                                  "natural_frequency_Hz = 378.0\nstiffness_Nm_per_rad = 1.0e5")),
                  {"s.toml:", "rig.torsion_bar.", "exactly one of", "natural_frequency_Hz", "stiffness_Nm_per_rad"});
}

TEST(CliRig, DriveSpeedAboveMotorRangeIsRejected) {
  expect_rejected(
      run_scenario("w_high", replace(base_rig_scenario(), "speed_rpm = [10.0, 10.0]", "speed_rpm = [10.0, 200.0]")),
      {"s.toml:", "drive.speed_rpm", "200", "[0.5, 125] rpm"});
}

TEST(CliRig, DriveSpeedBelowMotorRangeIsRejected) {
  expect_rejected(
      run_scenario("w_low", replace(base_rig_scenario(), "speed_rpm = [10.0, 10.0]", "speed_rpm = [0.1, 10.0]")),
      {"s.toml:", "drive.speed_rpm", "0.1", "[0.5, 125] rpm"});
}

TEST(CliRig, ForceAboveRigMaximumIsRejected) {
  expect_rejected(
      run_scenario("force", replace(base_rig_scenario(), "normal_force_N = 15000.0", "normal_force_N = 31000.0")),
      {"s.toml:", "drive.normal_force_N", "out of range", "[0, 30000]"});
}

// A 50 Hz bar is not one of the rig's (100–500 Hz) but a valid model: one warning line naming
// the key and the range, exit 0, and the run completes (the output is written).
TEST(CliRig, BarFrequencyOutsideRigBarsIsOnlyAWarning) {
  const Outcome o =
      run_scenario("f_50", replace(base_rig_scenario(), "natural_frequency_Hz = 378.0", "natural_frequency_Hz = 50.0"));
  EXPECT_EQ(o.r.exit_code, 0) << o.r.err;
  EXPECT_TRUE(o.output_exists);
  EXPECT_EQ(std::count(o.r.err.begin(), o.r.err.end(), '\n'), 1) << o.r.err;
  EXPECT_THAT(o.r.err, HasSubstr("warning"));
  EXPECT_THAT(o.r.err, HasSubstr("rig.torsion_bar.natural_frequency_Hz"));
  EXPECT_THAT(o.r.err, HasSubstr("100-500 Hz"));
  EXPECT_THAT(o.r.err, Not(HasSubstr("error")));
  EXPECT_THAT(o.r.out, HasSubstr("Output: out.h5"));
}
