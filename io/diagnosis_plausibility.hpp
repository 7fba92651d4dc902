#pragma once
// Plausibility of measured runs before a diagnosis: the checks that catch a wrong unit or a
// wrong file, which would otherwise be fitted into a confident but meaningless diagnosis.
//
//   kelvin       a temperature column (temp_C, sump_temp_C, ir_temp_C) whose median exceeds
//                200 °C: wet-clutch oils are run below ~150 °C (the thesis' rig stays under
//                120 °C), while 20–150 °C in kelvin reads 293–423 → exit 2.
//   kilonewton   normal_force_N whose largest value is below 100 N: the LSCTR applies 1–30 kN
//                (thesis Method), so 1–30 reads as kN → exit 2; below 500 N → warning.
//   identical    two runs with the same time, torque and temperature columns (the same file
//                given twice): the hold-out would be fit data → exit 2.
//   too short    a run shorter than 20 of the model's thermal steps (nothing thermal can be
//                fitted) → exit 2; a rig run shorter than 3 statistics blocks (under 5
//                half-overlapping blocks: the block jitter cannot be estimated) or all runs together shorter than 3 ×
//                the model's slowest enabled time constant (rig heat capacity C/G, sensor lag) → warning.
// Speed in rad/s under speed_rpm needs the model: analysis/diagnosis.cpp compares the measured
// temperature rise with the baseline's.

#include <string>
#include <vector>

#include "io/measured_run.hpp"
#include "studies/replay.hpp"

namespace shudder::io {

/// Throws InputError (exit 2) naming the file and column for what looks wrong; appends a
/// warning for what is only suspicious.
void check_plausibility(const std::vector<MeasuredRun>& runs, const studies::ReplayModel& model,
                        double statistics_block_s, std::vector<std::string>& warnings);

}  // namespace shudder::io
