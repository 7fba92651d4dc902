#pragma once
// Runs a network (components/network_builder.hpp) to the scenario's duration and records it;
// judging its clutches is a study of the run (studies/network_run.hpp).
//
// Integration: dynamics::Simulation (dopri5, exact stick/slip events) with every wet clutch
// coupled multi-rate (components/multirate_clutch.hpp: each clutch's thermal model advanced
// every thermal step with the friction heat its own contact accumulated, its ring temperatures
// on a first-order hold); the stepper restarts at every jump of an input signal. A network
// without wet clutches is integrated in one stretch between those jumps. With
// settings.integrator.fixed_step_s > 0 the same right-hand side is advanced by the fixed-step
// RK4 mode (dynamics/simulation.hpp): `shudder run --fixed-step`, the scalar `fixed_step_s` added.
//
// Recording (docs/formats/network_file.md "Output"): `time_s`, then channels named
// `<component>.<quantity>_<unit>`, e.g. `launch_clutch.slip_rpm`; summary scalars (the energy
// account; per clutch its friction work, per wet clutch its peak interface temperature and heat
// account); per wet clutch its friction data range block `friction_data_range.CLUTCH`.

#include <memory>
#include <vector>

#include "components/network_spec.hpp"
#include "components/network_stepper.hpp"
#include "dynamics/recording.hpp"

namespace shudder::components {

struct NetworkSimulation {
  dynamics::Recording recording;
  /// The network as the run left it (its clutches' held inputs, its control units' commands):
  /// what a linearisation about the run's states takes.
  std::unique_ptr<NetworkStepper> stepper;
  /// The run's states every 5 ms (or every sample, if sparser), ascending in time.
  std::vector<dynamics::Sample> snapshots;
  double energy_imbalance_J = 0.0, energy_scale_J = 0.0;
};

/// Builds and runs `spec` (which must outlive the result); throws NetworkError (bad network),
/// std::runtime_error (numerical failure).
NetworkSimulation simulate_network(const NetworkSpec& spec);

}  // namespace shudder::components
