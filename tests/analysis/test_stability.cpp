// Linear stability of steady sliding (analysis/stability) against closed forms:
//
//   * one inertia on a spring–damper, driven through a contact with a constant torque–speed
//     slope: threshold c + s = 0, growth rate and frequency of J θ'' + (c + s) θ' + k θ = 0,
//   * two two-degree-of-freedom networks against the roots of det(M λ² + C λ + K) = 0 expanded
//     by hand (companion matrix), one with a motor's PI loop,
//   * a stuck contact is a constraint and its slope drops out,
//   * a free body behind a slipping contact: its angle drift (λ = 0) is left out of the margin,
//   * bad input names the quantity.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <Eigen/Eigenvalues>
#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>
#include <numbers>
#include <vector>

#include "analysis/stability.hpp"
#include "core/units.hpp"
#include "dynamics/network.hpp"
#include "tests/dynamics/test_laws.hpp"

namespace {

using shudder::analysis::linearise;
using shudder::analysis::StabilityPoint;
using shudder::analysis::SteadySliding;
using shudder::dynamics::kGround;
using shudder::dynamics::TorsionalNetwork;
using shudder::dynamics::testing::LinearSlopeLaw;

using shudder::units::kTwoPi;

// A constant-speed driver (its inertia is irrelevant: the source fixes its speed).
int add_driver(TorsionalNetwork& net, double speed_rad_s) {
  const int d = net.add_inertia({"driver", 1.0});
  net.add_speed_source({"source", d, [speed_rad_s](double) { return speed_rad_s; }, [](double) { return 0.0; }});
  return d;
}

std::shared_ptr<LinearSlopeLaw> slope_law(double slope_Nms) {
  return std::make_shared<LinearSlopeLaw>(20.0, slope_Nms, 30.0);
}

// Roots of a4 λ⁴ + a3 λ³ + a2 λ² + a1 λ + a0 from the eigenvalues of the companion matrix.
Eigen::VectorXcd quartic_roots(double a4, double a3, double a2, double a1, double a0) {
  Eigen::Matrix4d c = Eigen::Matrix4d::Zero();
  c(0, 0) = -a3 / a4;
  c(0, 1) = -a2 / a4;
  c(0, 2) = -a1 / a4;
  c(0, 3) = -a0 / a4;
  c(1, 0) = c(2, 1) = c(3, 2) = 1.0;
  return Eigen::EigenSolver<Eigen::Matrix4d>(c, false).eigenvalues();
}

// Largest distance from each expected root to the nearest eigenvalue (and the counts agree),
// relative to the largest |root|.
double relative_mismatch(const Eigen::VectorXcd& got, const Eigen::VectorXcd& want) {
  EXPECT_EQ(got.size(), want.size());
  double worst = 0.0, scale = 0.0;
  for (const auto& w : want) {
    double best = INFINITY;
    for (const auto& g : got) best = std::min(best, std::abs(g - w));
    worst = std::max(worst, best);
    scale = std::max(scale, std::abs(w));
  }
  return worst / scale;
}

double max_real(const Eigen::VectorXcd& v) {
  double m = -INFINITY;
  for (const auto& l : v) m = std::max(m, l.real());
  return m;
}

// ---------------------------------------------------------------------------------------------
// 1. One degree of freedom.
//
//     driver ══ Ω (speed source)
//        │ contact: M(Δω) = M₀ + s Δω,  Δω = Ω − ω > 0
//        J ── k, c ── ground
//
// The contact pushes J with +M(Ω − ω); with θ = θ₀ + q about the steady state k θ₀ = M(Ω):
//     J q'' = −k q − c q' − s q'   ⇒   J q'' + (c + s) q' + k q = 0
//     λ = −(c + s)/(2J) ± i √(k/J − ((c + s)/2J)²)
// Unstable exactly when c + s < 0, i.e. c + n F r² dmu/dv < 0 for a clutch. The driver's speed
// sign does not matter: d[sign(Δω) M(|Δω|)]/dΔω = s either way.
// Tolerance 1e-9 relative to ω_n = √(k/J) (the eigenvalues' scale; the margin passes through 0).
// ---------------------------------------------------------------------------------------------
TEST(Stability, OneDofThresholdGrowthRateAndFrequencyMatchClosedForm) {
  const double J = 0.02, k = 1.1e5, c = 0.95;
  const double wn = std::sqrt(k / J);
  for (const double drive : {10.0, -10.0}) {
    for (const double s : {3.0, 0.0, -0.5, -0.95, -1.5, -4.0}) {
      SCOPED_TRACE(::testing::Message() << "drive " << drive << " rad/s, slope " << s);
      TorsionalNetwork net;
      const int d = add_driver(net, drive);
      const int m = net.add_inertia({"mass", J});
      net.add_shaft({"spring", m, kGround, k, c});
      net.add_contact({"contact", d, m, slope_law(s)});
      net.validate();
      const StabilityPoint p = linearise(net, {{drive}, {}, 0.0});

      const double sigma = -(c + s) / (2.0 * J);
      const double wd = std::sqrt(k / J - sigma * sigma);
      EXPECT_NEAR(p.margin_per_s, sigma, 1e-9 * wn);
      EXPECT_NEAR(p.frequency_Hz, wd / kTwoPi, 1e-9 * wn / kTwoPi);
      EXPECT_NEAR(p.oscillatory_margin_per_s, sigma, 1e-9 * wn);
      EXPECT_NEAR(p.oscillatory_frequency_Hz, wd / kTwoPi, 1e-9 * wn / kTwoPi);
      EXPECT_EQ(p.eigenvalues.size(), 2);
      EXPECT_EQ(p.rigid_body_modes, 0);
      if (c + s != 0.0) {
        EXPECT_EQ(p.stable, c + s > 0.0);
      }
    }
  }
}

// Just either side of c + s = 0 the verdict flips, and at it the margin is 0.
TEST(Stability, OneDofVerdictFlipsAtCPlusSlopeZero) {
  const double J = 0.02, k = 1.1e5, c = 0.95;
  const auto at = [&](double s) {
    TorsionalNetwork net;
    const int d = add_driver(net, 5.0);
    const int m = net.add_inertia({"mass", J});
    net.add_shaft({"spring", m, kGround, k, c});
    net.add_contact({"contact", d, m, slope_law(s)});
    return linearise(net, {{5.0}, {}, 0.0});
  };
  EXPECT_NEAR(at(-c).margin_per_s, 0.0, 1e-9 * std::sqrt(k / J));
  EXPECT_TRUE(at(-c + 1e-4).stable);
  EXPECT_FALSE(at(-c - 1e-4).stable);
  EXPECT_NEAR(at(-c - 1e-4).margin_per_s, 1e-4 / (2.0 * J), 1e-9 * std::sqrt(k / J));
}

// ---------------------------------------------------------------------------------------------
// 2a. Two degrees of freedom in a chain, driven at one end through the contact.
//
//     driver ══ Ω ─┤s├─ J1 ── k2, c2 ── J2 ── k1, c1 ── ground
//
//     M = diag(J1, J2),  C = [s + c2, −c2; −c2, c1 + c2],  K = [k2, −k2; −k2, k1 + k2]
//     det(M λ² + C λ + K) = (J1 λ² + (s + c2) λ + k2)(J2 λ² + (c1 + c2) λ + k1 + k2) − (c2 λ + k2)²
//       = J1 J2 λ⁴ + [J1 (c1 + c2) + J2 (s + c2)] λ³
//         + [J1 (k1 + k2) + J2 k2 + (s + c2)(c1 + c2) − c2²] λ²
//         + [(s + c2)(k1 + k2) + k2 (c1 + c2) − 2 c2 k2] λ + k1 k2
// Its four roots (companion matrix) against the linearisation's eigenvalues, 1e-9 relative.
// ---------------------------------------------------------------------------------------------
TEST(Stability, TwoDofChainMatchesCharacteristicPolynomialRoots) {
  const double J1 = 0.5, J2 = 0.2, k1 = 400.0, k2 = 900.0, c1 = 0.3, c2 = 0.2;
  for (const double s : {1.0, 0.0, -0.4, -2.0}) {
    SCOPED_TRACE(::testing::Message() << "slope " << s);
    TorsionalNetwork net;
    const int d = add_driver(net, 3.0);
    const int a = net.add_inertia({"J1", J1});
    const int b = net.add_inertia({"J2", J2});
    net.add_contact({"contact", d, a, slope_law(s)});
    net.add_shaft({"k2", a, b, k2, c2});
    net.add_shaft({"k1", b, kGround, k1, c1});
    net.validate();
    const StabilityPoint p = linearise(net, {{3.0}, {}, 0.0});

    const Eigen::VectorXcd roots = quartic_roots(J1 * J2, J1 * (c1 + c2) + J2 * (s + c2),
                                                 J1 * (k1 + k2) + J2 * k2 + (s + c2) * (c1 + c2) - c2 * c2,
                                                 (s + c2) * (k1 + k2) + k2 * (c1 + c2) - 2.0 * c2 * k2, k1 * k2);
    EXPECT_LT(relative_mismatch(p.eigenvalues, roots), 1e-9);
    EXPECT_NEAR(p.margin_per_s, max_real(roots), 1e-9 * roots.cwiseAbs().maxCoeff());
    EXPECT_EQ(p.stable, max_real(roots) < 0.0);
  }
}

// ---------------------------------------------------------------------------------------------
// 2b. Two degrees of freedom with a speed-controlled motor (the rig's structure): the contact
// sits between two moving inertias and the PI loop enters as a spring K_i and damper K_p.
//
//     motor (K_p, K_i) ⇒ J1 ─┤s├─ J2 ── k2, c2 ── ground        Δω = ω1 − ω2 > 0
//
//     M = diag(J1, J2),  C = [K_p + s, −s; −s, c2 + s],  K = diag(K_i, k2)
//     det = (J1 λ² + (K_p + s) λ + K_i)(J2 λ² + (c2 + s) λ + k2) − s² λ²
//       = J1 J2 λ⁴ + [J1 (c2 + s) + J2 (K_p + s)] λ³ + [J1 k2 + J2 K_i + (K_p + s)(c2 + s) − s²] λ²
//         + [(K_p + s) k2 + K_i (c2 + s)] λ + K_i k2
// The stuck clutch instead ties J1 to J2: (J1 + J2) λ² + (K_p + c2) λ + K_i + k2 = 0, slope gone.
// ---------------------------------------------------------------------------------------------
TorsionalNetwork motor_pair(double J1, double J2, double kp, double ki, double k2, double c2, double s) {
  TorsionalNetwork net;
  const int a = net.add_inertia({"J1", J1});
  const int b = net.add_inertia({"J2", J2});
  net.add_motor({"motor", a, [](double) { return 4.0; }, kp, ki, 1e3});
  net.add_contact({"contact", a, b, slope_law(s)});
  net.add_shaft({"k2", b, kGround, k2, c2});
  net.validate();
  return net;
}

TEST(Stability, TwoDofWithMotorLoopMatchesCharacteristicPolynomialRoots) {
  const double J1 = 0.6, J2 = 0.05, kp = 3.0, ki = 20.0, k2 = 500.0, c2 = 0.1;
  for (const double s : {0.5, -0.05, -0.4}) {
    SCOPED_TRACE(::testing::Message() << "slope " << s);
    const StabilityPoint p = linearise(motor_pair(J1, J2, kp, ki, k2, c2, s), {{4.0}, {}, 0.0});
    const Eigen::VectorXcd roots =
        quartic_roots(J1 * J2, J1 * (c2 + s) + J2 * (kp + s), J1 * k2 + J2 * ki + (kp + s) * (c2 + s) - s * s,
                      (kp + s) * k2 + ki * (c2 + s), ki * k2);
    EXPECT_LT(relative_mismatch(p.eigenvalues, roots), 1e-9);
    EXPECT_NEAR(p.margin_per_s, max_real(roots), 1e-9 * roots.cwiseAbs().maxCoeff());
    EXPECT_EQ(p.stable, max_real(roots) < 0.0);
  }
}

TEST(Stability, StuckContactIsAConstraintAndItsSlopeDropsOut) {
  const double J1 = 0.6, J2 = 0.05, kp = 3.0, ki = 20.0, k2 = 500.0, c2 = 0.1;
  const double sigma = -(kp + c2) / (2.0 * (J1 + J2));
  const double wd = std::sqrt((ki + k2) / (J1 + J2) - sigma * sigma);
  for (const double s : {0.5, -3.0}) {
    const auto net = motor_pair(J1, J2, kp, ki, k2, c2, s);
    // Stuck by zero slip and by the flag (whatever the slip).
    for (const SteadySliding& steady : {SteadySliding{{0.0}, {}, 0.0}, SteadySliding{{4.0}, {true}, 0.0}}) {
      const StabilityPoint p = linearise(net, steady);
      ASSERT_EQ(p.eigenvalues.size(), 2);
      EXPECT_NEAR(p.margin_per_s, sigma, 1e-10 * wd);
      EXPECT_NEAR(p.frequency_Hz, wd / kTwoPi, 1e-10 * wd);
    }
  }
}

// ---------------------------------------------------------------------------------------------
// 3. A free body behind a slipping contact (no spring anywhere):
//     driver ══ Ω ─┤s├─ J        J q'' = −s q'   ⇒   λ = 0 (angle drift, no force depends on
// it) and λ = −s/J. The drift is left out: margin −s/J, one rigid-body mode, not oscillatory.
// ---------------------------------------------------------------------------------------------
TEST(Stability, RigidBodyDriftIsLeftOutOfTheMargin) {
  const double J = 0.3;
  for (const double s : {0.6, -0.6}) {
    TorsionalNetwork net;
    const int d = add_driver(net, 2.0);
    const int m = net.add_inertia({"free", J});
    net.add_contact({"contact", d, m, slope_law(s)});
    const StabilityPoint p = linearise(net, {{2.0}, {}, 0.0});
    EXPECT_EQ(p.rigid_body_modes, 1);
    ASSERT_EQ(p.eigenvalues.size(), 2);
    EXPECT_NEAR(p.margin_per_s, -s / J, 1e-12);
    EXPECT_EQ(p.frequency_Hz, 0.0);
    EXPECT_TRUE(std::isnan(p.oscillatory_margin_per_s));
    EXPECT_EQ(p.stable, s > 0);
  }
}

TEST(Stability, BadInputNamesTheQuantity) {
  const auto net = motor_pair(0.6, 0.05, 3.0, 20.0, 500.0, 0.1, 0.1);
  EXPECT_THAT(
      [&] {
        linearise(net, {{}, {}, 0.0});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("one slip (rad/s, 0 = stuck) per contact")));
  EXPECT_THAT(
      [&] {
        linearise(net, {{1.0}, {true, false}, 0.0});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(::testing::HasSubstr("stuck flags")));
  EXPECT_THAT(
      [&] {
        linearise(net, {{NAN}, {}, 0.0});
      },
      ::testing::ThrowsMessage<std::invalid_argument>(
          ::testing::HasSubstr("slip of contact 'contact' must be finite")));
}

}  // namespace
