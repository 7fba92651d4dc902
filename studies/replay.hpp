#pragma once
// Replaying measured runs on a model (the diagnosis' simulator, analysis/diagnosis.hpp).
//
// A ReplayModel is a scenario without its drive cycle: the clutch, fluid, rig and solver
// settings, and the effect switches. replay() drives it with a measured run's inputs:
//   * speed_rpm and normal_force_N, averaged over consecutive windows of input_window_s
//     (0.05 s: removes the sensors' noise and, on the rig, the encoder's vibration, while a
//     ramp's kink is rounded over only 0.05 s) and joined piecewise linearly at the window
//     centres. On the rig the speed is the loop's set point, recovered from the drive speed and
//     torque cell by inverting the loop (studies/speed_setpoint.hpp): under a rising
//     load, and in stick-slip, the drive lags its set point.
//   * a driveline's coupling (ReplayModel::kind kDriveline): slip and clamp force imposed as
//     measured, sample by sample (both continuous: the driveline integrates its hydraulics with
//     the motion), and the pack stepped at a tenth of the thermal step (docs/driveline.md).
//   * start temperatures: discs and inner boundary at the mean temp_C of the first 0.1 s (at
//     least 5 samples); sump at the mean sump_temp_C there when measured, else the same. With
//     `thermocouple_offset` on, the discs start at the sump's mean instead (the offset shows
//     as the thermocouple's gap to the oil at rest), or without a sump channel at the mean
//     temp_C less the offset (then the offset is seen only through the temperature
//     dependence of friction and heat flow: weakly; docs/effects.md).
//   * metadata: oil_flow_ml_min sets the supply flow; temp_sensor "… r_mm=R z_mm=Z" places
//     the thermocouple.
// The model's own recording rate is kept and its torque_Nm and temp_C are interpolated
// linearly to the measured times, as `shudder run --measurement` resamples its recording.
//
// The effects the diagnosis can add, their fitted parameters, bounds and starting guesses come
// from the effect registry (rig_models/effect_registry.hpp).

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "core/model_kind.hpp"
#include "rig_models/effect_registry.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"
#include "rig_models/rig_names.hpp"

namespace shudder::studies {

struct ReplayModel {
  // What the measured runs come from: kPrescribedSlip (slip imposed on the clutch), kRig (the
  // LSCTR rig), or kDriveline: a driveline's Haldex coupling replayed alone, the measured slip
  // and clamp force imposed on its pack (prescribed slip; rig_models/coupling_measurement.hpp
  // has the run's columns); its candidates are the effects that act in a driveline and in the
  // replay.
  ModelKind kind = ModelKind::kPrescribedSlip;
  clutch::WetClutchParams clutch;
  clutch::Fluid fluid;
  rig_models::PrescribedSlipSettings settings;  // solver steps, sampling; bearing drag for both models
  rig_models::RigParams rig_params;             // used when kind is kRig
  // A clutch inside a machine (a driveline's coupling, a network's wet clutch): its slip and
  // clamp force follow the machine's motion and are recorded finely, so they are imposed sample
  // by sample with the pack stepped at a tenth of the thermal step, not as window means.
  bool inputs_as_measured = false;
  // The `rig` metadata of the runs this model replays (a run from another rig is warned about).
  std::string rig{rig_models::kLsctrRig};
};

struct ReplayInputs {
  std::vector<double> time_s, speed_rpm, normal_force_N, temp_C;
  std::vector<double> torque_Nm;    // the rig's set-point estimate needs it (empty: set point = speed)
  std::vector<double> sump_temp_C;  // empty when not measured
  std::optional<double> oil_flow_ml_min, thermocouple_r_mm, thermocouple_z_mm;
  double input_window_s = 0.05;
};

struct ReplayOutput {
  std::vector<double> torque_Nm, temp_C, sump_temp_C, ir_temp_C;  // at ReplayInputs::time_s
  std::vector<double> speed_rpm;              // the model's drive speed (prescribed slip: the imposed one)
  std::vector<double> interface_mean_temp_C;  // area-mean interface temperature (no sensor can read it)
};

/// Throws std::invalid_argument if the model cannot be built or run on these inputs.
ReplayOutput replay(const ReplayModel& model, const ReplayInputs& inputs);

/// Parses "r_mm=48 z_mm=0.5" out of a temp_sensor metadata value (either may be absent).
void parse_temp_sensor(const std::string& value, ReplayInputs& inputs);

/// The structs a model's effects write into (rig_models/effect_registry.hpp).
rig_models::EffectTarget effect_target(ReplayModel& model);
rig_models::ConstEffectTarget effect_target(const ReplayModel& model);

/// Whether the registry effect `name` is on; std::invalid_argument listing the valid names.
bool effect_enabled(const ReplayModel& model, std::string_view name);
/// Switches the effect on with values (in its keys' units) of its fitted parameters, in
/// registry order; std::invalid_argument for an unknown name or a wrong number of values.
void enable_effect(ReplayModel& model, std::string_view name, const std::vector<double>& values);

/// The diagnosis' simulator: run k replays inputs[k] on `model` plus the added effects.
analysis::Simulator replay_simulator(ReplayModel model, std::vector<ReplayInputs> inputs);

/// The diagnosis' reproduction check: run k's inputs (flow, thermocouple place, windows) with
/// the pseudo-run's signals in place of the measured ones, replayed on the baseline `model`.
analysis::Reproducer replay_reproducer(ReplayModel model, std::vector<ReplayInputs> inputs);

/// Every registry effect the model has off, as a diagnosis candidate. Effects inert in this
/// model's kind (stick-time friction with imposed slip; for a driveline's coupling, also those
/// inert in a driveline) are left out, with a note in `skipped`.
std::vector<analysis::EffectCandidate> replay_candidates(const ReplayModel& model, std::vector<std::string>* skipped);

}  // namespace shudder::studies
