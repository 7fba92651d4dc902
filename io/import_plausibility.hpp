#pragma once
// Does a logged column look like the unit it claims? A clutch's normal force under 200 N looks
// like kN logged as N, times a second apart over more than 1000 s look like ms logged as s, a
// disc temperature above 200 degC throughout looks like K logged as degC, and so on (the rules
// and their reasons: docs/formats/import_mapping.md). A column that fails is an InputError
// naming the file, the column, the likely unit and the option that fixes it.

#include <string>
#include <vector>

#include "io/import_mapping.hpp"
#include "io/measured_run.hpp"

namespace shudder::io {

/// `values` are the column converted to the target's own unit. `fix_option` is the `--map`
/// the user would give with the likely unit substituted; `trust_option` the option that skips
/// the check. Throws InputError(file, 0, ...) when the column looks like another unit.
void check_unit_plausible(const std::string& file, const ColumnMapping& mapping, const ImportTarget& target,
                          const ImportUnit& unit, const std::vector<double>& values);

/// The same checks on a measured run's own columns (in their own units), for the commands that
/// read one: a run written by hand with the force in kN fails here with the `shudder import`
/// command that converts it, instead of later as an implausible friction coefficient.
void check_measured_run_units(const MeasuredRun& run);

}  // namespace shudder::io
