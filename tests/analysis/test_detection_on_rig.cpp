// Shudder detection end to end on the rig model (rig_models/lsctr_rig) with the shipped
// scenarios, loaded through io::load_scenario as the CLI does:
//
//   rig_shudder_negative_slope.toml  fluid whose mu falls with speed, 30 rpm, 15 kN, 378 Hz bar:
//                                    the clutch-side mode grows into a limit cycle with the slip
//                                    staying positive                    -> vibration at ~378 Hz
//   rig_stick_slip.toml              1 rpm, mu_s/mu_k = 1.3, from rest  -> stick_slip
//   rig_case1_25kN_378Hz.toml        fluid C, 1 -> 100 rpm at 25.3 kN   -> none (thesis: no shudder)
//
// Frequencies are checked against measures independent of the FFT: the housing-mode frequency
// of the rig's modal analysis, zero crossings of the housing speed, and the number of
// breakaways per second.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <filesystem>
#include <unistd.h>
#include <numbers>
#include <string>
#include <vector>

#include "analysis/shudder_detection.hpp"
#include "clutch/wet_clutch.hpp"
#include "core/units.hpp"
#include "dynamics/recording.hpp"
#include "io/hdf5_run.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/models.hpp"
#include "tests/support/recording.hpp"
#include "tests/support/record_property.hpp"

