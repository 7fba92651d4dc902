#include "studies/driveline_stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "clutch/fluid.hpp"
#include "clutch/interface_thermal_impedance.hpp"
#include "core/units.hpp"
#include "dynamics/signal_names.hpp"

namespace shudder::studies {

namespace {

using D = rig_models::HaldexDriveline;

// The rear group's nodes: they turn with coupling_out.
constexpr std::array<int, 6> kRearGroup{D::kCouplingOut,   D::kRearDiff,      D::kRearSideLeft,
                                        D::kRearSideRight, D::kRearLeftWheel, D::kRearRightWheel};

bool in_rear_group(int node) {
  for (int r : kRearGroup)
    if (r == node) return true;
  return false;
}

// Node speeds: everything rolling with V, the rear group scaled so that the coupling slips by Δω.
Eigen::VectorXd rolling_node_speeds(const rig_models::HaldexDriveline& dl, double speed_m_s, double slip_rad_s) {
  const Eigen::VectorXd s = dl.rolling_speed_ratios();
  const double wv = speed_m_s / dl.params().wheel_radius_m;
  Eigen::VectorXd w = s * wv;
  const double out = w[D::kCouplingIn] - slip_rad_s;
  const double scale = w[D::kCouplingOut] != 0.0 ? out / w[D::kCouplingOut] : 0.0;
  for (int node : kRearGroup) w[node] = w[D::kCouplingOut] != 0.0 ? w[node] * scale : 0.0;
  if (w[D::kCouplingOut] == 0.0 && slip_rad_s != 0.0) {
    // At rest: the slip appears on the rear group alone (its wheels turning backwards).
    const Eigen::VectorXd s_rear = s / s[D::kCouplingOut];
    for (int node : kRearGroup) w[node] = -slip_rad_s * s_rear[node];
  }
  return w;
}

// A tyre's load when the car accelerates steadily at a (m/s²): its static load and transfer.
double tyre_load_N(const components::BrushTyre& tyre, double vehicle_speed_m_s, double acceleration_m_s2) {
  std::array<double, 3> z{};
  tyre.steady_states(0.0, vehicle_speed_m_s, acceleration_m_s2, z.data());
  return tyre.vertical_load_N(z.data());
}

// The tyre deflection u that carries force F on the brush curve at load F_z (the edge if saturated).
double tyre_deflection_m(const components::BrushTyre& tyre, double force_N, double vertical_load_N) {
  const double limit = tyre.params().road_friction * vertical_load_N;
  const double frac = std::min(std::abs(force_N) / limit, 0.999);
  const double a = 1.0 - std::cbrt(1.0 - frac);
  return std::copysign(a * 3.0 * limit / tyre.carcass_stiffness_N_per_m(), force_N);
}

// The car's acceleration (m/s²) the tyre forces of a point give it (the vehicle node's balance:
// m a = Σ ρ_i F_i − road load + grade force).
double operating_acceleration_m_s2(const rig_models::HaldexDriveline& dl, const DrivelineOperatingPoint& op) {
  double sum_N = 0.0;
  for (int w = 0; w < 4; ++w)
    sum_N += dl.path_ratios()[static_cast<std::size_t>(w)] * op.tyre_force_N[static_cast<std::size_t>(w)];
  const double r = dl.params().wheel_radius_m;
  return (sum_N - dl.road_load().force_N(op.vehicle_speed_m_s) + dl.grade_torque_Nm() / r) /
         dl.params().vehicle_mass_kg;
}

}  // namespace

DrivelineOperatingPoint quasi_static_operating_point(const rig_models::HaldexDriveline& dl,
                                                     const clutch::WetClutch& clutch,
                                                     const rig_models::DrivelineInputs& inputs, double min_slip_rpm,
                                                     double clamp_force_N) {
  const rig_models::DrivelineParams& p = dl.params();
  DrivelineOperatingPoint op;
  op.t_s = 0.0;
  op.vehicle_speed_m_s = inputs.start_speed_km_h / 3.6;
  op.interface_temp_C = clutch.params().start_temp_C;
  const Eigen::VectorXd s = dl.rolling_speed_ratios();
  const double r = p.wheel_radius_m, wv = op.vehicle_speed_m_s / r;
  const double min_slip = units::rpm_to_rad_s(min_slip_rpm);
  const auto floor_slip = [&](double slip) {
    return std::abs(slip) >= min_slip ? slip : std::copysign(min_slip, slip);
  };
  const components::OwnedNetwork built = dl.build();
  built.clutch_context().set_ring_temperatures(
      Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), op.interface_temp_C));
  const dynamics::TorsionalNetwork& net = built.network();
  double j_eq = 0.0, j_front = 0.0, j_rear = 0.0;
  for (int i = 0; i < D::kNodes; ++i) {
    const double j = net.inertias()[static_cast<std::size_t>(i)].inertia_kg_m2;
    j_eq += j * s[i] * s[i];
    if (i == D::kVehicle) continue;
    if (in_rear_group(i))
      j_rear += j * (s[i] / s[D::kRearDiff]) * (s[i] / s[D::kRearDiff]);
    else
      j_front += j * (s[i] / s[D::kFrontDiff]) * (s[i] / s[D::kFrontDiff]);
  }

  // Fixed point: slip → clamp force and coupling torque → tyre forces → tyre slips → wheel
  // speeds → slip (the tyres' slip takes part of the turn's kinematic slip; converges in a few
  // rounds because the tyres' slip per newton is small).
  Eigen::VectorXd w = s * wv;
  const clutch::WaltherViscosity viscosity(clutch.fluid().nu40_cSt, clutch.fluid().nu100_cSt);
  op.coupling_slip_rad_s = floor_slip((s[D::kCouplingIn] - s[D::kCouplingOut]) * wv);
  for (int round = 0; round < 50; ++round) {
    // The steady pressure at that slip: the pump–valve–leak balance at the valve's opening (the
    // manoeuvre's or the controller's at these speeds), below the valve's setting or relief.
    dynamics::Sample at;
    at.omega_rad_s = w;
    const double leak_scale = viscosity.kinematic_cSt(40.0) / viscosity.kinematic_cSt(op.interface_temp_C);
    const double opening = dl.valve_opening(at);
    const double p_bar = dl.hydraulics().steady_pressure_bar(std::abs(op.coupling_slip_rad_s), opening, leak_scale,
                                                             dl.valve_setting_bar(0.0));
    op.clamp_force_N = std::isfinite(clamp_force_N) ? clamp_force_N : dl.hydraulics().clamp_force_N(p_bar);
    // The coupling law reads its clamp force from its pressure state.
    const Eigen::VectorXd z = dl.coupling_states(op.clamp_force_N, opening);
    const double m_c = std::copysign(
        net.contacts()[D::kCoupling].law->kinetic_torque_Nm(std::abs(op.coupling_slip_rad_s), 0.0, z.data()),
        op.coupling_slip_rad_s);
    const double t_engine = dl.engine_torque_Nm(0.0, w[D::kEngine]);
    // The car accelerating as one body: J_eq ω̇_v = engine and grade power − coupling loss − road load.
    const double road_N = dl.road_load().force_N(op.vehicle_speed_m_s);
    const double dwv = (t_engine * s[D::kEngine] + dl.grade_torque_Nm() -
                        m_c * (s[D::kCouplingIn] - s[D::kCouplingOut]) - road_N * r) /
                       j_eq;
    // Each axle group's torque balance about its carrier gives its two (equal) tyre forces.
    const double front_axle_Nm =
        t_engine * p.gear_ratio * p.final_drive_ratio - m_c * p.ptu_ratio - j_front * s[D::kFrontDiff] * dwv;
    const double rear_axle_Nm = m_c * p.rear_diff_ratio - j_rear * s[D::kRearDiff] * dwv;
    op.tyre_force_N = {front_axle_Nm / (2 * r), front_axle_Nm / (2 * r), rear_axle_Nm / (2 * r),
                       rear_axle_Nm / (2 * r)};
    // Wheel speeds from the steady slips κ = (ω r − V)/max(|V|, |ω r|) (components/tyre.hpp).
    const std::array<int, 4> wheel{D::kFrontLeftWheel, D::kFrontRightWheel, D::kRearLeftWheel, D::kRearRightWheel};
    const std::array<int, 4> side{D::kFrontSideLeft, D::kFrontSideRight, D::kRearSideLeft, D::kRearSideRight};
    for (int i = 0; i < 4; ++i) {
      const auto& tyre = dl.tyre(i);
      const double fz = tyre_load_N(tyre, op.vehicle_speed_m_s, dwv * r);
      const double kappa =
          tyre_deflection_m(tyre, op.tyre_force_N[static_cast<std::size_t>(i)], fz) / tyre.relaxation_length_m(fz);
      const double ground = s[wheel[static_cast<std::size_t>(i)]] * wv;
      w[wheel[static_cast<std::size_t>(i)]] = w[side[static_cast<std::size_t>(i)]] =
          kappa >= 0 ? ground / (1.0 - kappa) : ground * (1.0 + kappa);
    }
    w[D::kFrontDiff] = 0.5 * (w[D::kFrontLeftWheel] + w[D::kFrontRightWheel]);
    w[D::kRearDiff] = 0.5 * (w[D::kRearLeftWheel] + w[D::kRearRightWheel]);
    w[D::kEngine] = p.gear_ratio * p.final_drive_ratio * w[D::kFrontDiff];
    w[D::kPtu] = w[D::kCouplingIn] = p.ptu_ratio * w[D::kFrontDiff];
    w[D::kCouplingOut] = p.rear_diff_ratio * w[D::kRearDiff];
    const double slip = floor_slip(w[D::kCouplingIn] - w[D::kCouplingOut]);
    const bool converged = std::abs(slip - op.coupling_slip_rad_s) <= 1e-12 * std::max(1.0, std::abs(slip));
    op.coupling_slip_rad_s = slip;
    if (converged) break;
  }
  // The slip floor (a straight run or rest) puts the difference on the rear group.
  op.node_speeds_rad_s = w;
  const double out = w[D::kCouplingIn] - op.coupling_slip_rad_s;
  if (w[D::kCouplingOut] != 0.0) {
    const double scale = out / w[D::kCouplingOut];
    for (int node : kRearGroup) op.node_speeds_rad_s[node] *= scale;
  } else {
    op.node_speeds_rad_s = rolling_node_speeds(dl, op.vehicle_speed_m_s, op.coupling_slip_rad_s);
  }
  return op;
}

