// WetClutch: torque and heat of boundary friction (and optional viscous shear) summed over the
// radial rings of the thermal grid, against closed forms for a uniform-pressure annulus.
//
//          R_in                 R_out            p = F / (pi (R_out² - R_in²))
//           |<------ n_r rings of width dr ------>|   ring i: centre r_i, area A_i = 2 pi r_i dr
//
// Torque of n sliding interfaces with constant mu:
//     M = n mu p ∫ r 2 pi r dr = n mu p (2/3) pi (R_out³ - R_in³)
// The rings evaluate this integral by the midpoint rule. For f(r) = 2 pi r² (f'' = 4 pi, all
// higher derivatives 0) the midpoint error is exactly sum f'' dr³/24:
//     sum_i 2 pi r_i² dr = (2/3) pi (R_out³ - R_in³) - (pi/6) dr² (R_out - R_in)
//     relative error = dr² (R_out - R_in) / (4 (R_out³ - R_in³)) <= (dr/R_in)² / 12.
// Viscous (Couette) torque of the film, tau = eta r w / h:
//     M_v = n eta w/h ∫ r² 2 pi r dr = n eta w/h (pi/2) (R_out⁴ - R_in⁴),
// and for f = 2 pi r³ (f'' = 12 pi r, f'''' = 0) the midpoint error is again exactly
//     sum f''(r_i) dr³/24 = (pi/4) dr² (R_out² - R_in²),
//     relative error = dr² / (2 (R_out² + R_in²)).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>
#include <numbers>
#include <stdexcept>
#include <utility>
#include <vector>

#include "clutch/fluid.hpp"
#include "clutch/friction_law.hpp"
#include "clutch/maki_friction.hpp"
#include "clutch/wet_clutch.hpp"
#include "io/fluid_loader.hpp"

namespace {

using shudder::clutch::Fluid;
using shudder::clutch::FrictionLaw;
using shudder::clutch::WetClutch;
using shudder::clutch::WetClutchParams;

using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// mu = mu0 + dmu_dT * T + dmu_dF * F: constant, linear in temperature or linear in load.
class AffineFriction final : public FrictionLaw {
 public:
  AffineFriction(double mu0, double dmu_dT, double dmu_dF) : mu0_(mu0), dT_(dmu_dT), dF_(dmu_dF) {}
  double mu(double, double temp_C, double load_N) const override { return mu0_ + dT_ * temp_C + dF_ * load_N; }
  double dmu_dv_per_mm_s(double, double, double) const override { return 0.0; }
  double min_speed_mm_s() const override { return 1.0; }

