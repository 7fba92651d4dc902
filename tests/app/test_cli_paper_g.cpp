// The calibration targets (scenarios/validation.toml) as end-to-end tests of `shudder run`: each scenario is run
// by the real executable, its HDF5 read back, and the reported Paper G / Paper B results checked
// against the target ranges (themselves read off Paper G Figs. 8, 12, 14 and its
// Discussion, and Paper B Fig. 6). The ranges are the tolerances: they carry the scatter of the
// published figures, so no extra tolerance is added.
#include <gtest/gtest.h>

#include <algorithm>

#include "io/hdf5_run.hpp"
#include "tests/support/cli.hpp"

using namespace shudder;
using namespace shudder::test;

namespace {

dynamics::Recording run_scenario(const std::string& name) {
  const auto dir = scratch_dir("paper_" + name);
  const auto r = run_cli("run '" + source_path("scenarios/" + name + ".toml") + "' -o out.h5", dir);
  EXPECT_EQ(r.exit_code, 0) << r.err;
  return io::read_run_hdf5((dir / "out.h5").string());
}

double at(const dynamics::Recording& rec, const char* signal, double t) {
  const auto& ts = rec.find("time_s")->values;
  const auto& v = rec.find(signal)->values;
  const auto it = std::lower_bound(ts.begin(), ts.end(), t - 1e-9);
  return v[static_cast<std::size_t>(it - ts.begin())];
}

}  // namespace

TEST(PaperG, Case1At10kN_TorqueAndThermocouple) {
  const auto rec = run_scenario("paper_g_case1_10kN");
  EXPECT_GE(at(rec, "torque_Nm", 10.0), 40.0);
  EXPECT_LE(at(rec, "torque_Nm", 10.0), 50.0);
  EXPECT_GE(at(rec, "temp_C", 10.0), 85.0);
  EXPECT_LE(at(rec, "temp_C", 10.0), 95.0);
  EXPECT_LT(rec.find_scalar("energy_balance_relative_error")->value, 1e-6);
}

TEST(PaperG, Case1At25kN_OilFlowAndConstantTemperature) {
  const auto with_flow = run_scenario("paper_g_case1_25kN");
  const auto no_flow = run_scenario("paper_g_case1_25kN_no_oil_flow");
  const auto constant_T = run_scenario("paper_g_case1_25kN_constant_temperature");
  const double m = at(with_flow, "torque_Nm", 10.0);
  // Case 1 at 25.3 kN: torque >= 105 Nm, thermocouple 103–115 °C at t = 10 s.
  EXPECT_GE(m, 105.0);
  EXPECT_GE(at(with_flow, "temp_C", 10.0), 103.0);
  EXPECT_LE(at(with_flow, "temp_C", 10.0), 115.0);
  // Without interface oil flow: above 150 °C, torque 5–15 % below the case with flow.
  EXPECT_GT(at(no_flow, "temp_C", 10.0), 150.0);
  const double drop = 1.0 - at(no_flow, "torque_Nm", 10.0) / m;
  EXPECT_GE(drop, 0.05);
  EXPECT_LE(drop, 0.15);
  // Friction at the start temperature: torque at least 5 % above the thermal model's.
  EXPECT_GE(at(constant_T, "torque_Nm", 10.0) / m - 1.0, 0.05);
}

TEST(PaperB, RampSurfaceTemperatureRise) {
  const auto rec = run_scenario("paper_b_ramp_20kN");
  const double rise = at(rec, "ir_temp_C", 20.0) - at(rec, "ir_temp_C", 10.0);
  EXPECT_GE(rise, 12.0);
  EXPECT_LE(rise, 25.0);
}

// Paper D (thesis Figs. 30–31): in its Case 2 cycles "although the oil sump temperature is constant
// the interface temperature varies significantly". The sump thermocouple's accuracy is ±0.67 °C
// (thesis), so "constant" is read as a spread under 0.67 °C; the interface must still swing by
// more than 10 °C (the model's peak is ~25 °C above the start). With the sump warming by Paper G
// eq. 7 (the old calibration) the sump rose 9.7 °C here.
TEST(PaperD, Case2SumpConstantWhileInterfaceVaries) {
  const auto rec = run_scenario("paper_g_case2_15kN");
  const auto& sump = rec.find("sump_temp_C")->values;
  const auto [sump_min, sump_max] = std::minmax_element(sump.begin(), sump.end());
  EXPECT_LT(*sump_max - *sump_min, 0.67);
  const auto& ir = rec.find("ir_temp_C")->values;
  EXPECT_GT(*std::max_element(ir.begin(), ir.end()) - ir.front(), 10.0);
}

// Energy arithmetic behind docs/thermal_model.md ("Anchors that contradict each other"): per kJ
// of friction heat the model's surface rise in Paper B's ramp is within 15 % of Case 1's rise
// per kJ (same ramp, same oil flow law, loads 10.4–25.3 kN), whereas the measurements differ by
// 37 % (Paper B 15.5 °C / 5.1 kJ against Case 1's ~12 °C / 2.5 kJ and ~30 °C / 6.1 kJ). Fails if
// a recalibration made the flow law tell Paper B's start (60 °C) from Case 1's (77 °C), which
// only an oil flow that falls as the oil thins can (the grid's d = -5 rows).
TEST(PaperB, RisePerKilojouleMatchesCase1) {
  const auto pb = run_scenario("paper_b_ramp_20kN");
  const auto c25 = run_scenario("paper_g_case1_25kN");
  const double pb_rise_per_kJ =
      (at(pb, "ir_temp_C", 20.0) - at(pb, "ir_temp_C", 10.0)) / (pb.find_scalar("heat_generated_J")->value / 1e3);
  const double c25_rise_per_kJ =
      (at(c25, "ir_temp_C", 10.0) - at(c25, "ir_temp_C", 0.0)) / (c25.find_scalar("heat_generated_J")->value / 1e3);
  EXPECT_NEAR(pb_rise_per_kJ / c25_rise_per_kJ, 1.0, 0.15);
}
