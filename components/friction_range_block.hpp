#pragma once
// The run-level result block "friction_data_range" (docs/formats/run_output.md): how much of the run
// used the clutch's friction law outside its data (clutch/friction_data_range.hpp), written
// under /analysis/friction_data_range and printed once in the run summary.
//
//   texts    summary   one sentence: "within the friction law's data" or which ranges were
//                      left, by how much and for what share of the run
//   scalars  fraction_outside, fraction_speed_below, fraction_speed_above,
//            fraction_temp_below, fraction_temp_above, fraction_load_below, fraction_load_above
//            (share of the run's time, 1); the law's ranges (law_*) and the extremes the run
//            reached (run_*), in mm/s, degC and N (non-finite ends: the law has no limit there)

#include "clutch/friction_data_range.hpp"
#include "dynamics/recording.hpp"

namespace shudder::components {

inline constexpr const char* kFrictionRangeBlock = "friction_data_range";

dynamics::ResultBlock friction_range_block(const clutch::FrictionDataRange& r);

}  // namespace shudder::components
