// The brush tyre with a load-proportional slip stiffness and the car's longitudinal load transfer
// (components/tyre.hpp) against closed forms:
//   * slip stiffness ∝ load: at a small slip κ the brush force is C_κ κ (1 − a + a²/3),
//     a = κ/κ_sl, κ_sl = 3 μ/c_κ; with C_κ = c_κ F_z the force at one slip doubles exactly
//     with the load, and is c_κ F_z κ to within a (6e-4 at κ = 1e-4);
//   * power: T (ω_w − ρ ω_v) = dE/dt + P_reported, with E(z) the stored energy, also while the
//     load changes (the law's ∂E/∂F_z term);
//   * statics on a grade: moments about the front contact point,
//         F_zr L = m g cos θ (1 − s_f) L + m g sin θ h,   F_zf + F_zr = m g cos θ;
//   * load transfer under a constant tyre force (a car pushed by one driven wheel):
//
//         torque T ─► [wheel_r] ~tyre_r~ [car m] ~tyre_f~ [wheel_f]
//
//     the car accelerates steadily at a = Σ F / m, and once the lags have settled (t ≫ τ₁ + τ₂)
//     each axle's load is F_z0 ± m a h / L (one tyre per axle here);
//   * energy: the network's account closes with tyres sliding on a load that changes.
#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <array>
#include <cmath>

#include "dynamics/network.hpp"
#include "dynamics/simulation.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "components/tyre.hpp"

