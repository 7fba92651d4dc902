#pragma once
// Abstract boundary-friction law: mu(v, T, F) and its slope dmu/dv.
//
// v is the LOCAL sliding speed in mm/s (PHYSICS.md §1: the Mäki model's fitting speed unit),
// T the local interface temperature in °C, F the clutch normal force in N (the parameter
// matrices of Paper G are tabulated over load, not pressure). Laws are immutable after
// construction and safe to share between threads.

namespace shudder::clutch {

class FrictionLaw {
 public:
  virtual ~FrictionLaw() = default;

  /// Kinetic friction coefficient (dimensionless).
  virtual double mu(double speed_mm_s, double temp_C, double load_N) const = 0;

  /// Partial derivative of mu with respect to sliding speed at constant T and F, in 1/(mm/s).
  /// This is the isothermal slope that governs friction-induced vibration (PHYSICS.md §6).
  virtual double dmu_dv_per_mm_s(double speed_mm_s, double temp_C, double load_N) const = 0;

  /// Lowest speed at which the law is defined by data; below it the law is held constant.
  virtual double min_speed_mm_s() const = 0;
};

}  // namespace shudder::clutch