 private:
  double mu0_, dT_, dF_;
};

Fluid fluid_with(double mu0, double dmu_dT = 0.0, double dmu_dF = 0.0) {
  Fluid f;
  f.name = "test";
  f.friction = std::make_shared<AffineFriction>(mu0, dmu_dT, dmu_dF);
  return f;
}

WetClutchParams clutch_params() {
  WetClutchParams p;  // Paper G annulus, 20 rings
  p.sliding_interfaces = 3;
  p.start_temp_C = 60.0;
  p.sump_start_temp_C = 60.0;
  return p;
}

// Closed-form pieces of the annulus.
struct Annulus {
  double ri, ro, dr;
  explicit Annulus(const WetClutchParams& p)
      : ri(p.thermal.inner_radius_m), ro(p.thermal.outer_radius_m), dr((ro - ri) / p.thermal.radial_cells) {}
  double area() const { return std::numbers::pi * (ro * ro - ri * ri); }
  double r2_integral() const { return 2.0 / 3.0 * std::numbers::pi * (ro * ro * ro - ri * ri * ri); }
  double r2_midpoint_error() const { return std::numbers::pi / 6.0 * dr * dr * (ro - ri); }
  double r3_integral() const { return std::numbers::pi / 2.0 * (std::pow(ro, 4) - std::pow(ri, 4)); }
  double r3_midpoint_error() const { return std::numbers::pi / 4.0 * dr * dr * (ro * ro - ri * ri); }
};

// Sums are exact up to a few ulp per ring: relative 1e-12 wherever an identity is checked.
constexpr double kRoundOff = 1e-12;

TEST(WetClutch, ConstantMuTorqueMatchesTheUniformPressureAnnulus) {
  constexpr double mu = 0.12, force = 20000.0, slip = 5.0;
  const WetClutchParams p = clutch_params();
  const WetClutch clutch(p, fluid_with(mu));
  const Annulus an(p);
  const int n = p.sliding_interfaces;
  const Eigen::VectorXd temps = Eigen::VectorXd::Constant(p.thermal.radial_cells, 60.0);

  // The rings tile the annulus exactly, so p is the nominal pressure.
  EXPECT_NEAR(clutch.pressure_Pa(force) / (force / an.area()), 1.0, kRoundOff);

  const double torque = clutch.torque_Nm(slip, force, temps);
  const double closed = n * mu * (force / an.area()) * an.r2_integral();
  const double rel = torque / closed - 1.0;
  const double ratio = an.dr / an.ri;
  EXPECT_LT(std::abs(rel), ratio * ratio / 12.0);  // midpoint-rule bound (header): 5e-5
  EXPECT_LT(rel, 0.0);                             // the midpoint rule under-integrates r²
  // ... and the error is exactly the midpoint term, so nothing else is hidden in the sum.
  EXPECT_NEAR(torque / (n * mu * (force / an.area()) * (an.r2_integral() - an.r2_midpoint_error())), 1.0, kRoundOff);
  // Mean radius sum(r_i A_i)/A: the same midpoint sum over the area.
  EXPECT_NEAR(clutch.mean_radius_m() / ((an.r2_integral() - an.r2_midpoint_error()) / an.area()), 1.0, kRoundOff);
}

TEST(WetClutch, TorqueSignFollowsSlipAndHeatPerInterfaceIsSlipTimesTorqueOverN) {
  const WetClutchParams p = clutch_params();
  const WetClutch clutch(p, fluid_with(0.1));
  const Eigen::VectorXd temps = Eigen::VectorXd::LinSpaced(p.thermal.radial_cells, 60.0, 95.0);
  for (const double slip : {0.3, 7.0, 40.0}) {
    const double fwd = clutch.torque_Nm(slip, 15000.0, temps);
    const double back = clutch.torque_Nm(-slip, 15000.0, temps);
    EXPECT_GT(fwd, 0.0);
    EXPECT_EQ(back, -fwd);  // |slip| enters the friction law; the sign is copied afterwards
    for (const double s : {slip, -slip}) {
      Eigen::VectorXd heat;
      clutch.ring_heat_W(s, 15000.0, temps, heat);
      ASSERT_EQ(heat.size(), p.thermal.radial_cells);
      EXPECT_GE(heat.minCoeff(), 0.0);
      // q per interface = |slip| |M| / n: the friction power of one interface.
      EXPECT_NEAR(heat.sum(), std::abs(s) * std::abs(fwd) / p.sliding_interfaces, kRoundOff * heat.sum());
    }
  }
}

// mu = 0.15 - 5e-4 T on a radial temperature gradient 50..90 °C.
//   on:  M = n p sum_i r_i A_i (0.15 - 5e-4 T_i)           (each ring at its own temperature)
//   off: M = n p (0.15 - 5e-4 T_start) sum_i r_i A_i       (clutch start temperature, 60 °C)
TEST(WetClutch, TemperatureDependentFrictionOffUsesTheStartTemperature) {
  constexpr double mu0 = 0.15, dmu_dT = -5e-4, force = 20000.0, slip = 3.0;
  WetClutchParams p = clutch_params();
  const Eigen::VectorXd temps = Eigen::VectorXd::LinSpaced(p.thermal.radial_cells, 50.0, 90.0);
  const WetClutch on(p, fluid_with(mu0, dmu_dT));
  p.temperature_dependent_friction = false;
  const WetClutch off(p, fluid_with(mu0, dmu_dT));
  const auto& r = on.thermal().ring_radius_m();
  const auto& a = on.thermal().ring_area_m2();
  const double pressure = on.pressure_Pa(force);
  const int n = p.sliding_interfaces;

  double expected_on = 0.0;
  for (int i = 0; i < r.size(); ++i) expected_on += r[i] * a[i] * (mu0 + dmu_dT * temps[i]);
  expected_on *= n * pressure;
  EXPECT_NEAR(on.torque_Nm(slip, force, temps) / expected_on, 1.0, kRoundOff);

  const double expected_off = n * pressure * (mu0 + dmu_dT * p.start_temp_C) * r.dot(a);
  EXPECT_NEAR(off.torque_Nm(slip, force, temps) / expected_off, 1.0, kRoundOff);
  // Independent of the ring temperatures altogether.
  EXPECT_EQ(off.torque_Nm(slip, force, temps), off.torque_Nm(slip, force, Eigen::VectorXd::Constant(r.size(), 150.0)));
  // The gradient is mostly hotter than 60 °C, so switching the effect off raises the torque.
  EXPECT_GT(expected_off, expected_on);
}

// mu = 0.08 + 1e-6/N * F at F = 12 kN (mu 0.092) with reference_load_N = 20 kN (mu 0.100):
//   off: M = n (F/A) (0.08 + 1e-6 F_ref) sum r_i A_i   (pressure from the real load, mu from the
//        reference load)
TEST(WetClutch, LoadDependentFrictionOffUsesTheReferenceLoad) {
  constexpr double mu0 = 0.08, dmu_dF = 1e-6, force = 12000.0;
  WetClutchParams p = clutch_params();
  p.reference_load_N = 20000.0;
  const Eigen::VectorXd temps = Eigen::VectorXd::Constant(p.thermal.radial_cells, 70.0);
  const WetClutch on(p, fluid_with(mu0, 0.0, dmu_dF));
  p.load_dependent_friction = false;
  const WetClutch off(p, fluid_with(mu0, 0.0, dmu_dF));
  const auto& r = on.thermal().ring_radius_m();
  const auto& a = on.thermal().ring_area_m2();
  const double base = p.sliding_interfaces * on.pressure_Pa(force) * r.dot(a);
  EXPECT_NEAR(on.torque_Nm(2.0, force, temps) / (base * (mu0 + dmu_dF * force)), 1.0, kRoundOff);
  EXPECT_NEAR(off.torque_Nm(2.0, force, temps) / (base * (mu0 + dmu_dF * p.reference_load_N)), 1.0, kRoundOff);
}

// Viscous shear of the film at a uniform 80 °C, eta = rho * nu(T) from the Walther line through
// (40 °C, 35 cSt) and (100 °C, 6.7 cSt), computed here by hand:
//     log10(log10(nu + 0.7)) = A - B log10(T_K)
// With mu = 0 the torque is the viscous part alone; with mu = 0.1 it adds to the friction torque.
TEST(WetClutch, ViscousShearAddsTheCouetteTorqueOfTheAnnulus) {
  constexpr double temp = 80.0, slip = 10.0, force = 20000.0;
  WetClutchParams p = clutch_params();
  p.viscous_shear = true;
  p.viscous_gap_m = 10e-6;
  const Annulus an(p);
  const Eigen::VectorXd temps = Eigen::VectorXd::Constant(p.thermal.radial_cells, temp);
  const WetClutch shear_only(p, fluid_with(0.0));
  const Fluid& fluid = shear_only.fluid();

  const auto loglog = [](double nu) { return std::log10(std::log10(nu + 0.7)); };
  const double x40 = std::log10(313.15), x100 = std::log10(373.15);
  const double B = (loglog(fluid.nu40_cSt) - loglog(fluid.nu100_cSt)) / (x100 - x40);
  const double A = loglog(fluid.nu40_cSt) + B * x40;
  const double nu_cSt = std::pow(10.0, std::pow(10.0, A - B * std::log10(temp + 273.15))) - 0.7;
  EXPECT_NEAR(nu_cSt, 10.3, 0.05);  // docs/physics.md §3: ≈ 10.3 cSt at 80 °C (its 3 digits)
  const double eta = fluid.density_kg_m3 * nu_cSt * 1e-6;

  const int n = p.sliding_interfaces;
  const double torque = shear_only.torque_Nm(slip, force, temps);
  const double closed = n * eta * slip / p.viscous_gap_m * an.r3_integral();
  const double rel = torque / closed - 1.0;
  const double bound = an.dr * an.dr / (2.0 * (an.ro * an.ro + an.ri * an.ri));  // ≈ 1.8e-4
  EXPECT_LT(std::abs(rel), bound * (1.0 + 1e-9));
  EXPECT_NEAR(torque / (n * eta * slip / p.viscous_gap_m * (an.r3_integral() - an.r3_midpoint_error())), 1.0,
              1e-11);  // hand Walther vs the class: a few ulp through pow(10, pow(10, .))
  EXPECT_EQ(shear_only.torque_Nm(-slip, force, temps), -torque);

  // Added to friction, and its heat counted: q per interface = |slip| (M_f + M_v) / n.
  const WetClutch both(p, fluid_with(0.1));
  p.viscous_shear = false;
  const WetClutch friction_only(p, fluid_with(0.1));
  const double m_both = both.torque_Nm(slip, force, temps);
  EXPECT_NEAR(m_both, friction_only.torque_Nm(slip, force, temps) + torque, kRoundOff * m_both);
  Eigen::VectorXd heat;
  both.ring_heat_W(slip, force, temps, heat);
  EXPECT_NEAR(heat.sum(), slip * m_both / n, kRoundOff * heat.sum());
}

TEST(WetClutch, RejectsBadParametersNamingTheQuantity) {
  WetClutchParams p = clutch_params();
  p.sliding_interfaces = 0;
  EXPECT_THAT([&] { WetClutch c(p, fluid_with(0.1)); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("sliding interfaces must be in [1, 64]")));
  p = clutch_params();
  p.viscous_gap_m = 0.0;
  EXPECT_THAT([&] { WetClutch c(p, fluid_with(0.1)); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("viscous gap must be > 0")));
  Fluid no_law;
  EXPECT_THAT([&] { WetClutch c(clutch_params(), no_law); },
              ThrowsMessage<std::invalid_argument>(HasSubstr("clutch fluid has no friction law")));
}

}  // namespace

