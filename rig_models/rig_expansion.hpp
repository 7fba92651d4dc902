#pragma once
// A rig scenario's Limited Slip Clutch Test Rig (rig_models/lsctr_rig.hpp) expanded into network
// components (components/network_spec.hpp): the drive (motor, gearbox, coupling, shaft and
// friction disc as one inertia) with its PI speed loop, torque limit and torque ripple, the wet
// clutch clamped by the cycle's force, the separators' housing and the torsion bar to ground,
// the clutch judged on the bar as the torque cell reads it. The start is the rig's: steady
// sliding at the cycle's first speed with the bar already twisted by the friction torque and the
// speed loop's integrator holding it (the housing's start angle and the motor's start torque),
// or everything at rest. It is the network the rig kind runs (run_rig: LsctrRig::spec, stepped by
// components/network_stepper.hpp); tests/rig_models/test_rig_expansion.cpp holds every shipped
// rig scenario's kind run to its network run.
//
// Names: nodes `drive` and `housing`, `motor`, `clutch`, `torsion_bar`.

#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "components/network_spec.hpp"
#include "rig_models/lsctr_rig.hpp"

namespace shudder::rig_models {

/// Throws std::invalid_argument for what LsctrRig refuses.
components::NetworkSpec expand_rig(const RigParams& params, const clutch::WetClutchParams& clutch,
                                   const clutch::Fluid& fluid, const components::DriveCycle& cycle,
                                   const RigSettings& settings);

}  // namespace shudder::rig_models
