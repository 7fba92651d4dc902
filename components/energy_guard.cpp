#include "components/energy_guard.hpp"

#include <cmath>
#include <cstdio>

namespace shudder::components {

std::string energy_balance_violation(const dynamics::Recording& rec, const EnergyBalanceBounds& bounds) {
  std::string out;
  const auto check = [&](const char* scalar, const char* account, double bound) {
    const dynamics::Scalar* s = rec.find_scalar(scalar);
    // !(x <= bound) also catches NaN.
    if (!s || (std::isfinite(s->value) && s->value <= bound)) return;
    char line[256];
    std::snprintf(line, sizeof line, "%s%s energy balance error %.3g (relative, %s) exceeds the bound %.0e",
                  out.empty() ? "" : "; ", account, s->value, scalar, bound);
    out += line;
  };
  check("energy_balance_relative_error", "thermal", bounds.thermal_relative);
  check("mechanical_energy_relative_error", "mechanical", bounds.mechanical_relative);
  return out;
}

}  // namespace shudder::components
