// The fluid file's [table] law (docs/formats/fluid_file.md): read into a clutch::TableFriction with
// the values as written; a wrong shape, an implausible mu and a second law are InputErrors
// naming the file and the key.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>

#include "clutch/table_friction.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"

namespace {

using shudder::io::InputError;
using shudder::io::load_fluid_text;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

const std::string kTable = R"([fluid]
name = "t"
nu40_cSt = 35.0
nu100_cSt = 6.7

[static_friction]
breakaway_ratio = 1.0

[table]
speeds_mm_s = [5.0, 50.0, 500.0]
loads_N = [10000.0, 20000.0]

[[table.row]]
temp_C = 40.0
mu = [[0.08, 0.10, 0.11], [0.09, 0.11, 0.12]]

[[table.row]]
temp_C = 80.0
mu = [[0.07, 0.09, 0.10], [0.08, 0.10, 0.11]]
)";

std::string with(std::string s, const std::string& from, const std::string& to) {
  return s.replace(s.find(from), from.size(), to);
}

TEST(LoadFluidTable, ReadsTheGridAsWritten) {
  const auto fluid = load_fluid_text(kTable, "t.toml");
  const auto* law = dynamic_cast<const shudder::clutch::TableFriction*>(fluid.friction.get());
  ASSERT_NE(law, nullptr);
  EXPECT_EQ(law->value(1, 0, 2), 0.10);
  EXPECT_DOUBLE_EQ(fluid.friction->mu(50.0, 60.0, 15000.0), 0.25 * (0.10 + 0.11 + 0.09 + 0.10));
}

TEST(LoadFluidTable, RejectsAWrongShapeAnImplausibleMuAndTwoLaws) {
  EXPECT_THAT([&] { load_fluid_text(with(kTable, "[0.08, 0.10, 0.11]", "[0.08, 0.10]"), "t.toml"); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("t.toml"), HasSubstr("table.row[0].mu"),
                                              HasSubstr("has 2 values; expected one per speed"))));
  EXPECT_THAT([&] { load_fluid_text(with(kTable, "[0.08, 0.10, 0.11]", "[0.08, -0.10, 0.11]"), "t.toml"); },
              ThrowsMessage<InputError>(AllOf(HasSubstr("table.row[0].mu"), HasSubstr("<= 0"))));
  EXPECT_THAT(
      [&] {
        load_fluid_text(
            kTable + "\n[linear]\nmean_radius_mm = 46.0\nspeeds_rpm = [1.0]\nalpha_per_C = [0.0]\nbeta = [0.1]\n",
            "t.toml");
      },
      ThrowsMessage<InputError>(AllOf(HasSubstr("key 'table'"), HasSubstr("given together with [linear]"))));
}

}  // namespace
