// Bad scenario input through the real CLI: exit code 2, ONE line on stderr naming the file, the
// key and what is allowed, and no output file left behind.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;

namespace {

// A valid minimal scenario; each test breaks one thing in it.
std::string base_scenario() {
  return "[scenario]\n"
         "type = \"prescribed_slip\"\n"
         "duration_s = 0.5\n"
         "[clutch]\n"
         "fluid = \"" +
         source_path("scenarios/fluids/lsc_fluid_c.toml") +
         "\"\n"
         "start_temp_C = 77.0\n"
         "[drive]\n"
         "time_s = [0.0, 0.5]\n"
         "speed_rpm = [1.0, 10.0]\n"
         "normal_force_N = 10400.0\n";
}

Outcome run_bad(const std::string& name, const std::string& scenario_text) {
  return run_scenario_in("bad_" + name, scenario_text);
}

}  // namespace

TEST(CliBadInput, ValidBaseScenarioRuns) {
  const auto dir = scratch_dir("bad_base");
  write_file(dir / "s.toml", base_scenario());
  const auto r = run_cli("run s.toml -o out.h5", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  EXPECT_TRUE(std::filesystem::exists(dir / "out.h5"));
}

TEST(CliBadInput, MissingKey) {
  expect_rejected(run_bad("missing", replace(base_scenario(), "start_temp_C = 77.0\n", "")),
                  {"s.toml", "clutch.start_temp_C", "missing", "[-60, 250]"});
}

TEST(CliBadInput, UnknownKey) {
  expect_rejected(run_bad("unknown", replace(base_scenario(), "start_temp_C", "strat_temp_C = 1.0\nstart_temp_C")),
                  {"s.toml:", "clutch.strat_temp_C", "unknown key", "start_temp_C"});
}

TEST(CliBadInput, WrongType) {
  expect_rejected(run_bad("type", replace(base_scenario(), "duration_s = 0.5", "duration_s = \"long\"")),
                  {"s.toml:3", "scenario.duration_s", "is a string", "expected a number"});
}

TEST(CliBadInput, NegativeThickness) {
  expect_rejected(run_bad("thickness", base_scenario() + "[clutch.lining]\nthickness_mm = -0.5\n"),
                  {"s.toml:", "clutch.lining.thickness_mm", "out of range", "> 0"});
}

TEST(CliBadInput, NegativeConductivity) {
  expect_rejected(run_bad("conductivity", base_scenario() + "[clutch.separator]\nconductivity_W_per_mK = -46\n"),
                  {"clutch.separator.conductivity_W_per_mK", "out of range", "> 0"});
}

TEST(CliBadInput, NaN) {
  expect_rejected(run_bad("nan", replace(base_scenario(), "normal_force_N = 10400.0", "normal_force_N = nan")),
                  {"drive.normal_force_N", "not finite"});
}

TEST(CliBadInput, ForceAboveRigMaximum) {
  expect_rejected(run_bad("force", replace(base_scenario(), "normal_force_N = 10400.0", "normal_force_N = 31000.0")),
                  {"drive.normal_force_N", "[0, 30000]"});
}

TEST(CliBadInput, UnknownEffectListsValidNames) {
  expect_rejected(run_bad("effect", base_scenario() + "[effects.magic_cooling]\nenabled = true\n"),
                  {"effects.magic_cooling", "unknown effect", "rig_heat_capacity", "viscous_shear"});
}

TEST(CliBadInput, FrictionMatrixWithAHole) {
  const auto dir = scratch_dir("bad_hole");
  // Copy fluid C and drop the 25 kN set of one row.
  std::string fluid = slurp(source_path("scenarios/fluids/lsc_fluid_c.toml"));
  const auto row = fluid.find("temp_C = 40.0");
  ASSERT_NE(row, std::string::npos);
  const auto last = fluid.find("],  # 25 kN", row);
  ASSERT_NE(last, std::string::npos);
  const auto line_start = fluid.rfind('\n', last);
  fluid.erase(line_start, fluid.find('\n', last) - line_start);
  write_file(dir / "fluid.toml", fluid);
  write_file(dir / "s.toml", replace(base_scenario(), source_path("scenarios/fluids/lsc_fluid_c.toml"), "fluid.toml"));
  const auto r = run_cli("run s.toml -o out.h5", dir);
  EXPECT_EQ(r.exit_code, 2) << r.err;
  EXPECT_THAT(r.err, HasSubstr("fluid.toml"));
  EXPECT_THAT(r.err, HasSubstr("sets"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

TEST(CliBadInput, UnreadableFile) {
  const auto dir = scratch_dir("bad_unreadable");
  const auto r = run_cli("run does_not_exist.toml -o out.h5", dir);
  EXPECT_EQ(r.exit_code, 2);
  EXPECT_THAT(r.err, HasSubstr("does_not_exist.toml"));
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

TEST(CliBadInput, SyntaxErrorNamesLine) {
  expect_rejected(run_bad("syntax", base_scenario() + "[drive\n"), {"s.toml:11"});
}
