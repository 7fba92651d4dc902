// Model-based characterisation (studies/inverse_characterisation.hpp, --method inverse):
// round trips of known fluids through the project's clutch and thermal model with sensor noise
// (3 loads x 5 start temperatures, Paper D cycles), and through a thermal model that differs
// from the one the inverse method replays with (finer grid, slip-dependent oil flow, sensor lag).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/anti_shudder_indices.hpp"
#include "analysis/friction_characterisation.hpp"
#include "io/fluid_loader.hpp"
#include "studies/fluid_screening.hpp"
#include "studies/inverse_characterisation.hpp"
#include "tests/support/characterisation_errors.hpp"
#include "tests/support/ramp_runs.hpp"

namespace {

using namespace shudder;
using analysis::Characterisation;
using analysis::CharacterisationSettings;
using analysis::Compensation;
using analysis::LawKind;

std::vector<studies::ReplayInputs> replay_inputs(const std::vector<analysis::RampRun>& runs) {
  std::vector<studies::ReplayInputs> in;
  for (const auto& r : runs) {
    studies::ReplayInputs x;
    x.time_s = r.time_s;
    x.speed_rpm = r.speed_rpm;
    x.normal_force_N = r.normal_force_N;
    x.temp_C = r.temp_C;
    x.torque_Nm = r.torque_Nm;
    in.push_back(std::move(x));
  }
  return in;
}

CharacterisationSettings settings(LawKind law, Compensation comp = Compensation::kQuadratic) {
  CharacterisationSettings s;
  s.law = law;
  s.compensation = comp;  // the sensor method the inverse one starts from
  s.conversion.rule = analysis::RadiusRule::kUniformPressure;
  return s;
}

studies::InverseSettings inverse_settings(const clutch::Fluid& any_fluid) {
  studies::InverseSettings inv;
  inv.model.fluid = any_fluid;  // viscosities only; the law is replaced by every iterate
  inv.model.settings.thermal_step_s = 0.02;
  inv.jobs = 2;
  return inv;
}

struct Set {
  std::vector<analysis::RampRun> runs;
  std::vector<std::vector<double>> interface_C;  // the data model's mean interface temperature
  clutch::Fluid truth;
};

// 10, 15, 20 kN x 5 start temperatures, Paper D cycles (10 s ramps), 50 S/s, sensor noise.
Set round_trip(const std::string& fluid_file, std::vector<double> temps_C) {
  Set s;
  s.truth = io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + fluid_file);
  unsigned seed = 500;
  for (double load : {10000.0, 15000.0, 20000.0})
    for (double t0 : temps_C) {
      s.interface_C.emplace_back();
      s.runs.push_back(test::simulated_ramp_run(s.truth, test::paper_d_cycle(load), t0, seed++, 50.0, "temp_C", {},
                                                &s.interface_C.back()));
    }
  return s;
}

