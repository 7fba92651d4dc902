#include "rig_models/model.hpp"

#include "core/overloaded.hpp"

namespace shudder::rig_models {

ModelKind kind(const Model& model) {
  return std::visit(overloaded{[](const PrescribedSlipModel& m) { return kind(m); },
                               [](const RigModel& m) { return kind(m); },
                               [](const DrivelineModel& m) { return kind(m); }},
                    model);
}

double duration_s(const Model& model) {
  return std::visit(overloaded{[](const PrescribedSlipModel& m) { return m.settings.duration_s; },
                               [](const RigModel& m) { return m.settings.duration_s; },
                               [](const DrivelineModel& m) { return m.settings.duration_s; }},
                    model);
}

dynamics::Recording simulate(const PrescribedSlipModel& model, const clutch::WetClutch& clutch) {
  return run_prescribed_slip(clutch, model.cycle, model.settings);
}

dynamics::Recording simulate(const RigModel& model, const clutch::WetClutch& clutch) {
  return run_rig(model.params, clutch, model.cycle, model.settings);
}

dynamics::Recording simulate(const DrivelineModel& model, const clutch::WetClutch& clutch) {
  return run_driveline(model.params, clutch, model.manoeuvre, model.settings);
}

CaseOutcome evaluate_case(const PrescribedSlipModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec) {
  return evaluate_prescribed_case(clutch, model.cycle, model.settings, rec);
}

CaseOutcome evaluate_case(const RigModel& model, const clutch::WetClutch& clutch, dynamics::Recording& rec) {
  return evaluate_rig_case(model.params, clutch, model.cycle, model.settings, rec);
}

}  // namespace shudder::rig_models
