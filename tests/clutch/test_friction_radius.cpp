// The friction radius (clutch/friction_radius.hpp): one definition of M = mu F r_eff n, and a law
// fitted at one radius read by a clutch model of another so that it reproduces the torque it
// was fitted on. Closed forms:
//   uniform pressure  r_eff = 2/3 (ro³ − ri³)/(ro² − ri²) = 47.8406 mm for 38.1–56.4 mm;
//   the model's rings: sum r_i A_i / sum A_i, the midpoint rule on ∫ r² dr (A_i = 2 pi r_i dr is
//                     exact), below r_eff by less than r_eff (dr/ri)² / 12
//                     (tests/clutch/test_wet_clutch.cpp);
//   a law recorded at r_law in a clutch of radius r_model with a uniform mu0:
//                     M = mu0 F r_law n exactly (to round-off), whatever the slip.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <memory>

#include "clutch/fluid.hpp"
#include "clutch/friction_radius.hpp"
#include "clutch/maki_friction.hpp"
#include "clutch/wet_clutch.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"
#include "studies/fluid_screening.hpp"

namespace {

using namespace shudder;

class ConstantFriction final : public clutch::FrictionLaw {
 public:
  explicit ConstantFriction(double mu) : mu_(mu) {}
  double mu(double, double, double) const override { return mu_; }
  double dmu_dv_per_mm_s(double, double, double) const override { return 0.0; }
  double min_speed_mm_s() const override { return 1.0; }