DrivelineOperatingPoint sample_operating_point(const rig_models::HaldexDriveline& dl, const dynamics::Sample& s,
                                               double clamp_force_N, double interface_temp_C) {
  DrivelineOperatingPoint op;
  op.t_s = s.t_s;
  op.node_speeds_rad_s = s.omega_rad_s;
  op.vehicle_speed_m_s = s.omega_rad_s[D::kVehicle] * dl.params().wheel_radius_m;
  op.coupling_slip_rad_s = s.contact_slip_rad_s[D::kCoupling];
  op.clamp_force_N = clamp_force_N;
  op.interface_temp_C = interface_temp_C;
  for (int w = 0; w < 4; ++w)
    op.tyre_force_N[static_cast<std::size_t>(w)] = s.element_torque_Nm[w] / dl.params().wheel_radius_m;
  return op;
}

DrivelineOperatingPoint recorded_operating_point(const dynamics::Recording& rec, double from_s, double to_s) {
  namespace sn = dynamics::signal_names;
  const dynamics::Signal* time = rec.find(sn::kTime);
  if (!time) throw std::invalid_argument("driveline operating point: the recording has no time channel");
  const auto mean = [&](std::string_view name) {
    const dynamics::Signal* sig = rec.find(name);
    if (!sig)
      throw std::invalid_argument("driveline operating point: the recording has no '" + std::string(name) + "'");
    double sum = 0.0;
    int count = 0;
    for (std::size_t i = 0; i < time->values.size(); ++i)
      if (time->values[i] >= from_s && time->values[i] <= to_s) {
        sum += sig->values[i];
        ++count;
      }
    if (count == 0) throw std::invalid_argument("driveline operating point: no sample in the window");
    return sum / count;
  };
  DrivelineOperatingPoint op;
  op.t_s = to_s;
  op.vehicle_speed_m_s = mean(sn::kVehicleSpeed) / 3.6;
  op.coupling_slip_rad_s = units::rpm_to_rad_s(mean(sn::kCouplingSlip));
  op.clamp_force_N = mean(sn::kClampForce);
  op.interface_temp_C = mean(sn::kInterfaceMeanTemp);
  op.tyre_force_N = {mean(sn::kTyreForceFL), mean(sn::kTyreForceFR), mean(sn::kTyreForceRL), mean(sn::kTyreForceRR)};
  return op;
}

