#pragma once
// Finding the speed ramps in a measured friction run (thesis Method, docs/physics.md §4):
// Paper D's cycle (hold at N0, ramp up in 1–20 s, hold, ramp down, hold) and Paper E's
// characterisation cycle (1 rpm for 3 s, then 1 -> 100 rpm in 10 s, five times per start
// temperature) are both sequences of holds and monotone speed ramps.
//
// Method: the speed's rate of change is taken as a centred difference over ±`smoothing_s`
// (the encoder's resolution noise, 0.01 rpm, differentiated over 0.1 s is ~0.1 rpm/s, far
// below a ramp's 5–100 rpm/s). A sample belongs to an up-ramp when the rate exceeds
// `min_rate_rpm_s`, to a down-ramp when it is below −min_rate_rpm_s, else to a hold.
// Consecutive samples of one direction form a candidate; it is used when it
//   * spans at least `min_span_rpm` (a ramp that does not cross the low and middle speeds
//     cannot give a mu–v curve),
//   * lasts at least `min_duration_s`,
//   * holds the load within ±`max_load_spread` of its mean (one row of the friction matrix is
//     one load; Paper G tabulates per load).
// Candidates that fail are returned as rejected, with the reason. Flickers (candidates
// spanning less than `flicker_rpm`) are neither used nor reported.

#include <cstddef>
#include <string>
#include <vector>

namespace shudder::analysis {

/// One measured run's channels as the characterisation needs them (equal lengths).
struct RampRun {
  std::string name;  // the file, for messages
  std::vector<double> time_s, speed_rpm, normal_force_N, torque_Nm, temp_C;
};

enum class RampDirection { kUp, kDown };
const char* direction_name(RampDirection d);  // "up", "down"

struct Ramp {
  std::size_t run = 0;              // index of the run it came from
  std::size_t first = 0, last = 0;  // sample range [first, last] in the run
  RampDirection direction = RampDirection::kUp;
  double load_N = 0.0;        // mean normal force
  double start_temp_C = 0.0;  // temperature channel at the ramp's first samples
  double end_temp_C = 0.0;
  double min_rpm = 0.0, max_rpm = 0.0;
  double t_start_s = 0.0, t_end_s = 0.0;
};

struct RejectedRamp {
  std::size_t run = 0;
  double t_start_s = 0.0, t_end_s = 0.0;
  std::string reason;
};

struct RampSettings {
  double smoothing_s = 0.1;       // half-width of the rate's centred difference
  double min_rate_rpm_s = 1.0;    // Paper D's slowest ramp: 99 rpm in 20 s = 5 rpm/s
  double min_span_rpm = 20.0;     // a ramp must reach from low speeds past ~20 rpm
  double min_duration_s = 0.5;    // Paper D's fastest ramp: 1 s
  double max_load_spread = 0.05;  // ±5 % of the mean load
  double flicker_rpm = 2.0;       // candidates spanning less than this are noise
  double temp_window_s = 0.1;     // start/end temperature: mean over this time
};

struct RampSearch {
  std::vector<Ramp> ramps;
  std::vector<RejectedRamp> rejected;
};

/// Throws std::invalid_argument for a non-positive setting.
RampSearch find_ramps(const RampRun& run, std::size_t run_index, const RampSettings& settings = {});

}  // namespace shudder::analysis
