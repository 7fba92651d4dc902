// The Haldex car written as a network (scenarios/networks/haldex_car_*.toml: gears, open
// differentials, shafts, tyres with path ratios, the vehicle, a firing pulsation and the
// haldex_coupling component with its hydraulics and control unit) against the driveline kind's
// hand-assembled car on the same manoeuvre (scenarios/driveline_*.toml). The two assemble the
// same equations in a different order, so they agree to the integrator's error control, not to
// round-off: the network restarts at its signals' knots and orders nodes as the file does.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <string>

#include "studies/network_run.hpp"
#include "studies/driveline_judgement.hpp"
#include "io/input_error.hpp"
#include "io/network_scenario.hpp"
#include "io/scenario.hpp"
#include "rig_models/model.hpp"
#include "tests/components/network_helpers.hpp"
#include "tests/support/cli.hpp"

namespace shudder::components {
namespace {

struct Pair {
  dynamics::Recording network, driveline;
  studies::NetworkRun run;
};

Pair run_both(const std::string& network_file, const std::string& driveline_file) {
  const std::string root = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/";
  const auto net = io::load_network_scenario(root + network_file);
  Pair p;
  p.run = studies::run_network(net.spec);
  p.network = p.run.recording;
  const auto sc = io::load_scenario(root + driveline_file);
  const auto& model = std::get<rig_models::DrivelineModel>(sc.model);
  const auto clutch = sc.make_clutch();
  p.driveline = rig_models::simulate(model, clutch);
  studies::add_driveline_judgement(model.params, clutch, model.manoeuvre, model.settings, p.driveline);
  return p;
}

// Largest |a − b| over the run, relative to b's range over the run.
double relative_difference(const dynamics::Recording& a, const std::string& a_name, const dynamics::Recording& b,
                           const std::string& b_name) {
  const auto& x = test::channel(a, a_name);
  const auto& y = test::channel(b, b_name);
  EXPECT_EQ(x.size(), y.size()) << a_name;
  return test::relative_difference(x, y);
}

// The control unit's launch from rest: the two runs start from the same exact zeros, so they
// agree to round-off over the whole run (measured 1e-11 of the slip's range, 7e-13 of the
// torque's): the network's control unit sees the same sampled, filtered axle speeds at the same
// instants as the driveline kind's and sets the same valve. Bound 1e-9: round-off grown over 3 s,
// far below any modelling difference (a control instant missed or taken twice moves the torque by
// ~20 % of its range).
TEST(HaldexNetwork, ControlUnitLaunchEqualsTheDrivelineKind) {
  const Pair p = run_both("networks/haldex_car_low_mu_uphill.toml", "driveline_low_mu_uphill.toml");
  for (const auto& [net, drv] :
       std::vector<std::pair<std::string, std::string>>{{"haldex.torque_Nm", "coupling_torque_Nm"},
                                                        {"haldex.slip_rpm", "coupling_slip_rpm"},
                                                        {"haldex.pressure_bar", "pressure_bar"},
                                                        {"haldex.valve_opening", "valve_opening"},
                                                        {"haldex.normal_force_N", "clamp_force_N"},
                                                        {"haldex.interface_max_temp_C", "interface_max_temp_C"},
                                                        {"car.speed_km_h", "vehicle_speed_km_h"},
                                                        {"engine.speed_rpm", "engine_speed_rpm"},
                                                        {"wheel_fl.speed_rpm", "wheel_fl_speed_rpm"},
                                                        {"tyre_rr.force_N", "tyre_rr_force_N"}})
    EXPECT_LT(relative_difference(p.network, net, p.driveline, drv), 1e-9) << net << " vs " << drv;
  const auto& v = p.run.verdicts.at(0).verdict.judged;
  EXPECT_EQ(static_cast<double>(v.verdict), test::scalar(p.driveline, "coupling_verdict_code"));
  // The start's ringing of the 1.83 Hz shuffle dies away (none on both paths): the frequency is
  // NaN on both, the amplitude of what rang the same (1e-6 relative: the torques it is measured
  // on agree to 1e-9 above).
  const double f_drv = test::scalar(p.driveline, "coupling_oscillation_frequency_Hz");
  if (v.verdict == analysis::Verdict::kNone)
    EXPECT_TRUE(std::isnan(v.frequency_Hz) && std::isnan(f_drv));
  else
    EXPECT_NEAR(v.frequency_Hz, f_drv, 1e-6);
  EXPECT_NEAR(v.amplitude_Nm, test::scalar(p.driveline, "coupling_oscillation_amplitude_Nm"), 1e-6 * v.amplitude_Nm);
  // Fluid C's data start at 10 kN; the coupling clamps at 0-7 kN: the law is used below its data
  // for the whole run, and both paths tally it alike; the network puts it in its verdict block.
  const auto* nr = p.network.find_block("friction_data_range.haldex");
  const auto* dr = p.driveline.find_block("friction_data_range");
  const auto* nb = p.network.find_block("verdict.haldex");
  ASSERT_TRUE(nr && dr && nb);
  EXPECT_NEAR(nr->find_scalar("fraction_outside")->value, dr->find_scalar("fraction_outside")->value, 1e-9);
  ASSERT_NE(nb->find_scalar("outside_data_fraction"), nullptr);
  EXPECT_EQ(nb->find_scalar("outside_data_fraction")->value, nr->find_scalar("fraction_outside")->value);
  EXPECT_GT(nb->find_scalar("outside_data_fraction")->value, 0.99);
}

// The take-up judder with a raw pressure setting: a self-excited limit cycle, in which the start
// speeds' last-digit difference (the file gives them in rpm, the driveline kind computes them in
// rad/s) grows into a phase difference: measured 1e-4 of the torque's and 5e-4 of the slip's range;
// bound 2e-3. The verdict: the same class and frequency (measured equal to 4 digits; bound 0.1 %),
// the amplitude within 2 % (measured 0.7 %: the network judges the coupling's loaded window, the
// driveline kind the whole record).
TEST(HaldexNetwork, TakeUpJudderEqualsTheDrivelineKind) {
  const Pair p = run_both("networks/haldex_car_takeup_judder.toml", "driveline_takeup_judder.toml");
  for (const auto& [net, drv] :
       std::vector<std::pair<std::string, std::string>>{{"haldex.torque_Nm", "coupling_torque_Nm"},
                                                        {"haldex.slip_rpm", "coupling_slip_rpm"},
                                                        {"haldex.pressure_bar", "pressure_bar"},
                                                        {"haldex.normal_force_N", "clamp_force_N"},
                                                        {"haldex.interface_max_temp_C", "interface_max_temp_C"},
                                                        {"car.speed_km_h", "vehicle_speed_km_h"},
                                                        {"engine.speed_rpm", "engine_speed_rpm"},
                                                        {"tyre_fl.force_N", "tyre_fl_force_N"}})
    EXPECT_LT(relative_difference(p.network, net, p.driveline, drv), 2e-3) << net << " vs " << drv;
  const auto& v = p.run.verdicts.at(0).verdict.judged;
  EXPECT_EQ(static_cast<double>(v.verdict), test::scalar(p.driveline, "coupling_verdict_code"));
  const double f = test::scalar(p.driveline, "coupling_oscillation_frequency_Hz");
  EXPECT_NEAR(v.frequency_Hz, f, 1e-3 * f);
  const double a = test::scalar(p.driveline, "coupling_oscillation_amplitude_Nm");
  EXPECT_NEAR(v.amplitude_Nm, a, 0.02 * a);
}

// A coupling described wrongly gets one line naming the component or key and what to change.
std::string coupling_error(const std::string& from, const std::string& to) {
  const std::string path = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/networks/haldex_car_takeup_judder.toml";
  std::string text = shudder::test::slurp(path);
  const auto at = text.find(from);
  if (at == std::string::npos) return "test setup: '" + from + "' not in the file";
  text.replace(at, from.size(), to);
  try {
    io::load_network_scenario_text(text, path);
  } catch (const io::InputError& e) {
    return e.what();
  }
  return "";
}

TEST(HaldexNetwork, ABadCouplingIsOneHelpfulLine) {
  std::string e = coupling_error("rear_axle = \"rear_diff\"", "rear_axle = \"rear_dif\"");
  EXPECT_NE(e.find("network.haldex"), std::string::npos) << e;
  EXPECT_NE(e.find("did you mean 'rear_diff'"), std::string::npos) << e;
  e = coupling_error("valve_pressure_bar = 3.0", "valve_pressure_bar = 3.0\nvalve_opening = 0.5");
  EXPECT_NE(e.find("give one raw valve schedule"), std::string::npos) << e;
  e = coupling_error("valve_pressure_bar = 3.0",
                     "valve_pressure_bar = 3.0\n[network.haldex.controller]\nlock_slip_rpm = 10");
  EXPECT_NE(e.find("controller"), std::string::npos) << e;
  e = coupling_error("valve_pressure_bar = 3.0", "valve_pressure_bar = 300.0");
  EXPECT_NE(e.find("relief_pressure_bar"), std::string::npos) << e;
}

}  // namespace
}  // namespace shudder::components