namespace shudder::components {
namespace {

TyreParams level_tyre(double load_N) {
  TyreParams p;
  p.vertical_load_N = load_N;
  p.relaxation_length_m = 0.2;
  p.road_friction = 1.0;
  p.radius_m = 0.3;
  return p;
}

TEST(Tyre, SlipStiffnessFollowsTheLoad) {
  const double kappa = 1e-4;
  const BrushTyre light(level_tyre(3000.0)), heavy(level_tyre(6000.0));
  // The brush curve scales with F_z when C_κ does: twice the load, twice the force (round-off).
  EXPECT_NEAR(heavy.force_N(kappa), 2.0 * light.force_N(kappa), 1e-12 * heavy.force_N(kappa));
  // C_κ κ to within a = κ c_κ / (3 μ) = 6.3e-4 of curvature: 1e-3 relative.
  EXPECT_NEAR(light.force_N(kappa), kDefaultSlipStiffnessPerLoad * 3000.0 * kappa, 1e-3 * light.force_N(kappa));
  EXPECT_NEAR(heavy.slip_stiffness_N(6000.0), kDefaultSlipStiffnessPerLoad * 6000.0, 1e-9);
  // The relaxation length follows: the carcass stiffness C_κ/σ is the tyre's, not the load's.
  EXPECT_NEAR(heavy.relaxation_length_m(9000.0), 0.2 * 1.5, 1e-12);

  // An absolute C_κ: the same small-slip force at both loads (curvature a differs: 1e-3).
  TyreParams a = level_tyre(3000.0), b = level_tyre(6000.0);
  a.slip_stiffness_N = b.slip_stiffness_N = 8.0e4;
  const BrushTyre fixed_light(a), fixed_heavy(b);
  EXPECT_NEAR(fixed_light.force_N(kappa), 8.0e4 * kappa, 1e-3 * 8.0);
  EXPECT_NEAR(fixed_heavy.force_N(kappa), 8.0e4 * kappa, 1e-3 * 8.0);
  EXPECT_NEAR(fixed_heavy.relaxation_length_m(9000.0), 0.2, 1e-15);
}

TEST(Tyre, BothSlipStiffnessesIsOneHelpfulError) {
  TyreParams p = level_tyre(3000.0);
  p.slip_stiffness_N = 8.0e4;
  p.slip_stiffness_per_load = 18.0;
  try {
    BrushTyre t(p);
    FAIL() << "both slip stiffnesses were accepted";
  } catch (const std::invalid_argument& e) {
    EXPECT_THAT(e.what(), ::testing::HasSubstr("slip_stiffness_N and slip_stiffness_per_load are alternatives"));
  }
}

TEST(Tyre, PowerBalanceHoldsWhileTheLoadChanges) {
  // T Δω = ∇E · ż + P at states in the adhesion, the sliding range and full sliding, with the
  // car accelerating (ā ≠ 0, its rate ≠ 0): ∇E by central differences (1e-7 m/s, 1e-9 m),
  // accurate to ~1e-7 of the power.
  TyreParams p = level_tyre(4000.0);
  p.road_friction = 0.8;
  p.load_transfer.load_per_acceleration_kg = 180.0;
  const BrushTyre t(p);
  ASSERT_EQ(t.states(), 3);
  for (double u : {0.002, 0.006, 0.012, 0.05}) {
    const std::array<double, 3> z{u, 10.0, 9.7};
    const double w_wheel = 10.4 / 0.3, w_ground = 10.05 / 0.3;
    std::array<double, 3> dz{};
    const auto out = t.evaluate(w_wheel, w_ground, z.data(), dz.data());
    double de_dt = 0.0;
    for (int i = 0; i < 3; ++i) {
      const double h = i == 0 ? 1e-9 : 1e-7;
      std::array<double, 3> zp = z, zm = z;
      zp[static_cast<std::size_t>(i)] += h;
      zm[static_cast<std::size_t>(i)] -= h;
      de_dt +=
          (t.stored_energy_J(zp.data()) - t.stored_energy_J(zm.data())) / (2 * h) * dz[static_cast<std::size_t>(i)];
    }
    const double power_in = out.torque_Nm * (w_wheel - w_ground);
    EXPECT_NEAR(power_in, de_dt + out.dissipated_W, 1e-6 * std::abs(power_in)) << "u = " << u;
  }
}

TEST(Tyre, StaticAxleLoadsOnAGradeBalanceMoments) {
  rig_models::DrivelineParams p;
  const double g = rig_models::HaldexDriveline::kGravity_m_s2, m = p.vehicle_mass_kg, l = p.wheelbase_m,
               h = p.cg_height_m;
  for (double grade : {-20.0, 0.0, 10.0, 30.0}) {
    const double th = std::atan(grade / 100.0);
    const auto axle = rig_models::static_axle_loads_N(p, grade);
    // Moments about the front contact point (CG at (1 − s_f) L behind it, h above the road).
    const double rear = (m * g * std::cos(th) * (1.0 - p.front_axle_load_share) * l + m * g * std::sin(th) * h) / l;
    EXPECT_NEAR(axle[1], rear, 1e-9 * m * g) << grade;
    EXPECT_NEAR(axle[0] + axle[1], m * g * std::cos(th), 1e-9 * m * g) << grade;
  }
}

// A car of mass m on two tyres, one per axle, the rear wheel driven by a constant torque.
struct PushedCar {
  static constexpr double m = 1500.0, r = 0.3, h = 0.5, l = 2.5, j_wheel = 1.0;
  dynamics::TorsionalNetwork net;
  std::shared_ptr<const BrushTyre> front, rear;
  PushedCar(double torque_Nm, double mu) {
    const double weight = m * rig_models::HaldexDriveline::kGravity_m_s2;
    const auto tyre = [&](double share, double sign) {
      TyreParams p;
      p.vertical_load_N = share * weight;
      p.relaxation_length_m = 0.2;
      p.road_friction = mu;
      p.radius_m = r;
      p.load_transfer.load_per_acceleration_kg = sign * m * h / l;
      return std::make_shared<const BrushTyre>(p);
    };
    front = tyre(0.6, -1.0);
    rear = tyre(0.4, 1.0);
    const int wr = net.add_inertia({"wheel_r", j_wheel});
    const int car = net.add_inertia({"car", m * r * r});
    const int wf = net.add_inertia({"wheel_f", j_wheel});
    net.add_force_element({"tyre_r", wr, car, 1.0, rear});
    net.add_force_element({"tyre_f", wf, car, 1.0, front});
    net.add_torque_source({"drive", wr, [torque_Nm](double) { return torque_Nm; }});
  }
};

TEST(Tyre, ConstantForceTransfersMahOverL) {
  // 600 N m at the rear wheel: ~1.3 m/s², small slip (the linear range, forces independent of
  // the load: the acceleration is constant once the relaxation settles, σ/V = 0.02 s).
  PushedCar c(600.0, 1.0);
  dynamics::Simulation sim(c.net);
  const double w0 = 10.0 / c.r;
  sim.initialize(0.0, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Constant(3, w0));
  sim.advance(4.0);  // τ₁ + τ₂ = 0.25 s: the lags' transient e^(−4/0.16) ~ 1e-11
  const dynamics::Sample s = sim.sample();
  const double force_N = (s.element_torque_Nm[0] + s.element_torque_Nm[1]) / c.r;
  const double a = force_N / c.m;
  ASSERT_GT(a, 1.0);
  const double transfer_N = c.m * a * c.h / c.l;
  const double weight = c.m * rig_models::HaldexDriveline::kGravity_m_s2;
  // The lags track a steady ramp exactly (everything here is steady: a = T/r/(m + 2J/r²)); what
  // is left is the integration's: ~1e-5 m/s in v₁ − v₂ at 1e-6 relative on ~20 m/s, 1e-4 m/s² in
  // ā, 0.03 N of load: 0.1 N (2.5e-4 of the ~400 N transfer).
  EXPECT_NEAR(c.rear->vertical_load_N(s.element_states.data()), 0.4 * weight + transfer_N, 0.1);
  EXPECT_NEAR(c.front->vertical_load_N(s.element_states.data() + 3), 0.6 * weight - transfer_N, 0.1);
  // And the acceleration is the rigid body's, T/r/(m + 2J/r²) with the wheels' inertia, to the
  // driven wheel's slip (κ ≈ 0.02 adds J κ a/r² ≈ 1e-4 of the force): 1e-3.
  EXPECT_NEAR(a, 600.0 / c.r / (c.m + 2 * c.j_wheel / (c.r * c.r)), 1e-3 * a);
}

TEST(Tyre, EnergyAccountClosesWithTheLoadChanging) {
  // On snow (μ 0.3) 800 N m spins the rear wheel: the tyre slides at full saturation on a load
  // that grows with the acceleration — the ∂E/∂F_z exchange is exercised. The account closes to
  // the integrator's tolerance (1e-6 relative steps: 1e-6 of the kinetic energy gained).
  PushedCar c(800.0, 0.3);
  dynamics::Simulation sim(c.net);
  sim.initialize(0.0, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Constant(3, 5.0 / c.r));
  sim.advance(2.0);
  const auto e = sim.energy();
  const double gained = e.kinetic_J - e.initial_kinetic_J;
  ASSERT_GT(gained, 1e3);
  EXPECT_LT(std::abs(e.imbalance_J()), 1e-5 * gained);
  // And the rear tyre did slide at its (transferred) limit: its force is μ F_z.
  const dynamics::Sample s = sim.sample();
  const double fz = c.rear->vertical_load_N(s.element_states.data());
  EXPECT_GT(fz, 0.4 * c.m * rig_models::HaldexDriveline::kGravity_m_s2);
  EXPECT_NEAR(s.element_torque_Nm[0] / c.r, 0.3 * fz, 1e-3 * fz);
}

}  // namespace
}  // namespace shudder::components
