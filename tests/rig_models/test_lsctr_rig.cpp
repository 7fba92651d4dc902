// The Limited Slip Clutch Test Rig (rig_models/lsctr_rig) on the scenarios shipped in
// scenarios/rig_*.toml, loaded through io::load_scenario as the CLI does:
//
//   drive (motor+gearbox+shaft+disc, J_d) ─┤clutch├─ housing (J_h) ─ torsion bar k_bar ─ ground
//        ▲ PI speed loop                                   torque cell reads k_bar θ_h + c_bar ω_h
//
//   * the bar stiffness is derived from its target frequency (closed form k = J_h (2πf)²),
//   * the rig does not distort a quasi-static test: Case 1 against prescribed slip,
//   * fluid C on the 175 and 378 Hz bars: no shudder, the same mean friction,
//   * a negative mu-v slope shudders at the clutch-side damped natural frequency, which moves
//     with the bar,
//   * stick-slip: slip returns to zero each cycle, stuck phases have slip exactly 0, and the
//     torque jump is 2 (T_s − T_k) within a budget of the rig's departures from the ideal,
//   * halving the thermal step changes the rig's end torque and temperature < 0.5 %.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <string>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "core/units.hpp"
#include "dynamics/recording.hpp"
#include "io/scenario.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"
#include "tests/support/models.hpp"
#include "tests/support/recording.hpp"
#include "tests/support/record_property.hpp"

namespace {

using shudder::clutch::WetClutch;
using shudder::dynamics::Modes;
using shudder::dynamics::Recording;
using shudder::io::load_scenario;
using shudder::io::Scenario;
using shudder::rig_models::LsctrRig;
using shudder::rig_models::run_prescribed_slip;
using shudder::rig_models::run_rig;

using shudder::units::kTwoPi;

Scenario scenario(const std::string& name) {
  return load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/" + name);
}

using shudder::test::scalar;
using shudder::test::signal;

// Records a measured number in the test's XML output (--gtest_output=xml), printf-formatted.
using shudder::test::record;

// The closed forms below describe the undisturbed rig, so the motor's torque ripple (
// tests/components/test_motor_ripple.cpp) is switched off in every run of this file.
shudder::rig_models::RigParams without_ripple(shudder::rig_models::RigParams p) {
  p.motor_ripple.amplitude_Nm = 0.0;
  return p;
}

Recording run(const Scenario& sc) {
  const WetClutch clutch = sc.make_clutch();
  return run_rig(without_ripple(shudder::test::rig_model(sc).params), clutch, shudder::test::rig_model(sc).cycle,
                 shudder::test::rig_model(sc).settings);
}

// Rig Case 1 at the scenario's 10 ms thermal step, shared by two tests (0.15 s per run).
const Recording& rig_case1() {
  static const Recording rec = run(scenario("rig_case1_25kN_378Hz.toml"));
  return rec;
}

// Column of the mode in which the housing moves and the drive does not (the housing is
// decoupled while the clutch slips, so its mode has an exactly zero drive amplitude).
Eigen::Index housing_mode(const Modes& m) {
  Eigen::Index best = 0;
  for (Eigen::Index j = 1; j < m.shapes.cols(); ++j)
    if (std::abs(m.shapes(LsctrRig::kHousing, j)) - std::abs(m.shapes(LsctrRig::kDrive, j)) >
        std::abs(m.shapes(LsctrRig::kHousing, best)) - std::abs(m.shapes(LsctrRig::kDrive, best)))
      best = j;
  return best;
}

// The damped eigenvalue (imag > 0) of the housing mode: the one whose modulus is nearest the
// undamped housing frequency ω_n (|λ| = ω_n exactly for a single damped oscillator). The drive's
// loop poles are real (a double pole at −ω_c/2 = −63 1/s), far from 2π·100..500 Hz.
std::complex<double> housing_eigenvalue(const Modes& m) {
  const double wn = kTwoPi * m.frequencies_Hz[housing_mode(m)];
  std::complex<double> best{0.0, 0.0};
  for (const auto& l : m.damped_eigenvalues)
    if (l.imag() > 0 && std::abs(std::abs(l) - wn) < std::abs(std::abs(best) - wn)) best = l;
  return best;
}

// Frequency of a signal from its upward zero crossings in [t_from, t_to], Hz: (N − 1) periods
// between the first and last crossing, each crossing located by linear interpolation.
double zero_crossing_frequency_Hz(const std::vector<double>& t, const std::vector<double>& x, double t_from,
                                  double t_to, int* crossings = nullptr) {
  std::vector<double> up;
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (t[k - 1] < t_from || t[k] > t_to) continue;
    if (x[k - 1] < 0.0 && x[k] >= 0.0) up.push_back(t[k - 1] + (t[k] - t[k - 1]) * (-x[k - 1]) / (x[k] - x[k - 1]));
  }
  if (crossings) *crossings = static_cast<int>(up.size());
  if (up.size() < 2) return 0.0;
  return static_cast<double>(up.size() - 1) / (up.back() - up.front());
}

