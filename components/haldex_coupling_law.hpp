#pragma once
// The Haldex coupling as one friction contact of the torsional network: the wet disc pack
// (components/clutch_contact.hpp) clamped by the pressure of its own hydraulics
// (components/haldex_hydraulics.hpp), the pressure and the throttle valve's opening being the
// contact law's internal states (dynamics/contact_law.hpp), integrated with the motion:
//
//   z = [p (bar), u (0–1)]
//   dp/dt = HaldexHydraulics::pressure_rate_bar_s(p, |Δω|, u, p_set(t), ν(40 °C)/ν(T_oil))
//   du/dt = (u_cmd − u) / τ_v
//   F     = F_preload + A max(p, 0)   →   kinetic torque, static capacity and ring heats of the
//                                          pack at F (ClutchContact::*_at_force)
//
// The pump delivers with |Δω| (0 while the pack is stuck), so a locked coupling holds its
// pressure only against the valve and the leakage, and breaks away when that falls below what
// the driveline asks of it: the event is found on the same dense output as every other.
// What the run sets from outside, between integrator restarts (HaldexCommand): the control
// unit's commanded opening u_cmd (at its control instants), the pressure setting p_set(t) and the
// leakage scale (with the oil's temperature, per thermal step). The ring temperatures come from
// the pack's ClutchContext as for any wet clutch.
// Energy: the pump's own torque (p D, ≈ 1 N m at 30 bar against a pack that carries hundreds)
// is not modelled; the hydraulic power is outside the mechanical account, as an actuator's is.

#include <memory>
#include <optional>

#include "dynamics/contact_law.hpp"
#include "components/clutch_contact.hpp"
#include "components/drive_cycle.hpp"
#include "components/haldex_hydraulics.hpp"

namespace shudder::components {

/// The coupling's inputs a run holds between integrator restarts.
struct HaldexCommand {
  double opening = 1.0;      // u_cmd, 0 shut – 1 open
  double leak_scale = 1.0;   // ν(40 °C)/ν(T) of the coupling's oil
  double setting_bar = 1e9;  // the cap when no schedule is given (the relief valve still caps)
  std::optional<PiecewiseLinear> setting_schedule_bar;  // a raw pressure setting over time
  double setting_at_bar(double t_s) const { return setting_schedule_bar ? (*setting_schedule_bar)(t_s) : setting_bar; }
};

class HaldexCouplingLaw final : public dynamics::ContactLaw {
 public:
  static constexpr int kPressure = 0, kOpening = 1;

  HaldexCouplingLaw(ClutchContact pack, std::shared_ptr<ClutchContext> pack_context, HaldexHydraulics hydraulics,
                    std::shared_ptr<HaldexCommand> command, double start_pressure_bar = 0.0);

  double kinetic_torque_Nm(double abs_slip_rad_s, double t_s, const double* z) const override;
  double static_capacity_Nm(double t_s, double stick_time_s, const double* z) const override;
  double kinetic_torque_slope_Nms(double abs_slip_rad_s, double t_s, const double* z) const override;
  int heat_channels() const override { return pack_.heat_channels(); }
  void channel_heat_W(double abs_slip_rad_s, double t_s, const double* z, double* out) const override;
  int states() const override { return 2; }
  void state_rates(double slip_rad_s, double t_s, const double* z, double* dzdt) const override;
  /// The start pressure and the valve where the command has it.
  void initial_states(double* z) const override;

  /// The clamp force at states z, N.
  double clamp_force_N(const double* z) const { return hydraulics_.clamp_force_N(z[kPressure]); }
  const HaldexHydraulics& hydraulics() const { return hydraulics_; }

 private:
  ClutchContact pack_;
  std::shared_ptr<ClutchContext> context_;
  HaldexHydraulics hydraulics_;
  std::shared_ptr<HaldexCommand> command_;
  double start_pressure_bar_;
};

}  // namespace shudder::components
