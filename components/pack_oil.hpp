#pragma once
// A Haldex coupling's own oil in its disc pack's thermal model. The pack is splash- and
// pump-washed from the coupling's housing, with no forced cooling circuit of its own, so each of
// the n sliding interfaces' thermal domains gets
//   sump volume  V_i = V_pack / n          [m³]
//   supply flow  Q_i = Q_pack / n          [m³/s]
// in place of the rig's own 0.5 l sump and 200 ml/min forced flow per interface. Source:
// estimate (the split is even because the interfaces of one pack see the same oil); the volume
// and flow defaults are in rig_models/haldex_driveline.hpp and docs/formats/network_file.md.

#include "clutch/thermal_model.hpp"

namespace shudder::components {

/// Sets `thermal`'s sump volume and supply flow from the pack's oil volume [ml] and cooling
/// flow [ml/min]. Throws std::invalid_argument for fewer than one interface, a volume that is not
/// positive or a flow that is negative.
void apply_pack_oil(double pack_oil_volume_ml, double pack_cooling_flow_ml_min, int sliding_interfaces,
                    clutch::ThermalParams& thermal);

}  // namespace shudder::components
