// Paper E fluids A–E (scenarios/fluids/paper_e_fluid_{a..e}.toml): linear friction–temperature
// lines at 20 kN, mu1(T) = alpha1*T + beta1 at 1 rpm and mu50(T) = alpha50*T + beta50 at 50 rpm
// (Paper E Tables 2 and 3), checked against Paper E Table 4 (mu1, mu50 and mu1/mu50 "at 30 °C").
//
// Finding: Table 4 is NOT the lines at 30 °C. The lines give mu1/mu50 about 0.003 below the
// table for all five fluids (A: (0.1018 - 30*5.42e-4)/(0.1164 - 30*2.96e-4) = 0.08554/0.10752
// = 0.79557 against 0.7985). At 29 °C they reproduce every Table 4 entry to its printed 4 digits
// (A: 0.086082/0.107816 = 0.79842), and Table 5 likewise one degree below its stated
// temperatures: the tables were evaluated 1 °C below their labels. We keep the fit lines
// (Tables 2–3) and test (a) the ratio at 29 °C to the table's rounding (5e-4), (b) mu1 and mu50
// at 29 °C to their rounding (5e-5, + 1e-5 for the rounding of alpha and beta), and (c) that at
// 30 °C the ratio lies 0.002–0.004 below the table (the documented offset).
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <string>

#include "core/units.hpp"
#include "io/fluid_loader.hpp"

namespace {

struct TableFour {
  const char* file;
  double mu1, mu50, ratio;  // Paper E Table 4
};

constexpr TableFour kFluids[] = {
    {"paper_e_fluid_a.toml", 0.0861, 0.1078, 0.7985}, {"paper_e_fluid_b.toml", 0.0885, 0.1099, 0.8051},
    {"paper_e_fluid_c.toml", 0.0875, 0.1058, 0.8269}, {"paper_e_fluid_d.toml", 0.0878, 0.1057, 0.8309},
    {"paper_e_fluid_e.toml", 0.0865, 0.1023, 0.8455},
};

// 1 and 50 rpm at the 46 mm mean radius, as the files convert them.
const double kV1 = shudder::units::kRadPerSPerRpm * 46.0;
const double kV50 = 50.0 * kV1;

TEST(PaperEFluids, MatchTableFourOneDegreeBelowItsLabel) {
  for (const auto& f : kFluids) {
    const auto fluid = shudder::io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + f.file);
    const auto& law = *fluid.friction;
    const double mu1 = law.mu(kV1, 29.0, 20000.0), mu50 = law.mu(kV50, 29.0, 20000.0);
    EXPECT_NEAR(mu1, f.mu1, 6e-5) << f.file;
    EXPECT_NEAR(mu50, f.mu50, 6e-5) << f.file;
    EXPECT_NEAR(mu1 / mu50, f.ratio, 5e-4) << f.file;
    const double ratio30 = law.mu(kV1, 30.0, 20000.0) / law.mu(kV50, 30.0, 20000.0);
    EXPECT_GT(f.ratio - ratio30, 0.002) << f.file;
    EXPECT_LT(f.ratio - ratio30, 0.004) << f.file;
    EXPECT_EQ(fluid.breakaway_ratio, 1.0) << f.file;
  }
}

TEST(PaperEFluids, ViscositiesFromTableOne) {
  const double nu[5][2] = {{7.05, 2.18}, {9.74, 2.71}, {35.0, 6.70}, {58.9, 8.26}, {63.1, 9.71}};
  for (int i = 0; i < 5; ++i) {
    const auto fluid = shudder::io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + kFluids[i].file);
    EXPECT_EQ(fluid.nu40_cSt, nu[i][0]) << kFluids[i].file;
    EXPECT_EQ(fluid.nu100_cSt, nu[i][1]) << kFluids[i].file;
  }
}

}  // namespace
