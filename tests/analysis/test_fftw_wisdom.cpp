// FFTW wisdom shipped as code (analysis/fftw_wisdom.hpp): FFTW accepts it, it is what this
// machine's planner chooses, and a plan made from it transforms bit for bit like a plan the
// planner makes without it — so skipping the planner cannot change any result.
#include <fftw3.h>
#include <gtest/gtest.h>

#include <complex>
#include <cstring>
#include <random>
#include <string>
#include <vector>

#include "analysis/fftw_wisdom.hpp"
#include "analysis/spectrum.hpp"

namespace {

using namespace shudder::analysis;

// The FFTW build the shipped text was made with (its first comment line says so).
constexpr const char* kMadeWith = "fftw-3.3.10-sse2-avx";

bool same_fftw_as_the_shipped_wisdom() { return std::string(fftw_version) == kMadeWith; }

// out = r2c DFT of x with a plan made now, with the process' wisdom as it is.
std::vector<std::complex<double>> transform_now(std::vector<double> x) {
  const std::size_t n = x.size();
  std::vector<std::complex<double>> out(n / 2 + 1);
  const fftw_plan p = fftw_plan_dft_r2c_1d(static_cast<int>(n), x.data(), reinterpret_cast<fftw_complex*>(out.data()),
                                           FFTW_ESTIMATE | FFTW_UNALIGNED);
  fftw_execute(p);
  fftw_destroy_plan(p);
  return out;
}

TEST(FftwWisdom, ShippedWisdomIsAcceptedByTheFftwItWasMadeFor) {
  if (!same_fftw_as_the_shipped_wisdom())
    GTEST_SKIP() << "this FFTW is " << fftw_version << ", the shipped wisdom is for " << kMadeWith
                 << " (FFTW plans without it; regenerate with shudder_fftw_wisdom)";
  EXPECT_EQ(fftw_import_wisdom_from_string(kShippedFftwWisdom), 1);
}

TEST(FftwWisdom, ShippedWisdomIsWhatThePlannerChoosesHere) {
  if (!same_fftw_as_the_shipped_wisdom() || !__builtin_cpu_supports("avx"))
    GTEST_SKIP() << "the shipped wisdom was made by " << kMadeWith << " on a CPU with AVX";
  EXPECT_EQ(fftw_wisdom_for_lengths(kShippedFftwLengths), std::string(kShippedFftwWisdom))
      << "the planner now chooses differently: regenerate analysis/fftw_wisdom_data.cpp";
}

TEST(FftwWisdom, PlansFromTheShippedWisdomTransformBitForBitLikeFreshPlans) {
  std::mt19937 rng(7);
  std::normal_distribution<double> noise(0.0, 1.0);
  // The shipped lengths and two it does not cover (planned partly from its sub-problems).
  std::vector<std::size_t> lengths(std::begin(kShippedFftwLengths), std::end(kShippedFftwLengths));
  lengths.push_back(384);
  lengths.push_back(2560);
  for (std::size_t n : lengths) {
    std::vector<double> x(n);
    for (double& v : x) v = noise(rng);
    fftw_forget_wisdom();
    const auto fresh = transform_now(x);
    fftw_forget_wisdom();
    const int accepted = fftw_import_wisdom_from_string(kShippedFftwWisdom);
    const auto from_wisdom = transform_now(x);
    fftw_forget_wisdom();
    ASSERT_EQ(fresh.size(), from_wisdom.size());
    // Bit for bit: the same plan runs the same operations in the same order.
    EXPECT_EQ(std::memcmp(fresh.data(), from_wisdom.data(), fresh.size() * sizeof(fresh[0])), 0)
        << "length " << n << " (wisdom accepted: " << accepted << ")";
  }
}

TEST(FftwWisdom, FftPlanRecordsWhetherFftwAcceptedTheShippedWisdom) {
  // Run alone (as ctest runs each test), this is the process' first plan, so the flag is
  // FFTW's answer to the import; other tests here make the process forget the wisdom.
  const FftPlan plan(256);
  if (same_fftw_as_the_shipped_wisdom() && ::testing::UnitTest::GetInstance()->test_to_run_count() == 1) {
    EXPECT_TRUE(shipped_fftw_wisdom_in_use());
  }
  std::vector<double> x(256, 0.0);
  x[1] = 1.0;
  std::vector<std::complex<double>> X(plan.bins());
  plan.execute(x, X);
  EXPECT_DOUBLE_EQ(std::abs(X[3]), 1.0);  // a unit impulse has a flat unit spectrum
}

}  // namespace
