#include "rig_models/realtime_coupling.hpp"

#include <cmath>

namespace shudder::rig_models {

RealtimeCoupling::RealtimeCoupling(const clutch::WetClutch& clutch, const components::BearingDrag& drag,
                                   const RealtimeSettings& settings, double force_N)
    : clutch_(clutch, drag, settings, force_N),
      drag_(drag),
      heat_J_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())) {}

void RealtimeCoupling::step(double slip_rad_s, double force_N, double fraction) {
  const double dt = clutch_.settings().step_s * fraction;  // fraction 1: exactly the fixed step
  const double w = std::abs(slip_rad_s);
  const double drag_Nm = drag_.enabled ? drag_.equivalent_mu * force_N * drag_.radius_m : 0.0;
  const double kinetic = clutch_.kinetic_torque_Nm(w, force_N);
  torque_Nm_ = std::copysign(kinetic, slip_rad_s);
  clutch_torque_Nm_ = std::copysign(kinetic - drag_Nm, slip_rad_s);
  heat_J_ = clutch_.ring_torque_Nm() * (w * dt);
  heat_W_ = clutch_.clutch().params().sliding_interfaces * clutch_.ring_torque_Nm().sum() * w;
  steps_ += fraction;
  t_s_ = steps_ * clutch_.settings().step_s;  // a count times the step: no accumulated round-off
  clutch_.end_step(heat_J_, slip_rad_s * dt, t_s_, force_N, fraction);
}

void RealtimeCoupling::reset(double force_N) {
  clutch_.reset(force_N);
  steps_ = 0.0;
  t_s_ = torque_Nm_ = clutch_torque_Nm_ = heat_W_ = 0.0;
}

}  // namespace shudder::rig_models
