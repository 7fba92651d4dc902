#pragma once
// What a model kind's runs are judged and studied with, declared once per kind as free
// functions overloaded on the kind, as rig_models/model.hpp declares what the kinds are and
// how they run: the run's verdict and the analysis stored with it, the sweep's case, the model a
// measured run is replayed on for the diagnosis. Commands visit generically,
//   std::visit([&](const auto& m) { return studies::evaluate_case(m, clutch, rec); }, scenario.model);
// and a kind without one of these overloads does not compile (tests/rig_models/
// test_model_capabilities.cpp). A kind that cannot do something throws
// rig_models::KindNotSupported with the reason.

#include <string>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/model.hpp"
#include "studies/case_evaluation.hpp"
#include "studies/replay.hpp"

namespace shudder::studies {

// ---- shudder run ----------------------------------------------------------------------------

/// The run's extra analysis, stored in `rec`: every kind's verdict block (run_verdict.hpp:
/// judged verdict, operating point, and the prediction there — the rig's linear stability, "not
/// predicted" for the others) and the rig's stability map (/analysis/stability_map, for
/// `shudder plot`; a record too short to judge gets a "not_judged" block with the reason).
/// Returns warnings (without the "shudder: warning: " prefix): a map that cannot be made (e.g.
/// a cycle that never loads the clutch) costs the run nothing but is said.
std::vector<std::string> add_run_analysis(const rig_models::PrescribedSlipModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec);
std::vector<std::string> add_run_analysis(const rig_models::RigModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec);
std::vector<std::string> add_run_analysis(const rig_models::DrivelineModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec);

// ---- shudder sweep --------------------------------------------------------------------------

/// Whether sweeps judge this kind's cases; throws KindNotSupported if not. Checked on the
/// base scenario before any case runs.
void require_sweep(const rig_models::PrescribedSlipModel& model);
void require_sweep(const rig_models::RigModel& model);
void require_sweep(const rig_models::DrivelineModel& model);

/// One sweep case: runs the model into `rec`, predicts and judges it (case_evaluation.hpp).
/// Throws KindNotSupported where require_sweep does.
CaseOutcome evaluate_case(const rig_models::PrescribedSlipModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec);
CaseOutcome evaluate_case(const rig_models::RigModel& model, const clutch::WetClutch& clutch, dynamics::Recording& rec);
CaseOutcome evaluate_case(const rig_models::DrivelineModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec);

// ---- shudder diagnose -----------------------------------------------------------------------

/// The model a measured run is replayed on (studies/replay.hpp), without its clutch and
/// fluid, which the caller sets. `stick_time` is the scenario's [effects.stick_time_static_friction]
/// as read: a prescribed-slip model has no rig to hold it, but the candidate list must still
/// know whether that effect is on. A driveline replays its coupling alone (ReplayModel::kind kDriveline).
ReplayModel replay_model(const rig_models::PrescribedSlipModel& model, const components::StickTimeFriction& stick_time);
ReplayModel replay_model(const rig_models::RigModel& model, const components::StickTimeFriction& stick_time);
ReplayModel replay_model(const rig_models::DrivelineModel& model, const components::StickTimeFriction& stick_time);

// ---- shudder modes

}  // namespace shudder::studies
