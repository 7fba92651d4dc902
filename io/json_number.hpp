#pragma once
// A number as the JSON writers print it: 10 significant digits; null for NaN and infinities
// (JSON has neither), so a reader can tell "not available" from 0.

#include <cmath>
#include <cstdio>
#include <string>

namespace shudder::io {

inline std::string json_number(double x) {
  if (!std::isfinite(x)) return "null";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.10g", x);
  return buf;
}

}  // namespace shudder::io