namespace {

// The linear system of driveline_stability (see there), with the network's node names.
dynamics::LinearSystem linearise_driveline(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                           const DrivelineOperatingPoint& op, bool coupling_locked,
                                           const Eigen::MatrixXd& extra_damping, std::vector<std::string>* node_names) {
  if (!std::isfinite(op.clamp_force_N) || !(op.clamp_force_N > 0))
    throw std::invalid_argument("driveline stability: the clamp force must be a finite value > 0 N");
  if (!std::isfinite(op.interface_temp_C) || !std::isfinite(op.vehicle_speed_m_s) ||
      !std::isfinite(op.coupling_slip_rad_s) || !std::isfinite(op.t_s))
    throw std::invalid_argument("driveline stability: the operating point must be finite");
  const components::OwnedNetwork built = dl.build();
  built.clutch_context().set_ring_temperatures(
      Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), op.interface_temp_C));
  const dynamics::TorsionalNetwork& net = built.network();

  dynamics::LinearOperatingPoint lop;
  lop.t_s = op.t_s;
  lop.omega_rad_s = op.node_speeds_rad_s.size() == D::kNodes
                        ? op.node_speeds_rad_s
                        : rolling_node_speeds(dl, op.vehicle_speed_m_s, op.coupling_slip_rad_s);
  if (coupling_locked) {
    // Locked: both halves at their mean speed (the constraint holds them together).
    const double mean = 0.5 * (lop.omega_rad_s[D::kCouplingIn] + lop.omega_rad_s[D::kCouplingOut]);
    const double scale = lop.omega_rad_s[D::kCouplingOut] != 0.0 ? mean / lop.omega_rad_s[D::kCouplingOut] : 1.0;
    for (int node : kRearGroup) lop.omega_rad_s[node] *= scale;
  }
  // The tyres' states (their deflections, and the load transfer's lags behind the point's
  // acceleration), then the road load's (none).
  const double accel = operating_acceleration_m_s2(dl, op);
  std::vector<double> tyre_states;
  for (int w = 0; w < 4; ++w) {
    const auto& tyre = dl.tyre(w);
    std::array<double, 3> z{};
    tyre.steady_states(0.0, op.vehicle_speed_m_s, accel, z.data());
    z[0] = tyre_deflection_m(tyre, op.tyre_force_N[static_cast<std::size_t>(w)], tyre.vertical_load_N(z.data()));
    tyre_states.insert(tyre_states.end(), z.begin(), z.begin() + tyre.states());
  }
  lop.element_states =
      Eigen::Map<const Eigen::VectorXd>(tyre_states.data(), static_cast<Eigen::Index>(tyre_states.size()));
  lop.stuck = {coupling_locked};
  lop.extra_damping = extra_damping;
  {
    // The coupling's pressure and valve: at the clamp force's pressure, except where that is the
    // cap itself (a raw setting, or the relief) while the slip pumps: there the pump's flow
    // passes the relief valve, and the pressure sits on its active side, at the steady pressure.
    dynamics::Sample at;
    at.omega_rad_s = lop.omega_rad_s;
    const double opening = dl.valve_opening(at);
    lop.contact_states = dl.coupling_states(op.clamp_force_N, opening);
    double& p_bar = lop.contact_states[components::HaldexCouplingLaw::kPressure];
    const double cap_bar = std::min(dl.valve_setting_bar(op.t_s), dl.params().hydraulics.relief_pressure_bar);
    if (!coupling_locked && std::abs(p_bar - cap_bar) <= 1e-9 * cap_bar) {
      const clutch::WaltherViscosity viscosity(clutch.fluid().nu40_cSt, clutch.fluid().nu100_cSt);
      const double leak_scale = viscosity.kinematic_cSt(40.0) / viscosity.kinematic_cSt(op.interface_temp_C);
      p_bar = std::max(p_bar, dl.hydraulics().steady_pressure_bar(std::abs(op.coupling_slip_rad_s), opening, leak_scale,
                                                                  dl.valve_setting_bar(op.t_s)));
    }
  }
  if (node_names)
    for (const auto& in : net.inertias()) node_names->push_back(in.name);
  return dynamics::linearise_network(net, lop);
}

}  // namespace

