#pragma once
// A driveline run's own figures that are studies of its recording (rig_models/haldex_driveline.hpp
// runs it): the coupling judged for judder or stick-slip on its torque and slip as on the rig,
// with the channels and band every reader of the recording uses (studies/recording_detection.hpp),
// and the locked coupling's lowest oscillating mode (the shuffle) linearised about the run's mean
// operating point (studies/driveline_stability.hpp: the engine's torque–speed slope, the tyres'
// relaxation at the run's speed, the shafts' dampers) — the point and method that
// `shudder modes SCENARIO --run RUN.h5` prints, so both give the same numbers.
//
// Scalars appended: coupling_verdict_code (0 none, 1 vibration, 2 stick_slip),
// coupling_oscillation_frequency_Hz, coupling_oscillation_amplitude_Nm (NaN for a record too
// short to judge, < 64 samples), shuffle_frequency_Hz, shuffle_damping_ratio.

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/haldex_driveline.hpp"

namespace shudder::studies {

void add_driveline_judgement(const rig_models::DrivelineParams& params, const clutch::WetClutch& clutch,
                             const rig_models::DrivelineInputs& inputs, const rig_models::DrivelineSettings& settings,
                             dynamics::Recording& rec);

}  // namespace shudder::studies
