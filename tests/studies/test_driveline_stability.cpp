// The driveline's linearisation (studies/driveline_stability.hpp): against a finite-difference
// Jacobian of the nonlinear right-hand side, the undamped modes at rest, a two-inertia reduction,
// and the locked/slipping mode count.
#include "studies/driveline_stability.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <numbers>

#include "io/fluid_loader.hpp"
#include "rig_models/model.hpp"
#include "io/scenario.hpp"

namespace shudder::studies {

// The machines these studies are made of.
using namespace rig_models;

namespace {

using D = HaldexDriveline;

io::Scenario tight_turn() {
  return io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml");
}

// The take-up case of docs/driveline.md: ρ = 1.1 from 10 km/h, no engine torque, valve 3 bar.
DrivelineInputs take_up_inputs() {
  DrivelineInputs in;
  in.start_speed_km_h = 10.0;
  in.valve_pressure_bar = components::PiecewiseLinear({0.0}, {3.0});
  return in;
}

// The nonlinear right-hand side in the linearisation's coordinates x = [q; v; z; z_c] about ω₀
// (ω = ω₀ + N v, θ = N q; z_c the contact laws' states about `contact_z`): every element's torque
// from its own law, projected by Nᵀ, and every state's rate.
Eigen::VectorXd nonlinear_rhs(const dynamics::TorsionalNetwork& net, const dynamics::LinearSystem& sys,
                              const Eigen::VectorXd& w0, const Eigen::VectorXd& z0, const Eigen::VectorXd& contact_z,
                              double t, const Eigen::VectorXd& x) {
  const int r = sys.reduced_dofs, n = net.nodes();
  const Eigen::MatrixXd& nb = sys.basis;
  const Eigen::VectorXd theta = nb * x.head(r);
  const Eigen::VectorXd w = w0 + nb * x.segment(r, r);
  const Eigen::VectorXd z = z0 + x.segment(2 * r, sys.element_states);
  const Eigen::VectorXd zc = contact_z + x.tail(sys.contact_states);
  Eigen::VectorXd zc_dot = Eigen::VectorXd::Zero(sys.contact_states);
  Eigen::VectorXd tau = Eigen::VectorXd::Zero(n);
  const auto at = [](const Eigen::VectorXd& v, int i) { return i == dynamics::kGround ? 0.0 : v[i]; };
  const auto apply = [&](int a, int b, double ta, double tb) {
    tau[a] += ta;
    if (b != dynamics::kGround) tau[b] += tb;
  };
  for (const auto& s : net.shafts()) {
    const double tq =
        s.stiffness_Nm_per_rad * (at(theta, s.a) - at(theta, s.b)) + s.damping_Nms_per_rad * (at(w, s.a) - at(w, s.b));
    apply(s.a, s.b, -tq, tq);
  }
  const std::vector<int> contact_z_at = net.contact_state_indices();
  std::size_t ci = 0;
  for (const auto& c : net.contacts()) {
    const double dw = at(w, c.a) - at(w, c.b);
    const double tq = std::copysign(c.law->kinetic_torque_Nm(std::abs(dw), t, zc.data() + contact_z_at[ci]), dw);
    c.law->state_rates(dw, t, zc.data() + contact_z_at[ci], zc_dot.data() + contact_z_at[ci]);
    ++ci;
    apply(c.a, c.b, -tq, tq);
  }
  for (const auto& src : net.torque_sources())
    tau[src.node] += src.torque_at_speed_Nm ? src.torque_at_speed_Nm(t, w[src.node]) : src.torque_Nm(t);
  Eigen::VectorXd zdot(sys.element_states);
  int off = 0;
  for (const auto& e : net.force_elements()) {
    // A periodic forcing (the engine's firing pulsation) is a disturbance along the motion, not
    // part of the mean motion being linearised (dynamics/network.hpp).
    if (e.law->is_periodic_forcing()) continue;
    const double tq = e.law->evaluate(w[e.a], e.ratio * at(w, e.b), z.data() + off, zdot.data() + off).torque_Nm;
    apply(e.a, e.b, -tq, e.ratio * tq);
    off += e.law->states();
  }
  Eigen::VectorXd f(x.size());
  f.head(r) = x.segment(r, r);
  const Eigen::MatrixXd mr = nb.transpose() * net.mass_matrix() * nb;
  f.segment(r, r) = mr.llt().solve(nb.transpose() * tau);
  f.segment(2 * r, sys.element_states) = zdot;
  f.tail(sys.contact_states) = zc_dot;
  return f;
}

// A, assembled element by element, equals the finite-difference Jacobian of the nonlinear
// right-hand side at a slipping take-up point with a falling friction curve, loaded tyres in a
// turn and a mapped engine (its torque–speed slope): the coupling's slope comes from the law's
// own derivative on one side and from differences of its torque on the other.
TEST(DrivelineStability, MatrixEqualsFiniteDifferenceJacobianOfTheNonlinearRhs) {
  io::Scenario sc = tight_turn();
  sc.clutch.start_temp_C = 60.0;
  auto model = std::get<DrivelineModel>(sc.model);
  model.params.turn_ratio = 1.1;
  DrivelineInputs in = take_up_inputs();
  in.throttle = components::PiecewiseLinear({0.0}, {0.1});
  const clutch::WetClutch clutch(
      sc.clutch, io::load_fluid(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids/schematic_negative_slope.toml"));
  const HaldexDriveline dl(model.params, clutch, in);
  studies::DrivelineOperatingPoint op = studies::quasi_static_operating_point(dl, clutch, in);
  op.vehicle_speed_m_s = 10 / 3.6;
  op.coupling_slip_rad_s = 2.0;  // 19 rpm: on the falling branch
  op.clamp_force_N = 3000.0;
  op.tyre_force_N = {-900.0, -700.0, 1300.0, 1100.0};
  op.node_speeds_rad_s = Eigen::VectorXd();  // rolling with V, the rear group slipping by Δω
  const studies::DrivelineStability st = studies::driveline_stability(dl, clutch, op, false);
  ASSERT_LT(st.coupling_slope_Nms, 0.0);

  const components::OwnedNetwork built = dl.build();
  built.clutch_context().set_ring_temperatures(
      Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), op.interface_temp_C));
  const dynamics::TorsionalNetwork& net = built.network();
  // The same operating point as driveline_stability: its node speeds and tyre deflections.
  Eigen::VectorXd w0(D::kNodes);
  {
    const Eigen::VectorXd s = dl.rolling_speed_ratios() * (op.vehicle_speed_m_s / model.params.wheel_radius_m);
    w0 = s;
    const double scale = (s[D::kCouplingIn] - op.coupling_slip_rad_s) / s[D::kCouplingOut];
    for (int node :
         {D::kCouplingOut, D::kRearDiff, D::kRearSideLeft, D::kRearSideRight, D::kRearLeftWheel, D::kRearRightWheel})
      w0[node] *= scale;
  }
  // Each tyre's states [u, v₁, v₂]: the load transfer's lags behind the point's steady
  // acceleration (the vehicle node's balance, m a = Σ ρ_i F_i − F_road + grade force), u carrying
  // the point's force at that load.
  double sum_N = 0.0;
  for (int i = 0; i < 4; ++i)
    sum_N += dl.path_ratios()[static_cast<std::size_t>(i)] * op.tyre_force_N[static_cast<std::size_t>(i)];
  const double accel =
      (sum_N - dl.road_load().force_N(op.vehicle_speed_m_s) + dl.grade_torque_Nm() / model.params.wheel_radius_m) /
      model.params.vehicle_mass_kg;
  Eigen::VectorXd z0(12);
  for (int i = 0; i < 4; ++i) {
    const auto& tyre = dl.tyre(i);
    ASSERT_EQ(tyre.states(), 3);
    tyre.steady_states(0.0, op.vehicle_speed_m_s, accel, z0.data() + 3 * i);
    const double fz = tyre.vertical_load_N(z0.data() + 3 * i);
    // Invert the brush curve by bisection (independent of the code under test's closed form).
    double lo = -0.05, hi = 0.05;
    for (int it = 0; it < 200; ++it) {
      const double mid = 0.5 * (lo + hi);
      (tyre.force_at_N(mid, fz) < op.tyre_force_N[static_cast<std::size_t>(i)] ? lo : hi) = mid;
    }
    z0[3 * i] = 0.5 * (lo + hi);
  }
  // The coupling's pressure and valve at the operating point (as the linearisation takes them).
  dynamics::Sample at_w0;
  at_w0.omega_rad_s = w0;
  const Eigen::VectorXd coupling_z = dl.coupling_states(op.clamp_force_N, dl.valve_opening(at_w0));
  const Eigen::Index dim = st.system.a.rows();
  Eigen::MatrixXd jac(dim, dim);
  for (Eigen::Index j = 0; j < dim; ++j) {
    // Steps: 1e-7 rad / rad/s for angles and speeds, 1e-9 m for deflections of ~1e-3 m, 1e-7 m/s
    // for the load transfer's lagged speeds, 1e-7 for the coupling's pressure (bar) and valve
    // opening.
    const Eigen::Index elements_begin = 2 * st.system.reduced_dofs;
    const Eigen::Index elements_end = elements_begin + st.system.element_states;
    const bool deflection = j >= elements_begin && j < elements_end && (j - elements_begin) % 3 == 0;
    const double h = deflection ? 1e-9 : 1e-7;
    Eigen::VectorXd xp = Eigen::VectorXd::Zero(dim), xm = xp;
    xp[j] = h;
    xm[j] = -h;
    jac.col(j) = (nonlinear_rhs(net, st.system, w0, z0, coupling_z, op.t_s, xp) -
                  nonlinear_rhs(net, st.system, w0, z0, coupling_z, op.t_s, xm)) /
                 (2 * h);
  }
  // Central differences of O(1e3–1e6) entries: truncation and round-off ~1e-6 of the largest
  // entry of each column.
  for (Eigen::Index j = 0; j < dim; ++j) {
    const double scale = std::max(1.0, jac.col(j).cwiseAbs().maxCoeff());
    EXPECT_LT((jac.col(j) - st.system.a.col(j)).cwiseAbs().maxCoeff(), 1e-5 * scale) << "column " << j;
  }
}

// At rest the tyre's deflection follows the wheel's angle, u = r(θ_w − ρ θ_v): a spring C_κ r²/σ.
// Locked, the linearisation then has the eigenvalues of the network's own modes with the tyres
// as springs (TorsionalNetwork::modes) plus the road load's slope at rest, a damper
// r² F_rr/v_rr on the car (its tanh smoothing): the shuffle mode at 3.71 Hz of docs/driveline.md.
TEST(DrivelineStability, AtRestLockedEqualsTheNetworkModesWithTyreSprings) {
  const io::Scenario sc = tight_turn();
  const auto& model = std::get<DrivelineModel>(sc.model);
  const clutch::WetClutch clutch = sc.make_clutch();
  DrivelineInputs in = model.manoeuvre;
  in.start_speed_km_h = 0.0;
  const HaldexDriveline dl(model.params, clutch, in);
  studies::DrivelineOperatingPoint op;
  op.clamp_force_N = 1000.0;
  const studies::DrivelineStability st = studies::driveline_stability(dl, clutch, op, true);
  Eigen::MatrixXd road = Eigen::MatrixXd::Zero(D::kNodes, D::kNodes);
  const double r = model.params.wheel_radius_m;
  road(D::kVehicle, D::kVehicle) = (dl.road_load().force_N(1e-7) - dl.road_load().force_N(-1e-7)) / 2e-7 * r * r;
  const auto ref = dl.build().network().modes({true}, road);
  double shuffle_ref = 0;
  for (Eigen::Index j = 0; j < ref.damped_eigenvalues.size(); ++j)
    if (std::abs(ref.damped_eigenvalues[j].imag()) > 2 * std::numbers::pi * 0.5) {
      shuffle_ref = std::abs(ref.damped_eigenvalues[j].imag()) / (2 * std::numbers::pi);
      break;
    }
  const studies::CouplingMode least = studies::least_damped_mode(st);
  double shuffle = 0;
  for (const auto& m : st.modes)
    if (m.frequency_Hz > 0.5) {
      shuffle = m.frequency_Hz;
      break;
    }
  EXPECT_NEAR(shuffle, shuffle_ref, 1e-6 * shuffle_ref);  // the same linear system, two solvers
  EXPECT_NEAR(shuffle, 3.71, 0.005);                      // docs/driveline.md
  EXPECT_LE(least.growth_per_s, 0.0);
}

// Locked: the coupling's two halves are one degree of freedom fewer, so one oscillating pair
// fewer; slipping, the pair is the coupling's own mode.
TEST(DrivelineStability, SlippingHasOneDegreeOfFreedomMoreThanLocked) {
  const io::Scenario sc = tight_turn();
  const auto& model = std::get<DrivelineModel>(sc.model);
  const clutch::WetClutch clutch = sc.make_clutch();
  const HaldexDriveline dl(model.params, clutch, model.manoeuvre);
  const auto op = studies::quasi_static_operating_point(dl, clutch, model.manoeuvre);
  const auto slipping = studies::driveline_stability(dl, clutch, op, false);
  const auto locked = studies::driveline_stability(dl, clutch, op, true);
  EXPECT_EQ(slipping.system.reduced_dofs, locked.system.reduced_dofs + 1);
  EXPECT_EQ(slipping.system.a.rows(), locked.system.a.rows() + 2);
  EXPECT_EQ(locked.coupling_slope_Nms, 0.0);
  EXPECT_GT(slipping.coupling_slope_Nms, 0.0);  // fluid C: μ rises with speed, it damps
}

}  // namespace
}  // namespace shudder::studies