double max_abs(const std::vector<double>& t, const std::vector<double>& x, double t_from, double t_to) {
  double m = 0.0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= t_from && t[k] <= t_to) m = std::max(m, std::abs(x[k]));
  return m;
}

// ---------------------------------------------------------------------------------------------
// 1. Bar stiffness from the target frequency.
//
//   housing J_h ── k_bar ── ground,   clutch slipping ⇒ no stiffness between drive and housing
//
// While the clutch slips, K and M are diagonal in (drive, housing): the drive sees only its
// speed loop (K_i, K_p to ground) and the housing only the bar, so the clutch-side mode is the
// single oscillator ω² = k_bar / J_h, i.e. k_bar = J_h (2π f)², with shape (0, 1), and its
// damped eigenvalue λ = −ζ ω_n ± i ω_n √(1 − ζ²) with c_bar = 2 ζ √(k_bar J_h).
// Tolerances: the spec asks 0.5 %; the constructor refines k_bar on the modal analysis to
// 1e-10, and the closed forms hold to eigen-solver round-off (~1e-15 of the largest eigenvalue,
// which is the housing's here), so 1e-9 is asserted on them.
// ---------------------------------------------------------------------------------------------
TEST(RigBar, StiffnessDerivedFromTargetFrequencyMatchesClutchSideModeAndClosedForm) {
  const Scenario sc = scenario("rig_case1_25kN_378Hz.toml");
  const WetClutch clutch = sc.make_clutch();
  for (const double target_Hz : {100.0, 175.0, 378.0, 500.0}) {
    SCOPED_TRACE(target_Hz);
    auto params = shudder::test::rig_model(sc).params;
    params.bar_natural_frequency_Hz = target_Hz;
    const LsctrRig rig(params, clutch, shudder::test::rig_model(sc).cycle);
    const Modes m = rig.build().network().modes();
    const Eigen::Index j = housing_mode(m);
    const double f = m.frequencies_Hz[j];
    record("bar_" + std::to_string(static_cast<int>(target_Hz)) + "Hz",
           "target %.1f Hz: housing mode %.12f Hz (rel err %.2e)", target_Hz, f, f / target_Hz - 1.0);
    EXPECT_LT(std::abs(f / target_Hz - 1.0), 5e-3);  // the spec
    EXPECT_LT(std::abs(f / target_Hz - 1.0), 1e-9);  // what the refinement delivers
    EXPECT_NEAR(rig.clutch_side_frequency_Hz(), f, 1e-9 * f);

    // Closed form of the decoupled housing.
    const double J_h = params.housing_inertia_kg_m2;
    const double wn = kTwoPi * target_Hz;
    const double k_closed = J_h * wn * wn;
    EXPECT_NEAR(rig.bar_stiffness_Nm_per_rad() / k_closed, 1.0, 1e-9);
    const double c_closed = 2.0 * params.bar_damping_ratio * std::sqrt(k_closed * J_h);
    EXPECT_NEAR(rig.bar_damping_Nms_per_rad() / c_closed, 1.0, 1e-9);
    EXPECT_NEAR(m.shapes(LsctrRig::kHousing, j), 1.0, 1e-12);  // normalised to max |entry| = 1
    EXPECT_NEAR(m.shapes(LsctrRig::kDrive, j), 0.0, 1e-9);     // decoupled: drive at rest

    const double zeta = params.bar_damping_ratio;
    const std::complex<double> l = housing_eigenvalue(m);
    EXPECT_NEAR(l.real() / (-zeta * wn), 1.0, 1e-9);
    EXPECT_NEAR(l.imag() / (wn * std::sqrt(1.0 - zeta * zeta)), 1.0, 1e-9);
  }
}

// Given directly, the stiffness is used as is and the frequency follows: f = √(k/J_h) / 2π.
TEST(RigBar, GivenStiffnessIsUsedAsIs) {
  const Scenario sc = scenario("rig_case1_25kN_378Hz.toml");
  const WetClutch clutch = sc.make_clutch();
  auto params = shudder::test::rig_model(sc).params;
  params.bar_stiffness_Nm_per_rad = 5.0e4;
  const LsctrRig rig(params, clutch, shudder::test::rig_model(sc).cycle);
  EXPECT_EQ(rig.bar_stiffness_Nm_per_rad(), 5.0e4);
  const double f_closed = std::sqrt(5.0e4 / params.housing_inertia_kg_m2) / kTwoPi;  // 251.6 Hz
  EXPECT_NEAR(rig.clutch_side_frequency_Hz() / f_closed, 1.0, 1e-9);
}