namespace {

using shudder::analysis::ShudderDetector;
using shudder::analysis::ShudderResult;
using shudder::analysis::Verdict;
using shudder::dynamics::Recording;

using shudder::test::record;

shudder::io::Scenario scenario(const std::string& name) {
  return shudder::io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/" + name);
}

// `ripple`: false switches the motor's torque ripple off, for closed forms of the
// undisturbed rig.
Recording run(const shudder::io::Scenario& sc, bool ripple = true) {
  const auto clutch = sc.make_clutch();
  auto params = shudder::test::rig_model(sc).params;
  if (!ripple) params.motor_ripple.amplitude_Nm = 0.0;
  return shudder::rig_models::run_rig(params, clutch, shudder::test::rig_model(sc).cycle,
                                      shudder::test::rig_model(sc).settings);
}

using shudder::test::scalar;
using shudder::test::signal;

// Negative-slope fluid: vibration at the clutch-side frequency. Tolerances:
//   * against the housing mode of the modal analysis (clutch slipping, undamped): 5 %, as the
//     rig's own shudder test argues — damping ~1 N m s/rad against √(k J_h) ≈ 47 shifts the
//     frequency by ~(ζ_eff)² and the limit cycle's nonlinearity by a few per mille;
//   * against the mean period of the housing speed's upward zero crossings over the
//     oscillating part (the housing is tied to ground by the bar, so its speed oscillates
//     about 0): 0.2 %, one period miscounted in the ~400 counted.
// The slip stays far from zero (the fluid's rising branch below 10 rpm bounds the swing), so
// no cycle reaches zero. The onset's operating point is the scenario's: 30 rpm (the drive's
// speed; the housing barely moves yet), 15 kN, the 60 °C start temperature (+ < 5 K of
// warming by the onset).
TEST(DetectionOnRig, NegativeSlopeFluidIsVibrationAtTheClutchSideFrequency) {
  const auto sc = scenario("rig_shudder_negative_slope.toml");
  const Recording rec = run(sc);
  const ShudderDetector det;
  const ShudderResult r = det.detect(rec);
  const double f_mode = scalar(rec, "clutch_side_frequency_Hz");

  const auto& t = signal(rec, "time_s");
  const auto& wh = signal(rec, "housing_speed_rpm");
  std::vector<double> up;
  for (std::size_t k = 1; k < t.size(); ++k)
    if (t[k] >= r.oscillating_from_s && wh[k - 1] < 0.0 && wh[k] >= 0.0)
      up.push_back(t[k - 1] + (t[k] - t[k - 1]) * (-wh[k - 1]) / (wh[k] - wh[k - 1]));
  ASSERT_GT(up.size(), 100u);
  const double f_zc = static_cast<double>(up.size() - 1) / (up.back() - up.front());

  record("negative_slope",
         "%s: f %.3f Hz (mode %.3f Hz, zero crossings %.3f Hz), amplitude %.3f N m "
         "(threshold %.3f), onset %.4f s at slip %.2f rpm, %.2f degC, %.0f N; oscillating %.3f-%.3f s, "
         "cycles at zero %.3f",
         std::string(to_string(r.verdict)).c_str(), r.frequency_Hz, f_mode, f_zc, r.amplitude_Nm, r.threshold_Nm,
         r.onset_time_s, r.at_onset.slip_rpm, r.at_onset.interface_temp_C, r.at_onset.normal_force_N,
         r.oscillating_from_s, r.oscillating_to_s, r.stick_cycle_fraction);
  ASSERT_EQ(r.verdict, Verdict::kVibration);
  EXPECT_NEAR(r.frequency_Hz / f_mode, 1.0, 0.05);
  EXPECT_NEAR(r.frequency_Hz / 378.0, 1.0, 0.05);
  EXPECT_NEAR(r.frequency_Hz / f_zc, 1.0, 2e-3);
  EXPECT_EQ(r.stick_cycle_fraction, 0.0);
  EXPECT_GT(r.amplitude_Nm, 10.0 * r.threshold_Nm);  // a clear shudder, not a marginal call
  EXPECT_NEAR(r.at_onset.slip_rpm, 30.0, 1.0);
  EXPECT_DOUBLE_EQ(r.at_onset.normal_force_N, 15000.0);
  EXPECT_GE(r.at_onset.interface_temp_C, 60.0 - 1e-9);
  EXPECT_LT(r.at_onset.interface_temp_C, 65.0);
  EXPECT_LT(r.onset_time_s, r.oscillating_from_s);

  // Growth rate against the linearised housing equation at the start (docs/physics.md §6):
  //   J_h θ'' + (c_bar + dT_k/dΔω) θ' + k_bar θ = 0  ⇒  σ = −(c_bar + dT_k/dΔω) / (2 J_h)
  // with the kinetic-torque slope of the contact law at 30 rpm and the start temperature. The
  // drive is taken as fixed (J_d = 30 J_h: the reduced inertia J_h J_d/(J_h + J_d) is 3 %
  // smaller), the interface warms by ~1 K over the fitted span, and the fit ends where the
  // slip swings by ~±2 rpm about 30 rpm: each ≤ 3 %, the tolerance (measured 0.1 %).
  const auto clutch = sc.make_clutch();
  const auto rig_model = shudder::test::rig_model(sc);
  const shudder::rig_models::LsctrRig rig(rig_model.params, clutch, rig_model.cycle);
  shudder::components::ClutchContext start(
      {clutch.thermal().interface_temps_C(clutch.initial_state()), rig_model.cycle.normal_force_N});
  const double slope_Nms =
      rig.clutch_contact().kinetic_torque_slope_Nms(start, shudder::units::rpm_to_rad_s(30.0), 0.0);
  const double sigma_pred =
      -(rig.bar_damping_Nms_per_rad() + slope_Nms) / (2.0 * rig_model.params.housing_inertia_kg_m2);
  record("negative_slope_growth", "growth rate %.3f 1/s, linearised %.3f 1/s (c_bar %.3f, dT/dw %.3f N m s/rad)",
         r.growth_rate_per_s, sigma_pred, rig.bar_damping_Nms_per_rad(), slope_Nms);
  EXPECT_TRUE(r.growth_observed);
  EXPECT_NEAR(r.growth_rate_per_s / sigma_pred, 1.0, 0.03);

  // Through the run file: write and read back (io/hdf5_run, the layout `shudder run` writes);
  // the same detection, bit for bit.
  const auto path =
      std::filesystem::temp_directory_path() / ("shudder_test_detection_on_rig_" + std::to_string(::getpid()) + ".h5");
  shudder::io::write_run_hdf5(path.string(), rec, sc.text);
  const Recording back = shudder::io::read_run_hdf5(path.string());
  std::filesystem::remove(path);
  const ShudderResult rb = det.detect(back);
  EXPECT_EQ(rb.verdict, r.verdict);
  EXPECT_EQ(rb.frequency_Hz, r.frequency_Hz);
  EXPECT_EQ(rb.amplitude_Nm, r.amplitude_Nm);
  EXPECT_EQ(rb.onset_time_s, r.onset_time_s);
}

// End to end through the command line: `shudder run SCENARIO -o OUT.h5`, read back with
// io::read_run_hdf5, gives the detection of the in-process run exactly (the CLI runs the same
// model on the same scenario; the file stores doubles as they are).
TEST(DetectionOnRig, CliRunFileGivesTheSameDetectionAsTheInProcessRun) {
  const auto dir = shudder::test::scratch_dir("detection_on_rig_cli");
  const std::string scenario_path = shudder::test::source_path("scenarios/rig_shudder_negative_slope.toml");
  const auto res = shudder::test::run_cli("run '" + scenario_path + "' -o out.h5", dir);
  ASSERT_EQ(res.exit_code, 0) << res.err;
  const ShudderDetector det;
  const ShudderResult from_file = det.detect(shudder::io::read_run_hdf5((dir / "out.h5").string()));
  const ShudderResult in_process = det.detect(run(scenario("rig_shudder_negative_slope.toml")));
  EXPECT_EQ(from_file.verdict, Verdict::kVibration);
  EXPECT_EQ(from_file.verdict, in_process.verdict);
  EXPECT_EQ(from_file.frequency_Hz, in_process.frequency_Hz);
  EXPECT_EQ(from_file.amplitude_Nm, in_process.amplitude_Nm);
  EXPECT_EQ(from_file.onset_time_s, in_process.onset_time_s);
  std::filesystem::remove_all(dir);
}

// Stick-slip at 1 rpm: stuck phases every cycle -> stick_slip, at the breakaway rate. The
// first breakaway (~0.35 s) is the onset: the clutch sits stuck and winds the bar up
// smoothly before it, which puts next to nothing in the band (80 dB under the stick-slip).
// The first cycles are shorter (3.3 ms against 4.75 ms) while the motor's speed loop
// settles, so the FFT peak, dominated by the settled cycles, is checked against the
// breakaways per second after 0.5 s: 1 %, one cycle in the ~100 counted.
TEST(DetectionOnRig, LowSpeedStickSlipIsStickSlipAtTheBreakawayRate) {
  // Without the motor ripple: at 1 rpm it runs at 9.6 Hz and modulates the cycle lengths the
  // breakaway-rate check counts.
  const Recording rec = run(scenario("rig_stick_slip.toml"), false);
  const ShudderResult r = ShudderDetector().detect(rec);
  const auto& t = signal(rec, "time_s");
  const auto& stuck = signal(rec, "stuck");
  std::vector<double> breakaways;
  for (std::size_t k = 1; k < t.size(); ++k)
    if (stuck[k - 1] == 1.0 && stuck[k] == 0.0) breakaways.push_back(t[k]);
  ASSERT_GT(breakaways.size(), 50u);
  std::size_t k5 = 0;
  while (k5 < breakaways.size() && breakaways[k5] < 0.5) ++k5;
  ASSERT_LT(k5 + 50, breakaways.size());
  const double f_ba = static_cast<double>(breakaways.size() - 1 - k5) / (breakaways.back() - breakaways[k5]);

  record("stick_slip",
         "%s: f %.3f Hz (breakaways after 0.5 s %.3f Hz), amplitude %.3f N m, onset %.4f s (first breakaway "
         "%.4f s) at slip %.3f rpm, cycles at zero %.3f",
         std::string(to_string(r.verdict)).c_str(), r.frequency_Hz, f_ba, r.amplitude_Nm, r.onset_time_s,
         breakaways.front(), r.at_onset.slip_rpm, r.stick_cycle_fraction);
  ASSERT_EQ(r.verdict, Verdict::kStickSlip);
  EXPECT_NEAR(r.frequency_Hz / f_ba, 1.0, 0.01);
  EXPECT_GT(r.stick_cycle_fraction, 0.95);
  EXPECT_TRUE(r.growth_observed);
  // Onset within a frame length of the first breakaway (frames of 8 periods ≈ 37 ms, the
  // interpolated crossing smeared by the window over ±half a frame).
  const double frame_s = 1024.0 / 20000.0;
  EXPECT_NEAR(r.onset_time_s, breakaways.front(), frame_s);
}

// Fluid C (positive slope) on the 378 Hz bar from 1 to 100 rpm: no shudder. The torque's
// ripple about its one-period moving mean stays below the threshold (1 % of the mean torque).
TEST(DetectionOnRig, FluidCCase1IsNone) {
  const Recording rec = run(scenario("rig_case1_25kN_378Hz.toml"));
  const ShudderResult r = ShudderDetector().detect(rec);
  record("case1", "%s: amplitude %.4f N m, threshold %.4f N m, peak %.3f Hz, mean torque %.2f N m",
         std::string(to_string(r.verdict)).c_str(), r.amplitude_Nm, r.threshold_Nm, r.peak_frequency_Hz,
         r.mean_torque_Nm);
  EXPECT_EQ(r.verdict, Verdict::kNone);
  EXPECT_LT(r.amplitude_Nm, r.threshold_Nm);
  EXPECT_TRUE(std::isnan(r.onset_time_s));
}

}  // namespace