DrivelineStability driveline_stability(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                       const DrivelineOperatingPoint& op, bool coupling_locked,
                                       const Eigen::MatrixXd& extra_damping) {
  DrivelineStability st;
  st.system = linearise_driveline(dl, clutch, op, coupling_locked, extra_damping, &st.node_names);
  st.modes = dynamics::linear_modes(st.system);
  st.coupling_slope_Nms = st.system.contact_slope_Nms[D::kCoupling];
  Eigen::EigenSolver<Eigen::MatrixXd> es(st.system.a, false);
  st.point = analysis::stability_from_eigenvalues(es.eigenvalues(), st.system.rigid_body_modes);
  return st;
}

CouplingMode least_damped_slipping_mode(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                        const DrivelineOperatingPoint& op, const Eigen::MatrixXd& extra_damping) {
  DrivelineStability st;
  st.system = linearise_driveline(dl, clutch, op, false, extra_damping, nullptr);
  st.modes = dynamics::linear_modes(st.system, false);
  return least_damped_mode(st);
}

CouplingMode least_damped_mode(const DrivelineStability& st) {
  const double nan = std::numeric_limits<double>::quiet_NaN();
  CouplingMode best{nan, nan, nan};
  for (const auto& m : st.modes) {
    if (m.eigenvalue.imag() <= 0) continue;
    if (std::isnan(best.growth_per_s) || m.eigenvalue.real() > best.growth_per_s)
      best = {m.eigenvalue.real(), m.frequency_Hz, m.damping_ratio};
  }
  return best;
}

