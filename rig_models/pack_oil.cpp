// apply_pack_oil (rig_models/haldex_driveline.hpp): a Haldex pack's own oil shared by its
// interfaces. In a file of its own so that what builds a network's Haldex coupling
// (components/network_builder.cpp) links without the driveline runner, its stability study and
// its judgement (the network FMU's library, fmu/sources.cmake, has none of them).
#include <cmath>
#include <stdexcept>

#include "rig_models/haldex_driveline.hpp"

namespace shudder::rig_models {

void apply_pack_oil(const DrivelineParams& params, int sliding_interfaces, clutch::ThermalParams& thermal) {
  if (sliding_interfaces < 1) throw std::invalid_argument("driveline: the pack needs at least one sliding interface");
  if (!std::isfinite(params.pack_oil_volume_ml) || !(params.pack_oil_volume_ml > 0) ||
      !std::isfinite(params.pack_cooling_flow_ml_min) || params.pack_cooling_flow_ml_min < 0)
    throw std::invalid_argument("driveline: pack_oil_volume_ml must be > 0 and pack_cooling_flow_ml_min >= 0");
  thermal.sump_volume_m3 = params.pack_oil_volume_ml * 1e-6 / sliding_interfaces;
  thermal.supply_flow_m3_s = params.pack_cooling_flow_ml_min * 1e-6 / 60.0 / sliding_interfaces;
}

}  // namespace shudder::rig_models
