#include "rig_models/realtime_coupling.hpp"

#include <cmath>

namespace shudder::rig_models {

RealtimeCoupling::RealtimeCoupling(const clutch::WetClutch& clutch, const BearingDrag& drag,
                                   const RealtimeSettings& settings, double force_N)
    : clutch_(clutch, drag, settings, force_N),
      drag_(drag),
      heat_J_(Eigen::VectorXd::Zero(clutch.thermal().radial_cells())) {}

void RealtimeCoupling::step(double slip_rad_s, double force_N) {
  const double h = clutch_.settings().step_s;
  const double w = std::abs(slip_rad_s);
  const double drag_Nm = drag_.enabled ? drag_.equivalent_mu * force_N * drag_.radius_m : 0.0;
  const double kinetic = clutch_.kinetic_torque_Nm(w, force_N);
  torque_Nm_ = std::copysign(kinetic, slip_rad_s);
  clutch_torque_Nm_ = std::copysign(kinetic - drag_Nm, slip_rad_s);
  heat_J_ = clutch_.ring_torque_Nm() * (w * h);
  heat_W_ = clutch_.clutch().params().sliding_interfaces * clutch_.ring_torque_Nm().sum() * w;
  ++steps_;
  t_s_ = static_cast<double>(steps_) * h;  // exact multiple: no accumulated round-off
  clutch_.end_step(heat_J_, slip_rad_s * h, t_s_, force_N);
}

void RealtimeCoupling::reset(double force_N) {
  clutch_.reset(force_N);
  steps_ = 0;
  t_s_ = torque_Nm_ = clutch_torque_Nm_ = heat_W_ = 0.0;
}

}  // namespace shudder::rig_models
