#pragma once
// The stability map stored with a rig run (/analysis/stability_map, written by `shudder run`):
// the rig's stability of steady sliding (studies/rig_stability.hpp) over slip speed x
// interface temperature at the run's normal force at t = 0 (a cycle starting unloaded: its
// largest force), as a dynamics::Map2D:
//
//   x  speeds_rpm   (n_speeds) slip 1 … max(125 rpm, the cycle's largest speed), rpm, uniform
//   y  temps_C      (n_temps)  start temperature − 20 … + 80 °C, uniform
//   layers (n_speeds x n_temps):
//      margin_per_s               largest real part of the linearised rig (1/s); > 0 unstable
//      frequency_Hz               frequency of that mode (0 if not oscillatory)
//      oscillatory_margin_per_s   largest real part among the oscillatory modes (the
//                                 clutch-side mode at the bar's frequency), 1/s
//      oscillatory_frequency_Hz   its frequency
//      NaN where the clutch torque exceeds the motor's limit (no steady sliding)
//   scalars normal_force_N (the force the map is computed at)
//
// 125 rpm is the rig's top speed (thesis); the temperature span covers a run's heating from its
// start plus some cooling margin. 60 x 50 points take ~0.1 s (one linearisation each).

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "components/drive_cycle.hpp"
#include "rig_models/lsctr_rig.hpp"

namespace shudder::studies {

struct RunStabilityMapSettings {
  int n_speeds = 60;
  int n_temps = 50;
  double min_speed_rpm = 1.0;
  double max_speed_rpm = 125.0;  // raised to the cycle's largest speed if that is higher
  double temp_below_start_C = 20.0;
  double temp_above_start_C = 80.0;
};

/// The map for a rig run with `params`, `clutch` and `cycle` starting at `start_temp_C`.
/// Throws std::invalid_argument for a cycle that never loads the clutch, fewer than 2 points on
/// an axis or an empty span.
dynamics::Map2D run_stability_map(const rig_models::RigParams& params, const clutch::WetClutch& clutch,
                                  const components::DriveCycle& cycle, double start_temp_C,
                                  const RunStabilityMapSettings& settings = {});

}  // namespace shudder::studies
