// `shudder convergence` (app/cmd_convergence.cpp; docs/convergence.md) on every shipped
// scenario: each keeps its verdict class, frequency (3 %) and amplitude (25 %) when every
// numerical step it exposes is divided by 4. A shipped verdict that fails here is a property of
// its step, not of its physics, and must not ship.
// The command's own verdict is also tested: a scenario made to depend on its step (a thermal step
// of half the run) is reported NOT CONVERGED, exit 3.
#include <gtest/gtest.h>

#include <algorithm>
#include <cctype>
#include <filesystem>
#include <string>
#include <vector>

#include "tests/support/cli.hpp"

namespace shudder {
namespace {

namespace fs = std::filesystem;

std::vector<std::string> shipped_scenarios() {
  std::vector<std::string> files;
  for (const char* dir : {"scenarios", "scenarios/networks"})
    for (const auto& e : fs::directory_iterator(test::source_path(dir)))
      // validation.toml is a data file of `shudder validate`, not a scenario.
      if (e.path().extension() == ".toml" && test::slurp(e.path()).find("[scenario]") != std::string::npos)
        files.push_back(std::string(dir) + "/" + e.path().filename().string());
  std::sort(files.begin(), files.end());
  return files;
}

class ShippedScenariosConverge : public ::testing::TestWithParam<std::string> {};

TEST_P(ShippedScenariosConverge, WhenEveryStepIsDividedByFour) {
  const auto r = test::run_cli("convergence " + GetParam(), test::source_path(""));
  EXPECT_EQ(r.exit_code, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("CONVERGED"), std::string::npos) << r.out;
}

std::string test_name(const ::testing::TestParamInfo<std::string>& info) {
  std::string n = fs::path(info.param).stem().string();
  if (info.param.find("networks/") != std::string::npos) n = "network_" + n;
  for (char& c : n)
    if (!std::isalnum(static_cast<unsigned char>(c))) c = '_';
  return n;
}

INSTANTIATE_TEST_SUITE_P(Shipped, ShippedScenariosConverge, ::testing::ValuesIn(shipped_scenarios()), test_name);

TEST(Convergence, AStepDependentVerdictIsReportedNotConvergedWithExitThree) {
  // The wet launch with a 1.5 s thermal step (half the run): the first-order hold extrapolates
  // the disc temperatures over 1.5 s, and the judder's frequency and amplitude follow the
  // temperature the friction sees; a quarter of that step changes them by far more than 3 % and 25 %.
  const auto dir = test::scratch_dir("convergence_coarse");
  fs::create_directories(dir / "networks");
  fs::copy(test::source_path("scenarios/fluids"), dir / "fluids");
  std::string text = test::slurp(test::source_path("scenarios/networks/manual_launch_wet_clutch.toml"));
  const std::string key = "thermal_step_ms = ";
  const auto at = text.find(key);
  ASSERT_NE(at, std::string::npos);
  text.replace(at, text.find('\n', at) - at, key + "1500");
  test::write_file(dir / "networks" / "coarse.toml", text);
  const auto r = test::run_cli("convergence networks/coarse.toml", dir);
  EXPECT_EQ(r.exit_code, 3) << r.out << r.err;
  EXPECT_NE(r.out.find("NOT CONVERGED"), std::string::npos) << r.out;
}

TEST(Convergence, RejectsAFactorThatRefinesNothing) {
  const auto r = test::run_cli("convergence scenarios/rig_stick_slip.toml --factor 1", test::source_path(""));
  EXPECT_EQ(r.exit_code, 2) << r.out << r.err;
}

}  // namespace
}  // namespace shudder
