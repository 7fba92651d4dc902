#pragma once
// Output of `shudder characterise` (docs/characterisation.md):
//   * the fluid file (docs/formats/fluid_file.md): [fluid] identity and viscosity, [static_friction],
//     and the fitted law as [maki], [linear] or [table]; the header says how it was made
//     (runs, radius rule, compensation), so the file documents its own provenance;
//   * FIT.json, format "shudder-characterisation/1": settings, data ranges, ramps used and
//     rejected (with the reason), per row the fit's RMS and max residual, the Mäki parameters
//     and their standard errors, up/down agreement before and after compensation.
// Hand-written JSON as the other writers (io::json_string; numbers with 10 significant
// digits; NaN/inf as null). Both are written through a temporary file and a rename.

#include <string>
#include <vector>

#include "analysis/breakaway.hpp"
#include "analysis/friction_characterisation.hpp"
#include "studies/inverse_characterisation.hpp"

namespace shudder::io {

struct FluidIdentity {
  std::string name;
  std::string description;
  double nu40_cSt = 0.0, nu100_cSt = 0.0;
  double density_kg_m3 = 868.0;
  double breakaway_ratio = 1.0;
  std::string breakaway_source;
};

/// The fluid file's text. `runs` are the input file names, recorded in the header.
std::string characterised_fluid_toml(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                     const FluidIdentity& fluid, const std::vector<std::string>& runs);

/// FIT.json's text.
std::string characterisation_json(const analysis::Characterisation& c, const analysis::CharacterisationSettings& s,
                                  const std::vector<std::string>& runs, const std::string& fluid_path);

/// FIT.json of `--method inverse`: the document above for the inverse fit, plus "method":
/// "inverse", "temperature": "model_interface_mean" and "methods": both methods side by side — per row the
/// RMS and max residual and the parameters (Mäki sets or node mu), the replayed torque's RMS
/// misfit with each method's law, the thermal calibration (oil flow before/after, temperature
/// RMS) and the iteration count. `s` are the sensor method's settings.
std::string characterisation_json(const studies::InverseCharacterisation& r,
                                  const analysis::CharacterisationSettings& s, const std::vector<std::string>& runs,
                                  const std::string& fluid_path);

/// FIT.json `doc` (either form above) with a "breakaway" object appended: the ratio written, its
/// source, and each start from rest (run index from 0, peak time, speed, temperature, load, peak mu,
/// kinetic mu, ratio); "measured" false and "not_measured" with the reason when none was found.
std::string with_breakaway_json(std::string doc, const analysis::BreakawayMeasurement& m, double written_ratio,
                                const std::string& source);

}  // namespace shudder::io