// ---------------------------------------------------------------------------------------------
// 2. The rig does not distort a quasi-static test: Case 1 (fluid C, 25.3 kN, 1 -> 100 rpm in
// 10 s, 77 °C) on the 378 Hz rig against prescribed slip (paper_g_case1_25kN.toml, the same
// clutch, fluid and cycle).
//
// Torque cell: with the clutch slipping the housing is a 378 Hz oscillator loaded by the
// friction torque, which changes over seconds, so T_cell = T_clutch up to the dynamic factor
// (f_load / f_bar)² ≈ 0 and the bar's damper term c ω_h ≈ c Ṫ/k ≈ 1e-5 N m.
//
// Drive speed: the PI loop (K_p = J_d ω_c, K_i = J_d ω_c²/4 = 2369 N m/rad) has no error on a
// speed ramp at constant load, but the load (the friction torque) rises, and against a ramping
// load a PI loop lags by the quasi-steady error
//     e = ω_ref − ω_d ≈ Ṫ_load / K_i            (J_d ω'' = K_p e' + K_i e − Ṫ_load, ω'' ≈ e' ≈ 0)
// Fluid C's torque climbs steeply at low speed (≈ 45 N m/s at 3 rpm), so at t = 0.2 s the
// drive runs 0.02 rad/s (0.2 rpm, 7 %) slow, and with dT/dω ≈ 40 N m s/rad there the torque
// is ~1 % low; at 0.5 s the lag costs 0.2 %. The start transient of the spec is therefore
// this lag, not the loop's own poles (a double pole at −ω_c/2 = −63 1/s, gone in 0.1 s), and
// the same-time comparison starts at 0.5 s. The rig still measures the same friction curve:
// against the drive encoder's speed (what the rig reports as speed_rpm), the torque equals the
// prescribed-slip torque at that speed from 0.1 s on (tolerance 0.2 %: the matched prescribed
// sample is ≤ 0.02 s earlier, ~0.03 K cooler, mu ~1e-4 different; interpolating the 100 Hz
// record in speed adds ~1e-5).
// Tolerances: the spec's 1 % (torque) and 0.5 °C (thermocouple, both see the same heat).
// ---------------------------------------------------------------------------------------------
// A load cell reading g_F F on the rig (`load_sensor_gain`): the recorded normal force is
// g_F times the cylinder's (exactly: the recorder multiplies the cycle's value), the dynamics
// and the torque cell untouched (bit-identical: the cell's reading enters nothing else).
TEST(RigLoadCell, GainChangesOnlyTheRecordedForce) {
  const Scenario sc = scenario("rig_case1_25kN_378Hz.toml");
  auto params = without_ripple(shudder::test::rig_model(sc).params);
  params.load_cell = {true, 1.05};
  auto settings = shudder::test::rig_model(sc).settings;
  settings.duration_s = 1.0;
  const auto& cycle = shudder::test::rig_model(sc).cycle;
  const WetClutch clutch = sc.make_clutch();
  const Recording faulty = run_rig(params, clutch, cycle, settings);
  params.load_cell.gain_fault = false;
  const Recording plain = run_rig(params, clutch, cycle, settings);
  const auto& t = signal(faulty, "time_s");
  const auto& f = signal(faulty, "normal_force_N");
  for (std::size_t k = 0; k < t.size(); ++k)
    EXPECT_NEAR(f[k], 1.05 * cycle.normal_force_N(t[k]), 1e-9 * cycle.normal_force_N(t[k])) << "sample " << k;
  EXPECT_EQ(signal(faulty, "torque_Nm"), signal(plain, "torque_Nm"));
  EXPECT_EQ(signal(faulty, "temp_C"), signal(plain, "temp_C"));
}

