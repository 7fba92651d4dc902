#pragma once
// The variables of a network scenario's FMU (docs/fmu.md "Your drivetrain as an FMU"), from
// the scenario alone, so `shudder export-fmu` (which writes modelDescription.xml) and the
// network FMU's library (which serves the variables and checks the GUID) agree by
// construction.
//
// Inputs, in this order: each clutch's (or brake's) normal_force (1), or for a Haldex coupling
// its control unit's pedal (1) and, where the scenario gives them, its raw valve_opening (as
// valve_opening_command, 1: the output valve_opening is the valve's state) or
// valve_pressure_bar (bar), in the clutches' order; each torque source's torque_Nm (N.m), each
// speed source's speed_rpm (rpm), each motor's speed_rpm set point (rpm; not for a motor with
// torque ripple, whose ripple follows the scenario's schedule), each engine's throttle (1).
// Named COMPONENT.KEY after the scenario's key; the start value is the scenario's signal at
// t = 0; while the FMU runs the master's value replaces the signal.
// Outputs: the run's recorded channels but time_s (components/network_channels.hpp), named as
// in the HDF5 run file; a torque source's torque_Nm is its input, not also an output.
// Parameter: fixed_step_s, the internal RK4 step.
// Names: each dot-separated part keeps [A-Za-z0-9_], any other character becomes '_', a part
// that starts with a digit gets a leading '_' (FMI 2.0 structured names); two variables with one
// name are an error naming both.

#include <memory>
#include <string>
#include <vector>

#include "components/network_stepper.hpp"
#include "fmu/model_description_xml.hpp"
#include "io/network_scenario.hpp"

namespace shudder::fmu {

inline constexpr const char* kNetworkModelIdentifier = "shudder_network";
/// Where the FMU's resources/ say which scenario to run (scenario = "PATH", fixed_step_s = H).
inline constexpr const char* kNetworkFmuIndex = "network_fmu.toml";

/// One input: the spec's signal it replaces (in the spec it was made from).
struct NetworkInput {
  std::string name, unit, description;
  components::Signal* signal = nullptr;
};

/// The inputs of `spec`, in the header's order.
std::vector<NetworkInput> network_inputs(components::NetworkSpec& spec);

/// FMI name of a channel or input name (header's rule).
std::string fmi_name(const std::string& name);
/// FMI unit of a channel's unit ("N m" -> "N.m").
std::string fmi_unit(const std::string& unit);

/// The FMU's description: inputs (vr 0..), outputs (vr 1000000..), the parameter fixed_step_s
/// (vr 2000000); DefaultExperiment from 0 to the scenario's duration at its sample interval.
/// `sc.spec` is copied and built to learn the channels.
DescribedModel network_description(const io::NetworkScenario& sc, double fixed_step_s);

inline constexpr unsigned kFirstOutputVr = 1000000, kFixedStepVr = 2000000;

}  // namespace shudder::fmu
