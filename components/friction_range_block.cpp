#include "components/friction_range_block.hpp"

#include <cmath>
#include <cstdio>
#include <string>

namespace shudder::components {

namespace {

std::string four_digits(double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

std::string percent(double part, double whole) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.3g %%", whole > 0 ? 100.0 * part / whole : 0.0);
  return buf;
}

}  // namespace

dynamics::ResultBlock friction_range_block(const clutch::FrictionDataRange& r) {
  dynamics::ResultBlock b;
  b.name = kFrictionRangeBlock;
  b.description = "share of the run in which the clutch's friction law was used outside its data (held or clamped)";
  const double T = r.total_s;
  std::string parts;
  const auto part = [&](double time, const std::string& what) {
    if (time > 0) parts += (parts.empty() ? "" : "; ") + what + " for " + percent(time, T) + " of the run";
  };
  part(r.speed_below_s, "sliding speed down to " + four_digits(r.min_speed_mm_s) + " mm/s, below the data's " +
                            four_digits(r.speed_lo_mm_s) + " mm/s");
  part(r.speed_above_s, "sliding speed up to " + four_digits(r.max_speed_mm_s) + " mm/s, above the data's " +
                            four_digits(r.speed_hi_mm_s) + " mm/s");
  part(r.temp_below_s, "interface temperature down to " + four_digits(r.min_temp_C) + " °C, below the data's " +
                           four_digits(r.temp_lo_C) + " °C");
  part(r.temp_above_s, "interface temperature up to " + four_digits(r.max_temp_C) + " °C, above the data's " +
                           four_digits(r.temp_hi_C) + " °C");
  part(r.load_below_s,
       "clamp force down to " + four_digits(r.min_load_N) + " N, below the data's " + four_digits(r.load_lo_N) + " N");
  part(r.load_above_s,
       "clamp force up to " + four_digits(r.max_load_N) + " N, above the data's " + four_digits(r.load_hi_N) + " N");
  b.texts.push_back({"summary", parts.empty() ? "within the friction law's data (speed, temperature and load)"
                                              : "friction law used outside its data (held/clamped values): " + parts});
  const auto frac = [&](double t) { return T > 0 ? t / T : 0.0; };
  b.scalars = {
      {"fraction_outside", "1", frac(r.outside_s)},
      {"fraction_speed_below", "1", frac(r.speed_below_s)},
      {"fraction_speed_above", "1", frac(r.speed_above_s)},
      {"fraction_temp_below", "1", frac(r.temp_below_s)},
      {"fraction_temp_above", "1", frac(r.temp_above_s)},
      {"fraction_load_below", "1", frac(r.load_below_s)},
      {"fraction_load_above", "1", frac(r.load_above_s)},
      {"law_min_speed_mm_s", "mm/s", r.speed_lo_mm_s},
      {"law_max_speed_mm_s", "mm/s", r.speed_hi_mm_s},
      {"law_min_temp_C", "degC", r.temp_lo_C},
      {"law_max_temp_C", "degC", r.temp_hi_C},
      {"law_min_load_N", "N", r.load_lo_N},
      {"law_max_load_N", "N", r.load_hi_N},
      {"run_min_speed_mm_s", "mm/s", std::isfinite(r.min_speed_mm_s) ? r.min_speed_mm_s : 0.0},
      {"run_max_speed_mm_s", "mm/s", r.max_speed_mm_s},
      {"run_min_temp_C", "degC", r.min_temp_C},
      {"run_max_temp_C", "degC", r.max_temp_C},
      {"run_min_load_N", "N", r.min_load_N},
      {"run_max_load_N", "N", r.max_load_N},
  };
  return b;
}

}  // namespace shudder::components
