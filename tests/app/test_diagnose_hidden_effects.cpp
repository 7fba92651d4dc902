// The diagnosis on data in which one effect is hidden (the requirement: "tests on data in which the effect
// is hidden"). Measured runs are generated at test time by `shudder run --measurement --noise
// --seed` from the probe scenario with the effect on (or, for effects on by default, in their
// default state); the diagnosis model has the effect off. Two runs per case: A 12 kN from 75 °C
// and B 24 kN from 85 °C, 100 Hz, sensor noise at the rig's stated accuracy (torque ±1.25 Nm,
// thermocouple ±0.67 °C read as 2 sigma), fixed seeds. The ninth effect, stick-time static
// friction, needs sticking: rig stick-slip runs at 1 kHz (DiagnoseStickTime, below).
//
// Magnitudes (docs/diagnosis.md): bearing mu 0.005 (the thesis' value), a 300 J/K, 20 W/K rig
// mass, a 1 s sensor lag, a 0.5 µm viscous gap (1.2–2 Nm at 100 rpm), the calibrated oil flow.
//
// Pass criteria: the named effect is the hidden one; torque and temperature
// RMS gaps shrink at least 5× or end within 1.5× the noise; identifiable parameters within 20 %.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <map>

#include "analysis/diagnosis.hpp"
#include "tests/support/cli.hpp"
#include "tests/support/diagnosis_probe.hpp"
#include "tests/support/diagnosis_runs.hpp"

