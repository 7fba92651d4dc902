#pragma once
// A measured vehicle run of the Haldex coupling: what an instrumented coupling in a car gives,
// in the measured-run format (docs/formats/measured_run.md, io/measured_run.hpp), so that
// `shudder diagnose` can replay it through the coupling alone (studies/replay.hpp).
//
// The columns keep the format's meaning, read at the coupling instead of the rig's disc:
//   speed_rpm       the pack's slip, input half (propeller-shaft side) minus output half (rear
//                   differential side): two shaft encoders, or one encoder on each side, rpm
//   normal_force_N  the clamp force on the pack, F = A p from the piston pressure sensor, N
//   torque_Nm       the torque through the pack (a torque-instrumented output flange), N m
//   temp_C          a thermocouple in a separator plate, at the clutch's thermocouple place
//                   (the `temp_sensor` metadata, as on the rig), °C
//   sump_temp_C     the coupling's own oil (the pack's sump), °C
// and the metadata `rig: haldex_coupling` (kCouplingRig). The sensors' calibration faults act
// here, as on the rig's cells: the recorded torque is g·T + T0 (`torque_sensor_gain`,
// `torque_sensor_offset`) and the recorded clamp force g_F·F (`load_sensor_gain`, a
// pressure sensor's gain); the driveline's own recording keeps the true values.
//
// Source: the instrumentation is an estimate of a test car (a Gen I coupling has a pressure
// tap and an oil temperature sensor; torque flanges and plate thermocouples are what a
// development vehicle adds). Units as docs/formats/measured_run.md.

#include "dynamics/recording.hpp"
#include "rig_models/prescribed_slip.hpp"
#include "rig_models/rig_names.hpp"

namespace shudder::rig_models {

/// The measured-run channels of a driveline recording (rig_models/haldex_driveline.hpp), named
/// as the format's columns (file comment), with the sensors' faults applied. Throws
/// std::invalid_argument if the recording lacks one of the coupling's channels.
dynamics::Recording coupling_measurement(const dynamics::Recording& driveline,
                                         const components::TorqueCell& torque_cell,
                                         const components::LoadCell& load_cell);

}  // namespace shudder::rig_models
