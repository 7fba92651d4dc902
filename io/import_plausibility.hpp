#pragma once
// Does a logged column look like the unit it claims? A clutch's normal force under 200 N looks
// like kN logged as N, times a second apart over more than 1000 s look like ms logged as s, a
// disc temperature above 200 degC throughout looks like K logged as degC, and so on (the rules
// and their reasons: docs/formats/import_mapping.md). A column that fails is an InputError
// naming the file, the column, the likely unit and the option that fixes it.

#include <string>
#include <vector>

#include "io/import_mapping.hpp"

namespace shudder::io {

/// `values` are the column converted to the target's own unit. `fix_option` is the `--map`
/// the user would give with the likely unit substituted; `trust_option` the option that skips
/// the check. Throws InputError(file, 0, ...) when the column looks like another unit.
void check_unit_plausible(const std::string& file, const ColumnMapping& mapping, const ImportTarget& target,
                          const ImportUnit& unit, const std::vector<double>& values);

}  // namespace shudder::io
