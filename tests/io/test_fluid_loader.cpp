// Fluid file loader (docs/formats/fluid_file.md): a good file of each kind loads to the expected law,
// and every bad input gives an io::InputError whose message names the file, the key and the
// reason. Bad files are written to a temporary directory by the test.
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <unistd.h>

#include "clutch/linear_friction.hpp"
#include "clutch/maki_friction.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"

namespace {

namespace fs = std::filesystem;
using shudder::io::InputError;
using shudder::io::load_fluid;
using ::testing::AllOf;
using ::testing::HasSubstr;
using ::testing::ThrowsMessage;

// Two rows (20 and 70 °C) over four loads; every set is Paper G's 70 °C / 20 kN set except the
// 20 °C row, which is constant (C1 = C2 = C3 = 0, C4 = 0.12).
const std::string kMaki = R"([fluid]
name = "test-fluid"
description = "unit-test fluid"
nu40_cSt = 35.0
nu100_cSt = 6.7

[static_friction]
breakaway_ratio = 1.2
source = "test"

[maki]
loads_N = [10000, 15000, 20000, 25000]

[[maki.row]]
temp_C = 20.0
origin = "test"
sets = [[0, 0, 0, 0.12], [0, 0, 0, 0.12], [0, 0, 0, 0.12], [0, 0, 0, 0.12]]

[[maki.row]]
temp_C = 70.0
sets = [[-0.039, 0.001, 0.077, -0.024], [-0.039, 0.001, 0.077, -0.024],
        [-0.039, 0.001, 0.077, -0.024], [-0.039, 0.001, 0.077, -0.024]]
)";

const std::string kLinear = R"([fluid]
name = "lines"
nu40_cSt = 7.05
nu100_cSt = 2.18
density_kg_m3 = 850.0

[static_friction]
breakaway_ratio = 1.0

[linear]
load_N = 20000
mean_radius_mm = 46.0
speeds_rpm = [1, 50]
alpha_per_C = [-5.42e-4, -2.96e-4]
beta = [0.1018, 0.1164]
)";

// `text` with the first occurrence of `from` replaced by `to` (`from` must occur).
std::string with(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  if (at == std::string::npos) throw std::logic_error("test fixture lacks: " + from);
  return text.replace(at, from.size(), to);
}

// <tmp>/shudder_fluid_<pid>, removed when the test program exits.
const fs::path& scratch_dir() {
  struct Dir {
    fs::path path = fs::temp_directory_path() / ("shudder_fluid_" + std::to_string(::getpid()));
    ~Dir() {
      std::error_code ec;
      fs::remove_all(path, ec);
    }
  };
  static const Dir dir;
  return dir.path;
}

// Writes `text` to <scratch dir>/<test name>.toml and returns the path.
std::string write(const std::string& text) {
  const fs::path& dir = scratch_dir();
  fs::create_directories(dir);
  const std::string name = ::testing::UnitTest::GetInstance()->current_test_info()->name() + std::string(".toml");
  const fs::path path = dir / name;
  std::ofstream(path) << text;
  return path.string();
}

// Matches an InputError naming the file, the key and the reason.
auto fails_with(const std::string& path, const std::string& key, const std::string& reason) {
  return ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("key '" + key + "'"), HasSubstr(reason)));
}

TEST(LoadFluid, ReadsAMakiFluid) {
  const auto fluid = load_fluid(write(kMaki));
  EXPECT_EQ(fluid.name, "test-fluid");
  EXPECT_EQ(fluid.nu40_cSt, 35.0);
  EXPECT_EQ(fluid.nu100_cSt, 6.7);
  EXPECT_EQ(fluid.density_kg_m3, 868.0);  // default, Paper G Table 1
  EXPECT_EQ(fluid.breakaway_ratio, 1.2);
  const auto* m = dynamic_cast<const shudder::clutch::MakiFrictionMatrix*>(fluid.friction.get());
  ASSERT_NE(m, nullptr);
  EXPECT_EQ(m->min_speed_mm_s(), 6.0);  // defaults of the Paper G range rule
  EXPECT_EQ(m->max_speed_mm_s(), 590.0);
  // 70 °C / 20 kN at 241 mm/s: hand value 0.10003658 (tests/clutch/test_maki_friction.cpp).
  EXPECT_NEAR(fluid.friction->mu(241.0, 70.0, 20000.0), 0.10003658, 1e-8);
  // Half way between the rows (45 °C) at 241 mm/s: (0.12 + 0.10003657)/2 = 0.11001829.
  EXPECT_NEAR(fluid.friction->mu(241.0, 45.0, 20000.0), 0.11001829, 1e-8);
  // mu_s = 1.2 * mu(6 mm/s) = 1.2 * (-0.039*tanh(0.006) + 0.077*6^0.1 - 0.024)
  //      = 1.2 * (-0.00023400 + 0.09210980 - 0.024) = 1.2 * 0.06787581 = 0.08145097.
  EXPECT_NEAR(fluid.mu_static(70.0, 20000.0), 0.08145097, 1e-8);
}

