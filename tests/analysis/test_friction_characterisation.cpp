// Characterisation of measured ramps (analysis/friction_characterisation.hpp):
//   * the Mäki fit recovers a known Paper G set from exact samples;
//   * the ramp search finds Paper D's up- and down-ramps and rejects what is not a ramp;
//   * round trip: fluid C's matrix driven through the project's thermal model (Paper D cycles,
//     3 loads x 5 start temperatures, sensor noise) and characterised back; compensation must
//     bring the law closer to the truth than no compensation, up- and down-ramps must come
//     closer together, and the indices must follow;
//   * Paper E fluids A–E: their ramps characterised as linear laws give Table 4's mu1/mu50.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/anti_shudder_indices.hpp"
#include "analysis/friction_characterisation.hpp"
#include "clutch/maki_friction.hpp"
#include "io/fluid_loader.hpp"
#include "studies/fluid_screening.hpp"
#include "tests/support/characterisation_errors.hpp"
#include "tests/support/ramp_runs.hpp"

namespace {

using namespace shudder;
using analysis::Characterisation;
using analysis::CharacterisationSettings;
using analysis::Compensation;
using analysis::LawKind;

TEST(MakiFit, RecoversAPaperGSetFromExactSamples) {
  const clutch::MakiSet truth{-0.039, 0.001, 0.077, -0.024};  // Paper G Table 2, 70 °C, 20 kN
  std::vector<double> v, mu, w;
  for (int k = 0; k <= 40; ++k) {
    v.push_back(4.82 * std::pow(100.0, k / 40.0));
    mu.push_back(truth.mu(v.back()));
    w.push_back(1.0);
  }
  const auto p = analysis::fit_maki_curve(v, mu, w);
  // The separable fit is exact on exact data up to the golden-section tolerance in C2
  // (relative 1e-9 after 60 steps on a bracket of 0.4 in ln C2): mu agrees to ~1e-9.
  for (std::size_t k = 0; k < v.size(); ++k)
    EXPECT_NEAR(clutch::MakiSet({p[0], p[1], p[2], p[3]}).mu(v[k]), mu[k], 1e-7);
  EXPECT_NEAR(p[1], 0.001, 1e-5);
}

analysis::RampRun profile_run(const components::DriveCycle& cycle, double duration_s) {
  analysis::RampRun r;
  r.name = "profile";
  for (double t = 0.0; t <= duration_s + 1e-9; t += 0.01) {
    r.time_s.push_back(t);
    r.speed_rpm.push_back(cycle.slip_speed_rpm(t));
    r.normal_force_N.push_back(cycle.normal_force_N(t));
    r.torque_Nm.push_back(50.0);
    r.temp_C.push_back(40.0 + t);
  }
  return r;
}

TEST(RampSearch, FindsPaperDUpAndDownRamps) {
  const auto found = analysis::find_ramps(profile_run(test::paper_d_cycle(15000.0, 10.0), 30.0), 0);
  ASSERT_EQ(found.ramps.size(), 2u);
  EXPECT_TRUE(found.rejected.empty());
  const auto& up = found.ramps[0];
  const auto& down = found.ramps[1];
  EXPECT_EQ(up.direction, analysis::RampDirection::kUp);
  EXPECT_EQ(down.direction, analysis::RampDirection::kDown);
  // The rate is a centred difference over ±0.1 s, so a ramp's ends are found within 0.1 s.
  EXPECT_NEAR(up.t_start_s, 5.0, 0.11);
  EXPECT_NEAR(up.t_end_s, 15.0, 0.11);
  EXPECT_NEAR(down.t_start_s, 17.0, 0.11);
  EXPECT_NEAR(down.t_end_s, 27.0, 0.11);
  EXPECT_NEAR(up.min_rpm, 1.0, 1e-9);
  EXPECT_NEAR(up.max_rpm, 100.0, 1e-9);
  EXPECT_NEAR(up.load_N, 15000.0, 1e-6);
  EXPECT_NEAR(up.start_temp_C, 40.0 + up.t_start_s + 0.05, 0.01);  // mean over the first 0.1 s
}

TEST(RampSearch, RejectsAStepALoadChangeAndASmallSweep) {
  // Paper E's return from 100 to 1 rpm is a step (rejected: too short); a ramp during which
  // the load doubles is no row of a matrix; a 1 -> 15 rpm sweep spans too little.
  // The 26 -> 29 s return to 1 rpm is a proper (3 s) down-ramp and is used.
  components::DriveCycle c{
      components::PiecewiseLinear({0, 3, 13, 13.01, 16, 26, 29, 31}, {1, 1, 100, 1, 1, 100, 1, 15}),
      components::PiecewiseLinear({0, 15, 16, 26}, {20000, 20000, 10000, 20000})};
  const auto found = analysis::find_ramps(profile_run(c, 33.0), 0);
  ASSERT_EQ(found.ramps.size(), 2u);
  EXPECT_NEAR(found.ramps[0].t_start_s, 3.0, 0.11);
  EXPECT_NEAR(found.ramps[1].t_start_s, 26.0, 0.11);
  ASSERT_EQ(found.rejected.size(), 3u);
  std::string reasons;
  for (const auto& r : found.rejected) reasons += r.reason + "|";
  EXPECT_NE(reasons.find("lasts"), std::string::npos) << reasons;
  EXPECT_NE(reasons.find("load varies"), std::string::npos) << reasons;
  EXPECT_NE(reasons.find("rpm; a ramp must span at least 20 rpm"), std::string::npos) << reasons;
}

struct RoundTrip {
  std::vector<analysis::RampRun> runs;
  std::vector<std::vector<double>> interface_C;  // the model's area-mean interface temperature per run
  clutch::Fluid truth;
};

// Fluid C's reconstructed matrix, Paper D cycles (10 s ramps) at 10, 15, 20 kN from 30, 40,
// 50, 60, 70 °C, sensor noise, 50 Hz: 15 runs, 30 ramps.
const RoundTrip& fluid_c_round_trip() {
  static const RoundTrip rt = [] {
    RoundTrip r;
    r.truth = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
    unsigned seed = 1;
    for (double load : {10000.0, 15000.0, 20000.0})
      for (double t0 : {30.0, 40.0, 50.0, 60.0, 70.0}) {
        r.interface_C.emplace_back();
        r.runs.push_back(test::simulated_ramp_run(r.truth, test::paper_d_cycle(load), t0, seed++, 50.0, "temp_C", {},
                                                  &r.interface_C.back()));
      }
    return r;
  }();
  return rt;
}

CharacterisationSettings round_trip_settings(Compensation comp, LawKind law) {
  CharacterisationSettings s;
  s.compensation = comp;
  s.law = law;
  // The model integrates uniform pressure over Paper G's 38.1–56.4 mm annulus, so its torque
  // is mu at the uniform-pressure radius (docs/physics.md §9); the thesis' 46 mm would read mu 4 % high.
  s.conversion.rule = analysis::RadiusRule::kUniformPressure;
  return s;
}

struct Errors {
  double mu = 0.0, gap_raw = 0.0, gap_comp = 0.0;
};

Errors errors_of(const Characterisation& c, const clutch::FrictionLaw& truth) {
  Errors e;
  e.mu = test::max_error_at_rows(c, truth);
  for (const auto& row : c.rows) {
    e.gap_raw += row.up_down_gap_raw / double(c.rows.size());
    e.gap_comp += row.up_down_gap_comp / double(c.rows.size());
  }
  return e;
}

// The 1 % target on the matrix: compensation piecewise linear in T between the rows
// (analysis/temperature_surface.hpp) with the table law (linear in T between the rows, as the
// matrix itself) from the separator thermocouple. Judged where the ramps passed; the figures at
// the rows (including the coldest row at speeds every ramp passes warmer) are printed beside.
TEST(CharacteriseRoundTrip, FluidCMatrixPiecewiseTableWithinOnePercentWhereTheRampsPassed) {
  const RoundTrip& rt = fluid_c_round_trip();
  RoundTrip at_interface = rt;  // the model's mean interface temperature instead of the sensor
  for (std::size_t r = 0; r < rt.runs.size(); ++r) at_interface.runs[r].temp_C = rt.interface_C[r];
  double passed[2][2][2] = {};  // [sensor|interface][quadratic|piecewise][maki|table]
  for (int ch = 0; ch < 2; ++ch)
    for (int ic = 0; ic < 2; ++ic)
      for (int il = 0; il < 2; ++il) {
        const RoundTrip& data = ch == 0 ? rt : at_interface;
        const auto comp = ic == 0 ? Compensation::kQuadratic : Compensation::kPiecewise;
        const auto law = il == 0 ? LawKind::kMaki : LawKind::kTable;
        const Characterisation c = analysis::characterise(data.runs, round_trip_settings(comp, law));
        const Errors e = errors_of(c, *rt.truth.friction);
        passed[ch][ic][il] = test::max_error_where_passed(c, *rt.truth.friction, rt.runs, rt.interface_C);
        std::printf(
            "[ figures  ] fluid C matrix, %s temperature, %s + %s: max |mu/mu_true - 1| where the ramps "
            "passed %.4f, at the rows %.4f; up-down gap %.5f -> %.5f\n",
            ch == 0 ? "thermocouple" : "interface (model)", analysis::compensation_name(comp), analysis::law_name(law),
            passed[ch][ic][il], e.mu, e.gap_raw, e.gap_comp);
        if (ch == 0 && ic == 1 && il == 1) {
          // The torque cell's noise (sigma 1.3 % of mu per sample at 10 kN) averaged over a row's
          // bins around a node leaves ~0.3 %; the thermocouple's offset from the interface and the
          // matrix's clamp below 6 mm/s (1.2 rpm) at the first node the rest (measured 0.91 %).
          EXPECT_LT(passed[ch][ic][il], 0.01);  // the 1 % target
          EXPECT_LT(e.gap_comp, 0.6 * e.gap_raw);
          analysis::IndexSettings is;
          is.load_N = 15000.0;
          double worst = 0.0;
          for (double t : {40.0, 60.0}) {
            const auto a = analysis::anti_shudder_indices(*c.law, t, is);
            const auto b = analysis::anti_shudder_indices(*rt.truth.friction, t, is);
            worst = std::max(
                worst, std::abs(a[analysis::Index::kMu1OverMu50].value / b[analysis::Index::kMu1OverMu50].value - 1.0));
          }
          std::printf("[ figures  ] piecewise + table: mu1/mu50 at 15 kN, 40 and 60 °C within %.4f of the truth\n",
                      worst);
          EXPECT_LT(worst, 0.02);  // the 2 % target on the indices (a ratio of two values within 1 %)
        }
      }
  // Without the piecewise form the quadratic cannot follow the matrix's kinks: it misses more.
  EXPECT_LT(passed[0][1][1], passed[0][0][1]);
}

// The matrix through another thermal model (40 radial cells, oil flow growing with slip, a
// thermocouple lagging 0.5 s), 20 kN: the 2 % target for data from a model not the method's own.
TEST(CharacteriseRoundTrip, FluidCMatrixOtherThermalModelWithinTwoPercent) {
  RoundTrip rt;
  rt.truth = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
  unsigned seed = 900;
  for (double t0 : {30.0, 40.0, 50.0, 60.0, 70.0}) {
    rt.interface_C.emplace_back();
    rt.runs.push_back(test::simulated_ramp_run(rt.truth, test::paper_d_cycle(20000.0), t0, seed++, 50.0, "temp_C",
                                               test::other_thermal_model, &rt.interface_C.back()));
  }
  const Characterisation c =
      analysis::characterise(rt.runs, round_trip_settings(Compensation::kPiecewise, LawKind::kTable));
  const double passed = test::max_error_where_passed(c, *rt.truth.friction, rt.runs, rt.interface_C);
  std::printf(
      "[ figures  ] fluid C matrix through another thermal model, 20 kN, piecewise + table: where the ramps "
      "passed %.4f, at the rows %.4f\n",
      passed, errors_of(c, *rt.truth.friction).mu);
  EXPECT_LT(passed, 0.02);
}

TEST(CharacteriseRoundTrip, FluidCMatrixQuadraticCompensationBeatsNone) {
  const RoundTrip& rt = fluid_c_round_trip();
  const Characterisation none =
      analysis::characterise(rt.runs, round_trip_settings(Compensation::kNone, LawKind::kMaki));
  const Characterisation quad =
      analysis::characterise(rt.runs, round_trip_settings(Compensation::kQuadratic, LawKind::kMaki));
  const Characterisation lin =
      analysis::characterise(rt.runs, round_trip_settings(Compensation::kLinear, LawKind::kMaki));
  const Characterisation table =
      analysis::characterise(rt.runs, round_trip_settings(Compensation::kQuadratic, LawKind::kTable));
  ASSERT_EQ(quad.rows.size(), 15u);
  ASSERT_EQ(quad.used.size(), 30u);
  const Errors en = errors_of(none, *rt.truth.friction), eq = errors_of(quad, *rt.truth.friction),
               el = errors_of(lin, *rt.truth.friction), et = errors_of(table, *rt.truth.friction);
  std::printf(
      "[ figures  ] fluid C round trip, max |mu/mu_true - 1| over rows and 1-100 rpm nodes: none %.4f, "
      "linear %.4f (alpha %.3g), quadratic %.4f, table+quadratic %.4f; mean up-down gap raw %.5f -> quadratic %.5f\n",
      en.mu, el.mu, lin.alpha_per_C, eq.mu, et.mu, eq.gap_raw, eq.gap_comp);
  // Without compensation the data at 100 rpm are 10-30 °C hotter than the row: the bias is
  // several percent. The sensor reads the back of the separator (r = 48 mm, z = 0.5 mm), not
  // the interface, so compensation with it cannot be exact (~3 %); it must
  // still beat no compensation by a clear factor, and stay within 5 %.
  EXPECT_GT(en.mu, 0.03);
  EXPECT_LT(eq.mu, 0.05);
  EXPECT_LT(eq.mu, 0.6 * en.mu);
  // The up/down gap at the nodes is a mean of |difference of two ramp means|: the torque
  // cell's noise leaves a floor of ~2e-4 in it, so halving is not reachable; 70 % is.
  EXPECT_LT(eq.gap_comp, 0.7 * eq.gap_raw);
}

// Paper E's fluid C as linear lines (smooth in T, unlike the reconstructed matrix whose
// published 70 °C row puts kinks into mu(T) that no quadratic follows): with the mean
// interface temperature the method's own error (ramp search, radius, binning, compensation,
// fit) is what remains; with the separator thermocouple the sensor's lag adds to it.
TEST(CharacteriseRoundTrip, PaperELinearLawWithinOnePercentAtTheInterfaceTemperature) {
  const clutch::Fluid truth = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/paper_e_fluid_c.toml");
  double err[2][3] = {};
  for (int channel = 0; channel < 2; ++channel) {
    std::vector<analysis::RampRun> runs;
    unsigned seed = 100;
    for (double load : {10000.0, 15000.0, 20000.0})
      for (double t0 : {30.0, 45.0, 60.0, 75.0, 90.0})
        runs.push_back(test::simulated_ramp_run(truth, test::paper_d_cycle(load), t0, seed++, 50.0,
                                                channel == 0 ? "interface_mean_temp_C" : "temp_C"));
    const Characterisation none =
        analysis::characterise(runs, round_trip_settings(Compensation::kNone, LawKind::kLinear));
    const Characterisation quad =
        analysis::characterise(runs, round_trip_settings(Compensation::kQuadratic, LawKind::kLinear));
    const Characterisation table =
        analysis::characterise(runs, round_trip_settings(Compensation::kQuadratic, LawKind::kTable));
    err[channel][0] = errors_of(none, *truth.friction).mu;
    err[channel][1] = errors_of(quad, *truth.friction).mu;
    err[channel][2] = errors_of(table, *truth.friction).mu;
    // Piecewise compensation on a law smooth in T (rows 15 °C apart, knots there): no worse.
    const Characterisation pw =
        analysis::characterise(runs, round_trip_settings(Compensation::kPiecewise, LawKind::kLinear));
    const Characterisation pwt =
        analysis::characterise(runs, round_trip_settings(Compensation::kPiecewise, LawKind::kTable));
    std::printf("[ figures  ] Paper E fluid C, %s: piecewise + linear law %.4f, piecewise + table %.4f\n",
                channel == 0 ? "interface" : "thermocouple", errors_of(pw, *truth.friction).mu,
                errors_of(pwt, *truth.friction).mu);
    EXPECT_LT(errors_of(pw, *truth.friction).mu, 0.01);
  }
  std::printf(
      "[ figures  ] Paper E fluid C (linear law) round trip, max |mu/mu_true - 1|: interface temperature: "
      "none %.4f, quadratic+linear law %.4f, quadratic+table %.4f; thermocouple: none %.4f, quadratic+linear "
      "%.4f, quadratic+table %.4f\n",
      err[0][0], err[0][1], err[0][2], err[1][0], err[1][1], err[1][2]);
  EXPECT_LT(err[0][1], 0.01);
  EXPECT_LT(err[1][1], 0.01);
  EXPECT_LT(err[0][1], 0.5 * err[0][0]);
}

// A Paper E fluid is linear in ln v over the data: fitted with the Mäki form, tanh(C2 v) must be
// linear there, so C2 runs to its lower search bound on every row. The cause is one and is said
// once, naming the rows, not once per row.
TEST(CharacteriseWarnings, AMakiRateOnItsBoundInManyRowsIsOneWarningNamingThem) {
  const clutch::Fluid truth = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/paper_e_fluid_b.toml");
  std::vector<analysis::RampRun> runs;
  unsigned seed = 300;
  for (double load : {12000.0, 18000.0})
    for (double t0 : {50.0, 70.0, 90.0})
      runs.push_back(test::simulated_ramp_run(truth, test::paper_d_cycle(load), t0, seed++, 50.0));
  const Characterisation c =
      analysis::characterise(runs, round_trip_settings(Compensation::kQuadratic, LawKind::kMaki));
  std::vector<std::string> on_bound;
  for (const auto& w : c.warnings)
    if (w.find("search bound") != std::string::npos) on_bound.push_back(w);
  ASSERT_EQ(on_bound.size(), 1u) << (on_bound.empty() ? std::string("no bound warning") : on_bound[1]);
  const std::string& w = on_bound.front();
  EXPECT_NE(w.find("linear over the data"), std::string::npos) << w;
  EXPECT_NE(w.find("12 kN at"), std::string::npos) << w;
  EXPECT_NE(w.find("18 kN at"), std::string::npos) << w;
  EXPECT_NE(w.find(" of " + std::to_string(c.rows.size()) + " rows"), std::string::npos) << w;
}

// Data from a different thermal model: twice the radial resolution, an oil flow
// through the contact that grows with slip (a speed term the shipped calibration sets to
// zero), and a thermocouple lagging the disc by 0.5 s. The characterisation knows none of it.
TEST(CharacteriseRoundTrip, OtherThermalModelWithinTwoPercent) {
  const clutch::Fluid truth = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/paper_e_fluid_c.toml");
  std::vector<analysis::RampRun> runs;
  unsigned seed = 300;
  // One load (the linear law does not depend on it; the 3-load cases are above), to keep
  // the finer grid's runs quick.
  for (double t0 : {30.0, 45.0, 60.0, 75.0, 90.0})
    runs.push_back(test::simulated_ramp_run(truth, test::paper_d_cycle(20000.0), t0, seed++, 50.0, "temp_C",
                                            test::other_thermal_model));
  const double none =
      errors_of(analysis::characterise(runs, round_trip_settings(Compensation::kNone, LawKind::kLinear)),
                *truth.friction)
          .mu;
  const double quad =
      errors_of(analysis::characterise(runs, round_trip_settings(Compensation::kQuadratic, LawKind::kLinear)),
                *truth.friction)
          .mu;
  const double pw =
      errors_of(analysis::characterise(runs, round_trip_settings(Compensation::kPiecewise, LawKind::kLinear)),
                *truth.friction)
          .mu;
  std::printf(
      "[ figures  ] Paper E fluid C through another thermal model (finer grid, slip-dependent oil flow, "
      "0.5 s sensor lag): none %.4f, quadratic+linear law %.4f, piecewise+linear law %.4f\n",
      none, quad, pw);
  EXPECT_LT(quad, 0.02);  // the bound for data from another thermal model
  EXPECT_LT(pw, 0.02);
}

TEST(CharacteriseRoundTrip, IndicesFollowTheTruth) {
  const RoundTrip& rt = fluid_c_round_trip();
  const Characterisation quad =
      analysis::characterise(rt.runs, round_trip_settings(Compensation::kQuadratic, LawKind::kMaki));
  analysis::IndexSettings is;
  is.load_N = 15000.0;
  double worst = 0.0;
  for (double t : {40.0, 60.0}) {
    const auto a = analysis::anti_shudder_indices(*quad.law, t, is);
    const auto b = analysis::anti_shudder_indices(*rt.truth.friction, t, is);
    const double r = a[analysis::Index::kMu1OverMu50].value / b[analysis::Index::kMu1OverMu50].value - 1.0;
    worst = std::max(worst, std::abs(r));
  }
  std::printf("[ figures  ] fluid C round trip: mu1/mu50 at 15 kN, 40 and 60 °C within %.4f of the truth\n", worst);
  EXPECT_LT(worst, 0.05);  // the ratio of two values each within the mu bound above
  // The screening verdict (default 100/300/500 Hz rigs, 15 kN, 40 and 60 °C) is the truth's.
  clutch::Fluid fitted = rt.truth;
  fitted.friction = quad.law;
  studies::ScreeningOptions so;
  so.indices.load_N = 15000.0;
  so.temps_C = {40.0, 60.0};
  // Judged where the runs have data (starts 30–70 °C, ramps warm to ~100 °C): over the law's
  // whole -40…200 °C the truth's verdict comes from the published -40 °C rows alone (unstable at
  // -40…-30 °C since fluid C's reconstructed rows rise with speed), which no
  // characterisation of these runs can see.
  for (double t = 30.0; t <= 100.0; t += 5.0) so.map_temps_C.push_back(t);
  const auto a = studies::screen_fluid(fitted, so), b = studies::screen_fluid(rt.truth, so);
  std::printf("[ figures  ] screen verdict: characterised %s, truth %s\n", analysis::risk_level_name(a.verdict.level),
              analysis::risk_level_name(b.verdict.level));
  // The rigs' predictions must agree point for point in kind (stable everywhere or not). The
  // level may differ by one step: the truth's only negative slope here is the published 70 °C /
  // 15 kN set's dip above 87 rpm (CAUTION), within the fit's μ error, which the fit smooths away.
  ASSERT_EQ(a.rigs.size(), b.rigs.size());
  for (std::size_t i = 0; i < a.rigs.size(); ++i) EXPECT_EQ(a.rigs[i].unstable.empty(), b.rigs[i].unstable.empty());
  EXPECT_NE(a.verdict.level, analysis::RiskLevel::kRisk);
  EXPECT_NE(b.verdict.level, analysis::RiskLevel::kRisk);
}

// Paper E: fluids A–E, five Paper E ramps (1 rpm for 3 s, 1 -> 100 rpm in 10 s) from each of
// 30, 50, 70, 90 and 100 °C at 20 kN (Paper E: from 90–100 °C down to 30 °C), characterised as linear laws. Table 4 (30
// °C) and Table 5 (at each fluid's 10 cSt temperature, from its viscosities by Walther) give mu1/mu50.
TEST(CharacterisePaperE, FluidsAToEReproduceTables4And5) {
  const char* names[] = {"a", "b", "c", "d", "e"};
  const double table4[] = {0.7985, 0.8051, 0.8269, 0.8309, 0.8455};
  const double table5[] = {0.8069, 0.7791, 0.6680, 0.5611, 0.5660};
  const double table5_temp_C[] = {27.0, 39.0, 81.0, 92.0, 98.0};
  std::vector<double> got4;
  for (int f = 0; f < 5; ++f) {
    const clutch::Fluid truth =
        io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/paper_e_fluid_") + names[f] + ".toml");
    std::vector<analysis::RampRun> runs;
    unsigned seed = 200;
    for (double t0 : {30.0, 50.0, 70.0, 90.0, 100.0})
      runs.push_back(test::simulated_ramp_run(truth, test::paper_e_cycle(20000.0), t0, seed++, 50.0));
    const Characterisation c =
        analysis::characterise(runs, round_trip_settings(Compensation::kQuadratic, LawKind::kLinear));
    const double v1 = c.node_speeds_mm_s.front(), v50 = analysis::rpm_to_mm_s(50.0, c.effective_radius_mm);
    const auto ratio = [&](double t) { return c.law->mu(v1, t, 20000.0) / c.law->mu(v50, t, 20000.0); };
    // The temperature at which the fluid has 10 cSt (Walther, the fluid's nu40/nu100), by bisection.
    const clutch::WaltherViscosity nu(truth.nu40_cSt, truth.nu100_cSt);
    double lo = -30.0, hi = 200.0;
    for (int k = 0; k < 60; ++k) (nu.kinematic_cSt(0.5 * (lo + hi)) > 10.0 ? lo : hi) = 0.5 * (lo + hi);
    const double t10 = 0.5 * (lo + hi);
    got4.push_back(ratio(30.0));
    std::printf(
        "[ figures  ] Paper E fluid %s: mu1/mu50 at 30 °C %.4f (Table 4 %.4f, %+.2f %%); 10 cSt at %.1f °C "
        "(Table 5 %.0f °C); mu1/mu50 there %.4f (Table 5 %.4f, %+.2f %%)\n",
        names[f], ratio(30.0), table4[f], 100 * (ratio(30.0) / table4[f] - 1), t10, table5_temp_C[f], ratio(t10),
        table5[f], 100 * (ratio(t10) / table5[f] - 1));
    const auto truth_ratio = [&](double t) {
      return truth.friction->mu(v1, t, 20000.0) / truth.friction->mu(v50, t, 20000.0);
    };
    std::printf("[ figures  ]   the fluid's own lines give %.4f at %.1f °C: characterised %+.2f %%\n", truth_ratio(t10),
                t10, 100 * (ratio(t10) / truth_ratio(t10) - 1));
    EXPECT_NEAR(ratio(30.0) / table4[f], 1.0, 0.01) << names[f];  // the 1 % target
    // Table 5's ratios are measured; the Paper E lines the fluid files hold miss them by up to
    // 1.4 % (fluid E at 98 °C), so the characterisation is held to 1 % of the lines it was fed.
    EXPECT_NEAR(ratio(t10) / truth_ratio(t10), 1.0, 0.01) << names[f];
    EXPECT_NEAR(t10, table5_temp_C[f], 1.5) << names[f];  // Table 5 prints whole degrees
  }
  for (int f = 1; f < 5; ++f)
    EXPECT_GT(got4[std::size_t(f)], got4[std::size_t(f) - 1]) << "Table 4's ranking A < B < C < D < E";
}

}  // namespace
