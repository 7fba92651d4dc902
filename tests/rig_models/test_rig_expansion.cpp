// Every shipped rig scenario expanded into network components (rig_models/rig_expansion.hpp) and
// run through the network path gives the rig kind's run: the bar's torque (the torque cell's),
// the clutch's slip and torque and the temperatures, sample for sample, and the same verdict.
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
  // One stepper runs both: the rig kind writes this network (LsctrRig::spec) and records the
  // rig's channels from it, so they are the network's channels under the rig's names, sample
  // for sample.
  EXPECT_EQ(worst, 0.0);
  // The same run read by the network's clutch judge (studies/clutch_judgement.hpp) and by the
  // rig's (studies/run_verdict.hpp): the same torque cell, the same verdict and oscillation.
  const auto judged = studies::judge_run(rig).judged;
  const auto& v = run.verdicts.at(0).verdict.judged;
  EXPECT_EQ(v.verdict, judged.verdict);
  // The two judges reach the figures by their own arithmetic: a vibration's within 3e-8 of each
  // other (bound 1e-6), a stick-slip cycle's within 0.2 % in frequency and 7e-5 in amplitude
  // (bounds 0.5 % and 0.1 %).
  const bool stick_slip = judged.verdict == analysis::Verdict::kStickSlip;
  if (judged.verdict != analysis::Verdict::kNone) {
    EXPECT_NEAR(v.frequency_Hz, judged.frequency_Hz, (stick_slip ? 5e-3 : 1e-6) * judged.frequency_Hz);
    EXPECT_NEAR(v.amplitude_Nm, judged.amplitude_Nm, (stick_slip ? 1e-3 : 1e-6) * judged.amplitude_Nm);
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
