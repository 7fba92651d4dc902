#pragma once
// Abstract boundary-friction law: mu(v, T, F) and its slope dmu/dv.
//
// v is the LOCAL sliding speed in mm/s (docs/physics.md §1: the Mäki model's fitting speed unit),
// T the local interface temperature in °C, F the clutch normal force in N (the parameter
// matrices of Paper G are tabulated over load, not pressure). Laws are immutable after
// construction and safe to share between threads.

#include <limits>
#include <span>
#include <utility>
#include <vector>

namespace shudder::clutch {

/// mu as a function of speed alone at one (T, F), in the Mäki form
///     mu(v) = Σ_j a_j tanh(b_j v) + c v^0.1 + d,   v clamped to [v_min, v_max] (mm/s).
/// Built once per thermal step so the fast dynamics evaluate the friction cheaply.
struct SpeedCurve {
  std::vector<double> tanh_weight;  // a_j
  std::vector<double> tanh_rate;    // b_j, 1/(mm/s)
  double power_weight = 0.0;        // c
  double offset = 0.0;              // d
  double min_speed_mm_s = 0.0, max_speed_mm_s = 0.0;
};

/// What a law may keep between calls at the same speeds (the rings of a clutch at one slip:
/// a thermal step's end is evaluated with the old and then with the new temperatures). The
/// law owns the meaning of `values`; callers only keep one object per sequence of calls.
struct SpeedTerms {
  std::vector<double> speed_mm_s;  // the speeds `values` belong to
  std::vector<double> values;
};

class FrictionLaw {
 public:
  virtual ~FrictionLaw() = default;

  /// Kinetic friction coefficient (dimensionless).
  virtual double mu(double speed_mm_s, double temp_C, double load_N) const = 0;
  /// mu at several points of one load: out[i] = mu(speed_mm_s[i], temp_C[i], load_N), the same
  /// numbers bit for bit. A law may reuse speed-only work in `terms` while the speeds repeat.
  virtual void mu_at_load(std::span<const double> speed_mm_s, std::span<const double> temp_C, double load_N,
                          std::span<double> out, SpeedTerms& /*terms*/) const {
    for (std::size_t i = 0; i < out.size(); ++i) out[i] = mu(speed_mm_s[i], temp_C[i], load_N);
  }

  /// Partial derivative of mu with respect to sliding speed at constant T and F, in 1/(mm/s).
  /// This is the isothermal slope that governs friction-induced vibration (docs/physics.md §6).
  virtual double dmu_dv_per_mm_s(double speed_mm_s, double temp_C, double load_N) const = 0;

  /// Lowest speed at which the law is defined by data; below it the law is held constant.
  virtual double min_speed_mm_s() const = 0;

  /// Highest speed at which the law is defined by data; above it the law is held constant
  /// (+infinity: the law has no upper limit).
  virtual double max_speed_mm_s() const { return std::numeric_limits<double>::infinity(); }

  /// Temperatures spanned by the law's data, °C, as {lowest, highest}; outside them the law
  /// holds or extrapolates ({-inf, +inf}: the law is defined for any temperature, e.g. the
  /// lines mu = alpha*T + beta). Used to mark screening results outside the data.
  virtual std::pair<double, double> temp_range_C() const {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }

  /// Normal loads spanned by the law's data, N, as {lowest, highest}; outside them the law is
  /// clamped ({-inf, +inf}: the law does not depend on load). Used to tell a run that it left
  /// the data (clutch/friction_data_range.hpp).
  virtual std::pair<double, double> load_range_N() const {
    return {-std::numeric_limits<double>::infinity(), std::numeric_limits<double>::infinity()};
  }

  /// The law at fixed (T, F) as a SpeedCurve, if it has that form (false otherwise; callers
  /// then evaluate mu() directly).
  virtual bool speed_curve(double /*temp_C*/, double /*load_N*/, SpeedCurve& /*out*/) const { return false; }
};

}  // namespace shudder::clutch