namespace shudder::studies {
namespace {

// The maps' and the onset search's shortcut (no mode shapes, no stability point) gives the
// least-damped slipping mode of the full analysis to the bit, with and without extra damping,
// on the rising and the falling branch, at low and high clamp force; and the shape-free modes
// are the full modes' eigenvalues in the same order. Exact: the same Hessenberg and Schur steps.
TEST(DrivelineStability, ShapeFreeLeastDampedModeEqualsTheFullAnalysisBitForBit) {
  const io::Scenario sc = tight_turn();
  const auto& model = std::get<DrivelineModel>(sc.model);
  const clutch::WetClutch clutch(
      sc.clutch, io::load_fluid(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids/schematic_negative_slope.toml"));
  DrivelineInputs in = model.manoeuvre;
  in.start_speed_km_h = 10.0;
  const HaldexDriveline dl(model.params, clutch, in);
  const auto op = studies::quasi_static_operating_point(dl, clutch, in);
  Eigen::MatrixXd extra = Eigen::MatrixXd::Zero(D::kNodes, D::kNodes);
  extra(D::kCouplingIn, D::kCouplingIn) = extra(D::kCouplingOut, D::kCouplingOut) = -0.3;
  extra(D::kCouplingIn, D::kCouplingOut) = extra(D::kCouplingOut, D::kCouplingIn) = 0.3;
  for (const double slip_rpm : {2.0, 30.0})
    for (const double force_N : {400.0, 20000.0})
      for (const bool with_extra : {false, true}) {
        studies::DrivelineOperatingPoint p = op;
        p.node_speeds_rad_s = Eigen::VectorXd();
        p.coupling_slip_rad_s = slip_rpm * std::numbers::pi / 30.0;
        p.clamp_force_N = force_N;
        const Eigen::MatrixXd damping = with_extra ? extra : Eigen::MatrixXd();
        const studies::DrivelineStability full = studies::driveline_stability(dl, clutch, p, false, damping);
        const studies::CouplingMode a = studies::least_damped_mode(full);
        const studies::CouplingMode b = studies::least_damped_slipping_mode(dl, clutch, p, damping);
        ASSERT_TRUE(std::isfinite(a.growth_per_s));
        EXPECT_EQ(a.growth_per_s, b.growth_per_s);
        EXPECT_EQ(a.frequency_Hz, b.frequency_Hz);
        EXPECT_EQ(a.damping_ratio, b.damping_ratio);
        const auto bare = dynamics::linear_modes(full.system, false);
        ASSERT_EQ(bare.size(), full.modes.size());
        for (std::size_t k = 0; k < bare.size(); ++k) {
          EXPECT_EQ(bare[k].eigenvalue, full.modes[k].eigenvalue);
          EXPECT_TRUE(bare[k].node_amplitude.size() == 0);
        }
      }
}

// Each map cell is the linearisation at that cell's point; with the negative-slope fluid the
// growth rate rises with the clamp force (the negative damping n r F dμ/dv ∝ F) at every slip
// on the falling branch, and the rising branch below 10 rpm is stable.
TEST(DrivelineStability, CouplingMapsAreTheLinearisationAtEachCell) {
  const io::Scenario sc = tight_turn();
  const auto& model = std::get<DrivelineModel>(sc.model);
  const clutch::WetClutch clutch(
      sc.clutch, io::load_fluid(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids/schematic_negative_slope.toml"));
  DrivelineInputs in = model.manoeuvre;
  in.start_speed_km_h = 10.0;
  const HaldexDriveline dl(model.params, clutch, in);
  const auto op = studies::quasi_static_operating_point(dl, clutch, in);
  const std::vector<double> slips{5.0, 20.0, 40.0}, temps{30.0, 60.0}, forces{300.0, 3000.0};
  const auto maps = studies::coupling_stability_maps(dl, clutch, op, slips, temps, forces);
  ASSERT_EQ(maps.size(), 2u);
  EXPECT_EQ(maps[1].name, "coupling_stability_map_2");
  studies::DrivelineOperatingPoint p = op;
  p.node_speeds_rad_s = Eigen::VectorXd();
  p.coupling_slip_rad_s = std::copysign(40.0 * std::numbers::pi / 30.0, op.coupling_slip_rad_s);
  p.interface_temp_C = 60.0;
  p.clamp_force_N = 3000.0;
  const studies::CouplingMode direct = studies::least_damped_mode(studies::driveline_stability(dl, clutch, p, false));
  EXPECT_DOUBLE_EQ(maps[1].find("growth_per_s")->values(2, 1), direct.growth_per_s);
  for (Eigen::Index j = 0; j < 2; ++j) {
    EXPECT_LT(maps[0].find("growth_per_s")->values(0, j), 0.0);  // 5 rpm: rising branch
    EXPECT_LT(maps[1].find("growth_per_s")->values(0, j), 0.0);
    for (Eigen::Index i = 1; i < 3; ++i)
      EXPECT_GT(maps[1].find("growth_per_s")->values(i, j), maps[0].find("growth_per_s")->values(i, j));
  }
}

}  // namespace
}  // namespace shudder::studies

namespace shudder::studies {
namespace {

// Two-inertia reduction of the locked, straight driveline at rest, in the axle's speed:
//
//   J1 = engine side: J_e (i_g i_f)² + front diff + (ptu, coupling halves) i_ptu² + rear diff
//        + side gears                                       (all turn with the axles)
//   J2 = car m r² + the four wheels (held to the road by the stiff tyres relative to the shafts)
//   k  = front: 2 k_h ⊕ 2 k_t;  rear: k_p i_r² ⊕ 2 k_h ⊕ 2 k_t (the propshaft seen at the axle); in parallel
//        (⊕: springs in series; k_t = C_κ r²/σ the tyre's spring at rest)
//   f  = √(k (J1 + J2)/(J1 J2)) / 2π
// The full linearisation's shuffle mode lies within 2 % (the reduction lumps the wheels with the
// car and ignores the side gears' own motion).
TEST(DrivelineStability, LockedShuffleMatchesATwoInertiaReduction) {
  const io::Scenario sc = tight_turn();
  const auto& model = std::get<DrivelineModel>(sc.model);
  const DrivelineParams& p = model.params;
  const clutch::WetClutch clutch = sc.make_clutch();
  DrivelineInputs in;  // straight, at rest
  const HaldexDriveline dl(p, clutch, in);
  studies::DrivelineOperatingPoint op;
  op.clamp_force_N = 1000.0;
  const auto st = studies::driveline_stability(dl, clutch, op, true);
  double shuffle = 0;
  for (const auto& m : st.modes)
    if (m.frequency_Hz > 0.5) {
      shuffle = m.frequency_Hz;
      break;
    }
  const double ig = p.gear_ratio * p.final_drive_ratio, ip = p.ptu_ratio, ir = p.rear_diff_ratio;
  const double j1 = p.engine_inertia_kg_m2 * ig * ig + p.front_diff_inertia_kg_m2 +
                    (p.ptu_inertia_kg_m2 + 2 * p.coupling_half_inertia_kg_m2) * ip * ip + p.rear_diff_inertia_kg_m2 +
                    4 * p.side_gear_inertia_kg_m2;
  const double r = p.wheel_radius_m;
  const double j2 = p.vehicle_mass_kg * r * r + 4 * p.wheel_inertia_kg_m2;
  const double k_t = dl.tyre(0).modal_stiffness_Nm_per_rad();
  const auto series = [](double a, double b) { return a * b / (a + b); };
  const double k_front = series(2 * p.halfshaft_stiffness_Nm_per_rad, 2 * k_t);
  const double k_rear =
      series(series(p.propshaft_stiffness_Nm_per_rad * ir * ir, 2 * p.halfshaft_stiffness_Nm_per_rad), 2 * k_t);
  const double f2 = std::sqrt((k_front + k_rear) * (j1 + j2) / (j1 * j2)) / (2 * std::numbers::pi);
  EXPECT_NEAR(shuffle, f2, 0.02 * f2) << "two-inertia " << f2 << " Hz";
}

}  // namespace
}  // namespace shudder::studies