ThermalFeedback coupling_thermal_feedback(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                          const DrivelineOperatingPoint& op, double frequency_Hz) {
  const int n_rings = clutch.thermal().radial_cells();
  const components::OwnedNetwork built = dl.build();
  components::ClutchContext* ctx = &built.clutch_context();
  const auto& law = *built.network().contacts()[D::kCoupling].law;
  const double slip = std::abs(op.coupling_slip_rad_s);
  const Eigen::VectorXd z = dl.coupling_states(op.clamp_force_N, 1.0);
  const auto torque_at = [&](double temp_C) {
    ctx->set_ring_temperatures(Eigen::VectorXd::Constant(n_rings, temp_C));
    return law.kinetic_torque_Nm(slip, op.t_s, z.data());
  };
  ThermalFeedback fb;
  fb.frequency_Hz = frequency_Hz;
  fb.torque_temperature_slope_Nm_per_K = torque_at(op.interface_temp_C + 0.5) - torque_at(op.interface_temp_C - 0.5);
  fb.coupling_torque_Nm = torque_at(op.interface_temp_C);
  fb.isothermal_slope_Nms = law.kinetic_torque_slope_Nms(slip, op.t_s, z.data());
  fb.impedance_m2K_per_W = clutch::interface_thermal_impedance(clutch.thermal().params(), units::kTwoPi * frequency_Hz);
  const double n = clutch.params().sliding_interfaces, area = clutch.thermal().contact_area_m2();
  const std::complex<double> gz = fb.torque_temperature_slope_Nm_per_K / n * fb.impedance_m2K_per_W / area;
  fb.effective_slope_Nms = n * (fb.isothermal_slope_Nms / n + gz * fb.coupling_torque_Nm / n) / (1.0 - gz * slip);
  fb.added_damping_Nms = fb.effective_slope_Nms.real() - fb.isothermal_slope_Nms;
  return fb;
}

