// Plausibility of a logged column's unit (see import_plausibility.hpp). Each rule compares the
// column, converted to the target's unit, with what a wet-clutch rig can produce; the limits sit
// a factor of 10 or more away from the thesis rig's range (loads 5-30 kN, torques up to 500 N m,
// temperatures 20-200 degC, sampling 10 Hz-10 kHz), so a correct file does not trip them.
#include "io/import_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "io/input_error.hpp"

namespace shudder::io {

namespace import_plausibility_impl {

std::string g4(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", v);
  return buf;
}

double median_step(const std::vector<double>& t) {
  std::vector<double> d;
  d.reserve(t.size());
  for (std::size_t i = 1; i < t.size(); ++i) d.push_back(t[i] - t[i - 1]);
  if (d.empty()) return 0.0;
  std::nth_element(d.begin(), d.begin() + static_cast<std::ptrdiff_t>(d.size() / 2), d.end());
  return d[d.size() / 2];
}

double max_abs(const std::vector<double>& v) {
  double m = 0.0;
  for (double x : v) m = std::max(m, std::abs(x));
  return m;
}

}  // namespace import_plausibility_impl

void check_unit_plausible(const std::string& file, const ColumnMapping& mapping, const ImportTarget& target,
                          const ImportUnit& unit, const std::vector<double>& values) {
  using namespace import_plausibility_impl;
  if (values.size() < 2) return;
  const auto fail = [&](const std::string& seen, const std::string& likely) {
    const std::string map = map_option_text(mapping.source, target.column, likely);
    if (mapping.origin == "measured run")
      throw InputError(file, 0, "",
                       "column '" + target.column + "': " + seen + " look like " + likely + ", not " + unit.name +
                           " as the measured-run format has it; if so convert the file: shudder import " + file +
                           " -o FIXED.csv " + map);
    throw InputError(file, 0, "",
                     "column '" + mapping.source + "' (" + target.column + ", read as " + unit.name + "): " + seen +
                         " look like " + likely + ", not " + unit.name + "; if so give " + map +
                         " (or --trust-units if " + unit.name + " is right)");
  };
  const double lo = *std::min_element(values.begin(), values.end());
  const double hi = *std::max_element(values.begin(), values.end());
  const std::string& col = target.column;
  if (col == "time_s") {
    const double step = median_step(values);
    // A 10 s ramp logged at 1 kHz in ms read as s: steps of 1 s over 10000 s.
    if (unit.name == "s" && step >= 0.5 && hi - lo > 1000.0)
      fail("steps of " + g4(step) + " s over " + g4(hi - lo) + " s", "ms");
    // The same log in s read as ms: steps of 1 microsecond, a sampling rate above 100 kHz.
    if (unit.name == "ms" && step > 0.0 && step < 1e-5)
      fail("steps of " + g4(step * 1e3) + " ms (a rate of " + g4(1.0 / step) + " Hz)", "s");
  } else if (col == "normal_force_N") {
    if (unit.name == "N" && hi > 0.0 && hi < 200.0) fail("forces of at most " + g4(hi) + " N", "kN");
    if (unit.name == "kN" && hi > 1e6) fail("forces up to " + g4(hi / 1e3) + " kN", "N");
  } else if (col == "torque_Nm") {
    if (unit.name == "kN m" && max_abs(values) > 1e5)
      fail("torques up to " + g4(max_abs(values) / 1e3) + " kN m", "N m");
  } else if (col == "speed_rpm") {
    if (unit.name == "rad/s" && max_abs(values) > 1e5)
      fail("speeds up to " + g4(max_abs(values) / (60.0 / (2.0 * 3.141592653589793))) + " rad/s", "rpm");
  } else if (target.quantity.find("temperature") != std::string::npos) {
    // Degrees Celsius read from kelvin: a wet clutch's oil and discs start between -40 and
    // 200 degC; a column that never drops below 200 "degC" is 473 K or more throughout.
    if (unit.name == "degC" && lo > 200.0 && hi < 600.0)
      fail("temperatures of " + g4(lo) + "-" + g4(hi) + " degC", "K");
    if (unit.name == "K" && hi < -60.0)
      fail("temperatures of " + g4(lo + 273.15) + "-" + g4(hi + 273.15) + " K", "degC");
  }
}

}  // namespace shudder::io

namespace shudder::io {

void check_measured_run_units(const MeasuredRun& run) {
  for (const auto& target : import_targets())
    if (const auto* values = run.column(target.column)) {
      ColumnMapping m;
      m.source = m.target = target.column;
      m.origin = "measured run";
      check_unit_plausible(run.path, m, target, target.units.front(), *values);
    }
}

}  // namespace shudder::io
