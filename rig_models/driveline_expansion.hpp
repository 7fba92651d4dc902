#pragma once
// A driveline scenario's car (rig_models/haldex_driveline.hpp) expanded into network components
// (components/network_spec.hpp): the same 15 bodies, shafts, gears and differentials, the four
// tyres with their turn's path ratios and road friction, the vehicle with its road load and
// grade, the engine (its throttle map or a torque schedule) with its firing pulsation, and the
// Haldex coupling with its pack, hydraulics and control unit, the manoeuvre's schedules as table
// signals, every part rolling with the start speed. It is the network the driveline kind runs
// (run_driveline: HaldexDriveline::spec, stepped by components/network_stepper.hpp;
// tests/rig_models/test_driveline_expansion.cpp holds every shipped driveline scenario's kind run
// to its network run), and what a user starts from to change the car's layout
// (docs/formats/network_file.md).
//
// Component names follow the driveline's nodes and shafts; the coupling is `haldex`, the
// engine `engine_torque` (a schedule) or `engine_map` (a throttle), the pulsation `firing`,
// the tyres `tyre_fl` … `tyre_rr`, the vehicle `vehicle`, the gears `gearbox_and_final_drive`,
// `power_take_off` and `rear_final_drive`, the differentials `front_differential` and
// `rear_differential`.

#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "components/network_spec.hpp"
#include "rig_models/haldex_driveline.hpp"

namespace shudder::rig_models {

/// Throws std::invalid_argument for what HaldexDriveline refuses.
components::NetworkSpec expand_driveline(const DrivelineParams& params, const clutch::WetClutchParams& pack,
                                         const clutch::Fluid& fluid, const DrivelineInputs& inputs,
                                         const DrivelineSettings& settings);

}  // namespace shudder::rig_models
