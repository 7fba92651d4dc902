// Take-up judder of the Haldex coupling: the linear prediction (rig_models/driveline_stability.hpp)
// against the simulation (rig_models/haldex_driveline.hpp), issue 13 part 4.
//
// Case: the tight-turn car on a legacy turn ratio ρ = 1.1 from 10 km/h, no engine torque, the
// valve holding a constant pressure p (so the coupling keeps slipping at ~20 rpm on the turn's
// kinematic slip), the schematic negative-slope fluid (μ falls above 10 rpm). The friction slope's
// negative damping grows with the clamp force, i.e. with p: the onset is a valve pressure.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "io/fluid_loader.hpp"
#include "io/scenario.hpp"
#include "rig_models/driveline_stability.hpp"
#include "rig_models/model.hpp"

namespace shudder::rig_models {
namespace {

struct TakeUp {
  DrivelineParams params;
  clutch::WetClutch clutch;
  DrivelineInputs inputs;
};

TakeUp take_up() {
  const io::Scenario sc =
      io::load_scenario(std::string(SHUDDER_SOURCE_DIR) + "/scenarios/driveline_tight_turn.toml");
  DrivelineParams params = std::get<DrivelineModel>(sc.model).params;
  params.turn_ratio = 1.1;
  DrivelineInputs in;
  in.start_speed_km_h = 10.0;
  return {params,
          clutch::WetClutch(sc.clutch, io::load_fluid(std::string(SHUDDER_SOURCE_DIR) +
                                                      "/scenarios/fluids/schematic_negative_slope.toml")),
          in};
}

dynamics::Recording simulate_at(const TakeUp& c, double valve_bar, double duration_s) {
  DrivelineInputs in = c.inputs;
  in.valve_pressure_bar = PiecewiseLinear({0.0}, {valve_bar});
  DrivelineSettings settings;
  settings.duration_s = duration_s;
  return run_driveline(c.params, c.clutch, in, settings);
}

double scalar(const dynamics::Recording& rec, const char* name) { return rec.find_scalar(name)->value; }

TEST(DrivelinePrediction, TakeUpJudderOnsetAndFrequencyMatchTheSimulation) {
  const TakeUp c = take_up();
  const double onset = onset_valve_pressure_bar(c.params, c.clutch, c.inputs, 0.0, 30.0);
  const double onset_thermal = onset_valve_pressure_bar(c.params, c.clutch, c.inputs, 0.0, 30.0, true);
  std::printf("onset isothermal %.4f bar, with thermal %.4f bar\n", onset, onset_thermal);
  for (double f : {0.8, 0.9, 1.1, 1.2}) {
    const auto rec = simulate_at(c, f * onset, 4.0);
    std::printf("p = %.3f bar: verdict %g freq %.3f amp %.3f\n", f * onset, scalar(rec, "coupling_verdict_code"),
                scalar(rec, "coupling_oscillation_frequency_Hz"), scalar(rec, "coupling_oscillation_amplitude_Nm"));
    const auto op = recorded_operating_point(rec, 3.0, 4.0);
    DrivelineInputs in = c.inputs;
    in.valve_pressure_bar = PiecewiseLinear({0.0}, {f * onset});
    const HaldexDriveline dl(c.params, c.clutch, in);
    const auto m = least_damped_mode(driveline_stability(dl, c.clutch, op, false));
    std::printf("   op V %.3f slip %.3f F %.1f T %.2f: growth %.4f freq %.3f\n", op.vehicle_speed_m_s,
                op.coupling_slip_rad_s, op.clamp_force_N, op.interface_temp_C, m.growth_per_s, m.frequency_Hz);
  }
}

}  // namespace
}  // namespace shudder::rig_models
