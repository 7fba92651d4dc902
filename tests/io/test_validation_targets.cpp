// The validation data file (io/validation_targets.hpp): the shipped scenarios/validation.toml
// loads with the targets the thesis bands give (docs/physics.md §5), and a broken file is an
// InputError naming the key and what is allowed.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <unistd.h>

#include <cstdio>
#include <fstream>
#include <string>

#include "io/input_error.hpp"
#include "io/validation_targets.hpp"

namespace {

using shudder::io::load_validation_spec;
using shudder::io::TargetKind;
using ::testing::HasSubstr;

std::string write_temp(const std::string& text) {
  char name[] = "/tmp/shudder-validation-XXXXXX";
  const int fd = ::mkstemp(name);
  if (fd < 0) throw std::runtime_error("mkstemp failed");
  ::close(fd);
  std::ofstream(name) << text;
  return name;
}

std::string error_of(const std::string& text) {
  const std::string path = write_temp(text);
  try {
    load_validation_spec(path);
  } catch (const shudder::io::InputError& e) {
    std::remove(path.c_str());
    return e.what();
  }
  std::remove(path.c_str());
  return "no error";
}

const char* kCases = R"(
[[case]]
scenario = "a"
label = "Case A"
[[case]]
scenario = "b"
label = "Case B"
)";
const char* kDocument = R"(
[document]
ramp_case = "a"
ramp_plot_file = "r.png"
comparison_title = "t"
comparison_heading = "h"
comparison_file = "c.png"
)";

TEST(ValidationTargets, ShippedFileCarriesThePaperBands) {
  const auto spec = load_validation_spec(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/validation.toml");
  ASSERT_EQ(spec.cases.size(), 6u);
  EXPECT_EQ(spec.cases[spec.ramp_case].scenario, "paper_g_case2_15kN");
  ASSERT_EQ(spec.targets.size(), 11u);
  // Paper G Fig. 8: 10.4 kN torque 40–50 N m at 10 s.
  const auto& t0 = spec.targets[0];
  EXPECT_EQ(spec.cases[t0.case_index].scenario, "paper_g_case1_10kN");
  EXPECT_EQ(t0.kind, TargetKind::kValue);
  EXPECT_EQ(*t0.min, 40.0);
  EXPECT_EQ(*t0.max, 50.0);
  // Paper G Discussion: without oil flow the torque falls 5–15 % below the case with flow.
  const auto& below = spec.targets[7];
  EXPECT_EQ(below.kind, TargetKind::kPercentBelow);
  EXPECT_EQ(spec.cases[*below.reference_index].scenario, "paper_g_case1_25kN");
  // Paper B: the IR rise 10 → 20 s within 12–25 °C.
  const auto& rise = spec.targets[9];
  EXPECT_EQ(rise.kind, TargetKind::kRise);
  EXPECT_EQ(rise.from_s, 10.0);
  EXPECT_EQ(rise.to_s, 20.0);
  // Paper D: the sump stays within its thermocouple's ±0.67 °C over Case 2.
  const auto& sump = spec.targets[10];
  EXPECT_EQ(sump.kind, TargetKind::kRise);
  EXPECT_EQ(sump.signal, "sump_temp_C");
  EXPECT_EQ(*sump.max, 0.67);
  EXPECT_EQ(spec.comparison.size(), 3u);
}

TEST(ValidationTargets, ATargetMustNameACase) {
  const std::string e = error_of(std::string(kCases) + R"(
[[target]]
case = "c"
quantity = "q"
signal = "torque_Nm"
time_s = 10.0
unit = "Nm"
)" + kDocument);
  EXPECT_THAT(e, HasSubstr("target[0].case"));
  EXPECT_THAT(e, HasSubstr("'c' is not a [[case]]; cases are: a, b"));
}

TEST(ValidationTargets, AMeanNeedsItsInterval) {
  const std::string e = error_of(std::string(kCases) + R"(
[[target]]
case = "a"
quantity = "q"
kind = "mean"
signal = "torque_Nm"
from_s = 10.0
to_s = 2.0
unit = "Nm"
)" + kDocument);
  EXPECT_THAT(e, HasSubstr("to_s"));
  EXPECT_THAT(e, HasSubstr("must be later than from_s"));
}

TEST(ValidationTargets, UnknownKindsAndKeysAreRejected) {
  EXPECT_THAT(error_of(std::string(kCases) + R"(
[[target]]
case = "a"
quantity = "q"
kind = "median"
signal = "torque_Nm"
time_s = 1.0
unit = "Nm"
)" + kDocument),
              HasSubstr("percent_below"));
  EXPECT_THAT(error_of(std::string(kCases) + R"(
[[target]]
case = "a"
quantity = "q"
signal = "torque_Nm"
time_s = 1.0
unit = "Nm"
mni = 3.0
)" + kDocument),
              HasSubstr("mni"));
}

TEST(ValidationTargets, BandsMustBeOrderedAndNotMixed) {
  const std::string head = std::string(kCases) + R"(
[[target]]
case = "a"
quantity = "q"
signal = "torque_Nm"
time_s = 1.0
unit = "Nm"
)";
  EXPECT_THAT(error_of(head + "min = 5.0\nmax = 1.0\n" + kDocument), HasSubstr("must not be below min"));
  EXPECT_THAT(error_of(head + "min = 5.0\ngreater_than = 1.0\n" + kDocument), HasSubstr("not both"));
}

}  // namespace
