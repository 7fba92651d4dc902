#pragma once
// The typed model a scenario describes: one of a closed set of kinds, each holding what that
// kind needs to run (the clutch itself is common to all and built by the caller).
//
// What each kind can do -- or why it cannot -- is declared here, once per kind, as a free
// function overloaded on the kind (the capability list below). Commands visit generically,
//   std::visit([&](const auto& m) { return rig_models::simulate(m, clutch); }, scenario.model);
// and overload resolution picks the kind's function at compile time, so a new kind that lacks
// a capability's overload does not compile (tests/rig_models/test_model_capabilities.cpp checks
// every alternative against the list). There is deliberately no catch-all template.
//
// A kind that cannot do something still has the overload; it throws KindNotSupported with the
// reason, which the command turns into its input error (io/kind_refusal.hpp: exit 2, naming the
// scenario file and key). Adding a kind: docs/architecture_kinds.md.

#include <optional>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "clutch/wet_clutch.hpp"
#include "core/model_kind.hpp"
#include "dynamics/recording.hpp"
#include "rig_models/case_evaluation.hpp"
#include "rig_models/drive_cycle.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"
#include "rig_models/replay.hpp"

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
  // The instrumented coupling's sensors: they act on its measured run only (coupling_measurement.hpp).
  TorqueCell torque_cell;
  LoadCell load_cell;
};

using Model = std::variant<PrescribedSlipModel, RigModel, DrivelineModel>;

/// A kind asked for something it cannot do; what() is the reason as the user reads it.
class KindNotSupported : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// ---- Identity -------------------------------------------------------------------------------

constexpr ModelKind kind(const PrescribedSlipModel&) { return ModelKind::kPrescribedSlip; }
constexpr ModelKind kind(const RigModel&) { return ModelKind::kRig; }
constexpr ModelKind kind(const DrivelineModel&) { return ModelKind::kDriveline; }
ModelKind kind(const Model& model);

/// Simulated duration, s (every kind's settings hold duration_s).
double duration_s(const Model& model);

// ---- shudder run ----------------------------------------------------------------------------

/// Runs the model and returns its recording (docs/formats/run_output.md).
dynamics::Recording simulate(const PrescribedSlipModel& model, const clutch::WetClutch& clutch);
dynamics::Recording simulate(const RigModel& model, const clutch::WetClutch& clutch);
dynamics::Recording simulate(const DrivelineModel& model, const clutch::WetClutch& clutch);

/// The run's extra analysis, stored in `rec`: every kind's verdict block (run_verdict.hpp:
/// judged verdict, operating point, and the prediction there — the rig's linear stability, "not
/// predicted" for the others) and the rig's stability map (/analysis/stability_map, for
/// `shudder plot`; a record too short to judge gets a "not_judged" block with the reason).
/// Returns warnings (without the "shudder: warning: " prefix): a map that cannot be made (e.g.
/// a cycle that never loads the clutch) costs the run nothing but is said.
std::vector<std::string> add_run_analysis(const PrescribedSlipModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec);
std::vector<std::string> add_run_analysis(const RigModel& model, const clutch::WetClutch& clutch, double start_temp_C,
                                          dynamics::Recording& rec);
std::vector<std::string> add_run_analysis(const DrivelineModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec);

/// Whether the run report draws the rig's plots (spectrogram, stability map; report/plots.hpp).
constexpr bool has_rig_plots(const PrescribedSlipModel&) { return false; }
constexpr bool has_rig_plots(const RigModel&) { return true; }
constexpr bool has_rig_plots(const DrivelineModel&) { return false; }

/// `run --measurement`: what the measured run (io/measurement_csv.hpp) is written from. The rig
/// and prescribed slip: their own recording, a log of the LSCTR's sensors (rig "lsctr"); the
/// driveline: its coupling's sensors (rig "haldex_coupling", rig_models/coupling_measurement.hpp).
struct MeasuredExport {
  std::string rig;                              // the file's `rig` metadata
  std::optional<dynamics::Recording> coupling;  // the driveline's coupling channels; empty: the run's own
  const dynamics::Recording& channels(const dynamics::Recording& run) const { return coupling ? *coupling : run; }
};
MeasuredExport measured_run_export(const PrescribedSlipModel& model, const dynamics::Recording& rec);
MeasuredExport measured_run_export(const RigModel& model, const dynamics::Recording& rec);
MeasuredExport measured_run_export(const DrivelineModel& model, const dynamics::Recording& rec);

// ---- shudder sweep --------------------------------------------------------------------------

/// Whether sweeps judge this kind's cases; throws KindNotSupported if not. Checked on the
/// base scenario before any case runs.
void require_sweep(const PrescribedSlipModel& model);
void require_sweep(const RigModel& model);
void require_sweep(const DrivelineModel& model);

/// One sweep case: runs the model into `rec`, predicts and judges it (case_evaluation.hpp).
/// Throws KindNotSupported where require_sweep does.
CaseOutcome evaluate_case(const PrescribedSlipModel& model, const clutch::WetClutch& clutch, dynamics::Recording& rec);
CaseOutcome evaluate_case(const RigModel& model, const clutch::WetClutch& clutch, dynamics::Recording& rec);
CaseOutcome evaluate_case(const DrivelineModel& model, const clutch::WetClutch& clutch, dynamics::Recording& rec);

// ---- shudder diagnose -----------------------------------------------------------------------

/// The model a measured run is replayed on (rig_models/replay.hpp), without its clutch and
/// fluid, which the caller sets. `stick_time` is the scenario's [effects.stick_time_static_friction]
/// as read: a prescribed-slip model has no rig to hold it, but the candidate list must still
/// know whether that effect is on. A driveline replays its coupling alone (ReplayModel::kind kDriveline).
ReplayModel replay_model(const PrescribedSlipModel& model, const StickTimeFriction& stick_time);
ReplayModel replay_model(const RigModel& model, const StickTimeFriction& stick_time);
ReplayModel replay_model(const DrivelineModel& model, const StickTimeFriction& stick_time);

// ---- shudder modes, shudder screen --rig ----------------------------------------------------

/// What `shudder modes` analyses: a rig's torsional network (bar and housing), or a driveline
/// linearised about its manoeuvre's operating point (rig_models/driveline_stability.hpp).
/// Throws KindNotSupported for kinds without a network.
using ModalSubject = std::variant<const RigModel*, const DrivelineModel*>;
ModalSubject modal_subject(const PrescribedSlipModel& model);
ModalSubject modal_subject(const RigModel& model);
ModalSubject modal_subject(const DrivelineModel& model);

/// The rig `shudder screen --rig` screens a fluid on; throws KindNotSupported for kinds that are
/// not a rig.
const RigParams& screening_rig(const PrescribedSlipModel& model);
const RigParams& screening_rig(const RigModel& model);
const RigParams& screening_rig(const DrivelineModel& model);

// ---- shudder validate -----------------------------------------------------------------------

/// The prescribed-slip model `shudder validate` compares with the papers; throws
/// KindNotSupported for the other kinds.
const PrescribedSlipModel& validation_model(const PrescribedSlipModel& model);
const PrescribedSlipModel& validation_model(const RigModel& model);
const PrescribedSlipModel& validation_model(const DrivelineModel& model);

}  // namespace shudder::rig_models
