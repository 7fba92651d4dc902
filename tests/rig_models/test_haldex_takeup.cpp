// The shipped take-up judder (scenarios/driveline_takeup_judder.toml): the coupling held slipping
// at 6–20 rpm on the negative-slope fluid vibrates, and the frequency is one of the driveline's
// modes with the coupling slipping (its halves free of each other), from the network's
// eigenvalues — the explanation docs/driveline.md gives for why it is not in the 5–20 Hz
// take-up band. With fluid C the same manoeuvre slides smoothly.
#include <gtest/gtest.h>

#include <cmath>
#include <string>

#include "studies/driveline_judgement.hpp"
#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "tests/support/recording.hpp"

namespace shudder::rig_models {
namespace {

TEST(HaldexTakeUp, NegativeSlopeJudderSitsAtASlippingCouplingMode) {
  const auto sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_takeup_judder.toml");
  const auto& model = std::get<DrivelineModel>(sc.model);
  const auto clutch = sc.make_clutch();
  auto rec = simulate(model, clutch);
  studies::add_driveline_judgement(model.params, clutch, model.manoeuvre, model.settings, rec);
  ASSERT_EQ(test::scalar(rec, "coupling_verdict_code"), 1.0) << "vibration expected";
  const double judder_Hz = test::scalar(rec, "coupling_oscillation_frequency_Hz");
  EXPECT_GT(judder_Hz, 20.0);  // above the take-up band: measured 28.63 Hz
  EXPECT_LT(test::scalar(rec, "mechanical_energy_relative_error"), 1e-6);

  // The modes with the coupling slipping (no friction stiffness across it): the nearest one.
  const HaldexDriveline dl(model.params, clutch, model.manoeuvre);
  const auto modes = dl.build().network().modes({false});
  double nearest_Hz = 0;
  for (Eigen::Index j = 0; j < modes.frequencies_Hz.size(); ++j)
    if (std::abs(modes.frequencies_Hz[j] - judder_Hz) < std::abs(nearest_Hz - judder_Hz))
      nearest_Hz = modes.frequencies_Hz[j];
  // Undamped modes with the tyres as their standstill springs: measured 28.63 Hz against the
  // 32.41 Hz mode (−11.7 %; the friction slope and the tyres' relaxation at 10 km/h, which this
  // eigen-analysis leaves out, shift it): 15 %. The next modes are 35.5 and 37.9 Hz, the one below
  // 2.7 Hz (the car against the rear wheels through the tyres): none in 5–20 Hz.
  EXPECT_NEAR(judder_Hz, nearest_Hz, 0.15 * nearest_Hz) << "modes: " << modes.frequencies_Hz.transpose();
  for (Eigen::Index j = 0; j < modes.frequencies_Hz.size(); ++j)
    EXPECT_FALSE(modes.frequencies_Hz[j] > 5.0 && modes.frequencies_Hz[j] < 20.0) << modes.frequencies_Hz[j];

  // Fluid C: the same manoeuvre slides smoothly.
  io::Scenario smooth = io::load_scenario_text(
      [&] {
        std::string t = sc.text;
        t.replace(t.find("schematic_negative_slope.toml"), 29, "lsc_fluid_c.toml");
        return t;
      }(),
      sc.path);
  const auto& smooth_model = std::get<DrivelineModel>(smooth.model);
  const auto smooth_clutch = smooth.make_clutch();
  auto smooth_rec = simulate(smooth_model, smooth_clutch);
  studies::add_driveline_judgement(smooth_model.params, smooth_clutch, smooth_model.manoeuvre, smooth_model.settings,
                                   smooth_rec);
  EXPECT_EQ(test::scalar(smooth_rec, "coupling_verdict_code"), 0.0);
}

}  // namespace
}  // namespace shudder::rig_models
