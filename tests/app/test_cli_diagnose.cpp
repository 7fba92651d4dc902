// `shudder diagnose` end to end: JSON and report of a real diagnosis, and every bad input the
// usage lists (exit 2, one clear line naming the file and what is wrong).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>

#include "tests/support/cli.hpp"

namespace shudder {
namespace {

using test::expect_rejected;
using test::replace;
using test::run_cli;
using test::scratch_dir;
using test::slurp;
using test::source_path;
using test::write_file;
using ::testing::HasSubstr;

std::string probe(const std::string& extra = "") {
  return test::shipped_scenario_text("diagnosis_probe.toml") + "\n" + extra;
}

// A measured run of the probe (bearing drag hidden), written by `shudder run --measurement`.
std::filesystem::path generate(const std::filesystem::path& dir, const std::string& name, unsigned seed) {
  write_file(dir / (name + ".toml"), probe("[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.005\n"));
  const auto r = run_cli("run " + name + ".toml -o " + name + ".h5 --measurement " + name +
                             ".csv --sample-rate 100 --noise --seed " + std::to_string(seed),
                         dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return dir / (name + ".csv");
}

TEST(CliDiagnose, WritesJsonReportAndSummary) {
  const auto dir = scratch_dir("cli_diagnose_ok");
  generate(dir, "a", 1);
  // One run at one constant force: a bearing drag mu F r and a torque-cell offset are the same
  // constant (held-out J 0.9941 and 0.9939), so the model declares its cell zeroed (the offset
  // effect on at 0 is no candidate), as a user with a zeroed cell would.
  write_file(dir / "model.toml", probe("[effects.torque_sensor_offset]\nenabled = true\noffset_Nm = 0.0\n"));
  const auto r = run_cli("diagnose model.toml a.csv --json d.json --report rep --jobs 2", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Missing effects: bearing_drag"));
  const std::string json = slurp(dir / "d.json");
  for (const char* key : {"\"format\": \"shudder-diagnosis/1\"", "\"runs\"", "\"baseline\"", "\"disagreements\"",
                          "\"steps\"", "\"missing_effects\"", "\"final\"", "\"torque_rms_Nm\"", "\"temp_rms_C\"",
                          "\"holdout_torque_rms_Nm\"", "\"tracks\"", "\"correlation\"", "\"final_effects\""})
    EXPECT_THAT(json, HasSubstr(key));
  EXPECT_THAT(json, HasSubstr("\"missing_effects\": [\"bearing_drag\"]"));
  EXPECT_THAT(json, HasSubstr("{\"effect\": \"bearing_drag\", \"parameters\": {\"equivalent_mu\": 0.00"));
  EXPECT_THAT(r.out, HasSubstr("Final model, refitted on all runs:\n  bearing_drag  equivalent_mu = 0.00"));
  EXPECT_TRUE(std::filesystem::exists(dir / "rep" / "summary.txt"));
  EXPECT_TRUE(std::filesystem::exists(dir / "rep" / "candidates.md"));
}

TEST(CliDiagnose, MaxEffectsLimitsTheSearch) {
  // Bearing drag is hidden and clearly missing; with --max-effects 0 nothing may be added and
  // the summary must say why the search stopped.
  const auto dir = scratch_dir("cli_diagnose_max_effects");
  generate(dir, "a", 1);
  write_file(dir / "model.toml", probe());
  const auto r = run_cli("diagnose model.toml a.csv --max-effects 0 --jobs 1", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  EXPECT_THAT(r.out, HasSubstr("Missing effects: none"));
  EXPECT_THAT(r.out, HasSubstr("the limit of 0 added effects was reached"));
  EXPECT_EQ(run_cli("diagnose model.toml a.csv --max-effects -1", dir).exit_code, 2);
}

TEST(CliDiagnose, RejectsAMeasuredRunThatBreaksTheFormat) {
  const auto dir = scratch_dir("cli_diagnose_bad_csv");
  write_file(dir / "model.toml", probe());
  std::string csv = "# format: shudder-measurement/1\ntime_s,speed_rpm,normal_force_N,torque_Nm,temp_C\n";
  for (int i = 0; i < 30; ++i)
    csv += std::to_string(0.1 * i) + ",1," + (i == 17 ? "-5" : "12000") + ",40,75\n";  // row 17 = line 20
  write_file(dir / "bad.csv", csv);
  expect_rejected(run_cli("diagnose model.toml bad.csv", dir), {"bad.csv:20", "negative normal force"});
}

TEST(CliDiagnose, RejectsRunsFromDifferentRigs) {
  const auto dir = scratch_dir("cli_diagnose_rigs");
  write_file(dir / "model.toml", probe());
  const auto a = generate(dir, "a", 1);
  std::string other = slurp(a);
  other = replace(other, "# rig: lsctr", "# rig: haldex_bench");
  write_file(dir / "b.csv", other);
  expect_rejected(run_cli("diagnose model.toml a.csv b.csv", dir), {"b.csv", "haldex_bench", "lsctr", "one rig"});
}

TEST(CliDiagnose, RejectsAModelNamingAnUnknownEffectAndListsTheValidOnes) {
  const auto dir = scratch_dir("cli_diagnose_effect");
  generate(dir, "a", 1);
  write_file(dir / "model.toml", probe("[effects.clutch_glazing]\nenabled = true\n"));
  expect_rejected(run_cli("diagnose model.toml a.csv", dir),
                  {"model.toml", "clutch_glazing", "temperature_dependent_friction", "rig_heat_capacity",
                   "load_dependent_friction"});
}

TEST(CliDiagnose, RejectsARunTooShortToFit) {
  const auto dir = scratch_dir("cli_diagnose_short");
  write_file(dir / "model.toml", probe());
  std::string csv = "# format: shudder-measurement/1\ntime_s,speed_rpm,normal_force_N,torque_Nm,temp_C\n";
  for (int i = 0; i < 12; ++i) csv += std::to_string(0.01 * i) + ",1,12000,40,75\n";
  write_file(dir / "short.csv", csv);
  expect_rejected(run_cli("diagnose model.toml short.csv", dir), {"short.csv", "12 rows", "at least 20 rows"});
}

}  // namespace
}  // namespace shudder
