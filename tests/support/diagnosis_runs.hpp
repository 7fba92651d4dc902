#pragma once
// The two halves of the end-to-end diagnosis tests: make noisy "measured" runs with `shudder run`
// from scenario text (the generating rig, effects hidden in it), then diagnose them against a
// model scenario the way `shudder diagnose` does (app/cmd_diagnose.cpp: the replay model's
// candidates and simulator, and its reproducer for the error scale), in-process so that the
// test can inspect the whole result.
#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <utility>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/diagnosis_inputs.hpp"
#include "io/measured_run.hpp"
#include "io/scenario.hpp"
#include "studies/replay.hpp"
#include "tests/support/cli.hpp"

namespace shudder::test {

/// `shudder run` of scenario `text` (written to dir/STEM.toml) recorded as a measured run with
/// sensor noise from `seed`; `sampling` is the run's sampling option ("--sample-rate 100", or
/// "" for the scenario's own rate). Returns dir/STEM.csv; a failed run fails the calling test.
inline std::filesystem::path make_measured_run(const std::filesystem::path& dir, const std::string& stem,
                                               const std::string& text, unsigned seed,
                                               const std::string& sampling = "--sample-rate 100") {
  write_file(dir / (stem + ".toml"), text);
  const auto out = run_cli("run " + stem + ".toml -o " + stem + ".h5 --measurement " + stem + ".csv " + sampling +
                               " --noise --seed " + std::to_string(seed),
                           dir);
  EXPECT_EQ(out.exit_code, 0) << out.err;
  return dir / (stem + ".csv");
}

/// Whether the replay's reproduction error enters the error scale, as it does in `shudder
/// diagnose`; the hidden-effect cases were set up without it and are kept so.
enum class Reproduction { kCounted, kNotCounted };

/// Diagnoses `runs` against the scenario `model` with `o`, as `shudder diagnose` does.
inline analysis::DiagnosisResult diagnose_measured(const std::vector<io::MeasuredRun>& runs, const io::Scenario& model,
                                                   const analysis::DiagnosisOptions& o,
                                                   Reproduction reproduction = Reproduction::kCounted) {
  const auto replay = io::replay_model(model);
  auto data = io::diagnosis_data(runs, replay);
  const auto reproduce =
      reproduction == Reproduction::kCounted ? studies::replay_reproducer(replay, data.inputs) : analysis::Reproducer{};
  return analysis::diagnose(data.runs, studies::replay_candidates(replay, nullptr),
                            studies::replay_simulator(replay, std::move(data.inputs)), o, reproduce);
}

/// The same on the measured CSVs `csvs`, against the scenario `model_text` read as if it stood
/// at `model_path` (under the source tree; relative paths inside resolve from there).
inline analysis::DiagnosisResult diagnose_measured(const std::vector<std::filesystem::path>& csvs,
                                                   const std::string& model_text, const std::string& model_path,
                                                   const analysis::DiagnosisOptions& o,
                                                   Reproduction reproduction = Reproduction::kCounted) {
  std::vector<io::MeasuredRun> runs;
  for (const auto& c : csvs) runs.push_back(io::read_measured_run(c.string()));
  return diagnose_measured(runs, io::load_scenario_text(model_text, source_path(model_path)), o, reproduction);
}

}  // namespace shudder::test
