#include "rig_models/realtime_rig.hpp"

#include <algorithm>
#include <cmath>

#include "core/units.hpp"

namespace shudder::rig_models {

RealtimeRig::RealtimeRig(const RigParams& params, const clutch::WetClutch& clutch, const DriveCycle& cycle,
                         const RealtimeSettings& settings)
    : rig_(params, clutch, cycle),
      context_(rig_.start_inputs()),
      cycle_(cycle),
      ripple_(params.motor_ripple, cycle.slip_speed_rpm),
      clutch_(clutch, params.bearing_drag, settings, cycle.normal_force_N(0.0)),
      j_d_(params.drive_inertia_kg_m2),
      j_h_(params.housing_inertia_kg_m2),
      t_max_(params.motor_torque_limit_Nm) {
  const int nr = clutch.thermal().radial_cells();
  for (auto* v : {&k1_, &k2_, &k3_, &k4_, &heat_J_}) *v = Eigen::VectorXd::Zero(nr);
  // run_rig's two starts: steady sliding at the first speed (the bar carries the friction
  // torque, the speed loop's integrator supplies it), or everything at rest with the clutch
  // stuck (also when the first speed is 0).
  const double w0 = units::rpm_to_rad_s(cycle.slip_speed_rpm(0.0));
  x_.setZero();
  if (!params.start_at_rest && w0 != 0.0) {
    const double m0 = std::copysign(clutch_.kinetic_torque_Nm(std::abs(w0), cycle.normal_force_N(0.0)), w0);
    x_[kThetaH] = m0 / rig_.bar_stiffness_Nm_per_rad();
    x_[kOmegaD] = w0;
    x_[kIntegral] = m0 / rig_.motor_ki();
    direction_ = w0 > 0 ? 1.0 : -1.0;
  } else {
    stuck_ = true;
  }
  d1_ = derivative(x_, 0.0, k1_, motor_Nm_, clutch_Nm_);
  initial_energy_J_ = 0.5 * (j_d_ * x_[kOmegaD] * x_[kOmegaD] + rig_.bar_stiffness_Nm_per_rad() * x_[kThetaH] * x_[kThetaH]);
}

double RealtimeRig::energy_relative_error() const {
  const double kinetic = 0.5 * (j_d_ * x_[kOmegaD] * x_[kOmegaD] + j_h_ * x_[kOmegaH] * x_[kOmegaH]);
  const double elastic = 0.5 * rig_.bar_stiffness_Nm_per_rad() * x_[kThetaH] * x_[kThetaH];
  const double imbalance =
      x_[kSourceWork] - (kinetic + elastic - initial_energy_J_) - x_[kFrictionWork] - x_[kDamperLoss];
  return x_[kSourceWork] != 0.0 ? std::abs(imbalance) / std::abs(x_[kSourceWork]) : 0.0;
}

RealtimeRig::State RealtimeRig::derivative(const State& x, double t, Eigen::VectorXd& heat_W, double& motor_Nm,
                                           double& clutch_Nm) {
  const double kp = rig_.motor_kp(), ki = rig_.motor_ki();
  const double e = units::rpm_to_rad_s(cycle_.slip_speed_rpm(t)) - x[kOmegaD];
  const double u = kp * e + ki * x[kIntegral];
  motor_Nm = std::clamp(u, -t_max_, t_max_);
  const double slip = x[kOmegaD] - x[kOmegaH];
  const double w = std::abs(slip);
  const double drive = motor_Nm + ripple_(t);
  const double bar = rig_.bar_stiffness_Nm_per_rad() * x[kThetaH] + rig_.bar_damping_Nms_per_rad() * x[kOmegaH];
  State d;
  d[kThetaD] = x[kOmegaD];
  d[kThetaH] = x[kOmegaH];
  if (stuck_) {
    // One body: (J_d + J_h) ω̇ = T_m + T_r − T_bar; the clutch carries what keeps Δω = 0.
    const double acc = (drive - bar) / (j_d_ + j_h_);
    clutch_Nm = drive - j_d_ * acc;
    heat_W.setZero();
    d[kOmegaD] = d[kOmegaH] = acc;
  } else {
    // The friction keeps the mode's direction within a step, as the adaptive run's modes do: a
    // stage that overshoots Δω = 0 must not flip it (the crossing is handled at the step's end).
    clutch_Nm = direction_ * clutch_.kinetic_torque_Nm(w, cycle_.normal_force_N(t));
    heat_W = clutch_.ring_torque_Nm() * w;
    d[kOmegaD] = (drive - clutch_Nm) / j_d_;
    d[kOmegaH] = (clutch_Nm - bar) / j_h_;
  }
  d[kIntegral] = kp > 0 ? e + (motor_Nm - u) / (0.9 * kp) : e;
  d[kSourceWork] = drive * x[kOmegaD];
  d[kFrictionWork] = clutch_Nm * slip;
  d[kDamperLoss] = rig_.bar_damping_Nms_per_rad() * x[kOmegaH] * x[kOmegaH];
  return d;
}

double RealtimeRig::static_capacity_Nm(double t) {
  if (thermal().time_s != capacity_temps_time_s_) {  // new latched temperatures (same size: no allocation)
    context_.set_ring_temperatures(thermal().ring_temp_C);
    capacity_temps_time_s_ = thermal().time_s;
  }
  return rig_.clutch_contact().static_capacity_Nm(context_, t, t - stick_start_s_);
}

void RealtimeRig::update_modes(State& next, double t_end) {
  double motor, held;
  if (stuck_) {
    // Breakaway when the torque that holds Δω = 0 exceeds the static capacity.
    derivative(next, t_end, k1_, motor, held);
    if (std::abs(held) > static_capacity_Nm(t_end)) {
      stuck_ = false;
      direction_ = held > 0 ? 1.0 : -1.0;
      ++breakaways_;
    }
    return;
  }
  const double slip_after = next[kOmegaD] - next[kOmegaH];
  if (direction_ * slip_after > 0.0) return;  // still slipping the same way
  // Δω reached zero within the step (located to the step, not finer): the two sides merge with
  // their momentum and stick if the clutch can hold the torque that keeps them together.
  State merged = next;
  const double w = (j_d_ * next[kOmegaD] + j_h_ * next[kOmegaH]) / (j_d_ + j_h_);
  merged[kOmegaD] = merged[kOmegaH] = w;
  stuck_ = true;
  stick_start_s_ = t_end;
  derivative(merged, t_end, k1_, motor, held);
  if (std::abs(held) <= static_capacity_Nm(t_end)) {
    // The merge's kinetic-energy loss is friction work (as the adaptive run's impact loss).
    const auto kinetic = [&](const State& x) {
      return 0.5 * (j_d_ * x[kOmegaD] * x[kOmegaD] + j_h_ * x[kOmegaH] * x[kOmegaH]);
    };
    merged[kFrictionWork] += kinetic(next) - kinetic(merged);
    next = merged;
    ++sticks_;
  } else {
    stuck_ = false;
    direction_ = slip_after != 0.0 ? (slip_after > 0 ? 1.0 : -1.0) : -direction_;
    ++reversals_;
  }
}

void RealtimeRig::step() {
  const double h = clutch_.settings().step_s;
  const double t = t_s_;
  double m, c;
  const State d1 = d1_;  // k1_ holds its heats
  const State d2 = derivative(x_ + 0.5 * h * d1, t + 0.5 * h, k2_, m, c);
  const State d3 = derivative(x_ + 0.5 * h * d2, t + 0.5 * h, k3_, m, c);
  const State d4 = derivative(x_ + h * d3, t + h, k4_, m, c);
  State next = x_ + (h / 6.0) * (d1 + 2.0 * d2 + 2.0 * d3 + d4);
  heat_J_ = (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
  ++steps_;
  const double t_end = static_cast<double>(steps_) * h;
  update_modes(next, t_end);
  const double angle = (next[kThetaD] - next[kThetaH]) - (x_[kThetaD] - x_[kThetaH]);
  x_ = next;
  t_s_ = t_end;
  clutch_.end_step(heat_J_, angle, t_end, cycle_.normal_force_N(t_end));
  // Outputs at the step's end, with the temperatures the next step will use; that evaluation is
  // the next step's first stage (kept, so a step costs four evaluations, not five).
  d1_ = derivative(x_, t_end, k1_, motor_Nm_, clutch_Nm_);
}

}  // namespace shudder::rig_models
