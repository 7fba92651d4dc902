#pragma once
// The energy guard: a run whose energy accounts do not close is a numerical failure, not a
// result. It reads the two relative errors the runners record (components/energy_scalars.hpp):
//
//   energy_balance_relative_error     |generated - stored - to sump - to rig| / generated
//   mechanical_energy_relative_error  |mechanical imbalance| / the model's energy scale
//
// Bounds (stated once, docs/formats/run_output.md):
//   thermal    1e-6: the implicit thermal step conserves heat to round-off; the shipped
//              scenarios reach 1.4e-14 .. 1.7e-12, so the bound leaves a factor > 5e5.
//   mechanical 1e-3: the adaptive Odeint integration (and its event location) leaves a small
//              drift; the shipped scenarios reach 1.5e-9 .. 4.4e-6, a factor > 200 inside.
// A recording without one of the scalars (a kind that keeps no such account) is not judged on
// it; a non-finite value always fails.

#include <string>

#include "dynamics/recording.hpp"

namespace shudder::components {

struct EnergyBalanceBounds {
  double thermal_relative = 1e-6;
  double mechanical_relative = 1e-3;
};

/// "" if the recording's energy accounts close within `bounds`; otherwise a one-line message
/// naming each account that does not, its figure and its bound.
std::string energy_balance_violation(const dynamics::Recording& rec, const EnergyBalanceBounds& bounds = {});

}  // namespace shudder::components
