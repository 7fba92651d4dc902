#pragma once
// The typed model a scenario describes: one of a closed set of kinds, each holding what that
// kind needs to run (the clutch itself is common to all and built by the caller). Commands
// dispatch with std::visit over `overloaded{...}` (core/overloaded.hpp), one lambda per kind
// and no generic fallback, so a kind a command does not handle is a compile error. What a kind
// can do is a free function overloaded on it (simulate, evaluate_case); what only one kind can
// do (modes and stability maps of the rig) is called on that kind's alternative directly.

#include <variant>

#include "clutch/wet_clutch.hpp"
#include "core/model_kind.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/case_evaluation.hpp"
#include "rig_models/drive_cycle.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::rig_models {

/// Paper G's set-up: slip speed and force imposed (rig_models/prescribed_slip.hpp).
struct PrescribedSlipModel {
  DriveCycle cycle;
  PrescribedSlipSettings settings;  // duration, steps, sampling, snapshots, bearing drag
};

/// The LSCTR rig (rig_models/lsctr_rig.hpp) following a drive cycle.
struct RigModel {
  RigParams params;  // bearing drag and stick-time friction included
  DriveCycle cycle;
  RigSettings settings;
};

/// The Haldex-coupled car (rig_models/haldex_driveline.hpp) driven through a manoeuvre.
struct DrivelineModel {
  DrivelineParams params;  // stick-time friction included
  DrivelineInputs manoeuvre;
  DrivelineSettings settings;
};

using Model = std::variant<PrescribedSlipModel, RigModel, DrivelineModel>;

constexpr ModelKind kind(const PrescribedSlipModel&) { return ModelKind::kPrescribedSlip; }
constexpr ModelKind kind(const RigModel&) { return ModelKind::kRig; }
constexpr ModelKind kind(const DrivelineModel&) { return ModelKind::kDriveline; }
ModelKind kind(const Model& model);

/// Simulated duration, s.
double duration_s(const Model& model);

/// Runs the model and returns its recording (docs/run_output.md).
dynamics::Recording simulate(const PrescribedSlipModel& model, const clutch::WetClutch& clutch);
dynamics::Recording simulate(const RigModel& model, const clutch::WetClutch& clutch);
dynamics::Recording simulate(const DrivelineModel& model, const clutch::WetClutch& clutch);

/// One sweep case: runs the model into `rec`, predicts and judges it (case_evaluation.hpp).
CaseOutcome evaluate_case(const PrescribedSlipModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec);
CaseOutcome evaluate_case(const RigModel& model, const clutch::WetClutch& clutch, dynamics::Recording& rec);

}  // namespace shudder::rig_models
