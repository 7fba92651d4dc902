#include "rig_models/realtime_rig.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "core/units.hpp"

namespace shudder::rig_models {

namespace {
const RigParams& require_sliding_start(const RigParams& p) {
  if (p.start_at_rest)
    throw std::invalid_argument("the fixed-step rig starts in steady sliding; rig.start_at_rest is not supported");
  return p;
}
}  // namespace

RealtimeRig::RealtimeRig(const RigParams& params, const clutch::WetClutch& clutch, const DriveCycle& cycle,
                         const RealtimeSettings& settings)
    : rig_(require_sliding_start(params), clutch, cycle),
      cycle_(cycle),
      ripple_(params.motor_ripple, cycle.slip_speed_rpm),
      clutch_(clutch, params.bearing_drag, settings, cycle.normal_force_N(0.0)),
      j_d_(params.drive_inertia_kg_m2),
      j_h_(params.housing_inertia_kg_m2),
      t_max_(params.motor_torque_limit_Nm) {
  const int nr = clutch.thermal().radial_cells();
  for (auto* v : {&k1_, &k2_, &k3_, &k4_, &heat_J_}) *v = Eigen::VectorXd::Zero(nr);
  // Steady sliding at the first speed: the bar carries the friction torque and the speed
  // loop's integrator supplies it (run_rig's start).
  const double w0 = units::rpm_to_rad_s(cycle.slip_speed_rpm(0.0));
  if (w0 == 0.0) throw std::invalid_argument("the fixed-step rig needs a non-zero speed at t = 0");
  const double m0 = std::copysign(clutch_.kinetic_torque_Nm(std::abs(w0), cycle.normal_force_N(0.0)), w0);
  x_.setZero();
  x_[kThetaH] = m0 / rig_.bar_stiffness_Nm_per_rad();
  x_[kOmegaD] = w0;
  x_[kIntegral] = m0 / rig_.motor_ki();
  d1_ = derivative(x_, 0.0, k1_, motor_Nm_, clutch_Nm_);
  initial_energy_J_ = 0.5 * (j_d_ * w0 * w0 + rig_.bar_stiffness_Nm_per_rad() * x_[kThetaH] * x_[kThetaH]);
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
  clutch_Nm = std::copysign(clutch_.kinetic_torque_Nm(w, cycle_.normal_force_N(t)), slip);
  heat_W = clutch_.ring_torque_Nm() * w;
  const double bar = rig_.bar_stiffness_Nm_per_rad() * x[kThetaH] + rig_.bar_damping_Nms_per_rad() * x[kOmegaH];
  State d;
  d[kThetaD] = x[kOmegaD];
  d[kThetaH] = x[kOmegaH];
  d[kOmegaD] = (motor_Nm + ripple_(t) - clutch_Nm) / j_d_;
  d[kOmegaH] = (clutch_Nm - bar) / j_h_;
  d[kIntegral] = kp > 0 ? e + (motor_Nm - u) / (0.9 * kp) : e;
  d[kSourceWork] = (motor_Nm + ripple_(t)) * x[kOmegaD];
  d[kFrictionWork] = clutch_Nm * slip;
  d[kDamperLoss] = rig_.bar_damping_Nms_per_rad() * x[kOmegaH] * x[kOmegaH];
  return d;
}

void RealtimeRig::step() {
  const double h = clutch_.settings().step_s;
  const double t = t_s_;
  double m, c;
  const State d1 = d1_;  // k1_ holds its heats
  const State d2 = derivative(x_ + 0.5 * h * d1, t + 0.5 * h, k2_, m, c);
  const State d3 = derivative(x_ + 0.5 * h * d2, t + 0.5 * h, k3_, m, c);
  const State d4 = derivative(x_ + h * d3, t + h, k4_, m, c);
  const double slip_before = x_[kOmegaD] - x_[kOmegaH];
  const State next = x_ + (h / 6.0) * (d1 + 2.0 * d2 + 2.0 * d3 + d4);
  heat_J_ = (h / 6.0) * (k1_ + 2.0 * k2_ + 2.0 * k3_ + k4_);
  const double slip_after = next[kOmegaD] - next[kOmegaH];
  ++steps_;
  const double t_end = static_cast<double>(steps_) * h;
  if (!(slip_before * slip_after > 0.0))
    throw std::runtime_error("fixed-step rig: the clutch slip reached zero at t = " + std::to_string(t_end) +
                             " s; the fixed-step mode models sliding only (stick-slip needs the adaptive run)");
  const double angle = (next[kThetaD] - next[kThetaH]) - (x_[kThetaD] - x_[kThetaH]);
  x_ = next;
  t_s_ = t_end;
  clutch_.end_step(heat_J_, angle, t_end, cycle_.normal_force_N(t_end));
  // Outputs at the step's end, with the temperatures the next step will use; that evaluation is
  // the next step's first stage (kept, so a step costs four evaluations, not five).
  d1_ = derivative(x_, t_end, k1_, motor_Nm_, clutch_Nm_);
}

}  // namespace shudder::rig_models
