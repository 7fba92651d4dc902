// The mechanical energy error of the runs (components/energy_scalars.hpp): |imbalance| over the
// scale each model uses, on a hand-made account whose imbalance is known.
#include <gtest/gtest.h>

#include "dynamics/simulation.hpp"
#include "components/energy_scalars.hpp"

namespace shudder::components {
namespace {

// Source 10 J; kinetic 1 -> 3 J, elastic 0.5 -> 2 J, friction 4 J, dampers 1 J:
// imbalance = 10 − 2 − 1.5 − 4 − 1 = 1.5 J.
dynamics::EnergyAccount account(double source_work_J) {
  dynamics::EnergyAccount e;
  e.source_work_J = source_work_J;
  e.kinetic_J = 3.0;
  e.initial_kinetic_J = 1.0;
  e.elastic_J = 2.0;
  e.initial_elastic_J = 0.5;
  e.friction_heat_J = 4.0;
  e.damper_loss_J = 1.0;
  return e;
}

// Tolerance: a few roundings of numbers of order 1.
constexpr double kTol = 1e-15;

TEST(MechanicalEnergyError, SourceWorkScaleDividesByTheWorkAndIsZeroWithoutIt) {
  EXPECT_NEAR(mechanical_energy_relative_error(account(10.0), MechanicalEnergyScale::kSourceWork), 0.15, kTol);
  EXPECT_EQ(mechanical_energy_relative_error(account(0.0), MechanicalEnergyScale::kSourceWork), 0.0);
}

TEST(MechanicalEnergyError, LargestEnergyScaleFallsBackToWhatWasInPlay) {
  // With work: max(10, 1 + 0.5, 4 + 1) = 10.
  EXPECT_NEAR(mechanical_energy_relative_error(account(10.0), MechanicalEnergyScale::kLargestEnergyInPlay), 0.15, kTol);
  // Coasting (no work): imbalance −8.5 J against max(0, 1.5, 5) = 5 J.
  EXPECT_NEAR(mechanical_energy_relative_error(account(0.0), MechanicalEnergyScale::kLargestEnergyInPlay), 1.7, kTol);
}

}  // namespace
}  // namespace shudder::components
