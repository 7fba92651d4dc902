// Every shipped driveline scenario expanded into network components
// (rig_models/driveline_expansion.hpp) and run through the network path gives the driveline
// kind's run: the coupling's torque, slip and pressure, the car's speed and a tyre's force,
// sample for sample, and the same verdict from the same judge.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "rig_models/driveline_expansion.hpp"
#include "studies/network_run.hpp"
#include "studies/driveline_judgement.hpp"
#include "io/scenario.hpp"
#include "dynamics/signal_names.hpp"
#include "rig_models/model.hpp"
#include "studies/recording_detection.hpp"
#include "tests/components/network_helpers.hpp"

namespace shudder::rig_models {
namespace {

namespace test = components::test;

class DrivelineExpansion : public ::testing::TestWithParam<std::string> {};

TEST_P(DrivelineExpansion, NetworkPathGivesTheDrivelineRun) {
  const auto sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/" + GetParam() + ".toml");
  const auto& m = std::get<rig_models::DrivelineModel>(sc.model);
  const components::NetworkSpec spec = expand_driveline(m.params, sc.clutch, sc.fluid, m.manoeuvre, m.settings);
  const studies::NetworkRun run = studies::run_network(spec);
  const auto clutch = sc.make_clutch();
  auto drv = rig_models::simulate(m, clutch);
  studies::add_driveline_judgement(m.params, clutch, m.manoeuvre, m.settings, drv);
  double worst = 0;
  for (const auto& [net, kind] :
       std::vector<std::pair<std::string, std::string>>{{"haldex.torque_Nm", "coupling_torque_Nm"},
                                                        {"haldex.slip_rpm", "coupling_slip_rpm"},
                                                        {"haldex.pressure_bar", "pressure_bar"},
                                                        {"vehicle.speed_km_h", "vehicle_speed_km_h"},
                                                        {"tyre_rl.force_N", "tyre_rl_force_N"},
                                                        {"haldex.interface_max_temp_C", "interface_max_temp_C"}}) {
    const double d = test::relative_difference(test::channel(run.recording, net), test::channel(drv, kind));
    worst = std::max(worst, d);
  }
  // One stepper runs both: the driveline kind writes this network (HaldexDriveline::spec) and
  // records its channels from it, so they are the network's under the driveline's names, sample
  // for sample.
  EXPECT_EQ(worst, 0.0);
  // The same run judged by the same judge: the network run's coupling channels under the driveline
  // kind's names, judged as the driveline kind judges its own (studies/recording_detection.hpp).
  // The network's own clutch judge (studies/clutch_judgement.hpp) has its own sustained rule
  // and may read a run at that rule's edge otherwise (docs/driveline.md); that is a property of
  // the judges, not of the expansion this test holds to the driveline run.
  namespace sn = dynamics::signal_names;
  dynamics::Recording as_driveline;
  for (const auto& [net, kind] :
       std::vector<std::pair<std::string, std::string_view>>{{"time_s", sn::kTime},
                                                             {"haldex.torque_Nm", sn::kCouplingTorque},
                                                             {"haldex.slip_rpm", sn::kCouplingSlip},
                                                             {"haldex.normal_force_N", sn::kClampForce},
                                                             {"haldex.interface_mean_temp_C", sn::kInterfaceMeanTemp},
                                                             {"haldex.stuck", sn::kStuck}})
    if (const auto* c = run.recording.find(net))
      as_driveline.add_signal(std::string(kind), c->units).values = c->values;
  const auto detection = studies::recording_detection(as_driveline);
  ASSERT_TRUE(detection.has_value());
  const analysis::ShudderResult judged = studies::judge_recording(*detection);
  EXPECT_EQ(static_cast<double>(judged.verdict), test::scalar(drv, "coupling_verdict_code"));
}

std::vector<std::string> shipped_drivelines() {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(std::string(SHUDDER_SOURCE_DIR) + "/scenarios")) {
    const std::string stem = e.path().stem().string();
    if (e.path().extension() == ".toml" && stem.rfind("driveline_", 0) == 0) names.push_back(stem);
  }
  std::sort(names.begin(), names.end());
  return names;
}

INSTANTIATE_TEST_SUITE_P(Shipped, DrivelineExpansion, ::testing::ValuesIn(shipped_drivelines()),
                         [](const auto& info) { return info.param; });

}  // namespace
}  // namespace shudder::rig_models
