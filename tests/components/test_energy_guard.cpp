// The energy guard (components/energy_guard.hpp): a recording whose energy accounts do not close
// is a numerical failure. On the old code nothing judged the figures: a run printed
// "mechanical energy error 5.01e+00" and exited 0. Recordings here are hand-made; that every
// shipped scenario passes is checked end to end by the CLI tests that run them (exit 0).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <limits>

#include "components/energy_guard.hpp"

using shudder::components::energy_balance_violation;
using shudder::dynamics::Recording;
using ::testing::HasSubstr;

namespace {

Recording with_errors(double thermal, double mechanical) {
  Recording rec;
  rec.scalars = {{"energy_balance_relative_error", "1", thermal},
                 {"mechanical_energy_relative_error", "1", mechanical}};
  return rec;
}

}  // namespace

TEST(EnergyGuard, FiguresOfTheShippedScenariosPass) {
  // The largest figures the shipped scenarios reach (thermal 1.7e-12, mechanical 4.4e-6).
  EXPECT_EQ(energy_balance_violation(with_errors(1.69e-12, 4.44e-6)), "");
  // The bounds themselves pass (<=).
  EXPECT_EQ(energy_balance_violation(with_errors(1e-6, 1e-3)), "");
}

TEST(EnergyGuard, ThermalErrorAboveOneMillionthFailsNamingTheFigure) {
  const std::string v = energy_balance_violation(with_errors(2.5e-3, 1e-9));
  EXPECT_THAT(v, HasSubstr("thermal energy balance error 0.0025 (relative, energy_balance_relative_error) "
                           "exceeds the bound 1e-06"));
  EXPECT_THAT(v, ::testing::Not(HasSubstr("mechanical")));
}

TEST(EnergyGuard, LargeMechanicalErrorFailsAndBothAreNamed) {
  // A run on a fluid with beta negated gives "mechanical energy error 5.01e+00".
  const std::string v = energy_balance_violation(with_errors(3e-6, 5.01));
  EXPECT_THAT(v, HasSubstr("thermal energy balance error 3e-06"));
  EXPECT_THAT(v, HasSubstr("; mechanical energy balance error 5.01 (relative, mechanical_energy_relative_error) "
                           "exceeds the bound 1e-03"));
}

TEST(EnergyGuard, NonFiniteFiguresFail) {
  EXPECT_THAT(energy_balance_violation(with_errors(std::numeric_limits<double>::quiet_NaN(), 0.0)),
              HasSubstr("thermal energy balance error nan"));
  EXPECT_THAT(energy_balance_violation(with_errors(0.0, std::numeric_limits<double>::infinity())),
              HasSubstr("mechanical energy balance error inf"));
}

TEST(EnergyGuard, AccountsARecordingDoesNotKeepAreNotJudged) { EXPECT_EQ(energy_balance_violation(Recording{}), ""); }

TEST(EnergyGuard, BoundsCanBeTightened) {
  EXPECT_THAT(energy_balance_violation(with_errors(1e-9, 0.0), {1e-10, 1e-3}), HasSubstr("exceeds the bound 1e-10"));
}
