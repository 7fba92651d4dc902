#pragma once
// `shudder diagnose --write-model FIXED.toml`: the baseline scenario with the effects the
// diagnosis named switched on at their fitted parameters ("adds it to the model"). The file is
// the baseline's TOML with `[effects.NAME]` tables set (enabled = true and the fitted keys, in
// the effect's key units, full precision); its fluid path is rewritten relative to where the
// file is written, so `shudder run FIXED.toml` runs from anywhere.

#include <string>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "io/network_scenario.hpp"
#include "io/scenario.hpp"

namespace shudder::io {

/// The fixed scenario's text, for a file at `out_path`. InputError if the baseline text does
/// not parse (it was loaded, so it does).
std::string fixed_model_text(const Scenario& baseline, const std::vector<analysis::FittedEffect>& effects,
                             const std::string& out_path);

/// Writes fixed_model_text() atomically (io/atomic_file.hpp); InputError naming the path if it
/// cannot be written.
void write_fixed_model(const Scenario& baseline, const std::vector<analysis::FittedEffect>& effects,
                       const std::string& out_path);

/// The same for one clutch of a network scenario: its `[network.CLUTCH.effects.NAME]` tables set,
/// and every wet clutch's fluid path rewritten relative to `out_path`.
std::string fixed_network_text(const NetworkScenario& baseline, const std::string& clutch,
                               const std::vector<analysis::FittedEffect>& effects, const std::string& out_path);
void write_fixed_network(const NetworkScenario& baseline, const std::string& clutch,
                         const std::vector<analysis::FittedEffect>& effects, const std::string& out_path);

}  // namespace shudder::io
