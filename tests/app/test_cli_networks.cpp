// The shipped network examples (scenarios/networks/): each runs, closes its energy account, and
// shows what its header says. The judder examples are run twice: with their negative-slope fluid
// (a clutch verdict of vibration) and with fluid C, whose friction rises with slip (none).
#include <gtest/gtest.h>

#include <filesystem>
#include <string>

#include "io/hdf5_run.hpp"
#include "io/measured_run.hpp"
#include "tests/support/cli.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;

struct NetworkRun {
  test::CliResult r;
  dynamics::Recording rec;
};

// Copies the example into a scratch directory beside a copy of the fluids (its fluid paths are
// relative), optionally swapping the fluid file name, and runs it.
NetworkRun run_example(const std::string& name, const std::string& fluid_from = "", const std::string& fluid_to = "") {
  const auto dir = test::scratch_dir("network_" + name + (fluid_to.empty() ? "" : "_swapped"));
  fs::create_directories(dir / "networks");
  fs::copy(test::source_path("scenarios/fluids"), dir / "fluids");
  std::string text = test::slurp(test::source_path("scenarios/networks/" + name + ".toml"));
  if (!fluid_from.empty()) {
    const auto at = text.find(fluid_from);
    EXPECT_NE(at, std::string::npos) << fluid_from;
    if (at != std::string::npos) text.replace(at, fluid_from.size(), fluid_to);
  }
  test::write_file(dir / "networks" / (name + ".toml"), text);
  NetworkRun run;
  run.r = test::run_cli("run networks/" + name + ".toml -o out.h5", dir);
  if (run.r.exit_code == 0) run.rec = io::read_run_hdf5((dir / "out.h5").string());
  return run;
}

std::string verdict_of(const dynamics::Recording& rec, const std::string& block) {
  const auto* b = rec.find_block(block);
  if (!b) return "no block " + block;
  const auto* t = b->find_text("verdict");
  return t ? t->value : "no verdict";
}

TEST(CliNetworks, EveryShippedNetworkRunsAndClosesItsEnergyAccount) {
  int n = 0;
  for (const auto& e : fs::directory_iterator(test::source_path("scenarios/networks"))) {
    if (e.path().extension() != ".toml") continue;
    ++n;
    const auto run = run_example(e.path().stem().string());
    ASSERT_EQ(run.r.exit_code, 0) << e.path() << "\n" << run.r.err;
    const auto* err = run.rec.find_scalar("mechanical_energy_relative_error");
    ASSERT_NE(err, nullptr);
    // The adaptive integration drifts by ~1e-10 on these runs; the guard's bound is 1e-3.
    EXPECT_LT(std::abs(err->value), 1e-6) << e.path();
    EXPECT_NE(run.rec.find_block("verdict"), nullptr) << e.path();
  }
  EXPECT_GE(n, 4);
}

// Four inertias, three clutches closing in turn: all lock, at the common speed
// sum(J w0) / sum(J) = 0.4 x 1500 / 1.0 = 600 rpm, and the heat is the kinetic energy lost.
TEST(CliNetworks, FourInertiaChainLocksAtTheMomentumSpeed) {
  const auto run = run_example("four_inertia_chain");
  ASSERT_EQ(run.r.exit_code, 0) << run.r.err;
  for (const char* node : {"input", "second", "third", "output"})
    EXPECT_NEAR(run.rec.find(std::string(node) + ".speed_rpm")->values.back(), 600.0, 1e-6) << node;
  const double w0 = 1500.0 * 2 * 3.141592653589793 / 60, w1 = 600.0 * 2 * 3.141592653589793 / 60;
  EXPECT_NEAR(run.rec.find_scalar("friction_heat_J")->value, 0.5 * 0.4 * w0 * w0 - 0.5 * 1.0 * w1 * w1, 1e-3);
  for (const char* c : {"c1", "c2", "c3"}) EXPECT_EQ(run.rec.find(std::string(c) + ".stuck")->values.back(), 1.0) << c;
}

// The upshift: the offgoing clutch ends open, the oncoming one locked at the second-gear speed.
TEST(CliNetworks, PowershiftHandsTheTorqueOver) {
  const auto run = run_example("powershift_two_clutches");
  ASSERT_EQ(run.r.exit_code, 0) << run.r.err;
  EXPECT_EQ(run.rec.find("second_clutch.stuck")->values.back(), 1.0);
  EXPECT_EQ(run.rec.find("first_clutch.normal_force_N")->values.back(), 0.0);
  const double crank = run.rec.find("crankshaft.speed_rpm")->values.back();
  const double out = run.rec.find("output_shaft.speed_rpm")->values.back();
  EXPECT_NEAR(crank, 5.2 * out, 1e-6 * crank);  // locked in second gear
}