TEST(RigQuasiStatic, Case1TorqueCellEqualsPrescribedSlipTorque) {
  const Recording& rig = rig_case1();
  const Scenario ps_sc = scenario("paper_g_case1_25kN.toml");
  const WetClutch ps_clutch = ps_sc.make_clutch();
  const Recording ps = run_prescribed_slip(ps_clutch, shudder::test::prescribed_model(ps_sc).cycle,
                                           shudder::test::prescribed_model(ps_sc).settings);

  const auto& t_r = signal(rig, "time_s");
  const auto& T_r = signal(rig, "torque_Nm");
  const auto& c_r = signal(rig, "temp_C");
  const auto& w_r = signal(rig, "speed_rpm");
  const auto& t_p = signal(ps, "time_s");
  const auto& T_p = signal(ps, "torque_Nm");
  const auto& c_p = signal(ps, "temp_C");
  ASSERT_EQ(t_r.size(), 10001u);  // 0, 1 ms, ..., 10 s
  ASSERT_EQ(t_p.size(), 1001u);   // 0, 10 ms, ..., 10 s
  EXPECT_EQ(scalar(rig, "stick_events"), 0.0);

  // Same time: every prescribed sample (100 Hz) is a rig sample (1 kHz).
  int compared = 0;
  double worst_T = 0.0, worst_c = 0.0;
  for (std::size_t k = 0; k < t_p.size(); ++k) {
    const auto i = static_cast<std::size_t>(std::llround(t_p[k] * 1000.0));
    ASSERT_NEAR(t_r[i], t_p[k], 1e-9);
    const double ec = std::abs(c_r[i] - c_p[k]);
    worst_c = std::max(worst_c, ec);
    EXPECT_LT(ec, 0.5) << "t = " << t_p[k] << ": rig " << c_r[i] << " °C, prescribed " << c_p[k];
    if (t_p[k] < 0.5) continue;
    const double eT = std::abs(T_r[i] / T_p[k] - 1.0);
    worst_T = std::max(worst_T, eT);
    EXPECT_LT(eT, 0.01) << "t = " << t_p[k] << ": rig " << T_r[i] << " N m, prescribed " << T_p[k];
    ++compared;
  }
  EXPECT_EQ(compared, 951);  // 0.50, 0.51, ..., 10.00 s

  // Same speed: prescribed slip runs 1 + 9.9 t rpm, so the speed w was applied at
  // (w − 1)/9.9 s; interpolate the prescribed torque there.
  double worst_same_speed = 0.0;
  for (std::size_t i = 100; i < t_r.size(); ++i) {
    const double tp = (w_r[i] - 1.0) / 9.9;
    const auto kp = static_cast<std::size_t>(tp * 100.0);
    if (kp + 1 >= T_p.size()) continue;  // the drive overshoots 100 rpm by ~1e-3 at the end
    const double a = tp * 100.0 - static_cast<double>(kp);
    const double e = std::abs(T_r[i] / ((1 - a) * T_p[kp] + a * T_p[kp + 1]) - 1.0);
    worst_same_speed = std::max(worst_same_speed, e);
    EXPECT_LT(e, 2e-3) << "t = " << t_r[i] << " s, drive " << w_r[i] << " rpm";
  }

  // The lag is the loop's ramp-load error, K_i e = Ṫ − K_p e' − J_d e'' (the loop equation with
  // ω_ref'' = 0), checked with the first two terms over 0.5–2 s, where e is 1e-3..1e-2 rad/s and
  // J_d e'' is < 1e-3 of K_i e (e decays on the ~1 s scale of the friction curve). Tolerance
  // 2 %: central differences over ±5 ms of sampled signals, across the small torque steps of
  // each 10 ms thermal update (ring temperatures are held within a step); measured 1 %.
  const Scenario rig_sc = scenario("rig_case1_25kN_378Hz.toml");
  const WetClutch rig_clutch = rig_sc.make_clutch();
  const LsctrRig loop(shudder::test::rig_model(rig_sc).params, rig_clutch, shudder::test::rig_model(rig_sc).cycle);
  const auto lag = [&](std::size_t i) { return shudder::units::rpm_to_rad_s(1.0 + 9.9 * t_r[i] - w_r[i]); };
  const auto rate = [&](const auto& f, std::size_t i) { return (f(i + 5) - f(i - 5)) / (t_r[i + 5] - t_r[i - 5]); };
  const auto torque = [&](std::size_t i) { return T_r[i]; };
  double worst_lag = 0.0;
  for (std::size_t i = 500; i <= 2000; i += 100) {
    const double predicted = (rate(torque, i) - loop.motor_kp() * rate(lag, i)) / loop.motor_ki();
    worst_lag = std::max(worst_lag, std::abs(lag(i) / predicted - 1.0));
    EXPECT_NEAR(lag(i) / predicted, 1.0, 0.02) << "t = " << t_r[i] << ": lag " << lag(i) << " rad/s";
  }
  record("case1",
         "rig vs prescribed: same time (t >= 0.5 s) worst torque %.3e rel, temp %.4f K; "
         "same speed (t >= 0.1 s) %.3e; lag vs (Tdot - Kp edot)/Ki worst %.3e",
         worst_T, worst_c, worst_same_speed, worst_lag);
}

