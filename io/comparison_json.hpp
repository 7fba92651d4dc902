#pragma once
// `shudder compare --json`: format "shudder-compare/1" (docs/characterisation.md). Per fluid:
// name, file, verdict, rank, breakaway ratio, the equal-viscosity temperature and every index
// there, per screening temperature every index and mu at 50 rpm, the largest stability margin;
// then the separations of neighbouring fluids in the ranking. Numbers with 10 significant
// digits, NaN as null; written through a temporary file and a rename by the caller.
#include <string>

#include "studies/fluid_comparison.hpp"

namespace shudder::io {

std::string comparison_json(const studies::Comparison& c);

}  // namespace shudder::io
