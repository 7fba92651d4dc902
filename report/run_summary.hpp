#pragma once
// Human-readable run summary: the verdict block (what the run shows, at which operating point,
// what linear theory predicted there), min / mean / max of the main signals over each fifth of
// the run, final temperatures, and the energy account.

#include <ostream>
#include <string_view>

#include "dynamics/recording.hpp"
#include "io/scenario.hpp"

namespace shudder::report {

/// Value of signal `name` at time t (linear interpolation), NaN if absent.
double signal_at(const dynamics::Recording& rec, std::string_view name, double t_s);

/// The line said beside a stick-slip verdict (run and network summaries): linear theory about
/// steady slipping, printed next to it, cannot see stick-slip, so "stable" there is no contradiction.
inline constexpr std::string_view kStickSlipNote =
    "Note: linear theory about the slipping point cannot predict stick-slip (a nonlinear phenomenon: the clutch "
    "sticks), so a 'stable' prediction does not contradict this verdict\n";

void print_run_summary(std::ostream& os, const io::Scenario& scenario, const dynamics::Recording& rec);

}  // namespace shudder::report
