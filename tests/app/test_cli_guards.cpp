// Physical guards and file safety end to end. Each test names what
// the code before these guards did with the same input.
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <toml++/toml.h>

#include <chrono>
#include <filesystem>

#include "io/hdf5_run.hpp"
#include "tests/support/cli.hpp"

using namespace shudder;
using namespace shudder::test;
using ::testing::HasSubstr;
namespace fs = std::filesystem;

namespace {

// Paper G Case 1 at 10 kN (10 s at 100 S/s: the quickest shipped run) with its fluid copied
// beside it at the relative path the scenario names, so the directory is self-contained.
fs::path case1_dir(const std::string& name) {
  const auto dir = scratch_dir(name);
  fs::create_directories(dir / "fluids");
  fs::copy_file(source_path("scenarios/paper_g_case1_10kN.toml"), dir / "s.toml");
  fs::copy_file(source_path("scenarios/fluids/lsc_fluid_c.toml"), dir / "fluids/lsc_fluid_c.toml");
  return dir;
}

}  // namespace

// ---- physical guards ------------------------------------------------------------------------

TEST(CliGuards, FluidWithBetaNegatedIsRejectedWhenLoaded) {
  // Unchecked, a scenario with this fluid runs to exit 0 with -4,923 J of heat.
  const auto dir = scratch_dir("guard_beta");
  write_file(dir / "neg.toml", replace(slurp(source_path("scenarios/fluids/paper_e_fluid_a.toml")),
                                       "beta = [0.1018, 0.1164]", "beta = [-0.1018, -0.1164]"));
  expect_rejected(run_cli("screen neg.toml", dir),
                  {"neg.toml", "key 'linear.beta'", "mu = -0.08012 <= 0", "speed 1 rpm", "temperature -40 °C"});
  write_file(dir / "s.toml",
             replace(shipped_scenario_text("paper_g_case1_10kN.toml"),
                     "fluid = \"" + source_path("scenarios/fluids/lsc_fluid_c.toml") + "\"", "fluid = \"neg.toml\""));
  const auto r = run_cli("run s.toml -o out.h5", dir);
  expect_rejected(r, {"neg.toml", "key 'linear.beta'"});
  EXPECT_FALSE(fs::exists(dir / "out.h5"));
}

TEST(CliGuards, FilmThicknessOf1e300MicronsIsRejectedWithItsBounds) {
  // Old code: accepted (> 0), the run reached 5e279 °C and exited 0.
  expect_rejected(run_scenario_in("guard_film", shipped_scenario_text("paper_g_case1_10kN.toml") +
                                                    "\n[clutch.oil]\nfilm_thickness_um = 1e-300\n"),
                  {"s.toml", "key 'clutch.oil.film_thickness_um'", "[0.01, 1000]"});
}

TEST(CliGuards, ViscousGapOf1e300MicronsIsRejectedWithItsBounds) {
  // Old code: accepted (> 0), the run reached 3.4e298 N m and exited 0.
  expect_rejected(run_scenario_in("guard_gap", shipped_scenario_text("paper_g_case1_10kN.toml") +
                                                   "\n[effects.viscous_shear]\nenabled = true\ngap_um = 1e-300\n"),
                  {"s.toml", "effects.viscous_shear.gap_um", "[0.01, 10000]"});
}

TEST(CliGuards, RunWhoseMechanicalEnergyDoesNotCloseIsANumericalFailureWithTheFileKept) {
  // The stick-slip rig with the loosest tolerances the reader accepts (1e-2): the integration
  // loses 4 % of the motor's work (mechanical energy error 3.96e-02). Old code: printed the
  // figure in the summary and exited 0.
  const auto dir = scratch_dir("guard_energy");
  write_file(dir / "s.toml", shipped_scenario_text("rig_stick_slip.toml") +
                                 "\n[solver]\nabs_tol = 1e-2\nrel_tol = 1e-2\nmax_step_ms = 1000\n");
  const auto r = run_cli("run s.toml -o out.h5", dir);
  EXPECT_EQ(r.exit_code, 1) << r.out << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_THAT(r.err, HasSubstr("shudder: simulation failed: numerical failure: mechanical energy balance error 0.0"));
  EXPECT_THAT(r.err, HasSubstr("exceeds the bound 1e-03; the run is written to out.h5 for inspection"));
  // The file is written and complete, its figure the one named.
  const auto rec = io::read_run_hdf5((dir / "out.h5").string());
  ASSERT_NE(rec.find_scalar("mechanical_energy_relative_error"), nullptr);
  EXPECT_GT(rec.find_scalar("mechanical_energy_relative_error")->value, 1e-3);
}

// ---- file safety ----------------------------------------------------------------------------

TEST(CliFileSafety, RunOutputOverTheScenarioIsRefusedAndTheScenarioKept) {
  // Old code: `run s.toml -o s.toml` replaced the scenario with the HDF5 file, exit 0.
  const auto dir = case1_dir("safe_over_scenario");
  const std::string before = slurp(dir / "s.toml");
  expect_rejected(run_cli("run s.toml -o ./s.toml", dir), {"output -o is the scenario 's.toml'"});
  EXPECT_EQ(slurp(dir / "s.toml"), before);
  expect_rejected(run_cli("run s.toml -o fluids/../fluids/lsc_fluid_c.toml", dir), {"output -o is the fluid file"});
}

