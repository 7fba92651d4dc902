#include "studies/run_stability_map.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

#include "studies/rig_stability.hpp"

namespace shudder::studies {

namespace {

std::vector<double> linspace(double lo, double hi, int n) {
  std::vector<double> v(static_cast<std::size_t>(n));
  for (int i = 0; i < n; ++i) v[static_cast<std::size_t>(i)] = lo + (hi - lo) * i / (n - 1);
  return v;
}

}  // namespace

dynamics::Map2D run_stability_map(const rig_models::RigParams& params, const clutch::WetClutch& clutch,
                                  const components::DriveCycle& cycle, double start_temp_C,
                                  const RunStabilityMapSettings& s) {
  if (s.n_speeds < 2 || s.n_temps < 2)
    throw std::invalid_argument("stability map: need at least 2 speeds and 2 temperatures");
  const double v_hi = std::max(s.max_speed_rpm, cycle.slip_speed_rpm.max_value());
  if (!(s.min_speed_rpm > 0 && v_hi > s.min_speed_rpm))
    throw std::invalid_argument("stability map: the slip span must satisfy 0 < min < max (rpm)");
  if (!(s.temp_below_start_C + s.temp_above_start_C > 0))
    throw std::invalid_argument("stability map: the temperature span must be > 0 degC");
  // The force at t = 0; a cycle that starts unloaded is mapped at its largest force.
  double force_N = cycle.normal_force_N(0.0);
  if (!(force_N > 0)) force_N = cycle.normal_force_N.max_value();

  const StabilityMap sm =
      stability_map(params, clutch, force_N, linspace(s.min_speed_rpm, v_hi, s.n_speeds),
                    linspace(start_temp_C - s.temp_below_start_C, start_temp_C + s.temp_above_start_C, s.n_temps));

  dynamics::Map2D m;
  m.name = "stability_map";
  char text[256];
  std::snprintf(text, sizeof text,
                "stability of steady sliding on the rig at %.6g N: eigenvalues of the linearised "
                "rig with the isothermal friction slope, ring temperatures uniform",
                force_N);
  m.description = text;
  m.x_name = "speeds_rpm";
  m.x_units = "rpm";
  m.x = sm.speeds_rpm;
  m.y_name = "temps_C";
  m.y_units = "degC";
  m.y = sm.temps_C;
  m.layers = {{"margin_per_s", "1/s", sm.margin_per_s},
              {"frequency_Hz", "Hz", sm.frequency_Hz},
              {"oscillatory_margin_per_s", "1/s", sm.oscillatory_margin_per_s},
              {"oscillatory_frequency_Hz", "Hz", sm.oscillatory_frequency_Hz}};
  m.scalars = {{"normal_force_N", "N", force_N}};
  return m;
}

}  // namespace shudder::studies