TEST(LoadFluid, ReadsALinearFluidAndConvertsRpmAtTheMeanRadius) {
  const auto fluid = load_fluid(write(kLinear));
  EXPECT_EQ(fluid.density_kg_m3, 850.0);
  const auto* law = dynamic_cast<const shudder::clutch::LinearTemperatureFriction*>(fluid.friction.get());
  ASSERT_NE(law, nullptr);
  // 1 rpm at 46 mm: 2*pi/60 * 46 = 4.8171087 mm/s; 50 rpm: 240.85544 mm/s.
  ASSERT_EQ(law->points().size(), 2u);
  EXPECT_NEAR(law->points()[0].speed_mm_s, 4.8171087, 1e-7);
  EXPECT_NEAR(law->points()[1].speed_mm_s, 240.85544, 1e-5);
  // mu1 at 30 °C: -5.42e-4*30 + 0.1018 = 0.08554 (exact decimal; tolerance for rounding).
  EXPECT_NEAR(fluid.friction->mu(4.8171087, 30.0, 20000.0), 0.08554, 1e-14);
}

TEST(LoadFluid, MissingKey) {
  const auto path = write(with(kMaki, "nu40_cSt = 35.0\n", ""));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "fluid.nu40_cSt", "missing"));
}

TEST(LoadFluid, MissingSetsOfARow) {
  const auto path = write(with(kMaki, "sets = [[0, 0, 0, 0.12]", "setz = [[0, 0, 0, 0.12]"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.row[0].sets", "missing; expected an array of 4 sets"));
}

// Found by fuzz_fluid under UBSan: a bare key running into "°" ("mean_°C") made
// toml++ 3.3.0 reach __builtin_unreachable while reading a file (io/toml_reader.cpp). A file is
// checked as text is: rejected with the line, before toml++ parses it.
TEST(LoadFluid, NonAsciiCharacterInABareKeyIsRejectedWithItsLine) {
  const auto path = write(with(kMaki, "nu40_cSt = 35.0\n",
                               "nu40_cSt = 35.0\nmean_\xC2\xB0"
                               "C = 1\n"));
  EXPECT_THAT([&] { load_fluid(path); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr(path + ":"), HasSubstr("non-ASCII character outside a string or comment"))));
}

TEST(LoadFluid, UnknownKey) {
  const auto path = write(with(kMaki, "nu40_cSt = 35.0\n", "nu40_cSt = 35.0\ncolour = \"red\"\n"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "fluid.colour", "unknown key; allowed keys here"));
}

TEST(LoadFluid, UnknownKeyInARow) {
  const auto path = write(with(kMaki, "origin = \"test\"", "orign = \"test\""));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.row[0].orign", "unknown key"));
}

TEST(LoadFluid, UnknownTopLevelTable) {
  const auto path = write(kMaki + "\n[viscosity]\nnu = 3\n");
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "viscosity", "unknown key"));
}

TEST(LoadFluid, WrongType) {
  const auto path = write(with(kMaki, "nu40_cSt = 35.0", "nu40_cSt = \"35\""));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "fluid.nu40_cSt", "is a string; expected a number in > 0"));
}

TEST(LoadFluid, NanNumber) {
  const auto path = write(with(kMaki, "nu40_cSt = 35.0", "nu40_cSt = nan"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "fluid.nu40_cSt", "not finite"));
}