TEST(CliFileSafety, MeasurementAndRunFileWithTheSameNameAreRefused) {
  // Old code: exit 0, and same.h5 held only /measurement (the run file was overwritten).
  const auto dir = case1_dir("safe_same_outputs");
  expect_rejected(run_cli("run s.toml --measurement same.h5 -o same.h5", dir),
                  {"same.h5", "output --measurement is also the output -o 'same.h5'"});
  EXPECT_FALSE(fs::exists(dir / "same.h5"));
}

TEST(CliFileSafety, SweepIntoAMissingDirectoryIsRefusedAndCreatesNothing) {
  // Old code: created nonexistent/ (and its parts folder) and ran; `run` refused the same -o.
  const auto dir = scratch_dir("safe_sweep_dir");
  write_file(dir / "s.toml", shipped_scenario_text("sweep_torsion_bar.toml"));
  const auto r = run_cli("sweep s.toml --set rig.torsion_bar.natural_frequency_Hz=200,300 -o nonexistent/s.h5", dir);
  expect_rejected(r, {"nonexistent/s.h5", "does not exist; create it first"});
  EXPECT_FALSE(fs::exists(dir / "nonexistent"));
  expect_rejected(run_cli("run s.toml -o nonexistent/r.h5", dir), {"does not exist; create it first"});
  expect_rejected(run_cli("sweep s.toml --set rig.torsion_bar.natural_frequency_Hz=200 -o s.toml", dir),
                  {"output -o is the scenario 's.toml'"});
}

TEST(CliFileSafety, HugeOutputIsRefusedBeforeSimulatingUnlessForced) {
  // Old code: simulated 30 s at 1 MHz for many minutes and wrote 3.6 GB without a word.
  // 30 s x 1e6 S/s + 1 = 30,000,001 samples x 15 channels x 8 bytes = 3.60 GB.
  const auto dir = scratch_dir("safe_size");
  write_file(dir / "s.toml", replace(shipped_scenario_text("rig_case2_15kN_175Hz.toml"), "sample_rate_Hz = 1000.0",
                                     "sample_rate_Hz = 1e6"));
  const auto t0 = std::chrono::steady_clock::now();
  const auto r = run_cli("run s.toml -o out.h5", dir);
  const double wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  expect_rejected(r, {"out.h5", "estimated output size 3.60 GB (30000001 samples x 15 channels x 8 bytes",
                      "exceeds the limit of 2 GB", "--force"});
  EXPECT_LT(wall_s, 10.0);  // refused before simulating (the simulation takes minutes)
  EXPECT_FALSE(fs::exists(dir / "out.h5"));
}

TEST(CliFileSafety, HugeSweepIsRefusedBeforeRunning) {
  // 3 cases x (20 s x 1e6 S/s + 1) samples x 5 kept signals x 8 bytes = 2.40 GB.
  const auto dir = scratch_dir("safe_sweep_size");
  write_file(dir / "s.toml", replace(shipped_scenario_text("sweep_torsion_bar.toml"), "sample_rate_Hz = 5000.0",
                                     "sample_rate_Hz = 1e6"));
  const auto r = run_cli("sweep s.toml --set rig.torsion_bar.natural_frequency_Hz=100,200,300 -o sw.h5", dir);
  expect_rejected(r, {"sw.h5", "estimated output size 2.40 GB (3 cases", "--force"});
  EXPECT_FALSE(fs::exists(dir / "sw.h5.parts"));
}

TEST(CliFileSafety, ForceIsAcceptedByRun) {
  // Old code: "--force" was an unknown option (exit 2).
  const auto dir = case1_dir("safe_force");
  const auto r = run_cli("run s.toml -o out.h5 --force", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
}

TEST(CliFileSafety, ARunIsReproducedFromItsFileAlone) {
  // Old code: the file held the scenario's text but not the fluid's, so `fluid` read "" and the
  // run could not be repeated without the original fluid file.
  const auto first = case1_dir("repro_first");
  auto r = run_cli("run s.toml -o a.h5", first);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const std::string scenario = io::read_run_attribute((first / "a.h5").string(), "scenario");
  const std::string fluid = io::read_run_attribute((first / "a.h5").string(), "fluid");
  ASSERT_EQ(fluid, slurp(source_path("scenarios/fluids/lsc_fluid_c.toml")));

  // A fresh directory with only what the file holds: the scenario, and the fluid at the
  // (relative) path the scenario names.
  const auto second = scratch_dir("repro_second");
  const std::string fluid_rel = toml::parse(scenario)["clutch"]["fluid"].value_or(std::string());
  ASSERT_EQ(fluid_rel, "fluids/lsc_fluid_c.toml");
  fs::create_directories((second / fluid_rel).parent_path());
  write_file(second / "s.toml", scenario);
  write_file(second / fluid_rel, fluid);
  r = run_cli("run s.toml -o b.h5", second);
  ASSERT_EQ(r.exit_code, 0) << r.err;

  // Bit-identical signals and thermal snapshots.
  const auto a = io::read_run_hdf5((first / "a.h5").string());
  const auto b = io::read_run_hdf5((second / "b.h5").string());
  ASSERT_EQ(a.signals.size(), b.signals.size());
  for (std::size_t k = 0; k < a.signals.size(); ++k) {
    EXPECT_EQ(a.signals[k].name, b.signals[k].name);
    EXPECT_EQ(a.signals[k].values, b.signals[k].values) << a.signals[k].name;
  }
  ASSERT_EQ(a.snapshots.size(), b.snapshots.size());
  for (std::size_t k = 0; k < a.snapshots.size(); ++k) EXPECT_EQ(a.snapshots[k].temp_C, b.snapshots[k].temp_C);
}
