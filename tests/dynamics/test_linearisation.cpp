// dynamics/linearisation.hpp against closed forms: a two-inertia shaft, a slipping contact's
// slope as (negative) damping, and a tyre's relaxation between a wheel and a car.
#include "dynamics/linearisation.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <complex>
#include <memory>

#include "components/tyre.hpp"
#include "tests/dynamics/test_laws.hpp"

namespace shudder::dynamics {
namespace {

// The oscillatory eigenvalue (Im > 0) of largest imaginary part.
std::complex<double> top_mode(const LinearSystem& sys) {
  const auto modes = linear_modes(sys);
  std::complex<double> best{0, 0};
  for (const auto& m : modes)
    if (m.eigenvalue.imag() > best.imag()) best = m.eigenvalue;
  return best;
}

//   J1 ─k, c─ J2,  free: one rigid drift (λ = 0) and ω_n² = k (J1 + J2)/(J1 J2),
//   σ = −c (J1 + J2)/(2 J1 J2).
TEST(Linearisation, TwoInertiaShaftMatchesClosedForm) {
  TorsionalNetwork net;
  net.add_inertia({"a", 2.0});
  net.add_inertia({"b", 0.5});
  net.add_shaft({"s", 0, 1, 8000.0, 3.0});
  LinearOperatingPoint op;
  op.omega_rad_s = Eigen::Vector2d(10.0, 10.0);
  op.element_states = Eigen::VectorXd(0);
  const LinearSystem sys = linearise_network(net, op);
  EXPECT_EQ(sys.rigid_body_modes, 1);
  const double jr = 2.0 * 0.5 / 2.5;
  const double sigma = -3.0 / (2 * jr), wn2 = 8000.0 / jr;
  const auto l = top_mode(sys);
  EXPECT_NEAR(l.real(), sigma, 1e-9 * std::abs(sigma));  // eigen-solver round-off
  EXPECT_NEAR(l.imag(), std::sqrt(wn2 - sigma * sigma), 1e-9 * std::sqrt(wn2));
}

//   J on a bar k, c to ground, driven through a slipping contact of slope s at 5 rad/s:
//   J δθ̈ + (c + s) δθ̇ + k δθ = 0 — a negative slope beyond −c makes it grow.
TEST(Linearisation, SlippingContactSlopeIsDamping) {
  for (double slope : {2.0, -0.5, -4.0}) {
    TorsionalNetwork net;
    net.add_inertia({"housing", 0.1});
    net.add_shaft({"bar", 0, kGround, 4.0e4, 1.0});
    net.add_contact({"clutch", 0, kGround, std::make_shared<testing::LinearSlopeLaw>(10.0, slope, 20.0)});
    LinearOperatingPoint op;
    op.omega_rad_s = Eigen::VectorXd::Constant(1, -5.0);  // either slip direction gives the same damper
    op.element_states = Eigen::VectorXd(0);
    const LinearSystem sys = linearise_network(net, op);
    EXPECT_EQ(sys.rigid_body_modes, 0);
    EXPECT_DOUBLE_EQ(sys.contact_slope_Nms[0], slope);
    const auto l = top_mode(sys);
    EXPECT_NEAR(l.real(), -(1.0 + slope) / (2 * 0.1), 1e-9 * 600);  // round-off of |λ| ≈ 630
    EXPECT_EQ(l.real() > 0, slope < -1.0);
    // Stuck: the contact is a constraint to ground and nothing moves.
    op.stuck = {true};
    EXPECT_EQ(linearise_network(net, op).reduced_dofs, 0);
  }
}

//   wheel J_w ~tyre~ car J_v (ρ = 1), both rolling at V = ω r, no load (u = 0):
//   δu̇ = r (δω_w − δω_v) − (V/σ) δu,  J_w δω̇_w = −r k_u δu,  J_v δω̇_v = r k_u δu  (k_u = C_κ/σ)
//   ⇒ δü + (V/σ) δu̇ + r² k_u (1/J_w + 1/J_v) δu = 0: the tyre's slip damping falls with speed.
TEST(Linearisation, TyreRelaxationMatchesClosedForm) {
  components::TyreParams tp;
  tp.slip_stiffness_N = 1.2e5;
  tp.relaxation_length_m = 0.4;
  tp.vertical_load_N = 5000.0;
  tp.radius_m = 0.3;
  const double jw = 1.2, jv = 150.0;
  for (double v : {0.0, 1.0, 10.0, 40.0}) {
    TorsionalNetwork net;
    net.add_inertia({"wheel", jw});
    net.add_inertia({"car", jv});
    net.add_force_element({"tyre", 0, 1, 1.0, std::make_shared<components::BrushTyre>(tp)});
    LinearOperatingPoint op;
    op.omega_rad_s = Eigen::Vector2d(v / tp.radius_m, v / tp.radius_m);
    op.element_states = Eigen::VectorXd::Zero(1);
    const LinearSystem sys = linearise_network(net, op);
    EXPECT_EQ(sys.rigid_body_modes, 2);  // no shaft: both angles drift freely
    const double a1 = v / tp.relaxation_length_m;
    const double a0 = tp.radius_m * tp.radius_m * (*tp.slip_stiffness_N) / tp.relaxation_length_m * (1 / jw + 1 / jv);
    const std::complex<double> expected = -a1 / 2 + std::sqrt(std::complex<double>(a1 * a1 / 4 - a0));
    const auto modes = linear_modes(sys);
    // Closest eigenvalue to the closed form; the other root is the common speed's zero.
    double err = 1e300;
    for (const auto& m : modes) err = std::min(err, std::abs(m.eigenvalue - expected));
    EXPECT_LT(err, 1e-6 * std::abs(expected)) << "V = " << v;  // central differences, ~1e-8 relative
  }
}

TEST(Linearisation, RejectsWrongSizes) {
  TorsionalNetwork net;
  net.add_inertia({"a", 1.0});
  net.add_shaft({"s", 0, kGround, 1.0, 0.0});
  LinearOperatingPoint op;
  op.omega_rad_s = Eigen::Vector2d(1, 2);
  try {
    linearise_network(net, op);
    FAIL();
  } catch (const std::invalid_argument& e) {
    EXPECT_STREQ(e.what(), "linearisation: node speeds must be 1 finite values");
  }
}

}  // namespace
}  // namespace shudder::dynamics