TEST(LoadFluid, NanCoefficient) {
  const auto path = write(
      with(kMaki, "[-0.039, 0.001, 0.077, -0.024], [-0.039, 0.001", "[-0.039, 0.001, 0.077, -0.024], [-0.039, nan"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.row[1].sets", "set 1 (load 15000 N) C2 is not finite"));
}

TEST(LoadFluid, WrongTypeCoefficient) {
  const auto path = write(with(kMaki, "[0, 0, 0, 0.12]]", "[0, 0, 0, \"0.12\"]]"));
  EXPECT_THAT([&] { load_fluid(path); },
              fails_with(path, "maki.row[0].sets", "set 3 (load 25000 N) C4 is a string; expected a finite number"));
}

TEST(LoadFluid, HoleInTheMatrixNamesRowLineAndCounts) {
  // The 20 °C row's `sets` is on line 17 of the fixture; drop its last set.
  const auto path = write(with(kMaki, ", [0, 0, 0, 0.12]]", "]"));
  EXPECT_THAT(
      [&] { load_fluid(path); },
      ThrowsMessage<InputError>(HasSubstr(path + ":17: key 'maki.row[0].sets': has 3 sets; expected one per load (4) "
                                                 "in the row at temp_C = 20")));
}

TEST(LoadFluid, SetWithOtherThanFourNumbers) {
  const auto path = write(with(kMaki, "[0, 0, 0, 0.12]]", "[0, 0, 0.12]]"));
  EXPECT_THAT([&] { load_fluid(path); },
              fails_with(path, "maki.row[0].sets", "set 3 (load 25000 N) has 3 numbers; expected 4 [C1, C2, C3, C4]"));
}

TEST(LoadFluid, RowsNotIncreasingInTemperature) {
  const auto path = write(with(kMaki, "temp_C = 70.0", "temp_C = 20.0"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.row[1].temp_C", "rows must be strictly increasing"));
}

TEST(LoadFluid, LoadsNotIncreasing) {
  const auto path = write(with(kMaki, "[10000, 15000,", "[15000, 10000,"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.loads_N", "must be strictly increasing"));
}

TEST(LoadFluid, SpeedRangeEmpty) {
  const auto path = write(with(kMaki, "[maki]\n", "[maki]\nmin_speed_mm_s = 600.0\n"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.max_speed_mm_s", "must exceed min_speed_mm_s"));
}

TEST(LoadFluid, ViscositiesInverted) {
  const auto path = write(with(kMaki, "nu100_cSt = 6.7", "nu100_cSt = 40.0"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "fluid.nu100_cSt", "out of range; allowed (0, 35)"));
}

TEST(LoadFluid, BreakawayRatioOutOfRange) {
  const auto path = write(with(kMaki, "breakaway_ratio = 1.2", "breakaway_ratio = 5"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "static_friction.breakaway_ratio", "allowed [0.5, 3]"));
}

TEST(LoadFluid, LinearArraysOfDifferentLengths) {
  const auto path = write(with(kLinear, "beta = [0.1018, 0.1164]", "beta = [0.1018]"));
  EXPECT_THAT([&] { load_fluid(path); },
              fails_with(path, "linear.beta", "has 1 elements; expected one per speed in speeds_rpm (2)"));
}

TEST(LoadFluid, LinearMissingMeanRadius) {
  const auto path = write(with(kLinear, "mean_radius_mm = 46.0\n", ""));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "linear.mean_radius_mm", "missing"));
}

TEST(LoadFluid, BothMakiAndLinear) {
  const auto linear_part = kLinear.substr(kLinear.find("[linear]"));
  const auto path = write(kMaki + "\n" + linear_part);
  EXPECT_THAT([&] { load_fluid(path); },
              fails_with(path, "linear", "given together with [maki]; a fluid has exactly one"));
}

TEST(LoadFluid, NeitherMakiNorLinear) {
  const auto path = write(kLinear.substr(0, kLinear.find("[linear]")));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki", "missing; a fluid needs exactly one friction law"));
}

TEST(LoadFluid, NonexistentFile) {
  const std::string path = (fs::temp_directory_path() / "shudder_no_such_fluid.toml").string();
  EXPECT_THAT([&] { load_fluid(path); },
              ThrowsMessage<InputError>(AllOf(HasSubstr(path), HasSubstr("could not be opened"))));
}

TEST(LoadFluid, UnreadableFileIsADirectory) {
  const fs::path dir = fs::path(write(kMaki)).parent_path() / "a_directory.toml";
  fs::create_directories(dir);
  EXPECT_THAT([&] { load_fluid(dir.string()); },
              ThrowsMessage<InputError>(AllOf(HasSubstr(dir.string()), HasSubstr("is not a regular file"))));
}

TEST(LoadFluid, TomlSyntaxErrorNamesTheLine) {
  const auto path = write(with(kMaki, "nu40_cSt = 35.0", "nu40_cSt = = 35.0"));
  EXPECT_THAT([&] { load_fluid(path); }, ThrowsMessage<InputError>(HasSubstr(path + ":4:")));
}

}  // namespace

// ---- Plausibility: mu in (0, 1] over the law's declared range ----------------------
// Unchecked, each of these files would load (a sign typo in `beta` gives -4,923 J of friction
// heat and a thermocouple at -65 °C, exit 0).

TEST(LoadFluidPlausibility, EveryShippedFluidLoads) {
  int loaded = 0;
  for (const auto& e : fs::directory_iterator(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids")) {
    EXPECT_NO_THROW(load_fluid(e.path().string())) << e.path();
    ++loaded;
  }
  EXPECT_GE(loaded, 11);
}

TEST(LoadFluidPlausibility, ShippedFluidWithBetaNegatedIsRejectedNamingKeyAndPoint) {
  // Paper E fluid A with `beta` negated: at 1 rpm and -40 °C, mu = -5.42e-4 * (-40) - 0.1018
  // = -0.08012 (the first point checked: first speed, low temperature end).
  std::ifstream in(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/fluids/paper_e_fluid_a.toml");
  std::string text((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  text = with(text, "beta = [0.1018, 0.1164]", "beta = [-0.1018, -0.1164]");
  const std::string path = write(text);
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "linear.beta", "gives mu = -0.08012 <= 0"));
  EXPECT_THAT([&] { load_fluid(path); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("speed 1 rpm"), HasSubstr("temperature -40 °C"), HasSubstr("from -40 to 150 °C"))));
}

TEST(LoadFluidPlausibility, LinearLineCrossingZeroBelow150CIsRejectedAtTheHotEnd) {
  // mu = -1e-3 T + 0.1 is 0.14 at -40 °C but -0.05 at 150 °C: the hot end fails.
  const std::string path =
      write(with(with(kLinear, "alpha_per_C = [-5.42e-4, -2.96e-4]", "alpha_per_C = [-1e-3, -2.96e-4]"),
                 "beta = [0.1018, 0.1164]", "beta = [0.1, 0.1164]"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "linear.beta", "gives mu = -0.05 <= 0"));
  EXPECT_THAT([&] { load_fluid(path); }, ThrowsMessage<InputError>(HasSubstr("temperature 150 °C")));
}

TEST(LoadFluidPlausibility, LinearMuAboveOneIsRejected) {
  // A shifted decimal point: beta = 1.018 gives mu = 1.018 + 5.42e-4 * 40 = 1.03968 at -40 °C.
  const std::string path = write(with(kLinear, "beta = [0.1018, 0.1164]", "beta = [1.018, 0.1164]"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "linear.beta", "gives mu = 1.03968 > 1"));
}

TEST(LoadFluidPlausibility, MakiSetNegativeAtLowSpeedNamesRowSetAndPoint) {
  // The 20 °C row's 15 kN set: mu = 0.05 tanh(0.001 v) - 0.01; tanh(0.001 v) ~ 0.001 v, so mu
  // <= 0 below v = 200 mm/s: the first sample, 6 mm/s, fails (0.05 tanh(0.006) - 0.01 =
  // -0.0097).
  const std::string path =
      write(with(kMaki, "[[0, 0, 0, 0.12], [0, 0, 0, 0.12]", "[[0, 0, 0, 0.12], [0.05, 0.001, 0, -0.01]"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.row[0].sets", "set 1 gives mu = -0.0097"));
  EXPECT_THAT([&] { load_fluid(path); },
              ThrowsMessage<InputError>(
                  AllOf(HasSubstr("speed 6 mm/s"), HasSubstr("temperature 20 °C"), HasSubstr("load 15000 N"))));
}

TEST(LoadFluidPlausibility, MakiSetNegativeOnlyAtHighSpeedIsFoundByTheSpeedGrid) {
  // mu = -0.2 tanh(0.01 v) + 0.12: positive at low speed, 0.12 - 0.2 tanh(5.9) < 0 at 590 mm/s;
  // mu = 0 at v = atanh(0.6)/0.01 = 69.3 mm/s, so the first failing sample lies just above it.
  const std::string path =
      write(with(kMaki, "[[0, 0, 0, 0.12], [0, 0, 0, 0.12]", "[[0, 0, 0, 0.12], [-0.2, 0.01, 0, 0.12]"));
  EXPECT_THAT([&] { load_fluid(path); }, fails_with(path, "maki.row[0].sets", "set 1 gives mu = -"));
}
