#pragma once
// Abstract friction law of a contact between two inertias. dynamics/ knows only this interface;
// rig_models/ implements it with the wet clutch (clutch/), so dynamics/ does not include clutch/.
//
//   slipping:  torque on the faster side = -sign(Δω) * kinetic_torque_Nm(|Δω|, t)
//              e.g. n * r_eff * F(t) * mu_k(r|Δω|, T, F)
//   stuck:     the contact carries whatever torque keeps Δω = 0 while it stays below
//              static_capacity_Nm(t, stick_time) = n * r_eff * F(t) * mu_s(stick_time)
//
// Heat channels: the kinetic dissipation can be split into channels (e.g. the radial rings of
// a clutch's thermal grid) whose powers the integrator accumulates as states, so a slow thermal
// model receives exactly the energy dissipated. The channels need not add up to the whole
// dissipation (e.g. bearing drag heats no disc); the integrator also accumulates the total.

namespace shudder::dynamics {

class ContactLaw {
 public:
  virtual ~ContactLaw() = default;
  // `z` points to the law's own internal states (states() values, see below); a law without
  // states ignores it (it may be nullptr then).
  /// Magnitude of the kinetic friction torque at relative speed |Δω| >= 0 (rad/s), N m.
  virtual double kinetic_torque_Nm(double abs_slip_rad_s, double t_s, const double* z) const = 0;
  /// Largest torque the stuck contact can carry after `stick_time_s` stuck, N m.
  virtual double static_capacity_Nm(double t_s, double stick_time_s, const double* z) const = 0;
  /// Largest torque the stuck contact can carry against a holding torque `held_Nm` (transmitted
  /// from a to b, i.e. −held_Nm on a, +held_Nm on b). A two-way clutch holds either sign up to its
  /// static capacity; a one-way clutch (components/one_way_clutch.hpp) holds one sign only.
  virtual double holding_capacity_Nm(double t_s, double stick_time_s, double /*held_Nm*/, const double* z) const {
    return static_capacity_Nm(t_s, stick_time_s, z);
  }
  /// d(kinetic torque)/d|Δω| at constant temperature and states, N m s/rad (for linearisation).
  virtual double kinetic_torque_slope_Nms(double abs_slip_rad_s, double t_s, const double* z) const = 0;
  /// Number of heat channels (0 if the law does not split its heat).
  virtual int heat_channels() const { return 0; }
  /// Heat power into each channel at |Δω| (array of heat_channels()), W.
  virtual void channel_heat_W(double /*abs_slip_rad_s*/, double /*t_s*/, const double* /*z*/, double* /*out*/) const {}

  // Internal states: what the contact's clamping has of its own dynamics (an actuator's
  // pressure, a valve's opening), integrated with the motion like a force element's states, so
  // the clamp force moves continuously with the slip that drives it instead of being held over
  // a slow step. The rates may depend on the signed slip Δω = ω_a − ω_b (0 while stuck).
  /// Number of internal states (0: none).
  virtual int states() const { return 0; }
  /// dz/dt (states() values) at slip Δω, time t and states z.
  virtual void state_rates(double /*slip_rad_s*/, double /*t_s*/, const double* /*z*/, double* /*dzdt*/) const {}
  /// The states' values at the start of a run.
  virtual void initial_states(double* /*z*/) const {}
};

}  // namespace shudder::dynamics
