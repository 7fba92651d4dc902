#pragma once
// The Haldex control unit of a first-generation coupling as a model: it sets the opening of the
// throttle valve on the pump's return flow (components/haldex_hydraulics.hpp) once per control
// step from what the Gen I unit reads (VW Self-Study Programme 206: the ABS wheel speeds and the
// accelerator pedal over the CAN bus; road speed, cornering, traction or overrun from them). Gen I
// can only LOWER the pressure the slip pumps (awdwiki "Haldex": "cannot pre-tension the clutch"):
// a closed valve lets the pump build pressure, an open one lets the coupling slip.
//
//   excess slip   s_x = |n_front − n_rear ρ̄_f/ρ̄_r|  (axle wheel speeds, rpm): the front–rear
//                 difference the turn's geometry does not explain (ρ̄: the axles' mean path ratios)
//   demand        d = max(s_x / s_lock, g_pedal · pedal),  clamped to [0, 1]
//   parking turn  v < v_park and ρ̄_f/ρ̄_r − 1 > δ_park: d = s_x / s_lock only (the pedal does not
//                 close the valve: a parking manoeuvre must not wind the driveline up — SSP 206's
//                 "no strain on the clutch when parking and manoeuvring")
//   high speed    d <= 1 − (1 − d_fast) · clamp((v − v_fast0)/(v_fast1 − v_fast0), 0, 1)
//                 (less pressure at speed: "at high speeds a much lower pressure", awdwiki)
//   opening       u = 1 − d
//
// Sampling (what a control unit has, not the model's exact speeds): the unit acts every control
// period T_c on the wheel speeds the ABS unit sends over the CAN bus. A toothed-wheel sensor
// counts pulses, so each reading is the MEAN speed over the period just ended (the angle turned
// over T_c), which no oscillation faster than 1/T_c can alias into a step; the unit then low-passes
// it (SampledSpeedSignal, a first-order filter τ_f), and holds its valve command until the next
// instant. The valve itself follows the command with its own lag (haldex_hydraulics.hpp).
//
// Every threshold is an ESTIMATE (the unit's calibration is not public), named and overridable.
// The pedal is the throttle of the engine map, or, with a raw torque schedule, the torque over
// the full-load torque at the engine's speed.

namespace shudder::components {

struct HaldexControllerParams {
  double lock_slip_rpm = 20.0;       // s_lock: excess axle slip that closes the valve (estimate: ~5 % at 30 km/h)
  double pedal_gain = 0.5;           // g_pedal: how far the pedal alone closes the valve (estimate)
  double parking_speed_km_h = 15.0;  // v_park (estimate: manoeuvring speeds)
  double parking_turn_ratio = 0.02;  // δ_park: front axle ≥ 2 % further than the rear (R ≲ 14 m for a Golf)
  double fast_speed_km_h = 80.0;     // v_fast0: demand starts to be limited (estimate)
  double top_speed_km_h = 160.0;     // v_fast1: limit reached (estimate)
  double fast_demand = 0.3;          // d_fast: the largest demand at and above v_fast1 (estimate)
  double control_period_ms = 10.0;   // T_c (estimate: wheel-speed messages on the CAN bus every 10–20 ms)
  double speed_filter_time_constant_ms = 20.0;  // τ_f (estimate: a few wheel-speed messages)
};

/// One speed as the control unit sees it: the mean over each control period from the angle
/// turned, then y_k = y_{k−1} + α (x_k − y_{k−1}), α = T/(τ_f + T) (backward Euler of
/// τ_f dy/dt = x − y, unconditionally stable whatever T/τ_f).
class SampledSpeedSignal {
 public:
  /// Starts at a steady speed `speed_rad_s` with the shaft at `angle_rad`.
  void start(double angle_rad, double speed_rad_s) {
    angle_rad_ = angle_rad;
    filtered_rad_s_ = speed_rad_s;
  }
  /// The reading at the end of a period of `period_s` (> 0) with the shaft at `angle_rad`.
  double update(double angle_rad, double period_s, double time_constant_s) {
    const double mean = (angle_rad - angle_rad_) / period_s;
    angle_rad_ = angle_rad;
    filtered_rad_s_ += period_s / (time_constant_s + period_s) * (mean - filtered_rad_s_);
    return filtered_rad_s_;
  }
  double value_rad_s() const { return filtered_rad_s_; }

 private:
  double angle_rad_ = 0.0, filtered_rad_s_ = 0.0;
};

struct ControllerReading {
  double vehicle_speed_km_h = 0;
  double front_axle_rpm = 0;   // mean of the front wheels
  double rear_axle_rpm = 0;    // mean of the rear wheels
  double turn_axle_ratio = 1;  // ρ̄_f/ρ̄_r of the steering (1 straight)
  double pedal = 0;            // 0–1
};

class HaldexController {
 public:
  /// Throws std::invalid_argument for non-finite, non-positive or inconsistent thresholds.
  explicit HaldexController(const HaldexControllerParams& params);
  /// The excess slip s_x, rpm.
  double excess_slip_rpm(const ControllerReading& r) const;
  /// Whether the reading is a parking turn (low speed, large steering).
  bool parking(const ControllerReading& r) const;
  /// The throttle valve's opening u, 0 (shut: full pump pressure) to 1 (open).
  double valve_opening(const ControllerReading& r) const;
  const HaldexControllerParams& params() const { return p_; }

 private:
  HaldexControllerParams p_;
};

}  // namespace shudder::components
