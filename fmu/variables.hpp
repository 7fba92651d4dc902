#pragma once
// The FMU's variables (docs/fmu.md): one table from which fmu/model_description.cpp writes
// modelDescription.xml and fmu/clutch_fmu.cpp serves fmi2Get*/fmi2Set*, so the two cannot
// disagree (tests/fmu/ checks the XML against this table).
//
// Inputs are continuous and held over each fixed step (zero-order hold); outputs are the
// values over the last fixed step (torque, heat) or the latched thermal result (temperatures,
// rig_models/realtime_coupling.hpp). Parameters are fixed: set before or during initialisation.
// Names and units follow the scenario format's keys (docs/formats/scenario_file.md) where one exists.

#include <string_view>

#include "fmu/fmi2_instance.hpp"

namespace shudder::fmu {

struct Variable {
  unsigned vr;
  std::string_view name;
  Type type;
  Causality causality;
  std::string_view unit;        // "" for none
  double start;                 // Real/Integer/Boolean start (unused for outputs and strings)
  std::string_view start_text;  // String start
  std::string_view description;
};

inline constexpr std::string_view kModelIdentifier = "shudder_clutch";
inline constexpr std::string_view kModelName = "shudder wet clutch (prescribed slip)";
// The GUID is derived from modelDescription.xml's text at build time (fmu/content_guid.hpp).

// DefaultExperiment: the internal step, and a stop time of a few seconds of clutch engagement.
inline constexpr double kDefaultStepSize_s = 1e-4;
inline constexpr double kDefaultStopTime_s = 10.0;

namespace vr {
inline constexpr unsigned kSpeedA = 0, kSpeedB = 1, kClampForce = 2, kApplyPressure = 3;
inline constexpr unsigned kTorque = 10, kClutchTorque = 11, kSlip = 12, kHeat = 13, kInterfaceMean = 14,
                          kInterfaceMax = 15, kThermocouple = 16, kIr = 17, kSump = 18;
inline constexpr unsigned kInnerRadius = 100, kOuterRadius = 101, kStartTemp = 102, kSumpStartTemp = 103,
                          kSupplyFlow = 104, kPistonArea = 105, kFixedStep = 106, kThermalStep = 107,
                          kBearingDragMu = 108, kBearingDragRadius = 109;
inline constexpr unsigned kSlidingInterfaces = 120, kRadialCells = 121;
inline constexpr unsigned kTemperatureDependentFriction = 130, kLoadDependentFriction = 131, kViscousShear = 132,
                          kInterfaceOilCooling = 133, kSumpHeating = 134, kBearingDrag = 135;
inline constexpr unsigned kFluidFile = 140;
}  // namespace vr

using enum Type;
using enum Causality;
inline constexpr Variable kVariables[] = {
    {vr::kSpeedA, "speed_a_rad_s", kReal, kInput, "rad/s", 0.0, "", "speed of shaft a (friction discs)"},
    {vr::kSpeedB, "speed_b_rad_s", kReal, kInput, "rad/s", 0.0, "", "speed of shaft b (separator discs); slip = a - b"},
    {vr::kClampForce, "clamp_force_N", kReal, kInput, "N", 0.0, "", "clamp force on the pack"},
    {vr::kApplyPressure, "apply_pressure_Pa", kReal, kInput, "Pa", 0.0, "",
     "apply pressure on the piston; adds pressure * piston_area_m2 to the clamp force"},
    {vr::kTorque, "torque_Nm", kReal, kOutput, "N.m", 0.0, "",
     "torque transmitted from shaft a to shaft b, bearing drag included; sign of the slip"},
    {vr::kClutchTorque, "clutch_torque_Nm", kReal, kOutput, "N.m", 0.0, "", "friction torque of the discs alone"},
    {vr::kSlip, "slip_speed_rad_s", kReal, kOutput, "rad/s", 0.0, "", "slip speed a - b over the last step"},
    {vr::kHeat, "heat_power_W", kReal, kOutput, "W", 0.0, "", "friction heat power of all interfaces"},
    {vr::kInterfaceMean, "interface_mean_temp_C", kReal, kOutput, "degC", 0.0, "",
     "area-weighted mean interface (film) temperature"},
    {vr::kInterfaceMax, "interface_max_temp_C", kReal, kOutput, "degC", 0.0, "",
     "hottest ring's interface temperature"},
    {vr::kThermocouple, "thermocouple_temp_C", kReal, kOutput, "degC", 0.0, "",
     "separator thermocouple (Paper G: r = 48 mm, 0.5 mm from the back face)"},
    {vr::kIr, "ir_temp_C", kReal, kOutput, "degC", 0.0, "", "IR pyrometer spot on the interface"},
    {vr::kSump, "sump_temp_C", kReal, kOutput, "degC", 0.0, "", "sump oil temperature"},
    {vr::kInnerRadius, "inner_radius_mm", kReal, kParameter, "mm", 38.1, "", "inner radius of the friction annulus"},
    {vr::kOuterRadius, "outer_radius_mm", kReal, kParameter, "mm", 56.4, "", "outer radius of the friction annulus"},
    {vr::kStartTemp, "start_temp_C", kReal, kParameter, "degC", 20.0, "", "disc temperature at the start"},
    {vr::kSumpStartTemp, "sump_start_temp_C", kReal, kParameter, "degC", 20.0, "", "sump temperature at the start"},
    {vr::kSupplyFlow, "supply_flow_ml_min", kReal, kParameter, "ml/min", 200.0, "", "oil supply flow to the pack"},
    {vr::kPistonArea, "piston_area_m2", kReal, kParameter, "m2", 0.0, "",
     "piston area converting apply_pressure_Pa to clamp force (0: the pressure input is unused)"},
    {vr::kFixedStep, "fixed_step_s", kReal, kParameter, "s", 1e-4, "",
     "internal fixed step; a communication step that is not a whole multiple ends with one shorter step"},
    {vr::kThermalStep, "thermal_step_s", kReal, kParameter, "s", 0.01, "",
     "thermal update interval, a whole multiple of fixed_step_s"},
    {vr::kBearingDragMu, "bearing_drag_mu", kReal, kParameter, "1", 0.005, "", "bearing_drag effect: equivalent mu"},
    {vr::kBearingDragRadius, "bearing_drag_radius_mm", kReal, kParameter, "mm", 47.25, "",
     "bearing_drag effect: radius"},
    {vr::kSlidingInterfaces, "sliding_interfaces", kInteger, kParameter, "", 1.0, "", "number of sliding interfaces"},
    {vr::kRadialCells, "radial_cells", kInteger, kParameter, "", 20.0, "", "radial rings of the thermal grid"},
    {vr::kTemperatureDependentFriction, "temperature_dependent_friction", kBoolean, kParameter, "", 1.0, "",
     "effect: friction follows the interface temperature"},
    {vr::kLoadDependentFriction, "load_dependent_friction", kBoolean, kParameter, "", 1.0, "",
     "effect: friction follows the clamp force"},
    {vr::kViscousShear, "viscous_shear", kBoolean, kParameter, "", 0.0, "", "effect: Couette torque of the oil film"},
    {vr::kInterfaceOilCooling, "interface_oil_cooling", kBoolean, kParameter, "", 1.0, "",
     "effect: oil through the interface carries heat away"},
    {vr::kSumpHeating, "sump_heating", kBoolean, kParameter, "", 1.0, "", "effect: the sump warms"},
    {vr::kBearingDrag, "bearing_drag", kBoolean, kParameter, "", 0.0, "", "effect: the torque includes bearing drag"},
    {vr::kFluidFile, "fluid_file", kString, kParameter, "", 0.0, "fluids/lsc_fluid_c.toml",
     "fluid TOML (docs/formats/fluid_file.md); relative paths are resolved in the FMU's resources/"},
};

}  // namespace shudder::fmu
