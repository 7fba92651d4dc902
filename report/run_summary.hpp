#pragma once
// Human-readable run summary: torque and temperatures at the drive cycle's key times, final
// temperatures, and the energy account.

#include <ostream>
#include <string_view>

#include "dynamics/recording.hpp"
#include "io/scenario.hpp"

namespace shudder::report {

/// Value of signal `name` at time t (linear interpolation), NaN if absent.
double signal_at(const dynamics::Recording& rec, std::string_view name, double t_s);

void print_run_summary(std::ostream& os, const io::Scenario& scenario,
                       const dynamics::Recording& rec);

}  // namespace shudder::report
