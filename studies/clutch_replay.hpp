#pragma once
// A network's wet clutch as the diagnosis replays it (`shudder diagnose NETWORK.toml RUN.csv
// --clutch NAME`; studies/replay.hpp): the clutch alone, its measured slip and clamp force
// imposed sample by sample (prescribed slip, the pack stepped at a tenth of the thermal step),
// with its fluid, geometry, thermal model, effects, bearing drag and stick-time friction exactly
// as the network builds them (a Haldex coupling's pack in its own oil). The run's sensors are
// ideal, as `shudder run --measurement` writes them. Runs are expected with the metadata
// `rig: network_clutch` (rig_models/rig_names.hpp) and `clutch: NAME`.

#include <string>
#include <vector>

#include "components/network_spec.hpp"
#include "studies/replay.hpp"

namespace shudder::studies {

/// The names of the network's wet clutches and Haldex couplings, in the spec's (name) order:
/// the clutches a measured run can come from.
std::vector<std::string> wet_clutch_names(const components::NetworkSpec& spec);

/// Throws NetworkError naming the clutch: not a clutch of the network (with the nearest name and
/// the list), or a plain clutch (no thermal model, nothing to diagnose).
studies::ReplayModel clutch_replay_model(const components::NetworkSpec& spec, const std::string& clutch);

}  // namespace shudder::studies