// The fast path of the rig dynamics: friction frozen per ring at held temperatures and load
// (FrozenFriction, the Mäki blend rewritten as Σ a_j tanh(b_j v) + c v^0.1 + d with one pow per
// call) must give the same ring torques as evaluating the law directly. Fluid C's matrix, a
// non-uniform ring temperature profile crossing matrix rows, slips on both sides of the speed
// clamps, viscous shear on. Tolerance 1e-12 relative: the two differ only in the order of
// floating-point operations (v^0.1 as r^0.1·|Δω|^0.1).

TEST(WetClutch, FrozenFrictionEqualsDirectEvaluation) {
  WetClutchParams p;
  p.start_temp_C = 60.0;
  p.viscous_shear = true;
  const WetClutch clutch(p, shudder::io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml"));
  const int n = clutch.thermal().radial_cells();
  Eigen::VectorXd temps(n);
  for (int i = 0; i < n; ++i) temps[i] = 45.0 + 60.0 * i / (n - 1);  // 45–105 °C: several rows and the 90 °C edge
  for (double force : {12000.0, 17500.0, 25300.0}) {
    const auto frozen = clutch.freeze(temps, force);
    for (double slip : {0.05, 0.2, 1.0, 5.0, 10.5, 14.0}) {  // rad/s: below 6 mm/s ... above 590 mm/s
      Eigen::VectorXd direct, fast, heat;
      clutch.ring_heat_W(slip, force, temps, heat);
      direct = heat / slip;
      clutch.ring_torque_Nm(frozen, slip, force, fast);
      for (int i = 0; i < n; ++i)
        EXPECT_NEAR(fast[i], direct[i], 1e-12 * std::abs(direct[i]))
            << "force " << force << " slip " << slip << " ring " << i;
    }
  }
}

// The two ends of a ring-temperature ramp in one pass (ring_torque_pair_Nm, the driveline's
// first-order hold): each end's ring torques must be those of ring_torque_Nm of that end, bit
// for bit (the pass only reuses v^0.1 and the tanh of rates both ends share, same operations in
// the same order). Fluid C: ends 0.4 K apart (one matrix bracket, every rate shared: the common
// case), ends in different rows (-30 vs 70-105 °C: some rates shared, some not) and at different
// loads' brackets cannot happen (one force); slips below, inside and above the speed clamps and
// 0; viscous shear on and off. A law without the SpeedCurve form falls back to two evaluations.
TEST(WetClutch, PairEvaluationOfTwoFrozenStatesEqualsTwoSingleEvaluationsBitForBit) {
  for (bool viscous : {false, true}) {
    WetClutchParams p;
    p.start_temp_C = 60.0;
    p.viscous_shear = viscous;
    const WetClutch clutch(p, shudder::io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml"));
    const int n = clutch.thermal().radial_cells();
    Eigen::VectorXd warm(n), warmer(n), cold(n);
    for (int i = 0; i < n; ++i) {
      warm[i] = 45.0 + 60.0 * i / (n - 1);
      warmer[i] = warm[i] + 0.4;
      cold[i] = -30.0 + 0.1 * i;
    }
    for (double force : {12000.0, 17500.0, 25300.0}) {
      for (const auto& [a_C, b_C] : {std::pair{warm, warmer}, std::pair{warmer, warm}, std::pair{cold, warm}}) {
        const auto fa = clutch.freeze(a_C, force);
        const auto fb = clutch.freeze(b_C, force);
        for (double slip : {0.0, 0.05, 0.2, 1.0, 5.0, 10.5, 14.0}) {
          Eigen::VectorXd single_a, single_b, pair_a, pair_b;
          clutch.ring_torque_Nm(fa, slip, force, single_a);
          clutch.ring_torque_Nm(fb, slip, force, single_b);
          clutch.ring_torque_pair_Nm(fa, fb, slip, force, pair_a, pair_b);
          ASSERT_EQ(pair_a.size(), n);
          ASSERT_EQ(pair_b.size(), n);
          for (int i = 0; i < n; ++i) {
            EXPECT_EQ(pair_a[i], single_a[i]) << "force " << force << " slip " << slip << " ring " << i;
            EXPECT_EQ(pair_b[i], single_b[i]) << "force " << force << " slip " << slip << " ring " << i;
          }
        }
      }
    }
  }
  // No SpeedCurve form (an affine law): the two plain evaluations.
  const WetClutch affine(clutch_params(), fluid_with(0.1, -2e-4));
  const int n = affine.thermal().radial_cells();
  const Eigen::VectorXd a_C = Eigen::VectorXd::Constant(n, 50.0), b_C = Eigen::VectorXd::Constant(n, 90.0);
  const auto fa = affine.freeze(a_C, 8000.0);
  const auto fb = affine.freeze(b_C, 8000.0);
  ASSERT_TRUE(fa.curves.empty());
  Eigen::VectorXd single_a, single_b, pair_a, pair_b;
  affine.ring_torque_Nm(fa, 2.0, 8000.0, single_a);
  affine.ring_torque_Nm(fb, 2.0, 8000.0, single_b);
  affine.ring_torque_pair_Nm(fa, fb, 2.0, 8000.0, pair_a, pair_b);
  EXPECT_EQ(pair_a, single_a);
  EXPECT_EQ(pair_b, single_b);
  EXPECT_LT(pair_b[0], pair_a[0]);  // the two ends really differ (mu falls with temperature)
}

// The frozen evaluation takes each rate's tanh along the rings by a recurrence on
// e = expm1(2 b v) (RingSpeedTerms, clutch/wet_clutch.cpp), restarted from an exact expm1 every
// 16 rings; the direct evaluation takes std::tanh ring by ring. The recurrence's round-off grows
// by a few ε per ring carried, so with the restarts it stays below ~50 ε (1e-14) of tanh for any
// number of rings: bound 1e-13 relative per ring torque. 200 rings (12 restarts); a Mäki matrix
// whose four sets have four rates: slow (fluid C's size, 0.002 per mm/s), saturating (0.5: e up
// to e^590, near the 600 carried limit), negative, and one beyond the limit (2.0: tanh ring by
// ring); slips with every ring inside the speed clamp and with rings on both clamps.
TEST(WetClutch, FrozenFrictionOnManyRingsStaysWithinRoundOffOfTheDirectEvaluation) {
  Fluid f;
  f.name = "four rates";
  f.friction = std::make_shared<shudder::clutch::MakiFrictionMatrix>(
      std::vector<double>{10000.0, 20000.0}, std::vector<double>{40.0, 80.0},
      std::vector<shudder::clutch::MakiSet>{
          {-0.03, 0.002, 0.08, 0.02}, {0.02, 0.5, 0.07, 0.01}, {0.025, -0.3, 0.075, 0.05}, {-0.02, 2.0, 0.085, 0.03}},
      6.0, 590.0);
  WetClutchParams p;
  p.thermal.radial_cells = 200;
  const WetClutch clutch(p, f);
  const int n = clutch.thermal().radial_cells();
  const Eigen::VectorXd temps = Eigen::VectorXd::LinSpaced(n, 50.0, 70.0);
  const auto frozen = clutch.freeze(temps, 15000.0);
  ASSERT_EQ(frozen.rates.size(), 4U);
  for (double slip : {0.15, 0.2, 1.0, 5.0, 10.0, 12.0}) {  // rad/s: lowest rings clamped ... highest rings clamped
    Eigen::VectorXd direct, fast;
    clutch.ring_torque_Nm(slip, 15000.0, temps, direct);
    clutch.ring_torque_Nm(frozen, slip, 15000.0, fast);
    for (int i = 0; i < n; ++i)
      EXPECT_NEAR(fast[i], direct[i], 1e-13 * std::abs(direct[i])) << "slip " << slip << " ring " << i;
  }
}
