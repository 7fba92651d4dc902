// Model-based characterisation (rig_models/inverse_characterisation.hpp, --method inverse):
// round trips of known fluids through the project's clutch and thermal model with sensor noise
// (3 loads x 5 start temperatures, Paper D cycles), and through a thermal model that differs
// from the one the inverse method replays with (finer grid, slip-dependent oil flow, sensor lag).
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>

#include "analysis/anti_shudder_indices.hpp"
#include "analysis/friction_characterisation.hpp"
#include "io/fluid_loader.hpp"
#include "rig_models/fluid_screening.hpp"
#include "rig_models/inverse_characterisation.hpp"
#include "tests/support/ramp_runs.hpp"

namespace {

using namespace shudder;
using analysis::Characterisation;
using analysis::CharacterisationSettings;
using analysis::Compensation;
using analysis::LawKind;

// Max over rows and the node speeds of |mu_fit / mu_true − 1| at the row's (T, F).
double max_error(const Characterisation& c, const clutch::FrictionLaw& truth) {
  double e = 0.0;
  for (const auto& row : c.rows)
    for (double v : c.node_speeds_mm_s)
      e = std::max(e, std::abs(c.law->mu(v, row.temp_C, row.load_N) / truth.mu(v, row.temp_C, row.load_N) - 1.0));
  return e;
}

std::vector<rig_models::ReplayInputs> replay_inputs(const std::vector<analysis::RampRun>& runs) {
  std::vector<rig_models::ReplayInputs> in;
  for (const auto& r : runs) {
    rig_models::ReplayInputs x;
    x.time_s = r.time_s;
    x.speed_rpm = r.speed_rpm;
    x.normal_force_N = r.normal_force_N;
    x.temp_C = r.temp_C;
    x.torque_Nm = r.torque_Nm;
    in.push_back(std::move(x));
  }
  return in;
}

CharacterisationSettings settings(LawKind law) {
  CharacterisationSettings s;
  s.law = law;
  s.compensation = Compensation::kQuadratic;  // the sensor method the inverse one starts from
  s.conversion.rule = analysis::RadiusRule::kUniformPressure;
  return s;
}

rig_models::InverseSettings inverse_settings(const clutch::Fluid& any_fluid) {
  rig_models::InverseSettings inv;
  inv.model.fluid = any_fluid;         // viscosities only; the law is replaced by every iterate
  inv.model.settings.thermal_step_s = 0.02;
  inv.jobs = 2;
  return inv;
}

struct Set {
  std::vector<analysis::RampRun> runs;
  clutch::Fluid truth;
};

// 10, 15, 20 kN x 5 start temperatures, Paper D cycles (10 s ramps), 50 S/s, sensor noise.
Set round_trip(const std::string& fluid_file, std::vector<double> temps_C) {
  Set s;
  s.truth = io::load_fluid(std::string(SHUDDER_SOURCE_DIR "/scenarios/fluids/") + fluid_file);
  unsigned seed = 500;
  for (double load : {10000.0, 15000.0, 20000.0})
    for (double t0 : temps_C) s.runs.push_back(test::simulated_ramp_run(s.truth, test::paper_d_cycle(load), t0, seed++, 50.0));
  return s;
}

TEST(InverseCharacterisation, FluidCMatrix) {
  const Set set = round_trip("lsc_fluid_c.toml", {30.0, 40.0, 50.0, 60.0, 70.0});
  for (LawKind law : {LawKind::kMaki, LawKind::kTable}) {
    const auto r = rig_models::characterise_inverse(set.runs, replay_inputs(set.runs), settings(law), "temp_C",
                                                    inverse_settings(set.truth));
    std::printf("[ figures  ] fluid C matrix, %s law: sensor (quadratic) %.4f, inverse %.4f; %d law updates, %d replays, "
                "last change %.2g; oil flow e %.4g a %.3g; temp rms %.3f -> %.3f C; torque rms %.4f -> %.4f N m\n",
                analysis::law_name(law), max_error(r.sensor, *set.truth.friction), max_error(r.inverse, *set.truth.friction),
                r.iterations, r.replays, r.last_change_mu, r.oil_flow.e, r.oil_flow.a, r.temp_rms_start_C, r.temp_rms_C,
                r.torque_rms_sensor_Nm, r.torque_rms_Nm);
  }
}

TEST(InverseCharacterisation, PaperELinearLaw) {
  const Set set = round_trip("paper_e_fluid_c.toml", {30.0, 45.0, 60.0, 75.0, 90.0});
  const auto r = rig_models::characterise_inverse(set.runs, replay_inputs(set.runs), settings(LawKind::kLinear),
                                                  "temp_C", inverse_settings(set.truth));
  std::printf("[ figures  ] Paper E fluid C linear: sensor %.4f, inverse %.4f; %d updates, %d replays; e %.4g a %.3g\n",
              max_error(r.sensor, *set.truth.friction), max_error(r.inverse, *set.truth.friction), r.iterations,
              r.replays, r.oil_flow.e, r.oil_flow.a);
}

}  // namespace
