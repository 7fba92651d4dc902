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
  /// Magnitude of the kinetic friction torque at relative speed |Δω| >= 0 (rad/s), N m.
  virtual double kinetic_torque_Nm(double abs_slip_rad_s, double t_s) const = 0;
  /// Largest torque the stuck contact can carry after `stick_time_s` stuck, N m.
  virtual double static_capacity_Nm(double t_s, double stick_time_s) const = 0;
  /// Largest torque the stuck contact can carry against a holding torque `held_Nm` (transmitted
  /// from a to b, i.e. −held_Nm on a, +held_Nm on b). A two-way clutch holds either sign up to its
  /// static capacity; a one-way clutch (components/one_way_clutch.hpp) holds one sign only.
  virtual double holding_capacity_Nm(double t_s, double stick_time_s, double /*held_Nm*/) const {
    return static_capacity_Nm(t_s, stick_time_s);
  }
  /// d(kinetic torque)/d|Δω| at constant temperature, N m s/rad (for linearisation).
  virtual double kinetic_torque_slope_Nms(double abs_slip_rad_s, double t_s) const = 0;
  /// Number of heat channels (0 if the law does not split its heat).
  virtual int heat_channels() const { return 0; }
  /// Heat power into each channel at |Δω| (array of heat_channels()), W.
  virtual void channel_heat_W(double /*abs_slip_rad_s*/, double /*t_s*/, double* /*out*/) const {}
};

}  // namespace shudder::dynamics
