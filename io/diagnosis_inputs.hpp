#pragma once
// From files to the diagnosis: a scenario becomes the model to replay (its drive cycle is
// dropped), measured runs become the data and the replay inputs. The checks that need file
// names live here: runs from different rigs, runs too short to fit anything.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/measured_run.hpp"
#include "io/scenario.hpp"
#include "studies/replay.hpp"

namespace shudder::io {

/// Fewest rows and shortest duration of a run the diagnosis accepts: the inputs are averaged
/// over 0.05 s windows and the hold-out takes alternate tenths, so below this nothing is fitted.
inline constexpr std::size_t diagnosis_min_rows = 20;
inline constexpr double diagnosis_min_duration_s = 1.0;

studies::ReplayModel replay_model(const Scenario& scenario);

struct DiagnosisData {
  std::vector<analysis::DiagnosisRun> runs;
  std::vector<studies::ReplayInputs> inputs;
  std::string rig;  // the runs' common `rig` metadata ("" if none says)
  std::vector<std::string> warnings;
};

/// Throws InputError (exit 2) naming the file: runs whose `rig` metadata differ, a run too
/// short to fit (see above), a temp_sensor/oil_flow_ml_min value that is not understood.
/// Warns when the runs' `rig` is not the model's (`model`: the replay model's kind of data,
/// "lsctr" or a driveline's rig_models::kCouplingRig).
DiagnosisData diagnosis_data(const std::vector<MeasuredRun>& runs);
DiagnosisData diagnosis_data(const std::vector<MeasuredRun>& runs, const studies::ReplayModel& model);

}  // namespace shudder::io