namespace shudder {
namespace {

using test::replace;
using test::scratch_dir;

struct Case {
  std::string name;
  std::string hidden;                        // [effects.*] tables of the generating "rig"
  std::string model;                         // [effects.*] tables of the diagnosis model
  std::vector<std::string> expected;         // missing effects, in order
  std::map<std::string, double> parameters;  // identifiable: name -> hidden value
  std::vector<std::string> withdrawn = {};   // added, then withdrawn by the backward check
};

void PrintTo(const Case& c, std::ostream* os) { *os << c.name; }

analysis::DiagnosisResult diagnose_case(const Case& c) {
  const auto dir = scratch_dir("diag_" + c.name);
  std::vector<std::filesystem::path> csvs;
  const struct {
    double force, temp;
    unsigned seed;
  } runs_spec[] = {{12000, 75, 11}, {24000, 85, 12}};
  for (const auto& r : runs_spec)
    csvs.push_back(test::make_measured_run(dir, "run_" + std::to_string(static_cast<int>(r.force / 1000)) + "kN",
                                           test::probe_scenario_text(c.hidden, r.force, r.temp), r.seed));
  analysis::DiagnosisOptions o;
  o.jobs = 1;  // ctest runs the cases in parallel
  return test::diagnose_measured(csvs, test::probe_scenario_text(c.model, 12000, 75), "scenarios/diagnosis_probe.toml",
                                 o, test::Reproduction::kNotCounted);
}

void expect_gap_shrinks(const analysis::DiagnosisResult& r) {
  // 5× shrink, or within 1.5× the estimated noise (a model as good as the data allows).
  EXPECT_TRUE(r.final.torque_rms_Nm <= r.baseline.torque_rms_Nm / 5 || r.final.torque_rms_Nm <= 1.5 * r.noise_torque_Nm)
      << "torque " << r.baseline.torque_rms_Nm << " -> " << r.final.torque_rms_Nm << " noise " << r.noise_torque_Nm;
  EXPECT_TRUE(r.final.temp_rms_C <= r.baseline.temp_rms_C / 5 || r.final.temp_rms_C <= 1.5 * r.noise_temp_C)
      << "temp " << r.baseline.temp_rms_C << " -> " << r.final.temp_rms_C << " noise " << r.noise_temp_C;
}

// A parameter is named by its key, or "effect/key" where two effects share the key (`gain`).
void expect_parameters(const analysis::DiagnosisResult& r, const Case& c) {
  for (const auto& [name, hidden] : c.parameters) {
    bool found = false;
    for (const auto& st : r.steps)
      for (const auto& [k, v] : st.parameters)
        if ((k == name || st.effect + "/" + k == name) && !found) {
          found = true;
          // The identifiability target: within 20 % of the hidden value; for a sensor
          // gain (near 1, where 20 % would pass a fit that found nothing) 20 % of its error g - 1.
          if (name.ends_with("gain"))
            EXPECT_NEAR((v - 1.0) / (hidden - 1.0), 1.0, 0.2) << name << " fitted " << v << ", hidden " << hidden;
          else
            EXPECT_NEAR(v / hidden, 1.0, 0.2) << name << " fitted " << v << ", hidden " << hidden;
        }
    EXPECT_TRUE(found) << name << " not fitted";
  }
}

class HiddenEffect : public ::testing::TestWithParam<Case> {};

TEST_P(HiddenEffect, IsNamedFittedAndClosesTheGap) {
  const Case& c = GetParam();
  const auto r = diagnose_case(c);
  EXPECT_EQ(r.missing_effects, c.expected) << test::describe_diagnosis(r);
  // A withdrawn effect is reported as such, with a held-out cost below the gain it would need.
  std::vector<std::string> withdrawn;
  for (const auto& f : r.withdrawn) {
    withdrawn.push_back(f.effect);
    EXPECT_LT(f.holdout_cost, f.needed_gain) << f.effect;
  }
  EXPECT_EQ(withdrawn, c.withdrawn) << test::describe_diagnosis(r);
  if (!c.expected.empty()) expect_gap_shrinks(r);
  expect_parameters(r, c);
}

const std::string off(const std::string& effect) { return "[effects." + effect + "]\nenabled = false\n"; }

INSTANTIATE_TEST_SUITE_P(
    Diagnose, HiddenEffect,
    ::testing::Values(
        Case{"temperature_dependent_friction",
             "",
             off("temperature_dependent_friction"),
             {"temperature_dependent_friction"},
             {}},
        Case{"interface_oil_cooling", "", off("interface_oil_cooling"), {"interface_oil_cooling"}, {{"e", 0.016}}},
        Case{"sump_heating", "", off("sump_heating"), {"sump_heating"}, {}},
        Case{"rig_heat_capacity",
             "[effects.rig_heat_capacity]\nenabled = true\nheat_capacity_J_per_K = 300.0\nconductance_W_per_K = 20.0\n",
             "",
             {"rig_heat_capacity"},
             {{"heat_capacity_J_per_K", 300.0}, {"conductance_W_per_K", 20.0}}},
        Case{"temperature_sensor_lag",
             "[effects.temperature_sensor_lag]\nenabled = true\ntime_constant_s = 1.0\n",
             "",
             {"temperature_sensor_lag"},
             {{"time_constant_s", 1.0}}},
        Case{"bearing_drag",
             "[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.005\n",
             "",
             {"bearing_drag"},
             {{"equivalent_mu", 0.005}}},
        Case{"viscous_shear",
             "[effects.viscous_shear]\nenabled = true\ngap_um = 0.5\n",
             "",
             {"viscous_shear"},
             {{"gap_um", 0.5}}},
        Case{"load_dependent_friction", "", off("load_dependent_friction"), {"load_dependent_friction"}, {}},
        // Half and double the thesis' bearing drag.
        Case{"bearing_drag_half",
             "[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.0025\n",
             "",
             {"bearing_drag"},
             {{"equivalent_mu", 0.0025}}},
        Case{"bearing_drag_double",
             "[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.01\n",
             "",
             {"bearing_drag"},
             {{"equivalent_mu", 0.01}}},
        // Two at once: the bearing drag (9-18 sigma of torque) outweighs the rig mass (3-6
        // sigma of temperature), so it must come first.
        Case{"two_effects",
             "[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.01\n"
             "[effects.rig_heat_capacity]\nenabled = true\nheat_capacity_J_per_K = 150.0\nconductance_W_per_K = 10.0\n",
             "",
             {"bearing_drag", "rig_heat_capacity"},
             {{"equivalent_mu", 0.01}}},
        // Nothing hidden: the baseline is the truth, nothing may be named.
        Case{"none", "", "", {}, {}}),
    [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// Rig faults of the measurement chain, each hidden alone and beside one
// effect of the other channel. Magnitudes: a 3 % torque-cell gain (a cell calibrated on a
// wrong lever arm or a drifted bridge), a 3 N m offset (2.4 sigma of the torque noise, an
// unzeroed cell), a +2 K thermocouple (a type K junction's standard tolerance is ±2.2 K).
// Order: the larger gap first (a 1 s lag moves the temperature by several sigma, more than a
// 3 % gain or 3 N m moves the torque).
const char* const kGain = "[effects.torque_sensor_gain]\nenabled = true\ngain = 1.03\n";
const char* const kTorqueOffset = "[effects.torque_sensor_offset]\nenabled = true\noffset_Nm = 3.0\n";
const char* const kThermocouple = "[effects.thermocouple_offset]\nenabled = true\noffset_K = 2.0\n";
const char* const kLag = "[effects.temperature_sensor_lag]\nenabled = true\ntime_constant_s = 1.0\n";
const char* const kDrag = "[effects.bearing_drag]\nenabled = true\nequivalent_mu = 0.005\n";
// A load cell 5 % low (a cell calibrated against a wrong reference or a drifted amplifier): the
// replay's force is 5 % low, so are its torque and heat (the temperature rise is ~1.5 K low at
// the hold, 4-5 sigma), which no torque-cell gain reproduces.
// Friction 5 % down over 2 m of sliding (the probe slides ~3.8 m at the mean radius, most of it in
// the 100 rpm hold): a "friction drifting 5 % down"; at the final 1 rpm rest the
// torque is ~4 % (2-3 N m, 3-4 sigma) below the fresh model's.
const char* const kDrift = "[effects.friction_drift]\nenabled = true\nchange = -0.05\ndistance_m = 2.0\n";
const char* const kLoadGain = "[effects.load_sensor_gain]\nenabled = true\ngain = 0.95\n";

INSTANTIATE_TEST_SUITE_P(
    DiagnoseRigFaults, HiddenEffect,
    ::testing::Values(Case{"torque_sensor_gain", kGain, "", {"torque_sensor_gain"}, {{"gain", 1.03}}},
                      Case{"torque_sensor_gain_and_lag",
                           std::string(kGain) + kLag,
                           "",
                           {"temperature_sensor_lag", "torque_sensor_gain"},
                           {{"gain", 1.03}, {"time_constant_s", 1.0}}},
                      Case{"torque_sensor_offset", kTorqueOffset, "", {"torque_sensor_offset"}, {{"offset_Nm", 3.0}}},
                      Case{"torque_sensor_offset_and_lag",
                           std::string(kTorqueOffset) + kLag,
                           "",
                           {"temperature_sensor_lag", "torque_sensor_offset"},
                           {{"offset_Nm", 3.0}, {"time_constant_s", 1.0}}},
                      Case{"thermocouple_offset", kThermocouple, "", {"thermocouple_offset"}, {{"offset_K", 2.0}}},
                      Case{"thermocouple_offset_and_drag",
                           std::string(kThermocouple) + kDrag,
                           "",
                           {"bearing_drag", "thermocouple_offset"},
                           {{"offset_K", 2.0}, {"equivalent_mu", 0.005}}},
                      Case{"load_sensor_gain", kLoadGain, "", {"load_sensor_gain"}, {{"gain", 0.95}}},
                      Case{"load_sensor_gain_high",
                           "[effects.load_sensor_gain]\nenabled = true\ngain = 1.08\n",
                           "",
                           {"load_sensor_gain"},
                           {{"gain", 1.08}}},
                      Case{"load_sensor_gain_and_lag",
                           std::string(kLoadGain) + kLag,
                           "",
                           {"temperature_sensor_lag", "load_sensor_gain"},
                           {{"gain", 0.95}, {"time_constant_s", 1.0}},
                           {"torque_sensor_gain"}},
                      Case{"load_sensor_gain_and_torque_offset",
                           std::string(kLoadGain) + kTorqueOffset,
                           "",
                           {"torque_sensor_offset", "load_sensor_gain"},
                           {{"gain", 0.95}, {"offset_Nm", 3.0}},
                           {"torque_sensor_gain"}},
                      // Both gains: only the heat tells them apart (the load gain moves it, the torque gain not).
                      // Both are named; their values are not identifiable to 20 % from these two runs (seen:
                      // g_F 0.924 for 0.95; the temperature carries g_F only through ~1.5 K of heat), so only
                      // the names are checked (docs/diagnosis.md).
                      Case{"load_and_torque_sensor_gains",
                           std::string(kLoadGain) + kGain,
                           "",
                           {"load_sensor_gain", "torque_sensor_gain"},
                           {}},
                      Case{"friction_drift", kDrift, "", {"friction_drift"}, {{"change", -0.05}, {"distance_m", 2.0}}},
                      Case{"friction_drift_and_lag",
                           std::string(kDrift) + kLag,
                           "",
                           {"temperature_sensor_lag", "friction_drift"},
                           {{"change", -0.05}, {"time_constant_s", 1.0}}}),
    [](const ::testing::TestParamInfo<Case>& i) { return i.param.name; });

// Stick-time static friction acts only where the surfaces stick, so it is hidden in rig runs of
// stick-slip (scenarios/rig_stick_time_probe.toml: 100 Hz bar, 15 kN, from rest), at 0.5 rpm
// (sticks of ~0.25 s, past τ: sets max_increase) and 1.5 rpm (sticks of ~0.05 s, near τ: sets
// the time constant), recorded at the rig's 1 kHz with sensor noise. Hidden: max_increase 0.15
// (breakaway 15 % up after a long stick; the scenario default), τ 0.05 s (Gao et al. report
// static friction growing within tens of ms of contact; estimate). Both are identifiable here.
std::string stick_probe_text(const std::string& extra, double speed_rpm) {
  std::string s = test::shipped_scenario_text("rig_stick_time_probe.toml");
  s = replace(s, "speed_rpm = [0.5, 0.5]",
              "speed_rpm = [" + std::to_string(speed_rpm) + ", " + std::to_string(speed_rpm) + "]");
  // The motor's torque ripple is on, as by default: at 0.5-1.5 rpm it runs at 5-15 Hz,
  // in the stick-slip band; the replay models it (its set-point recovery subtracts it).
  return s + "\n" + extra;
}

const char* const kHiddenStickTime =
    "[effects.stick_time_static_friction]\nenabled = true\nmax_increase = 0.15\ntime_constant_s = 0.05\n";

analysis::DiagnosisResult diagnose_stick_slip(const std::string& dir_name, const std::string& model_extra) {
  const auto dir = scratch_dir(dir_name);
  std::vector<std::filesystem::path> csvs;
  for (const auto& [rpm, seed] : {std::pair{0.5, 21u}, std::pair{1.5, 22u}})
    csvs.push_back(test::make_measured_run(dir, "stick_" + std::to_string(static_cast<int>(rpm * 10)) + "rpm",
                                           stick_probe_text(kHiddenStickTime, rpm), seed, ""));  // the rig's 1 kHz
  analysis::DiagnosisOptions o;
  o.jobs = 1;
  o.torque_block_statistics = true;  // as `shudder diagnose` does for rig models
  return test::diagnose_measured(csvs, stick_probe_text(model_extra, 0.5), "scenarios/rig_stick_time_probe.toml", o,
                                 test::Reproduction::kNotCounted);
}

TEST(DiagnoseStickTime, IsNamedFromRigStickSlipRuns) {
  const auto r = diagnose_stick_slip("diag_stick_time", "");
  EXPECT_EQ(r.missing_effects, std::vector<std::string>{"stick_time_static_friction"}) << test::describe_diagnosis(r);
  expect_gap_shrinks(r);
  expect_parameters(r, Case{"", "", "", {}, {{"max_increase", 0.15}, {"time_constant_s", 0.05}}});
}

TEST(DiagnoseStickTime, TheTrueModelNeedsNothingAdded) {
  // The replay of stick-slip itself (set point recovered from the loop, block statistics)
  // must not invent an effect when the model is the one that made the data.
  const auto r = diagnose_stick_slip("diag_stick_time_truth", kHiddenStickTime);
  EXPECT_TRUE(r.missing_effects.empty()) << test::describe_diagnosis(r);
  EXPECT_LT(r.baseline.torque_rms_Nm, 1.5 * r.noise_torque_Nm);
}

}  // namespace
}  // namespace shudder
