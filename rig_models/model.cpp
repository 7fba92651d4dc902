#include "rig_models/model.hpp"

#include "rig_models/coupling_measurement.hpp"
#include "rig_models/rig_names.hpp"

namespace shudder::rig_models {

namespace {

// A refusal that names the kind, as the user wrote it in `type`: "\"driveline\" <rest>".
[[noreturn]] void refuse_quoting_kind(ModelKind k, const char* rest) {
  throw KindNotSupported(std::string("\"").append(model_kind_name(k)).append(rest));
}

constexpr const char* kNoNetwork = "\" has no torsional network; modes needs type = \"rig\" or \"driveline\"";
constexpr const char* kNotARig = "\" is not a rig; --rig needs a scenario with type = \"rig\"";

[[noreturn]] void refuse_validation(ModelKind k) {
  throw KindNotSupported(std::string("is ")
                             .append(model_kind_name(k))
                             .append("; validation compares prescribed_slip runs with the papers"));
}

}  // namespace

ModelKind kind(const Model& model) {
  return std::visit([](const auto& m) { return kind(m); }, model);
}

double duration_s(const Model& model) {
  return std::visit([](const auto& m) { return m.settings.duration_s; }, model);
}

// ---- Prescribed slip --------------------------------------------------------------------------

dynamics::Recording simulate(const PrescribedSlipModel& model, const clutch::WetClutch& clutch) {
  return run_prescribed_slip(clutch, model.cycle, model.settings);
}

MeasuredExport measured_run_export(const PrescribedSlipModel&, const dynamics::Recording&) {
  return {std::string(kLsctrRig), {}};
}

ModalSubject modal_subject(const PrescribedSlipModel& model) { refuse_quoting_kind(kind(model), kNoNetwork); }

const RigParams& screening_rig(const PrescribedSlipModel& model) { refuse_quoting_kind(kind(model), kNotARig); }

const PrescribedSlipModel& validation_model(const PrescribedSlipModel& model) { return model; }

// ---- Rig ------------------------------------------------------------------------------------

dynamics::Recording simulate(const RigModel& model, const clutch::WetClutch& clutch) {
  return run_rig(model.params, clutch, model.cycle, model.settings);
}

MeasuredExport measured_run_export(const RigModel&, const dynamics::Recording&) { return {std::string(kLsctrRig), {}}; }

ModalSubject modal_subject(const RigModel& model) { return &model; }

const RigParams& screening_rig(const RigModel& model) { return model.params; }

const PrescribedSlipModel& validation_model(const RigModel& model) { refuse_validation(kind(model)); }

// ---- Driveline ------------------------------------------------------------------------------

dynamics::Recording simulate(const DrivelineModel& model, const clutch::WetClutch& clutch) {
  return run_driveline(model.params, clutch, model.manoeuvre, model.settings);
}

MeasuredExport measured_run_export(const DrivelineModel& model, const dynamics::Recording& rec) {
  return {std::string(kCouplingRig), coupling_measurement(rec, model.torque_cell, model.load_cell)};
}

ModalSubject modal_subject(const DrivelineModel& model) { return &model; }

const RigParams& screening_rig(const DrivelineModel& model) { refuse_quoting_kind(kind(model), kNotARig); }

const PrescribedSlipModel& validation_model(const DrivelineModel& model) { refuse_validation(kind(model)); }

}  // namespace shudder::rig_models
