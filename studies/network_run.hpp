#pragma once
// A network scenario's run and its judgement: components/network_run.hpp's recording, then every
// clutch judged on its loaded window (studies/clutch_judgement.hpp) with the linear prediction
// there (studies/clutch_prediction.hpp).
//
// Blocks added: a verdict block per clutch (`verdict.<clutch>`: studies/run_verdict.hpp's block
// judged on that clutch's torque and slip) and the run's `verdict` block, the worst clutch's
// verdict with text `clutch` naming it (stick_slip over vibration over none; between equals, the
// larger amplitude); in each judged wet clutch's blocks the share of the run its friction law
// was used outside its data (`outside_data_fraction`: a verdict reached there is an
// extrapolation of the law).

#include <vector>

#include "components/network_spec.hpp"
#include "dynamics/recording.hpp"
#include "studies/clutch_judgement.hpp"

namespace shudder::studies {

struct NetworkRun {
  dynamics::Recording recording;
  std::vector<ClutchVerdict> verdicts;  // one per clutch, in the spec's order
  int worst = -1;                       // index into verdicts of the run's verdict; -1: no clutch
  double energy_imbalance_J = 0.0, energy_scale_J = 0.0;
};

/// Builds, runs and judges; throws components::NetworkError (bad network), std::runtime_error
/// (numerical failure).
NetworkRun run_network(const components::NetworkSpec& spec);

}  // namespace shudder::studies
