#include "studies/clutch_replay.hpp"

#include "components/network_builder.hpp"
#include "core/nearest_name.hpp"
#include "rig_models/rig_names.hpp"

namespace shudder::studies {

std::vector<std::string> wet_clutch_names(const components::NetworkSpec& spec) {
  std::vector<std::string> names;
  for (const auto& c : spec.clutches)
    if (c.law != components::ClutchSpec::Law::kPlain) names.push_back(c.name);
  return names;
}

studies::ReplayModel clutch_replay_model(const components::NetworkSpec& spec, const std::string& name) {
  const std::vector<std::string> wet = wet_clutch_names(spec);
  std::string list;
  for (const auto& n : wet) list += (list.empty() ? "" : ", ") + n;
  const components::ClutchSpec* found = nullptr;
  for (const auto& c : spec.clutches)
    if (c.name == name) found = &c;
  if (!found) {
    const std::string near = nearest_key(name, wet);
    throw components::NetworkError(name, "is no clutch of the network" +
                                             (near.empty() ? "" : "; did you mean '" + near + "'?") +
                                             " (wet clutches: " + (list.empty() ? "none" : list) + ")");
  }
  if (found->law == components::ClutchSpec::Law::kPlain)
    throw components::NetworkError(
        name, "is a plain clutch: it has no thermal model or fluid to diagnose; name a wet clutch (" +
                  (list.empty() ? "the network has none" : list) + ")");
  studies::ReplayModel m;
  m.kind = ModelKind::kPrescribedSlip;
  m.inputs_as_measured = true;
  m.rig = std::string(rig_models::kNetworkClutchRig);
  try {
    m.clutch = components::pack_params(*found);
  } catch (const std::invalid_argument& e) {
    throw components::NetworkError(name, e.what());
  }
  m.fluid = found->wet.fluid;
  m.settings.thermal_step_s = spec.settings.thermal_step_s;
  m.settings.sample_rate_Hz = spec.settings.sample_rate_Hz;
  m.settings.duration_s = spec.settings.duration_s;
  m.settings.bearing_drag = found->wet.bearing_drag;
  m.rig_params.stick_time = found->wet.stick_time;
  return m;
}

}  // namespace shudder::studies
