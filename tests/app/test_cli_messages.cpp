// Messages: every error is ONE stderr line with the `shudder: error: ` prefix (CLI11's
// parse errors included), a misspelt key names itself with the key it should be, --seed without
// --noise is refused instead of ignored, `modes` on a driveline says what is true, and a grid too
// large for memory is an input error naming its size. Each test says what the old code did.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cstdlib>
#include <string>

#include "tests/support/cli.hpp"

using namespace shudder::test;
using ::testing::HasSubstr;
using ::testing::StartsWith;

// Old: CLI11 printed "The following argument was not expected: --bogus" and "Run with --help for
// more information." on two lines, without our prefix.
TEST(CliMessages, ParseErrorsAreOneLineWithThePrefixAndAHelpHint) {
  const auto dir = scratch_dir("msg_parse");
  auto r = run_cli("run s.toml --bogus", dir);
  expect_rejected(r, {"--bogus", "(see shudder run --help)"});
  EXPECT_THAT(r.err, StartsWith("shudder: error: "));
  r = run_cli("sweep s.toml -o out.h5", dir);  // --set is required
  expect_rejected(r, {"--set", "(see shudder sweep --help)"});
  EXPECT_THAT(r.err, StartsWith("shudder: error: "));
  r = run_cli("", dir);  // no subcommand
  expect_rejected(r, {"subcommand", "(see shudder --help)"});
  EXPECT_THAT(r.err, StartsWith("shudder: error: "));
}

// --help and --version still print as CLI11 prints them, exit 0, nothing on stderr.
TEST(CliMessages, HelpAndVersionStillExitZero) {
  const auto dir = scratch_dir("msg_help");
  auto r = run_cli("--help", dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("Subcommands:"));
  EXPECT_THAT(r.out, HasSubstr("export-fmu"));  // docs/fmu.md "Your drivetrain as an FMU"
  EXPECT_EQ(r.err, "");
  r = run_cli("run --help", dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_THAT(r.out, HasSubstr("--noise"));
  r = run_cli("--version", dir);
  EXPECT_EQ(r.exit_code, 0);
  EXPECT_NE(r.out, "");
  EXPECT_EQ(r.err, "");
}

// Old: --seed without --noise ran the scenario and exited 0, the seed ignored.
TEST(CliMessages, SeedWithoutNoiseIsRefused) {
  const auto dir = scratch_dir("msg_seed");
  const auto r = run_cli("run '" + source_path("scenarios/paper_g_case1_25kN.toml") + "' --seed 7 -o out.h5", dir);
  expect_rejected(r, {"shudder: error: --seed sets the sensor noise; give --noise too"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}

// Old: "key 'scenario.duration_s': missing; expected a number in > 0" — the misspelt key itself
// was never named.
TEST(CliMessages, MisspeltRequiredKeyIsNamedAsUnknownWithTheKeyItShouldBe) {
  std::string s = shipped_scenario_text("rig_shudder_negative_slope.toml");
  s = replace(s, "duration_s = 2.0", "durration_s = 2.0");
  const auto o = run_scenario_in("msg_misspelt", s);
  expect_rejected(o, {"s.toml:11: key 'scenario.durration_s': unknown key; did you mean 'duration_s'?"});
}

// Old: "unknown key; allowed keys here: ..." with no suggestion.
TEST(CliMessages, UnknownOptionalKeySuggestsTheNearestAllowedKey) {
  std::string s = shipped_scenario_text("rig_shudder_negative_slope.toml");
  s = replace(s, "start_temp_C = 60.0", "start_temp_C = 60.0\nsump_strat_temp_C = 60.0");
  const auto o = run_scenario_in("msg_unknown", s);
  expect_rejected(
      o, {"key 'clutch.sump_strat_temp_C': unknown key; did you mean 'sump_start_temp_C'? allowed keys here:"});
}

// Old: sweep_cases grew the 1e15-row grid row by row until memory ran out, then reported
// "shudder: sweep failed: std::bad_alloc" with exit 1 (a numerical failure). Now the grid is
// reserved at once and the failure is bad input naming its size. The 2 GB address-space limit
// (ulimit -v) keeps the old code's attempt bounded on any machine.
TEST(CliMessages, AGridTooLargeForMemoryIsBadInputNamingItsSize) {
  const auto dir = scratch_dir("msg_oom");
  write_file(dir / "s.toml", shipped_scenario_text("rig_shudder_negative_slope.toml"));
  const std::string axis = "=1:100000:1";
  const std::string cmd = "cd '" + dir.string() + "' && ulimit -v 2000000 && '" + SHUDDER_CLI +
                          "' sweep s.toml --set 'rig.torsion_bar.natural_frequency_Hz" + axis +
                          "' --set 'drive.normal_force_N" + axis + "' --set 'clutch.start_temp_C" + axis +
                          "' -o sw.h5 >stdout.txt 2>stderr.txt";
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "stdout.txt");
  r.err = slurp(dir / "stderr.txt");
  expect_rejected(r, {"shudder: error: --set: the grid has 1e+15 cases: ran out of memory listing them"});
  EXPECT_FALSE(std::filesystem::exists(dir / "sw.h5"));
}

// Old: a run asking for more memory than there is (1000 s at 1 MS/s: 1e9 samples per signal)
// printed "shudder: simulation failed: std::bad_alloc", exit 1 — as if the numerics had failed.
// Now it is bad input (exit 2) saying what to reduce. ulimit -v (2 GB) makes the refusal
// immediate and the same on any machine.
TEST(CliMessages, OutOfMemoryIsBadInputSayingWhatToReduce) {
  const auto dir = scratch_dir("msg_oom_run");
  std::string s = shipped_scenario_text("rig_shudder_negative_slope.toml");
  s = replace(s, "duration_s = 2.0", "duration_s = 1000.0");
  s = replace(s, "time_s = [0.0, 2.0]", "time_s = [0.0, 1000.0]");
  s = replace(s, "sample_rate_Hz = 20000.0", "sample_rate_Hz = 1000000.0");
  write_file(dir / "s.toml", s);
  const std::string cmd = "cd '" + dir.string() + "' && ulimit -v 2000000 && '" + SHUDDER_CLI +
                          "' run s.toml -o out.h5 --force >stdout.txt 2>stderr.txt";
  // --force: past the 2 GB output estimate (app/output_size), to the allocation itself.
  const int status = std::system(cmd.c_str());
  CliResult r;
  r.exit_code = WIFEXITED(status) ? WEXITSTATUS(status) : -1;
  r.out = slurp(dir / "stdout.txt");
  r.err = slurp(dir / "stderr.txt");
  expect_rejected(r, {"shudder: error: s.toml: ran out of memory; reduce the duration, sample_rate_Hz or the "
                      "number of cases"});
  EXPECT_FALSE(std::filesystem::exists(dir / "out.h5"));
}
