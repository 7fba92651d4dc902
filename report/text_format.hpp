#pragma once
// Numbers in text: one printf-style formatter for every summary, narrative and plot label.
#include <cstdio>
#include <string>

namespace shudder::report {

/// `value` formatted by a printf conversion for one double, e.g. "%.3g", "%.2f".
inline std::string number(double value, const char* printf_format = "%.3g") {
  char buf[64];
  std::snprintf(buf, sizeof buf, printf_format, value);
  return buf;
}

}  // namespace shudder::report
