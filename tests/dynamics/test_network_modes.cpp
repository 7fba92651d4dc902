// Linear behaviour of TorsionalNetwork and Simulation against closed forms: natural frequencies
// and damped eigenvalues from TorsionalNetwork::modes(), free responses from Simulation::advance.
//
// Tolerances: modes() solves small symmetric eigenproblems, exact to a few ulp, so frequencies
// and eigenvalues are checked to 1e-9 relative (margin for the sqrt and the 2x2/4x4 solvers).
// Simulated responses use dopri5 at abs = rel = 1e-12 and max_step 1e-4 s (about 30 steps per
// period): the global error after a few periods is ~1e-10 of the amplitude, checked at 1e-6.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <vector>

#include "core/units.hpp"
#include "dynamics/network.hpp"
#include "dynamics/simulation.hpp"
#include "tests/dynamics/test_laws.hpp"

namespace {

using namespace shudder::dynamics;
using shudder::dynamics::testing::CoulombLaw;

IntegratorSettings tight() {
  IntegratorSettings s;
  s.abs_tol = 1e-12;
  s.rel_tol = 1e-12;
  s.max_step_s = 1e-4;
  return s;
}

std::vector<double> grid(double t0, double dt, int n) {
  std::vector<double> t(n);
  for (int i = 0; i < n; ++i) t[i] = t0 + dt * (i + 1);
  return t;
}

// ---------------------------------------------------------------------------------------------
//   ground |--/\/\/\-- [ J ]        k = 2000 N m/rad, J = 0.05 kg m^2
//                 k
//   J θ'' + k θ = 0  →  ω_n = sqrt(k/J) = 200 rad/s,  f_n = ω_n / 2π = 31.831 Hz
//   θ(0) = θ0, ω(0) = 0  →  θ(t) = θ0 cos(ω_n t),  ω(t) = −θ0 ω_n sin(ω_n t)
// ---------------------------------------------------------------------------------------------
constexpr double kJ = 0.05, kK = 2000.0;

TorsionalNetwork single_oscillator(double damping) {
  TorsionalNetwork net;
  const int m = net.add_inertia({"mass", kJ});
  net.add_shaft({"spring", m, kGround, kK, damping});
  return net;
}

TEST(DynamicsNetworkModes, SingleInertiaFrequencyIsSqrtKOverJ) {
  const auto net = single_oscillator(0.0);
  const Modes modes = net.modes();
  ASSERT_EQ(modes.frequencies_Hz.size(), 1);
  EXPECT_NEAR(modes.frequencies_Hz[0] / (std::sqrt(kK / kJ) / shudder::units::kTwoPi), 1.0, 1e-9);
  EXPECT_DOUBLE_EQ(modes.shapes(0, 0), 1.0);  // normalised to max |entry| = 1
  // Undamped: eigenvalues ±i ω_n, zero real part (only rounding).
  ASSERT_EQ(modes.damped_eigenvalues.size(), 2);
  for (const auto& ev : modes.damped_eigenvalues) {
    EXPECT_NEAR(ev.real(), 0.0, 1e-9 * std::sqrt(kK / kJ));
    EXPECT_NEAR(std::abs(ev.imag()) / std::sqrt(kK / kJ), 1.0, 1e-9);
  }
}

TEST(DynamicsNetworkModes, FreeResponseIsACosine) {
  const auto net = single_oscillator(0.0);
  const double wn = std::sqrt(kK / kJ), theta0 = 0.01;
  Simulation sim(net, tight());
  sim.initialize(0.0, Eigen::VectorXd::Constant(1, theta0), Eigen::VectorXd::Zero(1));
  // 0.2 s = 6.4 periods, sampled every 0.5 ms.
  const auto times = grid(0.0, 5e-4, 400);
  int n = 0;
  sim.advance(0.2, times, [&](const Sample& s) {
    ++n;
    EXPECT_NEAR(s.theta_rad[0], theta0 * std::cos(wn * s.t_s), 1e-6 * theta0) << "t = " << s.t_s;
    EXPECT_NEAR(s.omega_rad_s[0], -theta0 * wn * std::sin(wn * s.t_s), 1e-6 * theta0 * wn) << "t = " << s.t_s;
    // The spring torque is k θ as carried by the shaft.
    EXPECT_NEAR(s.shaft_torque_Nm[0], kK * s.theta_rad[0], 1e-12 * kK * theta0);
  });
  EXPECT_EQ(n, 400);
  EXPECT_DOUBLE_EQ(sim.time_s(), 0.2);
}

// ---------------------------------------------------------------------------------------------
//   ground |--/\/\/\--[ J ]      J θ'' + c θ' + k θ = 0,  c = 1 N m s/rad
//          |---[=c=]--|
//   s = −σ ± i ω_d,  σ = c/(2J) = ζ ω_n = 10 1/s,  ω_d = sqrt(ω_n² − σ²)
//   θ(t) = θ0 e^{−σt} (cos ω_d t + σ/ω_d sin ω_d t), and for any t:
//   θ(t + N T_d) = e^{−σ N T_d} θ(t), T_d = 2π/ω_d  (log decrement δ = σ T_d)
// ---------------------------------------------------------------------------------------------
TEST(DynamicsNetworkModes, DampedEigenvalueRealPartIsMinusCOver2J) {
  const double c = 1.0;
  const auto net = single_oscillator(c);
  const Modes modes = net.modes();
  const double sigma = c / (2 * kJ), wd = std::sqrt(kK / kJ - sigma * sigma);
  ASSERT_EQ(modes.damped_eigenvalues.size(), 2);
  for (const auto& ev : modes.damped_eigenvalues) {
    EXPECT_NEAR(ev.real() / -sigma, 1.0, 1e-9);
    EXPECT_NEAR(std::abs(ev.imag()) / wd, 1.0, 1e-9);
  }
  // Sorted by |imag|, then positive imaginary part first.
  EXPECT_GT(modes.damped_eigenvalues[0].imag(), 0.0);
  // The undamped frequency ignores c.
  EXPECT_NEAR(modes.frequencies_Hz[0] / (std::sqrt(kK / kJ) / shudder::units::kTwoPi), 1.0, 1e-9);
}

TEST(DynamicsNetworkModes, SimulatedEnvelopeDecaysAtSigma) {
  const double c = 1.0, theta0 = 0.01;
  const auto net = single_oscillator(c);
  const double sigma = c / (2 * kJ), wd = std::sqrt(kK / kJ - sigma * sigma);
  const double td = shudder::units::kTwoPi / wd;
  Simulation sim(net, tight());
  sim.initialize(0.0, Eigen::VectorXd::Constant(1, theta0), Eigen::VectorXd::Zero(1));
  std::vector<double> times = grid(0.0, 5e-4, 300);
  times.push_back(3 * td);  // the log-decrement sample, 3 damped periods in
  std::sort(times.begin(), times.end());
  double theta_3td = 0.0;
  sim.advance(0.16, times, [&](const Sample& s) {
    const double t = s.t_s;
    const double exact = theta0 * std::exp(-sigma * t) * (std::cos(wd * t) + sigma / wd * std::sin(wd * t));
    EXPECT_NEAR(s.theta_rad[0], exact, 1e-6 * theta0) << "t = " << t;
    if (t == 3 * td) theta_3td = s.theta_rad[0];
  });
  ASSERT_NE(theta_3td, 0.0);
  // σ from the log decrement over 3 periods; θ errors of ~1e-10 θ0 on e^{-0.94} θ0 give ~1e-10.
  const double sigma_sim = std::log(theta0 / theta_3td) / (3 * td);
  EXPECT_NEAR(sigma_sim / sigma, 1.0, 1e-6);
  // Energy: the damper took exactly what the oscillator lost (both integrated to ~1e-12).
  const EnergyAccount e = sim.energy();
  EXPECT_NEAR(e.initial_elastic_J, 0.5 * kK * theta0 * theta0, 1e-15);
  EXPECT_NEAR(e.imbalance_J(), 0.0, 1e-6 * e.damper_loss_J);
}

// ---------------------------------------------------------------------------------------------
//   ground |--k1--[ J1 ]--k2--[ J2 ]      J1 = 0.02, J2 = 0.05 kg m², k1 = 1000, k2 = 3000 N m/rad
//   det(K − λM) = 0, λ = ω²:
//     J1 J2 λ² − (J1 k2 + J2 (k1 + k2)) λ + k1 k2 = 0
//   mode shape from row 2:  −k2 φ1 + (k2 − J2 λ) φ2 = 0  →  φ2/φ1 = k2 / (k2 − J2 λ)
// ---------------------------------------------------------------------------------------------
TEST(DynamicsNetworkModes, TwoDofFrequenciesAreTheCharacteristicRoots) {
  const double j1 = 0.02, j2 = 0.05, k1 = 1000.0, k2 = 3000.0;
  TorsionalNetwork net;
  const int a = net.add_inertia({"J1", j1});
  const int b = net.add_inertia({"J2", j2});
  net.add_shaft({"k1", a, kGround, k1, 0.0});
  net.add_shaft({"k2", a, b, k2, 0.0});
  // Roots of the quadratic, the small one from Vieta to avoid cancellation.
  const double qa = j1 * j2, qb = j1 * k2 + j2 * (k1 + k2), qc = k1 * k2;
  const double big = (qb + std::sqrt(qb * qb - 4 * qa * qc)) / (2 * qa);
  const double small = qc / (qa * big);
  const Modes modes = net.modes();
  ASSERT_EQ(modes.frequencies_Hz.size(), 2);
  const double lambda[2] = {small, big};
  for (int m = 0; m < 2; ++m) {
    EXPECT_NEAR(modes.frequencies_Hz[m] / (std::sqrt(lambda[m]) / shudder::units::kTwoPi), 1.0, 1e-9);
    const double ratio = k2 / (k2 - j2 * lambda[m]);
    EXPECT_NEAR(modes.shapes(1, m) / modes.shapes(0, m), ratio, 1e-9 * std::abs(ratio));
  }
  // The matrices the modes come from.
  EXPECT_DOUBLE_EQ(net.stiffness_matrix()(0, 0), k1 + k2);
  EXPECT_DOUBLE_EQ(net.stiffness_matrix()(0, 1), -k2);
  EXPECT_DOUBLE_EQ(net.mass_matrix()(1, 1), j2);
}

// ---------------------------------------------------------------------------------------------
// A geared inertia behaves like its reflected inertia.
//
//   ground |--k1--[ J1 ]==gear i==[ J2 ]--k2--| ground      ω1 = i ω2  (Gear{a=J1, b=J2, ratio=i})
//
// Kinetic and elastic energy in terms of θ1 (θ2 = θ1 / i):
//   T = ½ (J1 + J2/i²) ω1²,  V = ½ (k1 + k2/i²) θ1²
//   →  the single inertia  J_eff = J1 + J2/i²  on  k_eff = k1 + k2/i²  (i = 3: J_eff = 0.03 + 0.2/9).
// The same holds for the simulated response: θ1(t) = θ0 cos(sqrt(k_eff/J_eff) t), θ2 = θ1/i.
// ---------------------------------------------------------------------------------------------
constexpr double kJ1 = 0.03, kJ2 = 0.2, kK1 = 800.0, kK2 = 4500.0, kRatio = 3.0;

TorsionalNetwork geared() {
  TorsionalNetwork net;
  const int a = net.add_inertia({"motor side", kJ1});
  const int b = net.add_inertia({"load side", kJ2});
  net.add_shaft({"k1", a, kGround, kK1, 0.0});
  net.add_shaft({"k2", b, kGround, kK2, 0.0});
  net.add_gear({"gear", a, b, kRatio});
  return net;
}

TEST(DynamicsNetworkModes, GearedInertiaHasTheReflectedFrequency) {
  const double j_eff = kJ1 + kJ2 / (kRatio * kRatio), k_eff = kK1 + kK2 / (kRatio * kRatio);
  TorsionalNetwork reflected;
  reflected.add_shaft({"k", reflected.add_inertia({"J_eff", j_eff}), kGround, k_eff, 0.0});

  const Modes g = geared().modes(), r = reflected.modes();
  ASSERT_EQ(g.frequencies_Hz.size(), 1);  // the gear removes one degree of freedom
  ASSERT_EQ(r.frequencies_Hz.size(), 1);
  EXPECT_NEAR(g.frequencies_Hz[0] / r.frequencies_Hz[0], 1.0, 1e-9);
  EXPECT_NEAR(g.frequencies_Hz[0] / (std::sqrt(k_eff / j_eff) / shudder::units::kTwoPi), 1.0, 1e-9);
  // Shape: node amplitudes in the gear ratio, θ1 = i θ2, largest (θ1) normalised to 1.
  EXPECT_NEAR(g.shapes(0, 0), 1.0, 1e-12);
  EXPECT_NEAR(g.shapes(1, 0), 1.0 / kRatio, 1e-12);
}

TEST(DynamicsNetworkModes, GearedInertiaRespondsLikeTheReflectedInertia) {
  const double j_eff = kJ1 + kJ2 / (kRatio * kRatio), k_eff = kK1 + kK2 / (kRatio * kRatio);
  const double w = std::sqrt(k_eff / j_eff), theta0 = 0.02;
  const auto net = geared();
  Simulation sim(net, tight());
  sim.initialize(0.0, Eigen::Vector2d(theta0, theta0 / kRatio), Eigen::Vector2d::Zero());
  int n = 0;
  sim.advance(0.2, grid(0.0, 1e-3, 200), [&](const Sample& s) {
    ++n;
    EXPECT_NEAR(s.theta_rad[0], theta0 * std::cos(w * s.t_s), 1e-6 * theta0) << "t = " << s.t_s;
    // The gear holds ω1 = i ω2 at the acceleration level; the drift stays at rounding level.
    EXPECT_NEAR(s.omega_rad_s[0], kRatio * s.omega_rad_s[1], 1e-9 * theta0 * w);
    EXPECT_NEAR(s.theta_rad[0], kRatio * s.theta_rad[1], 1e-9 * theta0);
  });
  EXPECT_EQ(n, 200);
  // The gear is ideal: no energy is lost in it.
  EXPECT_NEAR(sim.energy().imbalance_J(), 0.0, 1e-9 * sim.energy().initial_elastic_J);
}

// ---------------------------------------------------------------------------------------------
// A stuck contact merges its two nodes:   [ J1 ]==contact==[ J2 ]--k--| ground
//   stuck:    one inertia J1 + J2 on k  →  ω = sqrt(k/(J1+J2))
//   slipping: J1 is free (rigid-body mode, 0 Hz) and J2 alone sits on k  →  ω = sqrt(k/J2)
// ---------------------------------------------------------------------------------------------
TEST(DynamicsNetworkModes, StuckContactMergesItsNodes) {
  const double j1 = 0.01, j2 = 0.04, k = 900.0;
  TorsionalNetwork net;
  const int a = net.add_inertia({"J1", j1});
  const int b = net.add_inertia({"J2", j2});
  net.add_shaft({"k", b, kGround, k, 0.0});
  net.add_contact({"c", a, b, std::make_shared<CoulombLaw>(1.0, 2.0)});
  const Modes stuck = net.modes({true});
  ASSERT_EQ(stuck.frequencies_Hz.size(), 1);
  EXPECT_NEAR(stuck.frequencies_Hz[0] / (std::sqrt(k / (j1 + j2)) / shudder::units::kTwoPi), 1.0, 1e-9);
  const Modes slipping = net.modes({false});
  ASSERT_EQ(slipping.frequencies_Hz.size(), 2);
  // Rigid-body mode: ω² is zero up to rounding of k/J (~1e-12 of 2e4 1/s²), so f ≲ 1e-6 Hz.
  EXPECT_NEAR(slipping.frequencies_Hz[0], 0.0, 1e-5);
  EXPECT_NEAR(slipping.frequencies_Hz[1] / (std::sqrt(k / j2) / shudder::units::kTwoPi), 1.0, 1e-9);
}

}  // namespace

