// core::median, shared by the detector's amplitude, the noise estimate and the plausibility checks.
#include <gtest/gtest.h>

#include <cmath>

#include "core/median.hpp"

namespace shudder {
namespace {

TEST(Median, OddCountIsTheMiddleValueOfTheSortedSamples) { EXPECT_EQ(core::median({5.0, -1.0, 3.0, 9.0, 0.5}), 3.0); }

TEST(Median, EvenCountIsTheMeanOfTheTwoMiddleValues) {
  // Sorted: 1 2 | 7 40 — the mean of 2 and 7, whatever order the samples come in.
  EXPECT_EQ(core::median({40.0, 2.0, 7.0, 1.0}), 4.5);
  EXPECT_EQ(core::median({7.0, 1.0, 40.0, 2.0}), 4.5);
}

TEST(Median, NoSamplesHaveNoMedian) { EXPECT_TRUE(std::isnan(core::median({}))); }

}  // namespace
}  // namespace shudder
