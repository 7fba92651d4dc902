// The open differential and the stateful force element of dynamics/network.hpp:
//   * differential: a torque T on the carrier (J_c) with two free side inertias J_l, J_r; both sides
//     take the same torque λ and ω_l + ω_r = 2 ω_c, so λ = (2T/J_c) / (1/J_l + 1/J_r + 4/J_c) and
//     each side accelerates at λ/J;
//   * force element: a Maxwell element (spring k in series with a damper c, its state the spring's
//     deflection z: dz/dt = Δω − k z/c, T = k z, E = ½ k z², P = (k z)²/c) through a ratio ρ between
//     a flywheel and a second inertia: the energy account closes and the momentum Σ(J ω ρ-weighted)
//     is conserved (−T on a, +ρT on b: J_a ω_a + J_b ω_b/ρ is constant).
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "dynamics/simulation.hpp"

namespace shudder::dynamics {
namespace {

TEST(DynamicsDifferential, SplitsTheCarriersTorqueEqually) {
  TorsionalNetwork net;
  const double jc = 0.5, jl = 1.0, jr = 3.0, torque = 10.0;
  const int c = net.add_inertia({"carrier", jc});
  const int l = net.add_inertia({"left", jl});
  const int r = net.add_inertia({"right", jr});
  net.add_differential({"diff", c, l, r});
  net.add_torque_source({"drive", c, [=](double) { return torque; }});
  Simulation sim(net, {1e-12, 1e-12, 1e-2, 1e-6, 1e-12});
  sim.initialize(0.0, Eigen::VectorXd::Zero(3), Eigen::VectorXd::Zero(3));
  sim.advance(1.0);
  const double lambda = (2 * torque / jc) / (1 / jl + 1 / jr + 4 / jc);
  const auto s = sim.sample();
  EXPECT_NEAR(s.omega_rad_s[l], lambda / jl, 1e-9);
  EXPECT_NEAR(s.omega_rad_s[r], lambda / jr, 1e-9);
  EXPECT_NEAR(s.omega_rad_s[l] + s.omega_rad_s[r], 2 * s.omega_rad_s[c], 1e-12);
  // The constraint belongs in the modes' basis too: 3 nodes, 1 constraint → 2 free coordinates.
  EXPECT_EQ(net.constraint_basis({}).cols(), 2);
}

class MaxwellLaw final : public ForceLaw {
 public:
  MaxwellLaw(double k, double c) : k_(k), c_(c) {}
  int states() const override { return 1; }
  Output evaluate(double wa, double wb, const double* z, double* dz) const override {
    dz[0] = (wa - wb) - k_ * z[0] / c_;
    return {k_ * z[0], k_ * z[0] * k_ * z[0] / c_};
  }
  double stored_energy_J(const double* z) const override { return 0.5 * k_ * z[0] * z[0]; }
  double modal_stiffness_Nm_per_rad() const override { return k_; }

 private:
  double k_, c_;
};

TEST(DynamicsForceElement, MaxwellElementConservesEnergyAndMomentum) {
  TorsionalNetwork net;
  const double ja = 2.0, jb = 0.5, rho = 1.5;
  const int a = net.add_inertia({"a", ja});
  const int b = net.add_inertia({"b", jb});
  net.add_force_element({"maxwell", a, b, rho, std::make_shared<MaxwellLaw>(400.0, 9.0)});
  Simulation sim(net, {1e-10, 1e-10, 1e-3, 1e-6, 1e-12});
  Eigen::VectorXd w(2);
  w << 10.0, 0.0;
  sim.initialize(0.0, Eigen::VectorXd::Zero(2), w);
  sim.advance(2.0);
  const auto s = sim.sample();
  EXPECT_NEAR(ja * s.omega_rad_s[a] + jb * s.omega_rad_s[b] / rho, ja * 10.0, 1e-7);
  const auto e = sim.energy();
  EXPECT_GT(e.damper_loss_J, 1.0);  // it did dissipate
  EXPECT_LT(std::abs(e.imbalance_J()), 1e-7 * e.initial_kinetic_J);
  // Settled: both ends turn together through the ratio, ω_a = ρ ω_b.
  EXPECT_NEAR(s.omega_rad_s[a], rho * s.omega_rad_s[b], 1e-3);
  EXPECT_NEAR(s.element_torque_Nm[0], 0.0, 1e-2);
}

}  // namespace
}  // namespace shudder::dynamics
