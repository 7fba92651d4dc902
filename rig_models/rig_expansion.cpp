#include "rig_models/rig_expansion.hpp"

#include <cmath>

#include "core/units.hpp"

namespace shudder::rig_models {

// The expansion writes in the network description's own vocabulary (components/network_spec.hpp).
using namespace components;

NetworkSpec expand_rig(const RigParams& p, const clutch::WetClutchParams& pack, const clutch::Fluid& fluid,
                       const components::DriveCycle& cycle, const RigSettings& cfg) {
  const clutch::WetClutch clutch(pack, fluid);
  const LsctrRig rig(p, clutch, cycle);  // validates; derives the bar and the loop gains
  NetworkSpec s;
  // The start the rig kind takes (run_rig): the friction torque at the first speed, with every
  // ring at the clutch's start temperature, carried by the bar and supplied by the integrator.
  double w0 = 0, torque0_Nm = 0;
  if (!p.start_at_rest) {
    w0 = units::rpm_to_rad_s(cycle.slip_speed_rpm(0.0));
    components::ClutchContext context(rig.clutch_contact().start_inputs(cycle.normal_force_N));
    torque0_Nm = rig.clutch_contact().kinetic_torque_Nm(context, std::abs(w0), 0.0) * (w0 >= 0 ? 1.0 : -1.0);
  }
  s.inertias.push_back({"drive", p.drive_inertia_kg_m2, w0, 0.0});
  s.inertias.push_back({"housing", p.housing_inertia_kg_m2, 0.0, torque0_Nm / rig.bar_stiffness_Nm_per_rad()});

  MotorSpec m;
  m.name = "motor";
  m.node = "drive";
  m.speed_rpm = Signal::table(cycle.slip_speed_rpm.times_s(), cycle.slip_speed_rpm.values(), true);
  m.kp_Nms_per_rad = rig.motor_kp();
  m.ki_Nm_per_rad = rig.motor_ki();
  m.torque_limit_Nm = p.motor_torque_limit_Nm;
  m.start_torque_Nm = torque0_Nm;
  m.ripple = p.motor_ripple;
  s.motors.push_back(m);

  ClutchSpec c;
  c.name = "clutch";
  c.a = "drive";
  c.b = "housing";
  c.law = ClutchSpec::Law::kWet;
  c.max_force_N = cycle.normal_force_N.max_value();
  std::vector<double> u;
  for (double f : cycle.normal_force_N.values()) u.push_back(c.max_force_N > 0 ? f / c.max_force_N : 0.0);
  c.force_signal = Signal::table(cycle.normal_force_N.times_s(), u, true);
  c.wet.fluid = fluid;
  c.wet.clutch = pack;
  c.wet.oil_volume_given = c.wet.oil_flow_given = true;
  c.wet.bearing_drag = p.bearing_drag;
  c.wet.stick_time = p.stick_time;
  c.judged_on = "torsion_bar";
  s.clutches.push_back(c);
  s.shafts.push_back(
      {"torsion_bar", "housing", kGroundNode, rig.bar_stiffness_Nm_per_rad(), rig.bar_damping_Nms_per_rad(), 0.0});

  s.settings.duration_s = cfg.duration_s;
  s.settings.sample_rate_Hz = cfg.sample_rate_Hz;
  s.settings.thermal_step_s = cfg.thermal_step_s;
  s.settings.integrator = p.integrator;
  return s;
}

}  // namespace shudder::rig_models