// ---------------------------------------------------------------------------------------------
// 3. Fluid C on the 175 Hz and 378 Hz bars, Paper G Case 2 (14.8 kN; 1 rpm 5 s, ramp to
// 100 rpm, hold, ramp down, 1 rpm): no shudder and the same mean friction (thesis).
//
// Shudder would be a self-excited oscillation at the bar frequency: the torque cell would
// oscillate about its slow trend. The slow trend is taken as the centred 50 ms moving average
// (≥ 8 periods of the 175 Hz mode average it out). The cycle's own torque is smooth within
// ±25 ms except at the schedule's kinks, where the average misses the kink by s W / 8 for a
// change s of the torque's slope over the window W: at the 1 rpm ends of the ramps fluid C's
// torque-speed slope is ~40 N m s/rad, times the ramp's 1.04 rad/s², s ≈ 42 N m/s, so
// ≈ 0.26 N m ≈ 0.4 % of the mean torque. A residual < 1 % of the mean torque thus means no
// oscillation (a shudder here is tens of percent, see RigShudder). Start transient: the first
// 0.2 s (the loop's own poles settle in ~0.1 s; the run starts at a constant 1 rpm).
// Mean friction: time mean of friction_coefficient over the whole run;
// the bars change the bar mode but not the quasi-static friction, so the means agree to 0.5 %
// (the spec; the heat input is the same to the same degree, so temperatures and mu too).
// ---------------------------------------------------------------------------------------------
TEST(RigNoShudder, FluidCOn175And378HzBarsHasNoShudderAndTheSameMeanFriction) {
  double mean_mu[2] = {0.0, 0.0};
  const char* files[2] = {"rig_case2_15kN_175Hz.toml", "rig_case2_15kN_378Hz.toml"};
  for (int b = 0; b < 2; ++b) {
    SCOPED_TRACE(files[b]);
    const Recording rec = run(scenario(files[b]));
    const auto& t = signal(rec, "time_s");
    const auto& T = signal(rec, "torque_Nm");
    const auto& stuck = signal(rec, "stuck");
    const auto& slip = signal(rec, "slip_rpm");
    const auto& mu = signal(rec, "friction_coefficient");
    ASSERT_EQ(t.size(), 30001u);

    // No stick: no events, never stuck, slip positive throughout.
    EXPECT_EQ(scalar(rec, "stick_events"), 0.0);
    EXPECT_EQ(*std::max_element(stuck.begin(), stuck.end()), 0.0);
    EXPECT_GT(*std::min_element(slip.begin(), slip.end()), 0.0);

    // Oscillation about the 50 ms centred moving average (51 samples at 1 kHz).
    double mean_T = 0.0;
    for (double x : T) mean_T += x;
    mean_T /= static_cast<double>(T.size());
    const std::size_t half = 25;
    double window = 0.0;
    for (std::size_t k = 0; k < 2 * half + 1; ++k) window += T[k];
    double worst = 0.0, worst_t = 0.0;
    for (std::size_t k = half; k + half + 1 < T.size(); ++k) {
      if (k > half) window += T[k + half] - T[k - half - 1];
      if (t[k] < 0.2) continue;
      const double dev = std::abs(T[k] - window / (2 * half + 1));
      if (dev > worst) {
        worst = dev;
        worst_t = t[k];
      }
    }
    record(files[b], "mean torque %.3f N m, worst oscillation %.4f N m (%.3e) at t = %.3f s", mean_T, worst,
           worst / mean_T, worst_t);
    EXPECT_LT(worst, 0.01 * mean_T) << "at t = " << worst_t;

    for (double x : mu) mean_mu[b] += x;
    mean_mu[b] /= static_cast<double>(mu.size());
  }
  record("mean_mu", "175 Hz %.6f, 378 Hz %.6f (rel diff %.3e)", mean_mu[0], mean_mu[1], mean_mu[1] / mean_mu[0] - 1.0);
  EXPECT_NEAR(mean_mu[0] / mean_mu[1], 1.0, 5e-3);
  EXPECT_GT(mean_mu[0], 0.05);  // a real friction level, not a degenerate run
}

