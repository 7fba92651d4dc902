// Every shipped rig scenario expanded into network components (rig_models/rig_expansion.hpp) and
// run through the network path gives the rig kind's run: the bar's torque (the torque cell's),
// the clutch's slip and torque and the temperatures, sample by sample where nothing oscillates,
// and the same oscillation where a judder grows.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <limits>
#include <string>

#include "studies/network_run.hpp"
#include "rig_models/rig_expansion.hpp"
#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "studies/run_verdict.hpp"
#include "tests/components/network_helpers.hpp"

namespace shudder::rig_models {
namespace {

namespace test = components::test;

class RigExpansion : public ::testing::TestWithParam<std::string> {};

TEST_P(RigExpansion, NetworkPathGivesTheRigRun) {
  const auto sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/" + GetParam() + ".toml");
  const auto& m = std::get<rig_models::RigModel>(sc.model);
  const components::NetworkSpec spec = expand_rig(m.params, sc.clutch, sc.fluid, m.cycle, m.settings);
  const studies::NetworkRun run = studies::run_network(spec);
  const auto rig = rig_models::simulate(m, sc.make_clutch());
  double worst = 0;
  for (const auto& [net, kind] :
       std::vector<std::pair<std::string, std::string>>{{"torsion_bar.torque_Nm", "torque_Nm"},
                                                        {"clutch.slip_rpm", "slip_rpm"},
                                                        {"clutch.torque_Nm", "clutch_torque_Nm"},
                                                        {"clutch.interface_max_temp_C", "interface_max_temp_C"},
                                                        {"clutch.temp_C", "temp_C"}})
    worst = std::max(worst, test::relative_difference(test::channel(run.recording, net), test::channel(rig, kind)));
  const auto judged = studies::judge_run(rig).judged;
  const auto& v = run.verdicts.at(0).verdict.judged;
  EXPECT_EQ(v.verdict, judged.verdict);
  if (judged.verdict == analysis::Verdict::kVibration) {
    // A self-excited judder grows from round-off: the two runs agree to round-off until it sets
    // in (rig_ramp_peak10: to 3.29 s), then their limit cycles drift apart in phase, sample by
    // sample up to 1.5 % of the clutch torque's range (0.1-0.7 % at the shipped tolerances, 1.5 %
    // at 1e-9, no trend: it is not a modelling difference). The oscillation is compared instead:
    // frequency within 0.5 %, amplitude within 5 %.
    EXPECT_NEAR(v.frequency_Hz, judged.frequency_Hz, 5e-3 * judged.frequency_Hz);
    EXPECT_NEAR(v.amplitude_Nm, judged.amplitude_Nm, 0.05 * judged.amplitude_Nm);
    EXPECT_LT(worst, 3e-2);
  } else {
    // No oscillation to carry a difference: the same equations assembled apart agree to the
    // integrator's tolerance (measured 1e-13 to 2e-4 of the range; bound 1e-3).
    EXPECT_LT(worst, 1e-3);
  }
}

std::vector<std::string> shipped_rigs() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(SHUDDER_SOURCE_DIR) + "/scenarios")) {
    if (e.path().extension() != ".toml") continue;
    try {
      const auto sc = io::load_scenario(e.path().string());
      if (std::holds_alternative<rig_models::RigModel>(sc.model)) names.push_back(e.path().stem().string());
    } catch (const std::exception&) {  // not a scenario (validation targets)
    }
  }
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Shipped, RigExpansion, ::testing::ValuesIn(shipped_rigs()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace shudder::rig_models
