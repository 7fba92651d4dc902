// The reconstructed fluid C Mäki matrix, scenarios/fluids/lsc_fluid_c.toml
// (scripts/reconstruct_fluid_c.py, docs/fluid_c_reconstruction.md):
//   * the Paper G Table 2 rows (-40, 70, 200 °C x 10, 15, 20, 25 kN) are kept exactly as printed;
//   * at 20 kN, mu at 1 rpm (4.82 mm/s) and 50 rpm (241 mm/s) follow fluid C's Paper E lines
//         mu1(T) = -4.45e-4*T + 0.1004,   mu50(T) = -1.72e-4*T + 0.1108
//     within 5 % from -20 to 90 °C (the acceptance band of the reconstruction; the published
//     70 °C set itself is 4.8 % below the mu1 line);
//   * friction is held at the end rows beyond -40 and 200 °C.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <vector>

#include "clutch/maki_friction.hpp"
#include "io/fluid_loader.hpp"

namespace {

using shudder::clutch::MakiFrictionMatrix;
using shudder::clutch::MakiSet;

constexpr double kV1 = 4.82, kV50 = 241.0;  // 1 and 50 rpm at the 46 mm mean radius

double line1(double t) { return -4.45e-4 * t + 0.1004; }
double line50(double t) { return -1.72e-4 * t + 0.1108; }

class FluidCMatrix : public ::testing::Test {
 protected:
  void SetUp() override {
    fluid_ = shudder::io::load_fluid(SHUDDER_SOURCE_DIR "/scenarios/fluids/lsc_fluid_c.toml");
    m_ = dynamic_cast<const MakiFrictionMatrix*>(fluid_.friction.get());
    ASSERT_NE(m_, nullptr);
  }
  // Index of temperature row `t`; fails the test if absent.
  std::size_t row(double t) const {
    const auto& ts = m_->temps_C();
    const auto it = std::find(ts.begin(), ts.end(), t);
    EXPECT_NE(it, ts.end()) << "no row at " << t;
    return static_cast<std::size_t>(it - ts.begin());
  }
  // The same matrix without the 6 mm/s speed clamp, so mu(4.82 mm/s) is the sets' own value
  // (the speed at which the reconstruction's targets are defined).
  MakiFrictionMatrix unclamped() const {
    std::vector<MakiSet> sets;
    for (std::size_t i = 0; i < m_->temps_C().size(); ++i)
      for (std::size_t j = 0; j < m_->loads_N().size(); ++j) sets.push_back(m_->set(i, j));
    return MakiFrictionMatrix(m_->loads_N(), m_->temps_C(), sets, 1.0, m_->max_speed_mm_s());
  }