// ---------------------------------------------------------------------------------------------
// 4. Friction-induced vibration with a negative mu-v slope (scenarios/
// rig_shudder_negative_slope.toml: 30 rpm, 15 kN, 378 Hz bar).
//
// Linearised about steady sliding, the housing obeys
//     J_h θ'' + (c_bar + dT_k/dv_slip) θ' + k_bar θ = 0   (dT_k/d|Δω| < 0 on the falling branch)
// so the clutch-side mode has negative net damping and grows from the start's small
// disturbances (the held friction steps at each 10 ms thermal update) until
// the slip swings into the fluid's rising branch below 10 rpm, which bounds it: a limit cycle
// with the slip staying positive (friction-induced vibration, not stick-slip). Its frequency is
// that of the housing on the bar: the damping terms are ~1 N m s/rad against √(k J_h) ≈ 47, so
// the limit cycle runs at the damped natural frequency within ~(ζ_eff)² ≪ 5 %, the spec's
// tolerance (which also covers the nonlinearity's small frequency shift). Frequency from the
// upward zero crossings of the housing speed (mean 0: the housing is tied to ground by the bar)
// over the last second. With the bar at 175 Hz the frequency follows the new bar.
// ---------------------------------------------------------------------------------------------
TEST(RigShudder, NegativeSlopeFluidOscillatesAtTheClutchSideDampedFrequencyAndFollowsTheBar) {
  Scenario sc = scenario("rig_shudder_negative_slope.toml");
  double measured_Hz[2] = {0, 0};
  const double bars_Hz[2] = {378.0, 175.0};
  for (int b = 0; b < 2; ++b) {
    SCOPED_TRACE(bars_Hz[b]);
    shudder::test::rig_model(sc).params.bar_natural_frequency_Hz = bars_Hz[b];
    const WetClutch clutch = sc.make_clutch();
    const LsctrRig rig(shudder::test::rig_model(sc).params, clutch, shudder::test::rig_model(sc).cycle);
    const double f_damped = housing_eigenvalue(rig.build().network().modes()).imag() / kTwoPi;
    const Recording rec = run_rig(without_ripple(shudder::test::rig_model(sc).params), clutch,
                                  shudder::test::rig_model(sc).cycle, shudder::test::rig_model(sc).settings);
    const auto& t = signal(rec, "time_s");
    const auto& wh = signal(rec, "housing_speed_rpm");
    const auto& slip = signal(rec, "slip_rpm");
    const double t_end = t.back();

    // Sustained and grown: the amplitude at the end far above the start's.
    const double a_start = max_abs(t, wh, 0.0, 0.05), a_end = max_abs(t, wh, t_end - 0.5, t_end);
    // Not stick-slip: slip stays positive, nothing sticks.
    const double min_slip = *std::min_element(slip.begin(), slip.end());
    int crossings = 0;
    measured_Hz[b] = zero_crossing_frequency_Hz(t, wh, t_end - 1.0, t_end, &crossings);
    record("bar_" + std::to_string(static_cast<int>(bars_Hz[b])) + "Hz",
           "bar %.0f Hz: damped %.4f Hz, measured %.4f Hz (%+.3e, %d crossings), "
           "amplitude %.3e -> %.3e rpm, min slip %.3f rpm, stick events %g",
           bars_Hz[b], f_damped, measured_Hz[b], measured_Hz[b] / f_damped - 1.0, crossings, a_start, a_end, min_slip,
           scalar(rec, "stick_events"));
    EXPECT_GT(a_end, 100.0 * a_start);
    EXPECT_GT(a_end, 1.0);  // rpm: a visible shudder, not round-off
    EXPECT_GT(min_slip, 0.0);
    EXPECT_EQ(scalar(rec, "stick_events"), 0.0);
    EXPECT_NEAR(measured_Hz[b] / f_damped, 1.0, 0.05);
  }
  // The frequency moved with the bar: ratio of the two damped frequencies, ≈ 378/175.
  EXPECT_NEAR(measured_Hz[0] / measured_Hz[1], 378.0 / 175.0, 0.05 * 378.0 / 175.0);
}

