#include "rig_models/driveline_expansion.hpp"

namespace shudder::rig_models {

components::NetworkSpec expand_driveline(const DrivelineParams& p, const clutch::WetClutchParams& pack,
                                         const clutch::Fluid& fluid, const DrivelineInputs& in,
                                         const DrivelineSettings& cfg) {
  const clutch::WetClutch clutch(pack, fluid);
  return HaldexDriveline(p, clutch, in).spec(cfg);  // validates, and gives the turn's geometry
}

}  // namespace shudder::rig_models
