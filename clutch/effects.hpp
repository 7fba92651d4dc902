#pragma once
// The catalogue of switchable physical effects (names fixed by FORMATS.md). A baseline model is
// a set of switches; the diagnosis names effects from this list. Where each one acts:
//   temperature_dependent_friction, load_dependent_friction, viscous_shear  -> WetClutch
//   interface_oil_cooling, sump_heating, rig_heat_capacity,
//   temperature_sensor_lag                                               -> ThermalModel
//   bearing_drag                                                         -> rig torque cell
//   stick_time_static_friction                                           -> dynamics (stick phases)

#include <array>
#include <string_view>

namespace shudder::clutch {

inline constexpr std::array<std::string_view, 9> kEffectNames = {
    "temperature_dependent_friction", "interface_oil_cooling", "sump_heating",
    "rig_heat_capacity",              "temperature_sensor_lag", "bearing_drag",
    "stick_time_static_friction",     "viscous_shear",          "load_dependent_friction",
};

}  // namespace shudder::clutch
