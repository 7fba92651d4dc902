#pragma once
// The closed set of model kinds a scenario can describe. The scenario loader turns the file's
// `type` string into a typed model (io/scenario.hpp); everything else uses this enum or the
// model variant, never the string. The effect registry says per kind where an effect acts.
#include <array>
#include <string_view>

namespace shudder {

enum class ModelKind { kPrescribedSlip, kRig, kDriveline };

inline constexpr std::array<ModelKind, 3> kModelKinds = {ModelKind::kPrescribedSlip, ModelKind::kRig,
                                                         ModelKind::kDriveline};

/// The scenario file's `type` value of a kind (docs/formats/scenario_file.md).
constexpr std::string_view model_kind_name(ModelKind kind) {
  switch (kind) {
    case ModelKind::kPrescribedSlip: return "prescribed_slip";
    case ModelKind::kRig: return "rig";
    case ModelKind::kDriveline: return "driveline";
  }
  return "?";
}

}  // namespace shudder
