#pragma once
// Linear stability of a network about one clutch's judged window (the prediction beside the
// judged verdict, studies/run_verdict.hpp): dynamics::linearise_network about the window's mean
// motion — node speeds and force-element states averaged over the run's snapshots inside the
// window, this clutch slipping at its mean slip, every other contact stuck or slipping as it was
// in most of those snapshots — with each slipping contact's friction slope as a damper
// (docs/physics.md §6: a falling friction curve is negative damping). A wet clutch's slope is taken
// with every ring at the window's mean interface temperature (as the rig's prediction,
// studies/run_verdict.hpp) at the window's middle time (its clamp force there).
//   margin              largest real part of the eigenvalues, 1/s (> 0: unstable)
//   oscillatory margin  the largest real part among oscillatory modes, and that mode's frequency
// Rigid-body zeros (a free driveline's rotation) are left out (dynamics/linearisation.hpp).

#include <vector>

#include "components/network_builder.hpp"
#include "dynamics/simulation.hpp"
#include "studies/run_verdict.hpp"

namespace shudder::studies {

/// The prediction for clutch `clutch` (index into built.clutches) over `window`, from the run's
/// `snapshots` (samples with element states, ascending in time). Prediction::none with the reason
/// where it cannot be made (no snapshot in the window, an unloaded clutch).
studies::Prediction predict_clutch(components::BuiltNetwork& built, std::size_t clutch,
                                   const studies::OperatingWindow& window,
                                   const std::vector<dynamics::Sample>& snapshots);

}  // namespace shudder::studies
