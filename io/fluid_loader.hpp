#pragma once
// Loads a fluid file (TOML, docs/fluid_format.md) into a clutch::Fluid.
//
//   [fluid]            name, optional description, nu40_cSt > nu100_cSt > 0 (cSt),
//                      optional density_kg_m3 (default 868, Paper G Table 1)
//   [static_friction]  breakaway_ratio in [0.5, 3]: mu_s = ratio * mu_k(v_min, T, F);
//                      optional source
//   exactly one of
//   [maki]             Paper G eq. 13 matrix over loads_N x [[maki.row]] (temp_C, sets),
//                      v in mm/s
//   [linear]           Papers B/C/E lines mu = alpha*T + beta per speed (speeds_rpm,
//                      mean_radius_mm)
//
// Strict: every table is finished, so unknown keys are errors. Every failure is an
// io::InputError naming the file, the line, the full key, what was wrong and what is allowed;
// std::invalid_argument from the clutch constructors is rethrown as InputError with the file
// and the friction table's key.

#include <string>

#include "clutch/fluid.hpp"

namespace shudder::io {

clutch::Fluid load_fluid(const std::string& path);

}  // namespace shudder::io
