#include "rig_models/rig_expansion.hpp"

namespace shudder::rig_models {

components::NetworkSpec expand_rig(const RigParams& p, const clutch::WetClutchParams& pack, const clutch::Fluid& fluid,
                                   const components::DriveCycle& cycle, const RigSettings& cfg) {
  const clutch::WetClutch clutch(pack, fluid);
  return LsctrRig(p, clutch, cycle).spec(cfg);  // validates; derives the bar and the loop gains
}

}  // namespace shudder::rig_models