TEST(CliNetworks, LockupClutchShuddersWithANegativeSlopeFluidAndNotWithFluidC) {
  const auto neg = run_example("lockup_clutch_controlled_slip");
  ASSERT_EQ(neg.r.exit_code, 0) << neg.r.err;
  EXPECT_EQ(verdict_of(neg.rec, "verdict.lockup_clutch"), "vibration") << neg.r.out;
  EXPECT_EQ(verdict_of(neg.rec, "verdict"), "vibration");
  EXPECT_NE(neg.r.out.find("clutch 'lockup_clutch'"), std::string::npos) << neg.r.out;
  // Linear theory about the judged window agrees: an unstable mode at the judder's frequency.
  const auto* b = neg.rec.find_block("verdict.lockup_clutch");
  EXPECT_GT(b->find_scalar("predicted_oscillatory_margin_per_s")->value, 0.0);
  EXPECT_NEAR(b->find_scalar("predicted_frequency_Hz")->value, b->find_scalar("frequency_Hz")->value,
              0.05 * b->find_scalar("frequency_Hz")->value);
  const auto c = run_example("lockup_clutch_controlled_slip", "schematic_negative_slope.toml", "lsc_fluid_c.toml");
  ASSERT_EQ(c.r.exit_code, 0) << c.r.err;
  EXPECT_EQ(verdict_of(c.rec, "verdict.lockup_clutch"), "none") << c.r.out;
  EXPECT_LT(c.rec.find_block("verdict.lockup_clutch")->find_scalar("predicted_oscillatory_margin_per_s")->value, 0.0);
}

TEST(CliNetworks, LaunchJuddersWithANegativeSlopeFluidAndNotWithFluidC) {
  const auto neg = run_example("manual_launch_wet_clutch");
  ASSERT_EQ(neg.r.exit_code, 0) << neg.r.err;
  EXPECT_EQ(verdict_of(neg.rec, "verdict.launch_clutch"), "vibration") << neg.r.out;
  const auto* b = neg.rec.find_block("verdict.launch_clutch");
  EXPECT_GT(b->find_scalar("predicted_oscillatory_margin_per_s")->value, 0.0);
  EXPECT_NEAR(b->find_scalar("predicted_frequency_Hz")->value, b->find_scalar("frequency_Hz")->value,
              0.05 * b->find_scalar("frequency_Hz")->value);
  const auto c = run_example("manual_launch_wet_clutch", "schematic_launch_negative_slope.toml", "lsc_fluid_c.toml");
  ASSERT_EQ(c.r.exit_code, 0) << c.r.err;
  EXPECT_EQ(verdict_of(c.rec, "verdict.launch_clutch"), "none") << c.r.out;
}

// The bench network, judged on its torsion bar as the rig's torque cell reads it, against the rig
// kind's scenario of the same machine (rig_shudder_negative_slope: 30 rpm, 15 kN, 378 Hz bar,
// the same estimated inertias, bar and speed loop): the same verdict at the same frequency and
// amplitude. They differ in their start (the network at rest on an unloaded bar, the rig in
// steady sliding), which the saturated oscillation forgets: 1 % on the frequency (the spectra's
// resolution) and 5 % on the amplitude.
TEST(CliNetworks, BenchJudgedOnItsBarMatchesTheRigKind) {
  const auto bench = run_example("wet_clutch_bench");
  ASSERT_EQ(bench.r.exit_code, 0) << bench.r.err;
  const auto dir = test::scratch_dir("network_bench_rig");
  const auto rig =
      test::run_cli("run '" + test::source_path("scenarios/rig_shudder_negative_slope.toml") + "' -o rig.h5", dir);
  ASSERT_EQ(rig.exit_code, 0) << rig.err;
  const auto rig_rec = io::read_run_hdf5((dir / "rig.h5").string());
  const auto* a = bench.rec.find_block("verdict");
  const auto* b = rig_rec.find_block("verdict");
  EXPECT_EQ(a->find_text("verdict")->value, b->find_text("verdict")->value);
  const double fa = a->find_scalar("frequency_Hz")->value, fb = b->find_scalar("frequency_Hz")->value;
  const double aa = a->find_scalar("amplitude_Nm")->value, ab = b->find_scalar("amplitude_Nm")->value;
  EXPECT_NEAR(fa, fb, 0.01 * fb);
  EXPECT_NEAR(aa, ab, 0.05 * ab);
  EXPECT_NE(a->find_text("judged_signals")->value.find("torsion_bar.torque_Nm"), std::string::npos);
}

