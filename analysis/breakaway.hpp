#pragma once
// The static/dynamic (breakaway) friction ratio, measured from runs that start an up-ramp from
// rest (Paper F ranks additives "based on the ratio between the static friction (peak
// value) and the dynamic friction", thesis; docs/physics.md §6).
//
//   start from rest   the drive speed stays within ±rest_rpm for at least rest_s, then rises
//                     past window_factor · v_min (v_min: the law's lowest speed); the window
//                     runs from the rest phase's start to that crossing.
//   ratio            r(t) = mu(t) / mu_k(max(v(t), v_min), T(t), F(t)) over the window,
//                     mu(t) = M / (n F r_eff) − mu_bearing as the characterisation reads it
//                     (a 3-sample moving mean: the torque cell's noise, sigma 0.625 N m, would
//                     bias a single-sample maximum up by ~2 sigma); the event's ratio is the
//                     maximum of r, i.e. the peak against the kinetic friction at the speed
//                     the peak happened — at or below v_min this is exactly the model's
//                     definition mu_s = ratio · mu_k(v_min) (clutch/fluid.hpp); a fluid
//                     without breakaway whose mu rises with speed gives ≈ 1, not the rise.
//   result           the median over events (one per start from rest); "not measured" with
//                     the reason when no run starts from rest.
//
// Units: speeds in rpm (drive encoder) and mm/s (at r_eff), torque N m, force N, T in °C.

#include <optional>
#include <string>
#include <vector>

#include "analysis/friction_characterisation.hpp"
#include "analysis/ramp_detection.hpp"
#include "clutch/friction_law.hpp"

namespace shudder::analysis {

struct BreakawaySettings {
  double rest_rpm = 0.05;      // 10 × the encoder's noise sigma (0.005 rpm, io/measurement_csv)
  double rest_s = 0.1;         // the stuck phase must be seen before the ramp
  double window_factor = 5.0;  // the window ends at 5 v_min (~6 rpm): past the start's stick-slip
};

struct BreakawayEvent {
  std::size_t run = 0;
  double t_peak_s = 0.0, mu_peak = 0.0, mu_kinetic = 0.0, ratio = 0.0;
  double speed_rpm = 0.0, temp_C = 0.0, load_N = 0.0;  // at the peak
};

struct BreakawayMeasurement {
  std::vector<BreakawayEvent> events;
  std::optional<double> ratio;  // median of the events' ratios
  double min_ratio = 0.0, max_ratio = 0.0;
  std::string not_measured;  // why, when !ratio
};

BreakawayMeasurement measure_breakaway(const std::vector<RampRun>& runs, const FrictionConversion& conversion,
                                       const clutch::FrictionLaw& law, const BreakawaySettings& settings = {});

}  // namespace shudder::analysis