CouplingMode least_damped_mode_with_thermal(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                            const DrivelineOperatingPoint& op) {
  CouplingMode mode = least_damped_slipping_mode(dl, clutch, op);
  for (int round = 0; round < 2 && std::isfinite(mode.frequency_Hz) && mode.frequency_Hz > 0; ++round) {
    const double added = coupling_thermal_feedback(dl, clutch, op, mode.frequency_Hz).added_damping_Nms;
    Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(D::kNodes, D::kNodes);
    extra(D::kCouplingIn, D::kCouplingIn) = extra(D::kCouplingOut, D::kCouplingOut) = added;
    extra(D::kCouplingIn, D::kCouplingOut) = extra(D::kCouplingOut, D::kCouplingIn) = -added;
    mode = least_damped_slipping_mode(dl, clutch, op, extra);
  }
  return mode;
}

double onset_clamp_force_N(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                           const rig_models::DrivelineInputs& inputs, double lo_N, double hi_N, bool thermal) {
  const auto growth = [&](double force_N) {
    const auto op = quasi_static_operating_point(dl, clutch, inputs, 1.0, force_N);
    return (thermal ? least_damped_mode_with_thermal(dl, clutch, op) : least_damped_slipping_mode(dl, clutch, op))
        .growth_per_s;
  };
  double g_lo = growth(lo_N);
  const double g_hi = growth(hi_N);
  if (!(g_lo * g_hi < 0)) return std::numeric_limits<double>::quiet_NaN();
  while (hi_N - lo_N > 1e-6 * hi_N) {
    const double mid = 0.5 * (lo_N + hi_N), g = growth(mid);
    if ((g < 0) == (g_lo < 0)) {
      lo_N = mid;
      g_lo = g;
    } else {
      hi_N = mid;
    }
  }
  return 0.5 * (lo_N + hi_N);
}

