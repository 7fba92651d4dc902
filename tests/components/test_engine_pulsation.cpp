// The engine's firing-order torque pulsation (components/engine_pulsation.hpp), the driveline's
// physical seed: T_p = A s(ω) sin(z/2 · θ) on the engine, θ the crank angle.
//
// Old behaviour (before it): a driveline run had no physical disturbance at all; the engine
// torque was the smooth map or schedule.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <vector>
#include <numbers>
#include <string>

#include "core/units.hpp"
#include "io/input_error.hpp"
#include "io/scenario.hpp"
#include "components/engine_pulsation.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/model.hpp"
#include "tests/support/recording.hpp"

namespace shudder::components {
namespace {

constexpr double kStall = 40.0, kIdle = 80.0;  // rad/s

// Closed form: full firing above idle, none below stall, the smoothstep's 1/2 half-way.
TEST(EnginePulsation, TorqueIsTheSineOfTheCrankAngleGatedByFiring) {
  const EnginePulsationLaw four({5.0, 4}, kStall, kIdle), six({5.0, 6}, kStall, kIdle);
  for (double th : {0.1, 1.0, 7.3}) {
    EXPECT_NEAR(four.torque_Nm(th, 200.0), 5.0 * std::sin(2.0 * th), 1e-12);  // z/2 = 2 per revolution
    EXPECT_NEAR(six.torque_Nm(th, 200.0), 5.0 * std::sin(3.0 * th), 1e-12);
    EXPECT_EQ(four.torque_Nm(th, 30.0), 0.0);
    EXPECT_NEAR(four.torque_Nm(th, 60.0), 0.5 * 5.0 * std::sin(2.0 * th), 1e-12);
  }
}

// The network's element contract (dynamics/network.hpp): T (ω_a − ρ ω_b) = dE/dt + P_diss with
// E = −W the stored energy; the element drives its node by +T_p (it acts −T on a).
TEST(EnginePulsation, KeepsTheNetworksEnergyBalanceWithItsDeliveredWork) {
  const EnginePulsationLaw law({5.0, 4}, kStall, kIdle);
  const double z[2] = {0.7, 3.0}, omega = 150.0;
  double dz[2];
  const auto out = law.evaluate(omega, 0.0, z, dz);
  EXPECT_DOUBLE_EQ(-out.torque_Nm, law.torque_Nm(0.7, omega));
  EXPECT_DOUBLE_EQ(dz[0], omega);
  EXPECT_DOUBLE_EQ(out.torque_Nm * omega, -dz[1]);  // = dE/dt with E = −W
  EXPECT_EQ(out.dissipated_W, 0.0);
  EXPECT_EQ(law.stored_energy_J(z), -3.0);
  EXPECT_EQ(law.modal_stiffness_Nm_per_rad(), 0.0);
}

TEST(EnginePulsation, RejectsBadParameters) {
  EXPECT_THROW(EnginePulsationLaw({-1.0, 4}, kStall, kIdle), std::invalid_argument);
  EXPECT_THROW(EnginePulsationLaw({5.0, 0}, kStall, kIdle), std::invalid_argument);
  EXPECT_THROW(EnginePulsationLaw({5.0, 4}, kIdle, kStall), std::invalid_argument);
}

// On a driveline run: a 2 s straight run from 20 km/h (engine 2321 rpm at the start, fully
// firing) with and without the default pulsation. The difference of the engine speeds oscillates
// at the 2nd order, 2 n/60 (measured: 88.0 Hz against 87.8 Hz at the last second's mean speed;
// the engine gains a few per cent over that second, so 5 % is the tolerance of counting zero
// crossings of the difference, detrended over that second), and the energy
// balance, which books the pulsation's work in its stored energy, stays within the 1e-6 bound
// the driveline tests use.
TEST(EnginePulsation, DrivelineEngineOscillatesAtTheFiringFrequency) {
  io::Scenario sc = io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml");
  const auto clutch = sc.make_clutch();
  auto& m = std::get<rig_models::DrivelineModel>(sc.model);
  ASSERT_EQ(m.params.engine_pulsation.amplitude_Nm, 5.0);  // the default
  rig_models::DrivelineInputs in = m.manoeuvre;
  in.engine_torque_Nm = PiecewiseLinear({0.0}, {30.0});
  in.turn_radius_m = 0.0;
  in.start_speed_km_h = 20.0;
  rig_models::DrivelineSettings s = m.settings;
  s.duration_s = 2.0;
  s.sample_rate_Hz = 2000.0;
  const auto with = rig_models::run_driveline(m.params, clutch, in, s);
  rig_models::DrivelineParams off = m.params;
  off.engine_pulsation.amplitude_Nm = 0.0;
  const auto without = rig_models::run_driveline(off, clutch, in, s);
  EXPECT_LT(test::scalar(with, "mechanical_energy_relative_error"), 1e-6);

  const auto& t = test::signal(with, "time_s");
  const auto& a = test::signal(with, "engine_speed_rpm");
  const auto& b = test::signal(without, "engine_speed_rpm");
  // Least-squares line through the difference over the last second, then zero crossings.
  std::vector<double> tt, d;
  for (std::size_t k = 0; k < t.size(); ++k)
    if (t[k] >= 1.0) {
      tt.push_back(t[k]);
      d.push_back(a[k] - b[k]);
    }
  const double n = static_cast<double>(d.size());
  double st = 0, sd = 0, stt = 0, std_ = 0;
  for (std::size_t k = 0; k < d.size(); ++k) {
    st += tt[k];
    sd += d[k];
    stt += tt[k] * tt[k];
    std_ += tt[k] * d[k];
  }
  const double slope = (n * std_ - st * sd) / (n * stt - st * st), icpt = (sd - slope * st) / n;
  int crossings = 0;
  double peak = 0;
  for (std::size_t k = 0; k < d.size(); ++k) {
    const double r = d[k] - (icpt + slope * tt[k]);
    peak = std::max(peak, std::abs(r));
    if (k > 0 && (r > 0) != (d[k - 1] - (icpt + slope * tt[k - 1]) > 0)) ++crossings;
  }
  const double mean_rpm = 0.5 * (a[a.size() / 2] + a.back());
  const double firing_Hz = 2.0 * mean_rpm / 60.0;
  const double measured_Hz = 0.5 * crossings / (tt.back() - tt.front());
  std::printf("engine %.0f rpm: firing %.2f Hz, difference oscillates at %.2f Hz, peak %.3g rpm\n", mean_rpm, firing_Hz,
              measured_Hz, peak);
  EXPECT_GT(peak, 1e-3);  // it acts (without it the runs are identical)
  EXPECT_NEAR(measured_Hz / firing_Hz, 1.0, 0.05);
}

TEST(EnginePulsation, ScenarioKeysSetItWithinTheirBounds) {
  const std::string path = std::string(SHUDDER_SOURCE_DIR) + "/scenarios/pulsation.toml";
  const auto text = [](const std::string& keys) {
    return "[scenario]\nname = \"x\"\ntype = \"driveline\"\nduration_s = 1.0\n"
           "[clutch]\nfluid = \"fluids/lsc_fluid_c.toml\"\nsliding_interfaces = 16\nstart_temp_C = 40.0\n"
           "[manoeuvre]\ntime_s = [0.0]\nengine_torque_Nm = 30.0\nvalve_pressure_bar = 30.0\n"
           "start_speed_km_h = 20.0\n[driveline.engine]\n" +
           keys + "\n";
  };
  auto sc = io::load_scenario_text(text("firing_pulsation_Nm = 2.5\ncylinders = 6"), path);
  const auto& p = std::get<rig_models::DrivelineModel>(sc.model).params.engine_pulsation;
  EXPECT_EQ(p.amplitude_Nm, 2.5);
  EXPECT_EQ(p.cylinders, 6);
  try {
    io::load_scenario_text(text("firing_pulsation_Nm = 150.0"), path);
    ADD_FAILURE() << "150 N m accepted";
  } catch (const io::InputError& e) {
    EXPECT_NE(std::string(e.what()).find("firing_pulsation_Nm"), std::string::npos) << e.what();
  }
  EXPECT_THROW(io::load_scenario_text(text("cylinders = 0"), path), io::InputError);
}

}  // namespace
}  // namespace shudder::components
