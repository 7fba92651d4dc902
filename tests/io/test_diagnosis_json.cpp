// Diagnosis result -> JSON (docs/formats/diagnosis_json.md) and report directory. The JSON text
// is read back by a small strict RFC 8259 parser (tests/support/json.hpp),
// so "valid JSON" is checked on the whole text, not on substrings; one test writes a real
// diagnosis (a fake linear model) through it. Checked: every required key
// with its value; the optional fields; NaN/inf -> null; escaping of quotes, backslashes and
// control characters; atomic write and InputError for an unwritable path; run-name stems; the
// report's files (PNGs only where gnuplot is installed).
#include <gmock/gmock.h>
#include <gtest/gtest.h>
#include <unistd.h>

#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <limits>
#include <map>
#include <memory>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/diagnosis_json.hpp"
#include "io/input_error.hpp"
#include "report/diagnosis_narrative.hpp"
#include "report/diagnosis_report.hpp"
#include "tests/support/json.hpp"
#include "tests/support/linear_diagnosis.hpp"
#include "tests/support/test_directory.hpp"

namespace fs = std::filesystem;
using shudder::analysis::CandidateScore;
using shudder::analysis::DiagnosisResult;
using shudder::analysis::DiagnosisStep;
using shudder::io::InputError;
using testing::HasSubstr;