// Two wet clutches on one motor, each with its own fluid, thermal model and verdict: the
// negative-slope clutch vibrates at its bar's frequency, the fluid C one does not; each clutch's
// heat account closes and its generated heat equals the friction work its contact integrated.
TEST(CliNetworks, TwoWetClutchesEachWithItsOwnFluidAndThermalModel) {
  const auto dir = test::scratch_dir("network_two_wet");
  fs::create_directories(dir / "networks");
  fs::copy(test::source_path("scenarios/fluids"), dir / "fluids");
  std::string text = test::slurp(test::source_path("scenarios/networks/wet_clutch_bench.toml"));
  text += R"(
[network.second_clutch]
type = "clutch"
law = "wet"
from = "drive"
to = "second_housing"
max_force_N = 15000
[network.second_clutch.clutch]
fluid = "../fluids/lsc_fluid_c.toml"
start_temp_C = 40.0
[network.second_housing]
type = "inertia"
inertia_kg_m2 = 0.02
[network.second_bar]
type = "shaft"
from = "second_housing"
to = "ground"
stiffness_Nm_per_rad = 1.128e5
damping_Nms_per_rad = 0.95
)";
  test::write_file(dir / "networks/two.toml", text);
  const auto r = test::run_cli("run networks/two.toml -o two.h5", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto rec = io::read_run_hdf5((dir / "two.h5").string());
  EXPECT_EQ(verdict_of(rec, "verdict.clutch"), "vibration");
  EXPECT_EQ(verdict_of(rec, "verdict.second_clutch"), "none");
  EXPECT_EQ(rec.find_block("verdict")->find_text("clutch")->value, "clutch");
  for (const std::string c : {"clutch", "second_clutch"}) {
    EXPECT_LT(rec.find_scalar(c + ".energy_balance_relative_error")->value, 1e-9) << c;
    const double generated = rec.find_scalar(c + ".heat_generated_J")->value;
    EXPECT_NEAR(generated, rec.find_scalar(c + ".friction_work_J")->value, 1e-6 * generated) << c;
  }
  // Their own thermal models: they started 20 K apart and stay apart.
  EXPECT_GT(rec.find("clutch.interface_mean_temp_C")->values.back(),
            rec.find("second_clutch.interface_mean_temp_C")->values.back() + 10.0);
}

// `run --measurement RUN.csv` on a network: one measured run per wet clutch, RUN.CLUTCH.csv, that
// the measured-run reader accepts: the clutch's slip as speed, its torque, force and thermocouple.
TEST(CliNetworks, MeasurementIsWrittenPerWetClutch) {
  const auto dir = test::scratch_dir("network_measurement");
  fs::create_directories(dir / "networks");
  fs::copy(test::source_path("scenarios/fluids"), dir / "fluids");
  fs::copy_file(test::source_path("scenarios/networks/lockup_clutch_controlled_slip.toml"), dir / "networks/l.toml");
  const auto r = test::run_cli("run networks/l.toml -o l.h5 --measurement l.csv --sample-rate 200", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  const auto m = io::read_measured_run((dir / "l.lockup_clutch.csv").string());
  EXPECT_EQ(m.meta("rig").value_or(""), "network_clutch");
  EXPECT_EQ(m.rows(), 601u);  // 3 s at 200 samples/s, both ends
  const auto rec = io::read_run_hdf5((dir / "l.h5").string());
  EXPECT_NEAR(m.required("torque_Nm").back(), rec.find("lockup_clutch.torque_Nm")->values.back(), 1e-3);
  // A network without a wet clutch has no sensor to log: refused, nothing written.
  fs::copy_file(test::source_path("scenarios/networks/four_inertia_chain.toml"), dir / "networks/c.toml");
  const auto plain = test::run_cli("run networks/c.toml -o c.h5 --measurement c.csv", dir);
  EXPECT_EQ(plain.exit_code, 2);
  EXPECT_NE(plain.err.find("no wet clutch"), std::string::npos) << plain.err;
  EXPECT_FALSE(fs::exists(dir / "c.h5"));
}

// `shudder plot` on a network's run file: the clutches' torques, their temperatures, and the
// spectra of the clutch the run's verdict names.
TEST(CliNetworks, PlotsDrawTheJudgedClutch) {
  const auto dir = test::scratch_dir("network_plots");
  fs::create_directories(dir / "networks");
  fs::copy(test::source_path("scenarios/fluids"), dir / "fluids");
  fs::copy_file(test::source_path("scenarios/networks/lockup_clutch_controlled_slip.toml"), dir / "networks/l.toml");
  ASSERT_EQ(test::run_cli("run networks/l.toml -o l.h5", dir).exit_code, 0);
  for (const char* what : {"torque", "temperature", "spectrum", "spectrogram"}) {
    const auto r = test::run_cli(std::string("plot l.h5 --what ") + what + " -o " + what + ".svg", dir);
    EXPECT_EQ(r.exit_code, 0) << what << ": " << r.err;
    EXPECT_TRUE(fs::exists(dir / (std::string(what) + ".svg"))) << what;
  }
  EXPECT_NE(test::slurp(dir / "torque.svg").find("lockup_clutch.torque_Nm"), std::string::npos);
  // --report: the summary, the verdict and the run's plots in one directory.
  const auto r = test::run_cli("run networks/l.toml -o l2.h5 --report rep", dir);
  ASSERT_EQ(r.exit_code, 0) << r.err;
  for (const char* f : {"summary.txt", "verdict.json", "torque.png", "temperature.png", "spectrum.png"})
    EXPECT_TRUE(fs::exists(dir / "rep" / f)) << f << "\n" << r.err;
  EXPECT_NE(test::slurp(dir / "rep" / "verdict.json").find("lockup_clutch"), std::string::npos);
}

}  // namespace
}  // namespace shudder
