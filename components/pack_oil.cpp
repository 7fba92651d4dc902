#include "components/pack_oil.hpp"

#include <cmath>
#include <stdexcept>

namespace shudder::components {

void apply_pack_oil(double pack_oil_volume_ml, double pack_cooling_flow_ml_min, int sliding_interfaces,
                    clutch::ThermalParams& thermal) {
  if (sliding_interfaces < 1) throw std::invalid_argument("driveline: the pack needs at least one sliding interface");
  if (!std::isfinite(pack_oil_volume_ml) || !(pack_oil_volume_ml > 0) || !std::isfinite(pack_cooling_flow_ml_min) ||
      pack_cooling_flow_ml_min < 0)
    throw std::invalid_argument("driveline: pack_oil_volume_ml must be > 0 and pack_cooling_flow_ml_min >= 0");
  thermal.sump_volume_m3 = pack_oil_volume_ml * 1e-6 / sliding_interfaces;
  thermal.supply_flow_m3_s = pack_cooling_flow_ml_min * 1e-6 / 60.0 / sliding_interfaces;
}

}  // namespace shudder::components