namespace {

// The file as `shudder diagnose --json` writes it: the result with the narrative's sentences.
std::string diagnosis_json(const DiagnosisResult& r) {
  return shudder::io::diagnosis_json(r, shudder::report::diagnosis_sentences(r));
}

using shudder::test::Json;
using shudder::test::parse;

// ---- fixtures --------------------------------------------------------------------------------

CandidateScore candidate(const std::string& effect, double holdout, double gain) {
  CandidateScore c;
  c.effect = effect;
  c.parameters = {{"heat_capacity_J_per_K", 150.0}, {"conductance_W_per_K", 10.0}};
  c.fit_misfit = 1.25;
  c.holdout_misfit = holdout;
  c.score = holdout + 0.04;
  c.gain = gain;
  c.signature_correlation = 0.93;
  c.evaluations = 42;
  return c;
}

std::vector<double> ramp(std::size_t n, double a, double b) {
  std::vector<double> v(n);
  for (std::size_t i = 0; i < n; ++i) v[i] = a + b * static_cast<double>(i);
  return v;
}

DiagnosisResult sample_result() {
  DiagnosisResult r;
  r.runs = {"data/a.csv", "b.csv"};
  r.noise_torque_Nm = 0.25;
  r.noise_temp_C = 0.5;
  r.holdout = {shudder::analysis::HoldoutSplit::Kind::kLastRun, "b.csv"};
  r.baseline = {8.12, 6.3};
  r.final = {1.21, 0.95};
  r.channels = {{"torque_Nm", "block_statistics", 0.25, 8.12, 1.21, 1055.0, 23.4},
                {"sump_temp_C", "pointwise", 0.1, 2.0, 0.09, 400.0, 0.81}};
  r.baseline_holdout_misfit = 512.0;
  r.final_holdout_misfit = 1.1;
  r.disagreements = {{"data/a.csv", "torque_Nm", 4.1, 10.0, -7.2, "temperature_rise", 0.97},
                     {"b.csv", "temp_C", 0.5, 3.25, 2.5, "time", 0.8}};
  r.final_disagreements = {{"b.csv", "temp_C", 1.0, 1.5, 0.6, "sliding_speed", -0.4}};
  r.tracking = {{"data/a.csv", "torque_Nm", {{"temperature_rise", 0.97}, {"time", 0.9}}}};
  DiagnosisStep st;
  st.effect = "temperature_dependent_friction";
  st.parameters = {{"mu_temp_slope_per_K", 0.002}};
  st.misfit = {1.21, 6.1};
  st.holdout = {1.3, 6.2};
  st.holdout_misfit_before = 512.0;
  st.holdout_misfit_after = 80.5;
  st.candidates = {candidate("temperature_dependent_friction", 80.5, 431.0), candidate("bearing_drag", 400.0, 112.0)};
  st.candidates[1].failure = "";
  st.description = "friction follows the interface temperature";
  st.torque_tracking_before = {{"temperature_rise", 0.97}, {"time", 0.9}};
  r.steps = {st};
  r.missing_effects = {"temperature_dependent_friction"};
  r.last_round = {candidate("sump_heating", 1.09, 0.001), candidate("viscous_shear", 1.2, -0.1)};
  r.last_round[1].failure = "every simulation failed: step size too small";
  r.stop.kind = shudder::analysis::StopReason::Kind::kNoGain;
  r.stop.needed_gain = 0.09;
  r.stop.best_effect = "sump_heating";
  r.stop.best_gain = 0.001;
  r.simulation_thread_s = 12.5;
  r.fitting_thread_s = 0.75;
  r.wall_s = 3.5;
  r.simulations = 1234;
  for (const auto& run : r.runs) {
    shudder::analysis::RunTraces tr;
    tr.run = run;
    tr.time_s = ramp(50, 0.0, 0.1);
    tr.torque_measured = ramp(50, 100.0, -0.5);
    tr.torque_baseline = ramp(50, 100.0, 0.0);
    tr.torque_final = ramp(50, 100.5, -0.5);
    tr.temp_measured = ramp(50, 40.0, 0.4);
    tr.temp_baseline = ramp(50, 40.0, 0.5);
    tr.temp_final = ramp(50, 40.0, 0.41);
    r.traces.push_back(tr);
  }
  return r;
}

bool gnuplot_installed() {
  const char* path = std::getenv("PATH");
  std::istringstream dirs(path ? path : "");
  std::string d;
  while (std::getline(dirs, d, ':'))
    if (::access((d + "/gnuplot").c_str(), X_OK) == 0) return true;
  return false;
}

class DiagnosisFiles : public shudder::test::TestDirectory {
 protected:
  DiagnosisFiles() : TestDirectory("djson") {}
};

std::string slurp(const std::string& p) {
  std::ifstream in(p, std::ios::binary);
  std::ostringstream os;
  os << in.rdbuf();
  return os.str();
}

// ---- tests -------------------------------------------------------------------------------

TEST(DiagnosisJson, ARealDiagnosisIsWrittenAsStrictJsonWithEveryKey) {
  // analysis::diagnose on the linear fake model (tests/support/linear_diagnosis.hpp: the run
  // misses torque_slope = 0.3 N m/rpm) written by the product writer: the whole text must parse
  // as strict JSON, hold every top-level key of docs/formats/diagnosis_json.md in order, and carry
  // the result's numbers and sentences.
  const std::vector<shudder::analysis::DiagnosisRun> runs{
      shudder::test::linear_measured_run({{"torque_slope", {0.3}}})};
  const auto simulate = [&](const std::vector<shudder::analysis::EffectSetting>& added, std::size_t k) {
    return shudder::test::linear_prediction(runs[k], added);
  };
  const DiagnosisResult r = shudder::analysis::diagnose(runs, shudder::test::linear_candidates(), simulate, {});
  const Json j = parse(diagnosis_json(r));
  const std::vector<std::string> keys{"format",
                                      "shudder_version",
                                      "verdict",
                                      "verdict_text",
                                      "runs",
                                      "noise",
                                      "holdout",
                                      "baseline",
                                      "disagreements",
                                      "tracking",
                                      "steps",
                                      "missing_effects",
                                      "not_explained",
                                      "tolerance_given",
                                      "withdrawn_effects",
                                      "indistinguishable_effects",
                                      "last_round",
                                      "final",
                                      "final_effects",
                                      "channels",
                                      "final_disagreements",
                                      "remaining",
                                      "conclusion",
                                      "timing"};
  ASSERT_EQ(j.members.size(), keys.size());
  for (std::size_t i = 0; i < keys.size(); ++i) EXPECT_EQ(j.members[i].first, keys[i]);
  ASSERT_EQ(j["steps"].items.size(), 1u);
  EXPECT_EQ(j["steps"][0]["effect"].str(), "torque_slope");
  const double slope = r.steps[0].parameters[0].second;
  EXPECT_NEAR(j["steps"][0]["parameters"]["slope_Nm_per_rpm"].num(), slope, 1e-9 * slope);  // 10 digits written
  EXPECT_THAT(j["steps"][0]["reason"].str(), HasSubstr("torque_slope (torque rises with the sliding speed)"));
  EXPECT_THAT(j["conclusion"].str(), testing::StartsWith("Missing: torque_slope. Torque RMS "));
  EXPECT_DOUBLE_EQ(j["timing"]["simulations"].num(), static_cast<double>(r.simulations));
}

TEST(DiagnosisJson, RequiredKeysHaveTheResultsValues) {
  const DiagnosisResult r = sample_result();
  const Json j = parse(diagnosis_json(r));
  EXPECT_EQ(j["format"].str(), "shudder-diagnosis/1");
  ASSERT_EQ(j["runs"].items.size(), 2u);
  EXPECT_EQ(j["runs"][0].str(), "data/a.csv");
  EXPECT_EQ(j["runs"][1].str(), "b.csv");
  EXPECT_DOUBLE_EQ(j["baseline"]["torque_rms_Nm"].num(), 8.12);
  EXPECT_DOUBLE_EQ(j["baseline"]["temp_rms_C"].num(), 6.3);

  ASSERT_EQ(j["disagreements"].items.size(), 2u);
  const Json& d = j["disagreements"][0];
  EXPECT_EQ(d["run"].str(), "data/a.csv");
  EXPECT_EQ(d["signal"].str(), "torque_Nm");
  EXPECT_DOUBLE_EQ(d["t_start_s"].num(), 4.1);
  EXPECT_DOUBLE_EQ(d["t_end_s"].num(), 10.0);
  EXPECT_DOUBLE_EQ(d["mean_error"].num(), -7.2);
  EXPECT_EQ(d["tracks"].str(), "temperature_rise");
  EXPECT_DOUBLE_EQ(d["correlation"].num(), 0.97);
  EXPECT_EQ(j["disagreements"][1]["signal"].str(), "temp_C");

  ASSERT_EQ(j["steps"].items.size(), 1u);
  const Json& s = j["steps"][0];
  EXPECT_EQ(s["effect"].str(), "temperature_dependent_friction");
  ASSERT_EQ(s["parameters"].members.size(), 1u);
  EXPECT_DOUBLE_EQ(s["parameters"]["mu_temp_slope_per_K"].num(), 0.002);
  EXPECT_DOUBLE_EQ(s["torque_rms_Nm"].num(), 1.21);
  EXPECT_DOUBLE_EQ(s["temp_rms_C"].num(), 6.1);
  EXPECT_DOUBLE_EQ(s["holdout_torque_rms_Nm"].num(), 1.3);

  ASSERT_EQ(j["missing_effects"].items.size(), 1u);
  EXPECT_EQ(j["missing_effects"][0].str(), "temperature_dependent_friction");
  EXPECT_DOUBLE_EQ(j["final"]["torque_rms_Nm"].num(), 1.21);
  EXPECT_DOUBLE_EQ(j["final"]["temp_rms_C"].num(), 0.95);

  // Exact formatting of the contract's example values.
  const std::string text = diagnosis_json(r);
  EXPECT_THAT(text, HasSubstr("\"format\": \"shudder-diagnosis/1\""));
  EXPECT_THAT(text, HasSubstr("\"baseline\": {\"torque_rms_Nm\": 8.12, \"temp_rms_C\": 6.3"));
  EXPECT_THAT(text, HasSubstr("\"t_start_s\": 4.1, \"t_end_s\": 10, \"mean_error\": -7.2"));
}

TEST(DiagnosisJson, OptionalFieldsAreWritten) {
  const Json j = parse(diagnosis_json(sample_result()));
  EXPECT_DOUBLE_EQ(j["noise"]["torque_Nm"].num(), 0.25);
  EXPECT_DOUBLE_EQ(j["noise"]["temp_C"].num(), 0.5);
  EXPECT_EQ(j["holdout"].str(), "run 'b.csv' (fits use the other runs)");
  EXPECT_DOUBLE_EQ(j["baseline"]["holdout_misfit"].num(), 512.0);
  EXPECT_DOUBLE_EQ(j["final"]["holdout_misfit"].num(), 1.1);

  const Json& s = j["steps"][0];
  EXPECT_DOUBLE_EQ(s["holdout_temp_rms_C"].num(), 6.2);
  EXPECT_DOUBLE_EQ(s["holdout_misfit_before"].num(), 512.0);
  EXPECT_DOUBLE_EQ(s["holdout_misfit_after"].num(), 80.5);
  EXPECT_THAT(s["reason"].str(), HasSubstr("tracked temperature_rise (0.97)"));
  ASSERT_EQ(s["candidates"].items.size(), 2u);
  const Json& c = s["candidates"][0];
  EXPECT_EQ(c["effect"].str(), "temperature_dependent_friction");
  EXPECT_DOUBLE_EQ(c["parameters"]["heat_capacity_J_per_K"].num(), 150.0);
  EXPECT_DOUBLE_EQ(c["parameters"]["conductance_W_per_K"].num(), 10.0);
  EXPECT_EQ(c["parameters"].members[0].first, "heat_capacity_J_per_K");  // order kept
  EXPECT_DOUBLE_EQ(c["fit_misfit"].num(), 1.25);
  EXPECT_DOUBLE_EQ(c["holdout_misfit"].num(), 80.5);
  EXPECT_DOUBLE_EQ(c["score"].num(), 80.54);
  EXPECT_DOUBLE_EQ(c["gain"].num(), 431.0);
  EXPECT_DOUBLE_EQ(c["signature_correlation"].num(), 0.93);
  EXPECT_DOUBLE_EQ(c["evaluations"].num(), 42.0);
  EXPECT_FALSE(c.has("failure"));  // only failed candidates carry it

  ASSERT_EQ(j["last_round"].items.size(), 2u);
  EXPECT_EQ(j["last_round"][0]["effect"].str(), "sump_heating");
  EXPECT_FALSE(j["last_round"][0].has("failure"));
  EXPECT_EQ(j["last_round"][1]["failure"].str(), "every simulation failed: step size too small");

  ASSERT_EQ(j["channels"].items.size(), 2u);
  const Json& ch = j["channels"][1];
  EXPECT_EQ(ch["signal"].str(), "sump_temp_C");
  EXPECT_EQ(ch["comparison"].str(), "pointwise");
  EXPECT_DOUBLE_EQ(ch["noise"].num(), 0.1);
  EXPECT_DOUBLE_EQ(ch["baseline_rms"].num(), 2.0);
  EXPECT_DOUBLE_EQ(ch["final_rms"].num(), 0.09);
  EXPECT_DOUBLE_EQ(ch["baseline_misfit"].num(), 400.0);
  EXPECT_DOUBLE_EQ(ch["final_misfit"].num(), 0.81);
  EXPECT_EQ(j["channels"][0]["comparison"].str(), "block_statistics");

  ASSERT_EQ(j["final_disagreements"].items.size(), 1u);
  EXPECT_EQ(j["final_disagreements"][0]["tracks"].str(), "sliding_speed");
  EXPECT_DOUBLE_EQ(j["final_disagreements"][0]["correlation"].num(), -0.4);
  ASSERT_EQ(j["tracking"].items.size(), 1u);
  EXPECT_EQ(j["tracking"][0]["run"].str(), "data/a.csv");
  EXPECT_EQ(j["tracking"][0]["signal"].str(), "torque_Nm");
  EXPECT_DOUBLE_EQ(j["tracking"][0]["correlations"]["temperature_rise"].num(), 0.97);
  EXPECT_DOUBLE_EQ(j["tracking"][0]["correlations"]["time"].num(), 0.9);
  // The sentences are written from the numbers (report/diagnosis_narrative): "%.3g" values, the
  // step's evidence, the stop reason.
  EXPECT_EQ(j["conclusion"].str(),
            "Missing: temperature_dependent_friction. Torque RMS 8.12 -> 1.21 Nm, temperature RMS 6.3 -> "
            "0.95 C (noise 0.25 Nm, 0.5 C). The search stopped because no candidate lowers the held-out "
            "misfit by more than 0.09 with interior parameters and a change that follows the residual "
            "(best: sump_heating, lowers it by 0.001).");
  EXPECT_EQ(j["steps"][0]["reason"].str(),
            "temperature_dependent_friction (friction follows the interface temperature): before it, the "
            "torque error tracked temperature_rise (0.97) and the temperature error nothing. The change this "
            "effect makes matches that residual (signature r = 0.93) with mu_temp_slope_per_K = 0.002, and it "
            "lowers the held-out misfit from 512 to 80.5 (1 = noise level); the next best, bearing_drag, "
            "reached 400.");
  EXPECT_DOUBLE_EQ(j["timing"]["simulation_thread_s"].num(), 12.5);
  EXPECT_DOUBLE_EQ(j["timing"]["fitting_thread_s"].num(), 0.75);
  EXPECT_DOUBLE_EQ(j["timing"]["wall_s"].num(), 3.5);
  EXPECT_DOUBLE_EQ(j["timing"]["simulations"].num(), 1234.0);
  EXPECT_THAT(diagnosis_json(sample_result()), HasSubstr("\"simulations\": 1234}"));
}

TEST(DiagnosisJson, BackwardCheckFindingsAreWrittenWithTheirCosts) {
  // docs/formats/diagnosis_json.md: `withdrawn_effects` without `kept_because`, an effect kept by the
  // tie rule under `indistinguishable_effects` with it; the summary and report say the same.
  DiagnosisResult r;
  shudder::analysis::BackwardFinding w{"torque_sensor_gain", {{"gain", 1.004}}, 0.0031, 0.0452, true, "", "", "", {}};
  shudder::analysis::BackwardFinding k{"interface_oil_cooling",
                                       {{"e", 0.0164}},
                                       0.0113,
                                       0.0464,
                                       false,
                                       "rig_heat_capacity",
                                       "heat_capacity_J_per_K 290 -> 2510",
                                       "rig_heat_capacity could stand in but has more parameters",
                                       {}};
  r.withdrawn.push_back(w);
  r.indistinguishable.push_back(k);
  const Json j = parse(diagnosis_json(r));
  ASSERT_EQ(j["withdrawn_effects"].items.size(), 1u);
  const Json& jw = j["withdrawn_effects"][0];
  EXPECT_EQ(jw["effect"].str(), "torque_sensor_gain");
  EXPECT_DOUBLE_EQ(jw["parameters"]["gain"].num(), 1.004);
  EXPECT_DOUBLE_EQ(jw["holdout_cost"].num(), 0.0031);
  EXPECT_DOUBLE_EQ(jw["needed_gain"].num(), 0.0452);
  EXPECT_EQ(jw["stand_in"].str(), "");
  EXPECT_FALSE(jw.has("kept_because"));
  ASSERT_EQ(j["indistinguishable_effects"].items.size(), 1u);
  const Json& jk = j["indistinguishable_effects"][0];
  EXPECT_EQ(jk["stand_in"].str(), "rig_heat_capacity");
  EXPECT_EQ(jk["stand_in_move"].str(), "heat_capacity_J_per_K 290 -> 2510");
  EXPECT_EQ(jk["kept_because"].str(), "rig_heat_capacity could stand in but has more parameters");
  EXPECT_EQ(shudder::report::backward_finding_text(w),
            "torque_sensor_gain: without it the held-out misfit rises by 0.0031, below the 0.0452 it would need; "
            "withdrawn");
  EXPECT_EQ(shudder::report::backward_finding_text(k),
            "interface_oil_cooling: without it the held-out misfit rises by 0.0113, below the 0.0464 it would "
            "need; rig_heat_capacity takes over (heat_capacity_J_per_K 290 -> 2510); kept: rig_heat_capacity "
            "could stand in but has more parameters (the data cannot separate the two)");
  EXPECT_THAT(shudder::report::diagnosis_candidates_markdown(r), HasSubstr("* Withdrawn: torque_sensor_gain: "));
}

TEST(DiagnosisJson, EmptyResultIsValidWithEmptyArrays) {
  const Json j = parse(diagnosis_json(DiagnosisResult{}));
  for (const char* k : {"runs", "disagreements", "steps", "missing_effects", "not_explained", "withdrawn_effects",
                        "indistinguishable_effects", "last_round", "final_disagreements", "tracking", "channels"}) {
    EXPECT_EQ(j[k].type, Json::Type::kArray) << k;
    EXPECT_TRUE(j[k].items.empty()) << k;
  }
  EXPECT_DOUBLE_EQ(j["final"]["torque_rms_Nm"].num(), 0.0);
}

TEST(DiagnosisJson, NonFiniteNumbersAreNull) {
  DiagnosisResult r = sample_result();
  const double nan = std::numeric_limits<double>::quiet_NaN();
  const double inf = std::numeric_limits<double>::infinity();
  r.baseline.torque_rms_Nm = nan;
  r.final.temp_rms_C = inf;
  r.final_holdout_misfit = -inf;
  r.disagreements[0].correlation = nan;
  r.steps[0].parameters[0].second = inf;
  r.steps[0].holdout.torque_rms_Nm = nan;
  r.last_round[1].holdout_misfit = nan;
  r.tracking[0].correlations[1].second = nan;
  r.wall_s = nan;
  r.channels[0].final_misfit = nan;
  const std::string text = diagnosis_json(r);
  // As JSON values (the sentences may spell a non-finite number out in words).
  for (const char* bad : {": nan", ": inf", ": -inf", "[nan", "[inf"}) EXPECT_THAT(text, testing::Not(HasSubstr(bad)));
  const Json j = parse(text);
  EXPECT_TRUE(j["baseline"]["torque_rms_Nm"].is_null());
  EXPECT_TRUE(j["final"]["temp_rms_C"].is_null());
  EXPECT_TRUE(j["final"]["holdout_misfit"].is_null());
  EXPECT_TRUE(j["disagreements"][0]["correlation"].is_null());
  EXPECT_TRUE(j["steps"][0]["parameters"]["mu_temp_slope_per_K"].is_null());
  EXPECT_TRUE(j["steps"][0]["holdout_torque_rms_Nm"].is_null());
  EXPECT_TRUE(j["last_round"][1]["holdout_misfit"].is_null());
  EXPECT_TRUE(j["tracking"][0]["correlations"]["time"].is_null());
  EXPECT_TRUE(j["timing"]["wall_s"].is_null());
  EXPECT_TRUE(j["channels"][0]["final_misfit"].is_null());
  EXPECT_DOUBLE_EQ(j["final"]["torque_rms_Nm"].num(), 1.21);  // neighbours untouched
}

TEST(DiagnosisJson, EscapesQuotesBackslashesAndControlCharacters) {
  DiagnosisResult r = sample_result();
  const std::string odd = "C:\\runs\\\"hot\" run\t1\n.csv";
  r.runs[0] = odd;
  r.disagreements[0].run = odd;
  r.steps[0].parameters[0].first = "key\"with\\quote";
  r.stop.best_effect = std::string("bell\x07 and unicode °C");
  const std::string text = diagnosis_json(r);
  EXPECT_THAT(text, HasSubstr(R"("C:\\runs\\\"hot\" run\t1\n.csv")"));
  EXPECT_THAT(text, HasSubstr(R"("key\"with\\quote": 0.002)"));
  EXPECT_THAT(text, HasSubstr(R"(bell\u0007 and unicode °C, lowers it by)"));
  const Json j = parse(text);
  EXPECT_EQ(j["runs"][0].str(), odd);
  EXPECT_EQ(j["disagreements"][0]["run"].str(), odd);
  EXPECT_DOUBLE_EQ(j["steps"][0]["parameters"]["key\"with\\quote"].num(), 0.002);
  EXPECT_THAT(j["conclusion"].str(), HasSubstr(r.stop.best_effect));
}

TEST_F(DiagnosisFiles, WriteIsAtomicAndMatchesTheText) {
  const DiagnosisResult r = sample_result();
  const std::string out = path("diag.json");
  { std::ofstream(out) << "old"; }
  shudder::io::write_diagnosis_json(out, r, shudder::report::diagnosis_sentences(r));
  EXPECT_EQ(slurp(out), diagnosis_json(r));
  EXPECT_FALSE(fs::exists(out + ".tmp"));
}

TEST_F(DiagnosisFiles, UnwritablePathIsAnInputErrorNamingIt) {
  const std::string out = path("no_such_dir/diag.json");
  EXPECT_THAT(
      [&] {
        shudder::io::write_diagnosis_json(out, sample_result(), shudder::report::diagnosis_sentences(sample_result()));
      },
      testing::ThrowsMessage<InputError>(HasSubstr(out)));
  EXPECT_FALSE(fs::exists(path("no_such_dir")));
}

TEST(DiagnosisReport, RunStemIsTheSanitizedFileStem) {
  using shudder::report::diagnosis_run_stem;
  EXPECT_EQ(diagnosis_run_stem("data/run_25kN.csv"), "run_25kN");
  EXPECT_EQ(diagnosis_run_stem("/abs/dir/a.b-c.csv"), "a.b-c");
  EXPECT_EQ(diagnosis_run_stem("hot \"run\" #2.csv"), "hot__run___2");
  EXPECT_EQ(diagnosis_run_stem("noext"), "noext");
  EXPECT_EQ(diagnosis_run_stem(".hidden"), "_hidden");
  EXPECT_EQ(diagnosis_run_stem("dir/"), "run");
  EXPECT_EQ(diagnosis_run_stem(""), "run");
}

TEST(DiagnosisReport, CandidatesMarkdownHasATablePerStepAndTheLastRound) {
  DiagnosisResult r = sample_result();
  r.last_round[0].failure = "a | b";
  const std::string md = shudder::report::diagnosis_candidates_markdown(r);
  EXPECT_THAT(md, HasSubstr("## Step 1: added temperature_dependent_friction"));
  EXPECT_THAT(md, HasSubstr("| effect | parameters | fit misfit | hold-out misfit | score | gain | "
                            "signature correlation |"));
  EXPECT_THAT(md, HasSubstr("| bearing_drag | heat_capacity_J_per_K = 150, conductance_W_per_K = 10 "
                            "| 1.25 | 400 | 400 | +112 | +0.930 | 42 |"));
  EXPECT_THAT(md, HasSubstr("## Last round (stopped the search)"));
  EXPECT_THAT(md, HasSubstr("| sump_heating |"));
  EXPECT_THAT(md, HasSubstr("failed: a \\| b"));  // a '|' must not split the cell
}

TEST_F(DiagnosisFiles, ReportWritesTextFilesAndPlots) {
  DiagnosisResult r = sample_result();
  r.traces.push_back(r.traces[1]);  // same stem twice: the second gets "_2"
  const std::string dir = path("report/sub");
  const shudder::report::Report rep = shudder::report::write_diagnosis_report(dir, r, "summary text\n");
  EXPECT_EQ(slurp(dir + "/summary.txt"), "summary text\n");
  EXPECT_EQ(slurp(dir + "/candidates.md"), shudder::report::diagnosis_candidates_markdown(r));
  for (const auto& f : fs::directory_iterator(dir)) EXPECT_NE(f.path().extension(), ".tmp") << f.path();
  if (!gnuplot_installed()) {
    EXPECT_EQ(rep.files.size(), 3u);  // summary.txt, candidates.md, index.html
    EXPECT_EQ(rep.skipped.size(), 3u);
    GTEST_SKIP() << "gnuplot not installed: PNGs not checked";
  }
  EXPECT_TRUE(rep.skipped.empty()) << rep.skipped.front();
  std::vector<std::string> expected = {dir + "/summary.txt", dir + "/candidates.md"};
  for (const char* stem : {"a", "b", "b_2"})
    for (const char* kind : {"_torque.png", "_temp.png", "_residuals.png"}) expected.push_back(dir + "/" + stem + kind);
  expected.push_back(dir + "/index.html");
  EXPECT_EQ(rep.files, expected);
  // The page shows every plot and links the text files.
  const std::string html = slurp(dir + "/index.html");
  EXPECT_THAT(html, HasSubstr("<img src=\"b_2_residuals.png\""));
  EXPECT_THAT(html, HasSubstr("<a href=\"candidates.md\">candidates.md</a>"));
  EXPECT_THAT(html, HasSubstr("torque above, temp_C below, each panel with its own zero line"));
  for (const auto& f : expected) {
    ASSERT_TRUE(fs::exists(f)) << f;
    if (fs::path(f).extension() == ".png") {
      EXPECT_EQ(slurp(f).substr(1, 3), "PNG") << f;
    }
  }
}

TEST_F(DiagnosisFiles, ReportSkipsARunWithoutSamples) {
  if (!gnuplot_installed()) GTEST_SKIP() << "gnuplot not installed";
  DiagnosisResult r = sample_result();
  r.traces.resize(1);
  r.traces[0].time_s.clear();
  const shudder::report::Report rep = shudder::report::write_diagnosis_report(path("rep"), r, "");
  EXPECT_EQ(rep.files.size(), 3u);  // summary.txt, candidates.md, index.html
  ASSERT_EQ(rep.skipped.size(), 1u);
  EXPECT_THAT(rep.skipped[0], HasSubstr("a_{torque,temp,residuals}.png"));
}

}  // namespace

namespace {

// The writer places the narrative's sentences; a reason missing for a step is a caller's bug
// that must not produce a file whose steps and reasons disagree.
TEST(DiagnosisJson, AReasonPerStepIsRequired) {
  DiagnosisResult r;
  r.steps.resize(2);
  shudder::io::DiagnosisSentences words{"held", {"only one"}, "done", "explained"};
  EXPECT_THROW(shudder::io::diagnosis_json(r, words), std::logic_error);
  words.step_reasons.push_back("second");
  EXPECT_THAT(shudder::io::diagnosis_json(r, words), HasSubstr("\"reason\": \"second\""));
}

}  // namespace

namespace {

TEST(DiagnosisJson, AJointStepNamesItsMembersInJointWith) {
  // docs/formats/diagnosis_json.md: a joint step (analysis/joint_step.hpp) is one step whose `effect`
  // is the first member and `joint_with` the others; `missing_effects` lists both; a finding of
  // the backward check on it names them too; the words say "a + b".
  DiagnosisResult r;
  shudder::analysis::DiagnosisStep st;
  st.effect = "temperature_dependent_friction";
  st.joint_with = {"load_dependent_friction"};
  shudder::analysis::CandidateScore pair;
  pair.effect = st.effect;
  pair.joint_with = st.joint_with;
  shudder::analysis::CandidateScore single;
  single.effect = "load_sensor_gain";
  single.parameters = {{"gain", 1.011}};
  st.candidates = {pair, single};
  r.steps.push_back(st);
  r.missing_effects = {"temperature_dependent_friction", "load_dependent_friction"};
  shudder::analysis::BackwardFinding f;
  f.effect = st.effect;
  f.joint_with = st.joint_with;
  r.indistinguishable.push_back(f);
  const Json j = parse(diagnosis_json(r));
  ASSERT_EQ(j["steps"].items.size(), 1u);
  EXPECT_EQ(j["steps"][0]["effect"].str(), "temperature_dependent_friction");
  ASSERT_EQ(j["steps"][0]["joint_with"].items.size(), 1u);
  EXPECT_EQ(j["steps"][0]["joint_with"][0].str(), "load_dependent_friction");
  EXPECT_EQ(j["steps"][0]["candidates"][0]["joint_with"][0].str(), "load_dependent_friction");
  EXPECT_FALSE(j["steps"][0]["candidates"][1].has("joint_with"));  // only on joint candidates
  EXPECT_EQ(j["missing_effects"].items.size(), 2u);
  EXPECT_EQ(j["indistinguishable_effects"][0]["joint_with"][0].str(), "load_dependent_friction");
  EXPECT_THAT(shudder::report::step_reason(st),
              HasSubstr("temperature_dependent_friction + load_dependent_friction, switched on together in one "
                        "joint step"));
  EXPECT_THAT(shudder::report::diagnosis_candidates_markdown(r),
              HasSubstr("## Step 1: added temperature_dependent_friction + load_dependent_friction"));
}

}  // namespace
