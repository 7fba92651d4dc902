#pragma once
// The quiet NaN that marks "not available" in results, one definition for every folder (a
// file-local copy in each .cpp would clash when a library is compiled as one unity file).

#include <limits>

namespace shudder {

inline constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();

}  // namespace shudder
