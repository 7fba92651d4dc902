#pragma once
// Runs a network (components/network_builder.hpp) and judges every clutch in it.
//
// Integration: dynamics::Simulation (dopri5, exact stick/slip events) with every wet clutch
// coupled multi-rate (rig_models/multirate_clutch.hpp: each clutch's thermal model advanced
// every thermal step with the friction heat its own contact accumulated, its ring temperatures
// on a first-order hold); the stepper restarts at every jump of an input signal. A network
// without wet clutches is integrated in one stretch between those jumps. With
// settings.integrator.fixed_step_s > 0 the same right-hand side is advanced by the fixed-step
// RK4 mode (dynamics/simulation.hpp): `shudder run --fixed-step`, the scalar `fixed_step_s` added.
//
// Recording (docs/formats/network_file.md "Output"): `time_s`, then channels named
// `<component>.<quantity>_<unit>`, e.g. `launch_clutch.slip_rpm`; summary scalars (the energy
// account; per clutch its friction work, per wet clutch its peak interface temperature); a
// verdict block per clutch (`verdict.<clutch>`: rig_models/run_verdict.hpp's block judged on that
// clutch's torque and slip) and the run's `verdict` block, the worst clutch's verdict with text
// `clutch` naming it (stick_slip over vibration over none; between equals, the larger amplitude).

// Judging: components/clutch_judgement.hpp.

#include <string>
#include <vector>

#include "components/network_spec.hpp"
#include "dynamics/recording.hpp"
#include "components/clutch_judgement.hpp"

namespace shudder::components {

struct NetworkRun {
  dynamics::Recording recording;
  std::vector<ClutchVerdict> verdicts;  // one per clutch, in the spec's order
  int worst = -1;                       // index into verdicts of the run's verdict; -1: no clutch
  double energy_imbalance_J = 0.0, energy_scale_J = 0.0;
};

/// Builds, runs and judges; throws NetworkError (bad network), std::runtime_error (numerical
/// failure).
NetworkRun run_network(const NetworkSpec& spec);

}  // namespace shudder::components
