#pragma once
// Test accessors for a loaded scenario's typed model: the scenario of a test is known to be of
// one kind, and std::get throws (failing the test) if it is not.
#include <variant>

#include "io/scenario.hpp"
#include "rig_models/model.hpp"

namespace shudder::test {

inline rig_models::RigModel& rig_model(io::Scenario& sc) { return std::get<rig_models::RigModel>(sc.model); }
inline const rig_models::RigModel& rig_model(const io::Scenario& sc) {
  return std::get<rig_models::RigModel>(sc.model);
}
inline rig_models::PrescribedSlipModel& prescribed_model(io::Scenario& sc) {
  return std::get<rig_models::PrescribedSlipModel>(sc.model);
}
inline const rig_models::PrescribedSlipModel& prescribed_model(const io::Scenario& sc) {
  return std::get<rig_models::PrescribedSlipModel>(sc.model);
}

}  // namespace shudder::test
