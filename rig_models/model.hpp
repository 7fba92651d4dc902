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
// What a kind's runs are judged and studied with (the run's verdict, sweep cases, the replay a
// diagnosis fits) is declared the same way, one level up, in studies/model_studies.hpp.
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
#include "components/drive_cycle.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::rig_models {

/// Paper G's set-up: slip speed and force imposed (rig_models/prescribed_slip.hpp).
struct PrescribedSlipModel {
  components::DriveCycle cycle;
  PrescribedSlipSettings settings;  // duration, steps, sampling, snapshots, bearing drag
};

/// The LSCTR rig (rig_models/lsctr_rig.hpp) following a drive cycle.
struct RigModel {
  RigParams params;  // bearing drag and stick-time friction included
  components::DriveCycle cycle;
  RigSettings settings;
};

/// The Haldex-coupled car (rig_models/haldex_driveline.hpp) driven through a manoeuvre.
struct DrivelineModel {
  DrivelineParams params;  // stick-time friction included
  DrivelineInputs manoeuvre;
  DrivelineSettings settings;
  // The instrumented coupling's sensors: they act on its measured run only (coupling_measurement.hpp).
  components::TorqueCell torque_cell;
  components::LoadCell load_cell;
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

// ---- shudder modes, shudder screen --rig ----------------------------------------------------

/// What `shudder modes` analyses: a rig's torsional network (bar and housing), or a driveline
/// linearised about its manoeuvre's operating point (studies/driveline_stability.hpp).
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