std::vector<dynamics::Map2D> coupling_stability_maps(const rig_models::HaldexDriveline& dl,
                                                     const clutch::WetClutch& clutch, const DrivelineOperatingPoint& op,
                                                     const std::vector<double>& slips_rpm,
                                                     const std::vector<double>& temps_C,
                                                     const std::vector<double>& forces_N) {
  if (slips_rpm.size() < 2 || temps_C.size() < 2 || forces_N.empty())
    throw std::invalid_argument("coupling stability map: at least 2 slips, 2 temperatures and 1 force");
  std::vector<dynamics::Map2D> maps;
  const auto n_s = static_cast<Eigen::Index>(slips_rpm.size()), n_t = static_cast<Eigen::Index>(temps_C.size());
  for (std::size_t k = 0; k < forces_N.size(); ++k) {
    dynamics::Map2D m;
    m.name = "coupling_stability_map_" + std::to_string(k + 1);
    m.description =
        "driveline: least-damped oscillatory mode of the slipping coupling over slip x interface "
        "temperature at one clamp force (isothermal slope; studies/driveline_stability.hpp)";
    m.x_name = "slip_rpm";
    m.x_units = "rpm";
    m.x = slips_rpm;
    m.y_name = "interface_temp_C";
    m.y_units = "degC";
    m.y = temps_C;
    Eigen::MatrixXd growth(n_s, n_t), freq(n_s, n_t), zeta(n_s, n_t);
    for (Eigen::Index i = 0; i < n_s; ++i)
      for (Eigen::Index j = 0; j < n_t; ++j) {
        DrivelineOperatingPoint p = op;
        p.node_speeds_rad_s = Eigen::VectorXd();
        p.coupling_slip_rad_s = std::copysign(units::rpm_to_rad_s(slips_rpm[static_cast<std::size_t>(i)]),
                                              op.coupling_slip_rad_s == 0.0 ? 1.0 : op.coupling_slip_rad_s);
        p.interface_temp_C = temps_C[static_cast<std::size_t>(j)];
        p.clamp_force_N = forces_N[k];
        const CouplingMode mode = least_damped_slipping_mode(dl, clutch, p);
        growth(i, j) = mode.growth_per_s;
        freq(i, j) = mode.frequency_Hz;
        zeta(i, j) = mode.damping_ratio;
      }
    m.layers = {{"growth_per_s", "1/s", growth}, {"frequency_Hz", "Hz", freq}, {"damping_ratio", "1", zeta}};
    m.scalars = {{"normal_force_N", "N", forces_N[k]}, {"vehicle_speed_km_h", "km/h", op.vehicle_speed_m_s * 3.6}};
    maps.push_back(std::move(m));
  }
  return maps;
}

Prediction predict_driveline(const rig_models::DrivelineParams& params, const clutch::WetClutch& clutch,
                             const rig_models::DrivelineInputs& inputs, const dynamics::Recording& rec,
                             const OperatingWindow& w) {
  try {
    const DrivelineOperatingPoint op = recorded_operating_point(rec, w.from_s, w.to_s);
    if (!(std::abs(units::rad_s_to_rpm(op.coupling_slip_rad_s)) >= 0.1))
      return Prediction::none("the coupling was stuck over the judged window");
    if (!(op.clamp_force_N > 0)) return Prediction::none("the coupling is not clamped over the judged window");
    const rig_models::HaldexDriveline dl(params, clutch, inputs);
    const DrivelineStability st = driveline_stability(dl, clutch, op, false);
    const CouplingMode least = least_damped_mode(st);
    Prediction out;
    out.made = true;
    out.method =
        "driveline linear stability at the window's mean point (coupling slipping, isothermal friction slope, "
        "tyre relaxation; studies/driveline_stability.hpp)";
    out.margin_per_s = st.point.margin_per_s;
    out.oscillatory_margin_per_s = least.growth_per_s;
    out.frequency_Hz = least.frequency_Hz;
    return out;
  } catch (const std::invalid_argument& e) {
    return Prediction::none(e.what());
  }
}

LockedShuffle run_shuffle_mode(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                               const dynamics::Recording& rec, double to_s) {
  constexpr double kRollingBelow_Hz = 0.5;  // the car's rolling (a rigid-body pair) is no shuffle
  const double nan = std::numeric_limits<double>::quiet_NaN();
  try {
    const DrivelineOperatingPoint op = recorded_operating_point(rec, 0.0, to_s);
    const DrivelineStability st = driveline_stability(dl, clutch, op, true);
    for (const auto& m : st.modes)  // sorted by frequency
      if (m.eigenvalue.imag() > 0 && m.frequency_Hz > kRollingBelow_Hz) return {m.frequency_Hz, m.damping_ratio};
  } catch (const std::invalid_argument&) {
  }
  return {nan, nan};
}

}  // namespace shudder::studies