  shudder::clutch::Fluid fluid_;
  const MakiFrictionMatrix* m_ = nullptr;
};

TEST_F(FluidCMatrix, FluidPropertiesAndAxes) {
  EXPECT_EQ(fluid_.name, "lsc-fluid-c");
  EXPECT_EQ(fluid_.nu40_cSt, 35.0);
  EXPECT_EQ(fluid_.nu100_cSt, 6.7);
  EXPECT_EQ(fluid_.density_kg_m3, 868.0);
  EXPECT_EQ(fluid_.breakaway_ratio, 1.0);
  EXPECT_EQ(m_->loads_N(), (std::vector<double>{10000, 15000, 20000, 25000}));
  EXPECT_EQ(m_->temps_C(), (std::vector<double>{-40, -20, -10, 0, 10, 20, 30, 40, 50, 60, 70, 80, 90, 200}));
  EXPECT_EQ(m_->min_speed_mm_s(), 6.0);
  EXPECT_EQ(m_->max_speed_mm_s(), 590.0);
}

TEST_F(FluidCMatrix, ReproducesPublishedTableTwoExactly) {
  // Paper G Table 2 as printed (15 kN / 70 °C C1 = -0.338 kept as printed). Exact equality: the
  // file holds the same decimal literals, which parse to the same doubles.
  const double published[3][4][4] = {{{-0.031, 0.0014, 0.057, 0.035},
                                      {-0.026, 0.0037, 0.035, 0.070},
                                      {-0.0025, 0.013, 0.012, 0.098},
                                      {-0.0024, 0.0098, 0.012, 0.101}},
                                     {{-0.024, 0.0024, 0.070, -0.010},
                                      {-0.338, 0.0001, 0.077, -0.025},
                                      {-0.039, 0.001, 0.077, -0.024},
                                      {-0.038, 0.002, 0.089, -0.036}},
                                     {{-0.024, 0.0024, 0.070, -0.038},
                                      {-0.027, 0.0021, 0.087, -0.067},
                                      {-0.092, 0.0006, 0.097, -0.082},
                                      {-0.038, 0.002, 0.089, -0.063}}};
  const double temps[3] = {-40.0, 70.0, 200.0};
  for (int r = 0; r < 3; ++r) {
    for (std::size_t j = 0; j < 4; ++j) {
      const MakiSet& s = m_->set(row(temps[r]), j);
      EXPECT_EQ(s.c1, published[r][j][0]) << temps[r] << " °C, load " << j;
      EXPECT_EQ(s.c2, published[r][j][1]) << temps[r] << " °C, load " << j;
      EXPECT_EQ(s.c3, published[r][j][2]) << temps[r] << " °C, load " << j;
      EXPECT_EQ(s.c4, published[r][j][3]) << temps[r] << " °C, load " << j;
    }
  }
}

TEST_F(FluidCMatrix, FollowsFluidCLinesWithinFivePercentFromMinusTwentyToNinety) {
  const auto free = unclamped();
  double worst1 = 0.0, worst50 = 0.0, worst1_clamped = 0.0;
  for (int t = -20; t <= 90; ++t) {
    // Interpolated between rows where t is not a row: that is part of what is checked.
    const double d1 = free.mu(kV1, t, 20000.0) / line1(t) - 1.0;
    const double d50 = free.mu(kV50, t, 20000.0) / line50(t) - 1.0;
    // As the simulation sees it: 1 rpm is below 6 mm/s, so mu is held at mu(6 mm/s).
    const double d1c = m_->mu(kV1, t, 20000.0) / line1(t) - 1.0;
    EXPECT_LT(std::abs(d1), 0.05) << t << " °C";
    EXPECT_LT(std::abs(d50), 0.05) << t << " °C";
    EXPECT_LT(std::abs(d1c), 0.05) << t << " °C";
    worst1 = std::max(worst1, std::abs(d1));
    worst50 = std::max(worst50, std::abs(d50));
    worst1_clamped = std::max(worst1_clamped, std::abs(d1c));
  }
  RecordProperty("max_mu1_deviation", std::to_string(worst1));
  RecordProperty("max_mu50_deviation", std::to_string(worst50));
  RecordProperty("max_mu1_clamped_deviation", std::to_string(worst1_clamped));

  // The worst point is the published 70 °C set: mu(4.82) = 0.0659267 (hand value in
  // test_maki_friction.cpp) against the line's 0.1004 - 0.03115 = 0.06925: -4.80 %.
  EXPECT_NEAR(free.mu(kV1, 70.0, 20000.0) / line1(70.0) - 1.0, -0.0480, 1e-4);
  // Reconstructed rows hit the lines up to the 6 significant digits C3, C4 are written with.
  for (double t : {-20.0, -10.0, 0.0, 10.0, 20.0, 30.0, 40.0, 50.0, 60.0, 80.0, 90.0}) {
    EXPECT_NEAR(free.mu(kV1, t, 20000.0) / line1(t), 1.0, 1e-5) << t << " °C";
    EXPECT_NEAR(free.mu(kV50, t, 20000.0) / line50(t), 1.0, 1e-5) << t << " °C";
  }
}

TEST_F(FluidCMatrix, IsHeldAtTheEndRowsBeyondMinusFortyAndTwoHundred) {
  for (double f : {10000.0, 15000.0, 20000.0, 25000.0, 17000.0}) {
    for (double v : {6.0, 50.0, 241.0, 590.0}) {
      EXPECT_EQ(m_->mu(v, -50.0, f), m_->mu(v, -40.0, f)) << f << " N, " << v << " mm/s";
      EXPECT_EQ(m_->mu(v, 250.0, f), m_->mu(v, 200.0, f)) << f << " N, " << v << " mm/s";
    }
  }
}

TEST_F(FluidCMatrix, FrictionStaysPhysicalEverywhere) {
  // Every set gives 0.03 < mu < 0.2 over the model's speed range (lowest: 0.0337, printed
  // 200 °C / 20 kN row at 6 mm/s), so no reconstructed row is degenerate.
  for (std::size_t i = 0; i < m_->temps_C().size(); ++i)
    for (std::size_t j = 0; j < m_->loads_N().size(); ++j)
      for (double v = 6.0; v <= 590.0; v *= 1.1) {
        const double mu = m_->set(i, j).mu(v);
        EXPECT_GT(mu, 0.03) << m_->temps_C()[i] << " °C, " << m_->loads_N()[j] << " N, " << v;
        EXPECT_LT(mu, 0.2) << m_->temps_C()[i] << " °C, " << m_->loads_N()[j] << " N, " << v;
      }
}

}  // namespace