// ---------------------------------------------------------------------------------------------
// 5. Stick-slip (scenarios/rig_stick_slip.toml: 1 rpm, 15 kN, 378 Hz bar, mu_s/mu_k = 1.3,
// started at rest with the clutch stuck).
//
//   stuck:  drive and housing move together; the bar winds up until the clutch torque reaches
//           its capacity T_s (breakaway)
//   slip:   J_h θ'' = T_k − k θ − c θ'  from k θ = T_s, θ' = ω_d (the speed it was stuck at)
// Undamped, with constant T_k and ω_d: u = θ − T_k/k starts at +(T_s − T_k)/k with u' = ω_d,
// and θ' = ω_d again (re-stick) exactly where u = −(T_s − T_k)/k (u² + (u'/ω)² is conserved and
// u' takes the value ω_d again at the mirror point), so the bar torque falls from T_s to
// 2 T_k − T_s: jump = 2 (T_s − T_k). The damper part c ω_d of the cell torque is the same at
// both ends. T_s and T_k come from the contact law at the held state (ring temperatures at the
// start temperature: the run warms the hottest ring by < 0.5 K, mu by < 1.5e-4, 0.15 %) and
// T_k at creep speed.
// The rig deviates from the ideal by (all estimated, the first computed from the law below):
//   * mu_k rising with slip speed (the schematic fluid: +0.004 from 1 to 50 rpm, log-linear);
//     the slip peaks at 5–7 rpm, the effective T_k is up to T_k(v_peak): −2 (T_k(v_peak) −
//     T_k) / jump ≈ −7 % at most;
//   * bar damping ζ = 1 %: the half swing decays by e^(−πζ): −(1 − e^(−πζ))/2 = −1.6 %;
//   * the drive speed is not constant (the motor loop sees the load): the stuck pair
//     (J_d + J_h = 0.62 kg m²) decelerates while the loop lags the wind-up and speeds up again
//     in slip. That winds the bar past T_s by J_h |ω'| ≈ 0.02 kg m² · 30 rad/s² ≈ 0.6 N m at
//     breakaway, and changes the housing's kinetic energy between breakaway and re-stick:
//     ±3 % of the 42 N m jump.
// So jump / (2 (T_s − T_k)) must lie in [1 − e_v − 1.6 % − 3 %, 1 + 3 %], e_v computed.
// Sampling: at the scenario's 20 kS/s the torque rises k ω_d / 20 kHz ≈ 0.6 N m between samples
// in a stuck phase (1.4 % of the jump); the test samples at 200 kS/s (0.06 N m).
// ---------------------------------------------------------------------------------------------
TEST(RigStickSlip, SlipReturnsToZeroEveryCycleStuckIsExactAndTheJumpIsTwiceTheFrictionDrop) {
  const Scenario sc = scenario("rig_stick_slip.toml");
  const WetClutch clutch = sc.make_clutch();
  auto settings = shudder::test::rig_model(sc).settings;
  settings.sample_rate_Hz = 200e3;
  const Recording rec = run_rig(without_ripple(shudder::test::rig_model(sc).params), clutch,
                                shudder::test::rig_model(sc).cycle, settings);
  const auto& t = signal(rec, "time_s");
  const auto& T = signal(rec, "torque_Nm");
  const auto& slip = signal(rec, "slip_rpm");
  const auto& stuck = signal(rec, "stuck");
  const auto& temp = signal(rec, "interface_max_temp_C");
  ASSERT_EQ(t.size(), 200001u);

  // Stuck samples have exactly zero relative speed (bitwise-equal speeds in a stuck group).
  long n_stuck = 0;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (stuck[k] == 1.0) {
      ++n_stuck;
      ASSERT_EQ(slip[k], 0.0) << "t = " << t[k];
    }
  EXPECT_GT(n_stuck, 100000);     // stuck most of the time (~2/3 of each cycle)
  ASSERT_EQ(stuck.front(), 1.0);  // started at rest, stuck

  // First breakaway.
  std::size_t k0 = 0;
  while (k0 < t.size() && stuck[k0] == 1.0) ++k0;
  ASSERT_LT(k0, t.size()) << "never broke away";

  // Every cycle after it sticks: between consecutive upward crossings of T − mean(T) there is
  // a stuck sample.
  double mean_T = 0.0;
  for (std::size_t k = k0; k < t.size(); ++k) mean_T += T[k];
  mean_T /= static_cast<double>(t.size() - k0);
  std::vector<std::size_t> up;
  for (std::size_t k = k0 + 1; k < t.size(); ++k)
    if (T[k - 1] < mean_T && T[k] >= mean_T) up.push_back(k);
  ASSERT_GT(up.size(), 100u);  // ~140 cycles of ~4.7 ms after the first breakaway at ~0.35 s
  for (std::size_t c = 1; c < up.size(); ++c) {
    bool any = false;
    for (std::size_t k = up[c - 1]; k < up[c] && !any; ++k) any = stuck[k] == 1.0;
    EXPECT_TRUE(any) << "no stick between t = " << t[up[c - 1]] << " and " << t[up[c]] << " s";
  }
  // Each slip phase ends in a stick (the last may be cut off by the end of the run).
  EXPECT_NEAR(scalar(rec, "stick_events"), scalar(rec, "breakaway_events"), 1.0);

  // Jumps: the cell torque at the last stuck sample before each breakaway minus that at the
  // first stuck sample after the slip phase (re-stick); the largest slip speed reached.
  std::vector<double> jumps, jump_times;
  double T_break = std::nan(""), v_peak_rpm = 0.0;
  for (std::size_t k = 1; k < t.size(); ++k) {
    if (stuck[k - 1] == 1.0 && stuck[k] == 0.0) T_break = T[k - 1];
    if (stuck[k - 1] == 0.0 && stuck[k] == 1.0 && std::isfinite(T_break)) {
      jumps.push_back(T_break - T[k]);
      jump_times.push_back(t[k]);
    }
    v_peak_rpm = std::max(v_peak_rpm, std::abs(slip[k]));
  }
  ASSERT_GT(jumps.size(), 100u);
  EXPECT_LT(temp.back() - temp.front(), 0.5);  // the held state stays the start state

  const LsctrRig rig(shudder::test::rig_model(sc).params, clutch, shudder::test::rig_model(sc).cycle);
  const auto& law = rig.clutch_contact();
  shudder::components::ClutchContext start(rig.start_inputs());
  const double t_mid = 0.5;  // constant force: any time
  const double T_s = law.static_capacity_Nm(start, t_mid, 0.0);
  const double T_k = law.kinetic_torque_Nm(start, 0.0, t_mid);
  const double expected = 2.0 * (T_s - T_k);
  const double e_v =
      2.0 * (law.kinetic_torque_Nm(start, shudder::units::rpm_to_rad_s(v_peak_rpm), t_mid) - T_k) / expected;
  const double e_z = 0.5 * (1.0 - std::exp(-std::numbers::pi * shudder::test::rig_model(sc).params.bar_damping_ratio));
  const double e_i = 0.03;
  EXPECT_NEAR(T_s / T_k, 1.3, 1e-9);  // the fluid's breakaway ratio, one load, one temperature
  EXPECT_LT(e_v, 0.08);               // the budget's first item as estimated
  double lo = jumps.front(), hi = jumps.front();
  for (std::size_t c = 0; c < jumps.size(); ++c) {
    lo = std::min(lo, jumps[c]);
    hi = std::max(hi, jumps[c]);
    EXPECT_GE(jumps[c] / expected, 1.0 - e_v - e_z - e_i) << "t = " << jump_times[c];
    EXPECT_LE(jumps[c] / expected, 1.0 + e_i) << "t = " << jump_times[c];
  }
  // Once the loop's start-up has died out (t > 0.5 s), the cycles repeat: a limit cycle whose
  // jumps agree to 2 samples of the wind-up (2 × 0.06 N m, 0.3 %).
  double lo_late = 1e300, hi_late = -1e300;
  for (std::size_t c = 0; c < jumps.size(); ++c)
    if (jump_times[c] > 0.5) {
      lo_late = std::min(lo_late, jumps[c]);
      hi_late = std::max(hi_late, jumps[c]);
    }
  EXPECT_LT(hi_late - lo_late, 3e-3 * expected);
  record("stick_slip",
         "T_s %.4f, T_k %.4f, 2(T_s-T_k) %.4f N m; %zu jumps in [%.4f, %.4f] (%+.3e .. %+.3e), "
         "after 0.5 s [%.4f, %.4f]; v_peak %.3f rpm, e_v %.4f, e_z %.4f; stick events %g, "
         "breakaways %g; temp rise %.4f K",
         T_s, T_k, expected, jumps.size(), lo, hi, lo / expected - 1.0, hi / expected - 1.0, lo_late, hi_late,
         v_peak_rpm, e_v, e_z, scalar(rec, "stick_events"), scalar(rec, "breakaway_events"),
         temp.back() - temp.front());
}

