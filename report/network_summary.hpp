#pragma once
// The readable summary of a network run: the run's verdict naming the clutch, each clutch's
// verdict, lock-up and heat, the energy account.

#include <ostream>

#include "studies/network_run.hpp"
#include "io/network_scenario.hpp"

namespace shudder::report {

void print_network_summary(std::ostream& os, const io::NetworkScenario& scenario, const studies::NetworkRun& run);

}  // namespace shudder::report