 private:
  double mu_;
};

clutch::Fluid constant_fluid(double mu, double radius_mm) {
  clutch::Fluid f;
  f.name = "constant";
  f.friction = std::make_shared<ConstantFriction>(mu);
  f.friction_radius_mm = radius_mm;
  f.friction_radius_convention = radius_mm > 0 ? "uniform_wear" : "";
  return f;
}

TEST(FrictionRadius, UniformPressureRadiusOfPaperGsAnnulus) {
  // 2/3 (56.4³ − 38.1³)/(56.4² − 38.1²) = 2/3 · 124099.803 / 1729.35 = 47.84063 mm.
  EXPECT_NEAR(clutch::uniform_pressure_radius(38.1, 56.4), 47.840635, 1e-6);
  EXPECT_THROW(clutch::uniform_pressure_radius(56.4, 38.1), std::invalid_argument);
}

TEST(FrictionRadius, TheModelsRingsGiveTheUniformPressureRadiusToTheirMidpointError) {
  const clutch::ThermalParams p;  // Paper G's annulus
  const double model_mm = clutch::model_friction_radius_m(p) * 1e3;
  const double exact_mm = clutch::uniform_pressure_radius(p.inner_radius_m * 1e3, p.outer_radius_m * 1e3);
  const double dr = (p.outer_radius_m - p.inner_radius_m) / p.radial_cells;
  EXPECT_LE(model_mm, exact_mm);  // the midpoint rule under-integrates r² (f'' > 0)
  EXPECT_LT(exact_mm - model_mm, exact_mm * std::pow(dr / p.inner_radius_m, 2) / 12.0);
}

TEST(FrictionRadius, TorqueAndMuConvertOneIntoTheOther) {
  // M = mu F r n: 0.12 · 15 kN · 47.84 mm · 2 = 172.22 N m.
  const double m = clutch::torque_from_mu(0.12, 15000.0, 0.04784, 2);
  EXPECT_NEAR(m, 172.224, 1e-9);
  EXPECT_NEAR(clutch::mu_from_torque(m, 15000.0, 0.04784, 2), 0.12, 1e-15);
  EXPECT_EQ(clutch::mu_from_torque(1.0, 0.0, 0.04784, 1), 0.0);
}

TEST(FrictionRadius, ALawRecordedAtAnotherRadiusReproducesItsTorqueInTheModel) {
  clutch::WetClutchParams p;
  p.sliding_interfaces = 2;
  const Eigen::VectorXd temps = Eigen::VectorXd::Constant(p.thermal.radial_cells, 70.0);
  // Recorded at the thesis' 46 mm: the model (47.84 mm) must give mu0 F 46 mm n.
  const clutch::WetClutch worn(p, constant_fluid(0.1, 46.0));
  for (double slip : {0.1, 3.0, 10.0})
    EXPECT_NEAR(worn.torque_Nm(slip, 20000.0, temps), clutch::torque_from_mu(0.1, 20000.0, 0.046, 2), 1e-10);
  // No radius recorded (a local coefficient, Paper G's matrix): the model's own radius.
  const clutch::WetClutch local(p, constant_fluid(0.1, 0.0));
  EXPECT_NEAR(local.torque_Nm(3.0, 20000.0, temps), clutch::torque_from_mu(0.1, 20000.0, local.mean_radius_m(), 2),
              1e-10);
  EXPECT_GT(std::abs(local.torque_Nm(3.0, 20000.0, temps) - worn.torque_Nm(3.0, 20000.0, temps)), 1.0);
}

TEST(FrictionRadius, AConvertedMakiLawKeepsItsFastSpeedCurveForm) {
  // The frozen (SpeedCurve) evaluation of the converted law equals the direct one: the rates,
  // weights and speed range scaled in friction_at_radius are mu(v) = k law(k v) term by term.
  const auto law = std::make_shared<clutch::MakiFrictionMatrix>(
      std::vector<double>{10000.0, 20000.0}, std::vector<double>{40.0, 80.0},
      std::vector<clutch::MakiSet>{{-0.04, 0.002, 0.08, -0.02},
                                   {-0.03, 0.003, 0.09, -0.03},
                                   {-0.035, 0.0015, 0.075, -0.025},
                                   {-0.03, 0.002, 0.085, -0.03}},
      6.0, 590.0);
  clutch::Fluid f;
  f.name = "maki";
  f.friction = law;
  f.friction_radius_mm = 46.0;
  const clutch::WetClutch c({}, f);
  const Eigen::VectorXd temps = Eigen::VectorXd::LinSpaced(c.thermal().ring_radius_m().size(), 50.0, 70.0);
  const auto frozen = c.freeze(temps, 15000.0);
  ASSERT_FALSE(frozen.curves.empty());
  for (double slip : {0.01, 0.5, 5.0, 12.0}) {  // below, inside and above the law's speeds
    Eigen::VectorXd direct, fast;
    c.ring_torque_Nm(slip, 15000.0, temps, direct);
    c.ring_torque_Nm(frozen, slip, 15000.0, fast);
    EXPECT_LT((direct - fast).cwiseAbs().maxCoeff(), 1e-12 * direct.cwiseAbs().maxCoeff()) << slip;
  }
  // The law's speed range in the model's terms: the recorded one times r_model / r_law.
  EXPECT_NEAR(c.fluid().friction->min_speed_mm_s(), 6.0 * c.mean_radius_m() * 1e3 / 46.0, 1e-12);
}

TEST(FrictionRadius, TheFluidFileRecordsItAndTheLoaderReadsItBack) {
  const std::string base =
      "[fluid]\nname = \"x\"\nnu40_cSt = 35.0\nnu100_cSt = 6.7\n[static_friction]\nbreakaway_ratio = 1.0\n"
      "[linear]\nmean_radius_mm = 46.0\nspeeds_rpm = [1.0, 100.0]\nalpha_per_C = [0.0, 0.0]\nbeta = [0.1, 0.12]\n";
  const auto f =
      io::load_fluid_text(base + "[friction_radius]\nconvention = \"uniform_wear\"\nradius_mm = 46.0\n", "f.toml");
  EXPECT_EQ(f.friction_radius_convention, "uniform_wear");
  EXPECT_EQ(f.friction_radius_mm, 46.0);
  EXPECT_EQ(io::load_fluid_text(base, "g.toml").friction_radius_mm, 0.0);
  EXPECT_THAT(
      [&] { io::load_fluid_text(base + "[friction_radius]\nconvention = \"worn\"\nradius_mm = 46.0\n", "h.toml"); },
      ::testing::ThrowsMessage<io::InputError>(
          ::testing::HasSubstr("expected \"uniform_pressure\" or \"uniform_wear\"")));
}

TEST(FrictionRadius, ScreenReadsRpmAtTheRecordedRadius) {
  // The screen converts rpm at the radius the fluid records (1 rpm means what it meant on the rig
  // that measured it), at the rig's 46 mm when it records none.
  clutch::Fluid f;
  f.name = "linear in v";
  f.friction = io::load_fluid_text(
                   "[fluid]\nname = \"x\"\nnu40_cSt = 35.0\nnu100_cSt = 6.7\n[static_friction]\nbreakaway_ratio = 1.0\n"
                   "[table]\nspeeds_mm_s = [1.0, 1000.0]\nloads_N = [20000.0]\n[[table.row]]\ntemp_C = 40.0\n"
                   "mu = [[0.1001, 0.2]]\n",
                   "t.toml")
                   .friction;
  studies::ScreeningOptions o;
  o.temps_C = {40.0};
  o.rigs = {};
  for (const double r_mm : {0.0, 40.0}) {
    f.friction_radius_mm = r_mm;
    const auto rep = studies::screen_fluid(f, o);
    EXPECT_EQ(rep.mean_radius_mm, r_mm > 0 ? r_mm : analysis::kRigMeanRadius_mm);
  }
}

}  // namespace