// Fluid C's matrix (kinks in mu(T) between its 10 °C rows), piecewise compensation and table
// law: the inverse method must converge in a few replays, recover the oil flow the data were
// made with from a wrong start, reduce the temperature misfit and the replayed-torque misfit,
// and stay within the noise's bound of the truth (docs/characterisation.md §2b).
TEST(InverseCharacterisation, FluidCMatrixRecoversTheOilFlowAndTheLaw) {
  const Set set = round_trip("lsc_fluid_c.toml", {30.0, 40.0, 50.0, 60.0, 70.0});
  auto is = inverse_settings(set.truth);
  is.model.clutch.thermal.oil_flow.e = 0.03;  // the data were made with 0.016 (Paper G defaults)
  const auto r = studies::characterise_inverse(set.runs, replay_inputs(set.runs),
                                               settings(LawKind::kTable, Compensation::kPiecewise), "temp_C", is);
  const double es = test::max_error_at_rows(r.sensor, *set.truth.friction),
               ei = test::max_error_at_rows(r.inverse, *set.truth.friction);
  const double ps = test::max_error_where_passed(r.sensor, *set.truth.friction, set.runs, set.interface_C),
               pi = test::max_error_where_passed(r.inverse, *set.truth.friction, set.runs, set.interface_C);
  std::printf(
      "[ figures  ] fluid C matrix, piecewise + table: max |mu/mu_true - 1| where the ramps passed: sensor %.4f, "
      "inverse %.4f\n",
      ps, pi);
  std::printf(
      "[ figures  ] fluid C matrix, piecewise + table: max |mu/mu_true - 1| at the rows: sensor %.4f, inverse %.4f; "
      "%d law updates, %d replays, last change %.2g; oil flow e 0.03 -> %.4g (truth 0.016), a %.3g; "
      "temp rms %.3f -> %.3f C; replayed torque rms sensor law %.4f, inverse law %.4f N m\n",
      es, ei, r.iterations, r.replays, r.last_change_mu, r.oil_flow.e, r.oil_flow.a, r.temp_rms_start_C, r.temp_rms_C,
      r.torque_rms_sensor_Nm, r.torque_rms_Nm);
  // The calibration sees the thermocouple's noise (0.2-0.4 °C) over ~30,000 samples and the
  // sensor law's 3 % friction-heat error: e within 10 %.
  EXPECT_NEAR(r.oil_flow.e, 0.016, 0.0016);
  EXPECT_LT(r.temp_rms_C, 0.2 * r.temp_rms_start_C);  // 5 °C with e = 0.03; the noise floor is 0.4 °C
  EXPECT_LE(r.iterations, 6);                         // the law enters the temperature field only through the heat
  EXPECT_LT(r.torque_rms_Nm, r.torque_rms_sensor_Nm);
  // Piecewise compensation + table law follow the matrix's kinks with either temperature; what
  // remains is the torque cell's noise in the rows' bins (measured on these seeds: sensor 0.71 %,
  // inverse 0.81 % where the ramps passed; 0.91 % for the sensor on the seeds of
  // test_friction_characterisation.cpp). The inverse method removes the thermocouple's offset
  // but not the noise, so it is held to the 1 % target, not to beat the sensor.
  EXPECT_LT(pi, 0.01);
  EXPECT_LT(ei, 0.015);  // at the rows, incl. the coldest row's extrapolated high speeds (0.89 %)

  // Indices and screening from the inverse law.
  analysis::IndexSettings idx;
  idx.load_N = 15000.0;
  double worst = 0.0;
  for (double t : {40.0, 60.0}) {
    const auto a = analysis::anti_shudder_indices(*r.inverse.law, t, idx);
    const auto b = analysis::anti_shudder_indices(*set.truth.friction, t, idx);
    worst = std::max(worst,
                     std::abs(a[analysis::Index::kMu1OverMu50].value / b[analysis::Index::kMu1OverMu50].value - 1.0));
  }
  clutch::Fluid fitted = set.truth;
  fitted.friction = r.inverse.law;
  studies::ScreeningOptions so;
  so.indices.load_N = 15000.0;
  so.temps_C = {40.0, 60.0};
  // Judged where the runs have data, as the sensor method's round trip is
  // (test_friction_characterisation.cpp: the truth's RISK over -40…200 °C comes from its -40 °C
  // rows alone, which these runs cannot see).
  for (double t = 30.0; t <= 100.0; t += 5.0) so.map_temps_C.push_back(t);
  const auto va = studies::screen_fluid(fitted, so), vb = studies::screen_fluid(set.truth, so);
  std::printf("[ figures  ] inverse: mu1/mu50 at 15 kN, 40 and 60 °C within %.4f of the truth; screen %s (truth %s)\n",
              worst, analysis::risk_level_name(va.verdict.level), analysis::risk_level_name(vb.verdict.level));
  EXPECT_LT(worst, 0.05);  // the ratio of two values each within the bound above
  // The rigs' predictions agree point for point in kind, and the level is the truth's.
  ASSERT_EQ(va.rigs.size(), vb.rigs.size());
  for (std::size_t i = 0; i < va.rigs.size(); ++i) EXPECT_EQ(va.rigs[i].unstable.empty(), vb.rigs[i].unstable.empty());
  EXPECT_EQ(va.verdict.level, vb.verdict.level);
}

// Paper E's fluid C as linear lines (smooth in T): the 1 % target.
TEST(InverseCharacterisation, PaperELinearLawWithinOnePercent) {
  const Set set = round_trip("paper_e_fluid_c.toml", {30.0, 45.0, 60.0, 75.0, 90.0});
  const auto r = studies::characterise_inverse(set.runs, replay_inputs(set.runs), settings(LawKind::kLinear), "temp_C",
                                               inverse_settings(set.truth));
  const double es = test::max_error_at_rows(r.sensor, *set.truth.friction),
               ei = test::max_error_at_rows(r.inverse, *set.truth.friction);
  std::printf(
      "[ figures  ] Paper E fluid C linear law: sensor %.4f, inverse %.4f; %d updates, %d replays; e %.4g a %.3g\n", es,
      ei, r.iterations, r.replays, r.oil_flow.e, r.oil_flow.a);
  EXPECT_LT(ei, 0.01);
}

// Data from another thermal model (40 radial cells instead of 20, oil flow growing with slip,
// a thermocouple lagging 0.5 s): the inverse method replays with its own 20-cell model and a
// lag-free sensor, calibrating the oil flow on the lagging thermocouple. The 2 % target.
TEST(InverseCharacterisation, OtherThermalModelWithinTwoPercent) {
  const clutch::Fluid truth = io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/paper_e_fluid_c.toml");
  std::vector<analysis::RampRun> runs;
  unsigned seed = 700;
  for (double t0 : {30.0, 45.0, 60.0, 75.0, 90.0})
    runs.push_back(test::simulated_ramp_run(truth, test::paper_d_cycle(20000.0), t0, seed++, 50.0, "temp_C",
                                            test::other_thermal_model));
  const auto r = studies::characterise_inverse(runs, replay_inputs(runs), settings(LawKind::kLinear), "temp_C",
                                               inverse_settings(truth));
  const double es = test::max_error_at_rows(r.sensor, *truth.friction),
               ei = test::max_error_at_rows(r.inverse, *truth.friction);
  std::printf(
      "[ figures  ] other thermal model: sensor %.4f, inverse %.4f; oil flow e %.4g a %.3g (data: 0.010, 0.002); "
      "temp rms %.3f -> %.3f C\n",
      es, ei, r.oil_flow.e, r.oil_flow.a, r.temp_rms_start_C, r.temp_rms_C);
  EXPECT_LT(ei, 0.02);
  EXPECT_LT(r.temp_rms_C, r.temp_rms_start_C);
}

}  // namespace