// ---------------------------------------------------------------------------------------------
// 6. Multi-rate coupling: halving the thermal step (10 -> 5 ms) on rig Case 1 moves the end
// torque and thermocouple temperature by < 0.5 %. Backward Euler is first order, so the change
// bounds the remaining error at 5 ms; within a step the ring temperatures are held, and the
// friction work per ring is handed exactly to the thermal step (integrated states).
// ---------------------------------------------------------------------------------------------
TEST(RigThermalCoupling, HalvingTheThermalStepChangesEndTorqueAndTemperatureByLessThanHalfAPercent) {
  const Recording& coarse = rig_case1();
  Scenario sc = scenario("rig_case1_25kN_378Hz.toml");
  ASSERT_DOUBLE_EQ(shudder::test::rig_model(sc).settings.thermal_step_s, 0.01);
  shudder::test::rig_model(sc).settings.thermal_step_s = 0.005;
  const Recording fine = run(sc);
  for (const char* name : {"torque_Nm", "temp_C"}) {
    const double a = signal(coarse, name).back(), b = signal(fine, name).back();
    record(name, "10 ms %.5f vs 5 ms %.5f (%.3e)", a, b, a / b - 1.0);
    EXPECT_LT(std::abs(a - b) / std::abs(b), 5e-3) << name << ": " << a << " vs " << b;
  }
  // Not a degenerate run: Case 1 ends over 80 N m and near 110 °C (Paper G Figure 12).
  EXPECT_GT(signal(fine, "torque_Nm").back(), 80.0);
  EXPECT_GT(signal(fine, "temp_C").back(), 90.0);
}

}  // namespace

// A drive cycle whose clamp force never rises above 0 N cannot load the clutch: refused with
// what to change, naming the cycle's force (not the network component the rig is written as).
TEST(RigCycle, ZeroNormalForceThroughoutIsRefused) {
  const Scenario sc = scenario("rig_case1_25kN_378Hz.toml");
  const WetClutch clutch = sc.make_clutch();
  auto cycle = shudder::test::rig_model(sc).cycle;
  cycle.normal_force_N = shudder::components::PiecewiseLinear({0.0}, {0.0});
  try {
    const LsctrRig rig(shudder::test::rig_model(sc).params, clutch, cycle);
    FAIL() << "a rig without clamp force was accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("normal force is 0 N throughout"), std::string::npos) << e.what();
  }
}
