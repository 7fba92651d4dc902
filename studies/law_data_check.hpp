#pragma once
// Whether a replay reads the model's friction law above the temperatures its data reach — the
// likely cause of a torque gap that no missing effect explains (a fluid characterised from runs
// whose ramps heat the clutch beyond the law's top row: docs/characterisation.md "Hot row").
//
// Each run is replayed once on the baseline model (studies/replay.hpp); a sample counts when
// its area-mean interface temperature exceeds the law's highest data temperature
// (FrictionLaw::temp_range_C; above it the law holds its top row).

#include <string>
#include <vector>

#include "studies/replay.hpp"

namespace shudder::studies {

/// One warning per run that spends more than 5 % of its samples above the law's data (a few
/// samples at a ramp's top are within what the row's own temperature spread covers), naming
/// the run, the share, the hottest interface temperature and the law's top temperature.
/// `names[k]` names inputs[k]. Runs the model cannot replay are skipped (the diagnosis reports them).
std::vector<std::string> law_above_its_data(const ReplayModel& model, const std::vector<ReplayInputs>& inputs,
                                            const std::vector<std::string>& names);

}  // namespace shudder::studies
