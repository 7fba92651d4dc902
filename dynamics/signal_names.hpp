#pragma once
// Names of the recorded signals (`/signals/<name>` in a run's HDF5, columns of a measured-run
// CSV): one definition, mirroring docs/formats/measured_run.md and docs/formats/run_output.md and
// docs/formats/run_output.md. The first block is the measured-run contract shared by the rig's logs and
// the simulations; the rest are channels the models add. Units are in the names.
#include <string_view>

namespace shudder::dynamics::signal_names {

// Measured-run columns (docs/formats/measured_run.md): required ...
inline constexpr std::string_view kTime = "time_s";
inline constexpr std::string_view kSpeed = "speed_rpm";  // drive speed (rig: the encoder)
inline constexpr std::string_view kNormalForce = "normal_force_N";
inline constexpr std::string_view kTorque = "torque_Nm";  // torque cell (through the bar)
inline constexpr std::string_view kTemp = "temp_C";       // the disc temperature sensor
// ... and optional.
inline constexpr std::string_view kSumpTemp = "sump_temp_C";
inline constexpr std::string_view kIrTemp = "ir_temp_C";

// Clutch and thermal channels (prescribed slip and rig).
inline constexpr std::string_view kClutchTorque = "clutch_torque_Nm";
inline constexpr std::string_view kInterfaceMeanTemp = "interface_mean_temp_C";
inline constexpr std::string_view kInterfaceMaxTemp = "interface_max_temp_C";
inline constexpr std::string_view kMaxTemp = "max_temp_C";
inline constexpr std::string_view kFrictionCoefficient = "friction_coefficient";
inline constexpr std::string_view kHeatPower = "heat_power_W";
inline constexpr std::string_view kInterfaceOilFlow = "interface_oil_flow_ml_min";
inline constexpr std::string_view kRigTemp = "rig_temp_C";

// The rig's torsional channels.
inline constexpr std::string_view kSlip = "slip_rpm";
inline constexpr std::string_view kMotorTorque = "motor_torque_Nm";
inline constexpr std::string_view kHousingSpeed = "housing_speed_rpm";
inline constexpr std::string_view kStuck = "stuck";  // 1 while the contact is stuck

// The driveline's channels.
inline constexpr std::string_view kEngineSpeed = "engine_speed_rpm";
inline constexpr std::string_view kVehicleSpeed = "vehicle_speed_km_h";
inline constexpr std::string_view kFrontWheelSpeed = "front_wheel_speed_rpm";
inline constexpr std::string_view kRearWheelSpeed = "rear_wheel_speed_rpm";
inline constexpr std::string_view kCouplingSlip = "coupling_slip_rpm";
inline constexpr std::string_view kCouplingTorque = "coupling_torque_Nm";
inline constexpr std::string_view kFrontAxleTorque = "front_axle_torque_Nm";
inline constexpr std::string_view kRearAxleTorque = "rear_axle_torque_Nm";
inline constexpr std::string_view kEngineTorque = "engine_torque_Nm";
inline constexpr std::string_view kPressure = "pressure_bar";
inline constexpr std::string_view kClampForce = "clamp_force_N";
inline constexpr std::string_view kValveOpening = "valve_opening";  // the Haldex throttle valve, 0 shut – 1 open
// The instrumented coupling's thermocouple (at the clutch's thermocouple place) and its pack oil.
inline constexpr std::string_view kCouplingTemp = "coupling_temp_C";
inline constexpr std::string_view kCouplingOilTemp = "coupling_oil_temp_C";
// Per wheel (fl, fr, rl, rr): speed and the tyre's longitudinal force.
inline constexpr std::string_view kWheelSpeedFL = "wheel_fl_speed_rpm";
inline constexpr std::string_view kWheelSpeedFR = "wheel_fr_speed_rpm";
inline constexpr std::string_view kWheelSpeedRL = "wheel_rl_speed_rpm";
inline constexpr std::string_view kWheelSpeedRR = "wheel_rr_speed_rpm";
inline constexpr std::string_view kTyreForceFL = "tyre_fl_force_N";
inline constexpr std::string_view kTyreForceFR = "tyre_fr_force_N";
inline constexpr std::string_view kTyreForceRL = "tyre_rl_force_N";
inline constexpr std::string_view kTyreForceRR = "tyre_rr_force_N";
inline constexpr std::string_view kRoadLoad = "road_load_N";

}  // namespace shudder::dynamics::signal_names
