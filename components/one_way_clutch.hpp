#pragma once
// A one-way clutch (freewheel, overrunning clutch) between a driving node a and a driven node b:
// it locks when a would turn faster than b and then carries any torque from a to b; b may
// overrun a freely (ω_b > ω_a), with an optional constant drag torque while overrunning.
//
//   locked:      ω_a = ω_b, transmitted torque λ (from a to b) >= 0, unbounded
//   overrunning: ω_a < ω_b, torque T_drag >= 0 resisting the relative motion
//
// As a contact of dynamics::Simulation: holding capacity unbounded for λ >= 0 and zero (1e-9 N m)
// for λ < 0, so a locked freewheel whose torque turns negative releases at that instant, and an
// overrunning one locks when Δω = ω_a − ω_b reaches 0 (the simulation's exact events). Source:
// the ideal freewheel of Modelica.Mechanics.Rotational.Components.OneWayClutch (fn → ∞).

#include "dynamics/contact_law.hpp"

namespace shudder::components {

class OneWayClutchLaw final : public dynamics::ContactLaw {
 public:
  /// A locked freewheel's capacity, N m: far above any drivetrain torque (a "never slips" bound).
  static constexpr double kLockedCapacity_Nm = 1e15;
  /// Capacity against torque in the free direction: zero, kept a hair above it so that a locked
  /// freewheel carrying exactly nothing stays locked until the torque reverses.
  static constexpr double kFreeCapacity_Nm = 1e-9;

  explicit OneWayClutchLaw(double drag_Nm = 0.0) : drag_Nm_(drag_Nm) {}
  double kinetic_torque_Nm(double, double, const double*) const override { return drag_Nm_; }
  double static_capacity_Nm(double, double, const double*) const override { return kLockedCapacity_Nm; }
  double holding_capacity_Nm(double, double, double held_Nm, const double*) const override {
    return held_Nm >= 0.0 ? kLockedCapacity_Nm : kFreeCapacity_Nm;
  }
  double kinetic_torque_slope_Nms(double, double, const double*) const override { return 0.0; }

 private:
  double drag_Nm_;
};

}  // namespace shudder::components
