#pragma once
// Loads a fluid file (TOML, docs/formats/fluid_file.md) into a clutch::Fluid.
//
//   [fluid]            name, optional description, nu40_cSt > nu100_cSt > 0 (cSt),
//                      optional density_kg_m3 (default 868, Paper G Table 1)
//   [static_friction]  breakaway_ratio in [0.5, 3]: mu_s = ratio * mu_k(v_min, T, F);
//                      optional source
//   [friction_radius]  optional: convention ("uniform_pressure" | "uniform_wear") and radius_mm,
//                      the radius a law fitted from torque was fitted at (written by
//                      `characterise`); a clutch model of another radius converts the law when
//                      it is built (clutch/friction_radius.hpp)
//   exactly one of
//   [maki]             Paper G eq. 13 matrix over loads_N x [[maki.row]] (temp_C, sets),
//                      v in mm/s
//   [linear]           Papers B/C/E lines mu = alpha*T + beta per speed (speeds_rpm,
//                      mean_radius_mm)
//
// Plausibility: mu must lie in (0, 1] over the law's whole declared range — every
// row and load of a [maki] matrix at speeds min_speed_mm_s..max_speed_mm_s, every line of a
// [linear] law from -40 to 150 °C — else InputError naming the key and the failing point.
//
// Strict: every table is finished, so unknown keys are errors. Every failure is an
// io::InputError naming the file, the line, the full key, what was wrong and what is allowed;
// std::invalid_argument from the clutch constructors is rethrown as InputError with the file
// and the friction table's key.

#include <string>

#include "clutch/fluid.hpp"

namespace shudder::io {

clutch::Fluid load_fluid(const std::string& path);

/// The same from the file's text (e.g. as stored in a run file); `path` names it in messages.
clutch::Fluid load_fluid_text(const std::string& text, const std::string& path);

}  // namespace shudder::io
