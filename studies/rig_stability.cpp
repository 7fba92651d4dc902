#include "studies/rig_stability.hpp"

#include <cmath>
#include <limits>
#include <optional>
#include <stdexcept>
#include <string>

#include "core/units.hpp"
#include "core/nan.hpp"

namespace shudder::studies {

namespace {

void check_operating_point(double force_N, double slip_rpm, double temp_C) {
  if (!(std::isfinite(force_N) && force_N > 0))
    throw std::invalid_argument("stability: normal force must be finite and > 0 N (got " + std::to_string(force_N) +
                                ")");
  if (!std::isfinite(slip_rpm)) throw std::invalid_argument("stability: slip speed must be finite (rpm)");
  if (!std::isfinite(temp_C)) throw std::invalid_argument("stability: interface temperature must be finite (degC)");
}

// Constant force, constant speed: the cycle the linearisation is about.
components::DriveCycle steady_cycle(double force_N, double slip_rpm) {
  return {components::PiecewiseLinear({0.0}, {slip_rpm}), components::PiecewiseLinear({0.0}, {force_N})};
}

// Every ring at temp_C, the force of `rig`'s cycle.
components::ClutchHeldInputs uniform_inputs(const rig_models::LsctrRig& rig, const clutch::WetClutch& clutch,
                                            double temp_C) {
  components::ClutchHeldInputs in = rig.start_inputs();
  in.ring_temp_C = Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), temp_C);
  return in;
}

// Steady clutch torque above the motor's limit: the speed loop cannot hold the slip.
bool motor_saturates(const rig_models::LsctrRig& rig, components::ClutchContext& clutch, double slip_rad_s,
                     double t_s) {
  if (slip_rad_s == 0.0) return false;  // stuck: the torque is whatever the bar carries
  return rig.clutch_contact().kinetic_torque_Nm(clutch, std::abs(slip_rad_s), t_s) > rig.params().motor_torque_limit_Nm;
}

StabilityPoint linearise_rig(const dynamics::TorsionalNetwork& network, double slip_rad_s, double t_s) {
  analysis::SteadySliding steady;
  steady.slip_rad_s = {slip_rad_s};
  steady.t_s = t_s;
  return analysis::linearise(network, steady);
}

// The stability of `network` (the rig's, its clutch law bound to `clutch`) at one slip.
StabilityPoint stability_at(const rig_models::LsctrRig& rig, components::ClutchContext& clutch,
                            const dynamics::TorsionalNetwork& network, double slip_rpm, double t_s = 0.0) {
  const double slip = units::rpm_to_rad_s(slip_rpm);
  if (motor_saturates(rig, clutch, slip, t_s))
    throw std::invalid_argument("stability: the clutch torque " +
                                std::to_string(rig.clutch_contact().kinetic_torque_Nm(clutch, std::abs(slip), t_s)) +
                                " N m at " + std::to_string(slip_rpm) + " rpm exceeds the motor's limit of " +
                                std::to_string(rig.params().motor_torque_limit_Nm) +
                                " N m, so there is no steady sliding to linearise about; lower the normal force");
  return linearise_rig(network, slip, t_s);
}

}  // namespace

StabilityPoint rig_stability(const rig_models::LsctrRig& rig, const components::ClutchHeldInputs& clutch_inputs,
                             double slip_rpm, double t_s) {
  const components::OwnedNetwork built = rig.build();
  built.clutch_context() = components::ClutchContext(clutch_inputs);
  return stability_at(rig, built.clutch_context(), built.network(), slip_rpm, t_s);
}

StabilityPoint rig_stability(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                             double slip_rpm, double interface_temp_C) {
  check_operating_point(force_N, slip_rpm, interface_temp_C);
  const rig_models::LsctrRig rig(params, clutch, steady_cycle(force_N, slip_rpm));
  return rig_stability(rig, uniform_inputs(rig, clutch, interface_temp_C), slip_rpm);
}