// ---------------------------------------------------------------------------------------------
//   ground |--[c]-- [ J ]      a pure damper (k = 0; e.g. a tyre's slip), c = 4 N m s/rad
//   J ω' = −c ω  →  ω(t) = ω0 e^(−c t / J);  modes(): one rigid-body mode (0 Hz), damped
//   eigenvalue −c/J.  A shaft with neither stiffness nor damping is refused.
// ---------------------------------------------------------------------------------------------
TEST(DynamicsNetworkModes, PureDamperDecaysExponentially) {
  constexpr double c = 4.0;
  TorsionalNetwork net;
  const int m = net.add_inertia({"mass", kJ});
  net.add_shaft({"damper", m, kGround, 0.0, c});
  net.validate();
  const Modes modes = net.modes();
  ASSERT_EQ(modes.frequencies_Hz.size(), 1);
  EXPECT_NEAR(modes.frequencies_Hz[0], 0.0, 1e-9);
  bool found = false;
  for (Eigen::Index j = 0; j < modes.damped_eigenvalues.size(); ++j)
    found = found || std::abs(modes.damped_eigenvalues[j] - std::complex<double>(-c / kJ, 0.0)) < 1e-9 * c / kJ;
  EXPECT_TRUE(found) << "no eigenvalue at -c/J = " << -c / kJ;

  Simulation sim(net, tight());
  sim.initialize(0.0, Eigen::VectorXd::Zero(1), Eigen::VectorXd::Constant(1, 10.0), Eigen::VectorXd());
  sim.advance(0.02);
  EXPECT_NEAR(sim.sample().omega_rad_s[0], 10.0 * std::exp(-c * 0.02 / kJ), 1e-6 * 10.0);

  TorsionalNetwork nothing;
  const int n = nothing.add_inertia({"mass", kJ});
  nothing.add_shaft({"void", n, kGround, 0.0, 0.0});
  EXPECT_THROW(nothing.validate(), std::invalid_argument);
}