StabilityMap stability_map(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                           const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C) {
  for (double v : speeds_rpm)
    for (double T : temps_C) check_operating_point(force_N, v, T);
  if (speeds_rpm.empty() || temps_C.empty()) check_operating_point(force_N, 0.0, 0.0);  // still validate the force
  StabilityMap map;
  map.force_N = force_N;
  map.speeds_rpm = speeds_rpm;
  map.temps_C = temps_C;
  const auto ns = static_cast<Eigen::Index>(speeds_rpm.size());
  const auto nt = static_cast<Eigen::Index>(temps_C.size());
  map.margin_per_s.resize(ns, nt);
  map.frequency_Hz.resize(ns, nt);
  map.oscillatory_margin_per_s.resize(ns, nt);
  map.oscillatory_frequency_Hz.resize(ns, nt);

  // One rig: the speed reference only feeds the motor's steady state, not its linear loop.
  const rig_models::LsctrRig rig(params, clutch, steady_cycle(force_N, speeds_rpm.empty() ? 0.0 : speeds_rpm.front()));
  const components::OwnedNetwork built = rig.build();
  components::ClutchContext* context = &built.clutch_context();
  const dynamics::TorsionalNetwork& network = built.network();
  // Temperatures outside: setting them rebuilds the law's frozen friction once per column.
  for (Eigen::Index j = 0; j < nt; ++j) {
    context->set_ring_temperatures(
        Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), temps_C[static_cast<std::size_t>(j)]));
    for (Eigen::Index i = 0; i < ns; ++i) {
      const double slip = units::rpm_to_rad_s(speeds_rpm[static_cast<std::size_t>(i)]);
      if (motor_saturates(rig, *context, slip, 0.0)) {
        map.margin_per_s(i, j) = map.frequency_Hz(i, j) = kNaN;
        map.oscillatory_margin_per_s(i, j) = map.oscillatory_frequency_Hz(i, j) = kNaN;
        continue;
      }
      const StabilityPoint p = linearise_rig(network, slip, 0.0);
      map.margin_per_s(i, j) = p.margin_per_s;
      map.frequency_Hz(i, j) = p.frequency_Hz;
      map.oscillatory_margin_per_s(i, j) = p.oscillatory_margin_per_s;
      map.oscillatory_frequency_Hz(i, j) = p.oscillatory_frequency_Hz;
    }
  }
  return map;
}

double critical_bar_damping_ratio(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                                  double slip_rpm, double interface_temp_C, double max_ratio) {
  check_operating_point(force_N, slip_rpm, interface_temp_C);
  if (!(std::isfinite(max_ratio) && max_ratio > 0))
    throw std::invalid_argument("critical bar damping: the bracket's upper ratio must be finite and > 0");
  // Hold the bar's stiffness at that of the given parameters while the damping changes.
  rig_models::RigParams p = params;
  p.bar_stiffness_Nm_per_rad =
      rig_models::LsctrRig(params, clutch, steady_cycle(force_N, slip_rpm)).bar_stiffness_Nm_per_rad();
  const rig_models::LsctrRig rig(p, clutch, steady_cycle(force_N, slip_rpm));
  const components::ClutchHeldInputs inputs = uniform_inputs(rig, clutch, interface_temp_C);
  const auto margin = [&](double zeta) {
    const components::OwnedNetwork built = rig.build(zeta);
    built.clutch_context() = components::ClutchContext(inputs);
    return stability_at(rig, built.clutch_context(), built.network(), slip_rpm).margin_per_s;
  };
  if (margin(0.0) <= 0.0) return 0.0;
  if (margin(max_ratio) > 0.0) return std::numeric_limits<double>::infinity();
  // Invariant: unstable at lo, stable at hi.
  double lo = 0.0, hi = max_ratio;
  while (hi - lo > 1e-12) {
    const double mid = 0.5 * (lo + hi);
    (margin(mid) > 0.0 ? lo : hi) = mid;
  }
  return 0.5 * (lo + hi);
}

CriticalBar critical_bar(const rig_models::RigParams& params, const clutch::WetClutch& clutch, double force_N,
                         double slip_rpm, double interface_temp_C, double lo_Hz, double hi_Hz) {
  check_operating_point(force_N, slip_rpm, interface_temp_C);
  if (!(std::isfinite(lo_Hz) && std::isfinite(hi_Hz) && lo_Hz > 0 && hi_Hz > lo_Hz))
    throw std::invalid_argument("critical bar: the frequency bracket needs 0 < lo_Hz < hi_Hz (finite)");
  // The bar is given by its frequency (stiffness derived from the modal analysis).
  rig_models::RigParams p = params;
  p.bar_stiffness_Nm_per_rad = 0.0;
  const components::DriveCycle cycle = steady_cycle(force_N, slip_rpm);
  std::optional<components::ClutchHeldInputs> inputs;  // the operating point, made with the first rig
  const auto unstable = [&](double f) {
    p.bar_natural_frequency_Hz = f;
    const rig_models::LsctrRig rig(p, clutch, cycle);
    if (!inputs) inputs = uniform_inputs(rig, clutch, interface_temp_C);
    const components::OwnedNetwork built = rig.build();
    built.clutch_context() = components::ClutchContext(*inputs);
    return stability_at(rig, built.clutch_context(), built.network(), slip_rpm).margin_per_s > 0.0;
  };
  const bool lo_unstable = unstable(lo_Hz);
  if (unstable(hi_Hz) == lo_unstable) return {kNaN, kNaN};
  // Invariant: the state at lo is lo_unstable, the other at hi.
  double lo = lo_Hz, hi = hi_Hz;
  while (hi - lo > 1e-10 * hi) {
    const double mid = 0.5 * (lo + hi);
    (unstable(mid) == lo_unstable ? lo : hi) = mid;
  }
  p.bar_natural_frequency_Hz = 0.5 * (lo + hi);
  const rig_models::LsctrRig rig(p, clutch, steady_cycle(force_N, slip_rpm));
  return {rig.clutch_side_frequency_Hz(), rig.bar_stiffness_Nm_per_rad()};
}

}  // namespace shudder::studies
