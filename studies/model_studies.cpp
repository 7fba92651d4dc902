#include "studies/model_studies.hpp"

#include <algorithm>
#include <cmath>
#include <limits>

#include "dynamics/signal_names.hpp"
#include "components/friction_range_block.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/rig_names.hpp"
#include "studies/driveline_judgement.hpp"
#include "studies/driveline_stability.hpp"
#include "studies/run_stability_map.hpp"
#include "studies/run_verdict.hpp"

namespace shudder::studies {

namespace {

// How far the coupling's clamp force swings over the judged oscillating window: RMS about its
// mean times √2 (the amplitude of a sine) over the mean. A friction-induced judder rides on a
// steady clamp force; an oscillation that the control loop carries (the valve and pressure
// hunting with the wheel slip) swings the clamp force with it. NaN without such a window.
double clamp_force_swing(const dynamics::Recording& rec, double from_s, double to_s) {
  const auto* t = rec.find(dynamics::signal_names::kTime);
  const auto* f = rec.find(dynamics::signal_names::kClampForce);
  if (!t || !f || !(to_s > from_s)) return std::numeric_limits<double>::quiet_NaN();
  double n = 0, sum = 0, sum2 = 0;
  for (std::size_t i = 0; i < t->values.size(); ++i)
    if (t->values[i] >= from_s && t->values[i] <= to_s) {
      n += 1;
      sum += f->values[i];
      sum2 += f->values[i] * f->values[i];
    }
  if (n < 2) return std::numeric_limits<double>::quiet_NaN();
  const double mean = sum / n;
  const double rms = std::sqrt(std::max(sum2 / n - mean * mean, 0.0));
  return mean > 0 ? std::sqrt(2.0) * rms / mean : std::numeric_limits<double>::quiet_NaN();
}

// Judges the run, adds the kind's prediction at its operating point (`predict`: OperatingWindow
// -> Prediction) and stores the verdict block (run_verdict.hpp). A recording that cannot be
// judged (e.g. fewer than 64 samples) is a valid run: its block says "not_judged" and why.
template <class Predict>
void add_verdict(dynamics::Recording& rec, Predict predict) {
  RunVerdict v;
  try {
    v = judge_run(rec);
  } catch (const std::invalid_argument& e) {
    rec.blocks.push_back(not_judged_block(e.what()));
    return;
  }
  v.prediction = predict(v.window);
  dynamics::ResultBlock block = verdict_block(v);
  // How much of the run the friction law was used outside its data (friction_range_block.hpp):
  // a verdict reached there is an extrapolation of the law, and says so.
  double outside = std::numeric_limits<double>::quiet_NaN();
  if (const auto* range = rec.find_block(components::kFrictionRangeBlock))
    if (const auto* f = range->find_scalar("fraction_outside")) outside = f->value;
  block.scalars.push_back({"outside_data_fraction", "1", outside});
  rec.blocks.push_back(std::move(block));
}

}  // namespace

std::vector<std::string> add_run_analysis(const rig_models::PrescribedSlipModel&, const clutch::WetClutch&, double,
                                          dynamics::Recording& rec) {
  add_verdict(rec, [](const OperatingWindow&) {
    return Prediction::none("the slip is imposed, so there are no torsional dynamics to linearise");
  });
  return {};
}

void require_sweep(const rig_models::PrescribedSlipModel&) {}

CaseOutcome evaluate_case(const rig_models::PrescribedSlipModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec) {
  return evaluate_prescribed_case(clutch, model.cycle, model.settings, rec);
}

ReplayModel replay_model(const rig_models::PrescribedSlipModel& model,
                         const components::StickTimeFriction& stick_time) {
  ReplayModel m;
  m.kind = ModelKind::kPrescribedSlip;
  m.settings = model.settings;
  m.rig_params.stick_time = stick_time;
  return m;
}

std::vector<std::string> add_run_analysis(const rig_models::RigModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec) {
  add_verdict(rec, [&](const OperatingWindow& window) { return predict_rig(model.params, clutch, window); });
  try {
    rec.maps.push_back(run_stability_map(model.params, clutch, model.cycle, start_temp_C));
  } catch (const std::invalid_argument& e) {
    return {std::string("no stability map stored: ") + e.what()};
  }
  return {};
}

void require_sweep(const rig_models::RigModel&) {}

CaseOutcome evaluate_case(const rig_models::RigModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec) {
  return evaluate_rig_case(model.params, clutch, model.cycle, model.settings, rec);
}

// The rig carries its own stick-time friction in params; the scenario's copy is the same.
ReplayModel replay_model(const rig_models::RigModel& model, const components::StickTimeFriction&) {
  ReplayModel m;
  m.kind = ModelKind::kRig;
  m.settings.duration_s = model.settings.duration_s;
  m.settings.thermal_step_s = model.settings.thermal_step_s;
  m.settings.sample_rate_Hz = model.settings.sample_rate_Hz;
  m.settings.snapshot_times_s = model.settings.snapshot_times_s;
  m.settings.bearing_drag = model.params.bearing_drag;
  m.settings.load_cell = model.params.load_cell;
  m.rig_params = model.params;
  return m;
}

std::vector<std::string> add_run_analysis(const rig_models::DrivelineModel& model, const clutch::WetClutch& clutch,
                                          double start_temp_C, dynamics::Recording& rec) {
  add_driveline_judgement(model.params, clutch, model.manoeuvre, model.settings, rec);
  add_verdict(
      rec, [&](const OperatingWindow& w) { return predict_driveline(model.params, clutch, model.manoeuvre, rec, w); });
  // The clamp force's swing over an oscillation (docs/formats/run_output.md, `clamp_force_swing`).
  double window_force_N = std::numeric_limits<double>::quiet_NaN();
  for (auto& b : rec.blocks) {
    if (b.name != kVerdictBlock) continue;
    const auto* from = b.find_scalar("window_from_s");
    const auto* to = b.find_scalar("window_to_s");
    const auto* force = b.find_scalar("normal_force_N");
    if (force) window_force_N = force->value;
    const auto* verdict = b.find_text("verdict");
    const bool oscillates = verdict && (verdict->value == "vibration" || verdict->value == "stick_slip");
    b.scalars.push_back({"clamp_force_swing", "1",
                         oscillates && from && to ? clamp_force_swing(rec, from->value, to->value)
                                                  : std::numeric_limits<double>::quiet_NaN()});
  }
  // Coupling stability maps (12 x 9 x 3 cells, ~0.25 ms each): slip 1–60 rpm, the start
  // temperature −20 … +80 °C, at half, once and twice the run's own clamp force (its mean over
  // the judged window; the manoeuvre's quasi-static point's when the run has none).
  try {
    const rig_models::HaldexDriveline dl(model.params, clutch, model.manoeuvre);
    DrivelineOperatingPoint op = quasi_static_operating_point(dl, clutch, model.manoeuvre);
    if (std::isfinite(window_force_N) && window_force_N > 0) op.clamp_force_N = window_force_N;
    std::vector<double> slips, temps;
    for (int i = 0; i < 12; ++i) slips.push_back(1.0 + 59.0 * i / 11.0);
    for (int j = 0; j < 9; ++j) temps.push_back(start_temp_C - 20.0 + 12.5 * j);
    for (auto& m : coupling_stability_maps(dl, clutch, op, slips, temps,
                                           {0.5 * op.clamp_force_N, op.clamp_force_N, 2.0 * op.clamp_force_N}))
      rec.maps.push_back(std::move(m));
  } catch (const std::invalid_argument& e) {
    return {std::string("no coupling stability map stored: ") + e.what()};
  }
  return {};
}

void require_sweep(const rig_models::DrivelineModel&) {}

CaseOutcome evaluate_case(const rig_models::DrivelineModel& model, const clutch::WetClutch& clutch,
                          dynamics::Recording& rec) {
  return evaluate_driveline_case(model.params, clutch, model.manoeuvre, model.settings, rec);
}

// The coupling alone: its measured slip and clamp force imposed on the pack (prescribed slip),
// the pack's oil already in the clutch's thermal parameters (io/scenario.cpp), the pack's
// thermal step; the instrumented coupling's sensors as the prescribed-slip cells.
ReplayModel replay_model(const rig_models::DrivelineModel& model, const components::StickTimeFriction&) {
  ReplayModel m;
  m.kind = ModelKind::kDriveline;
  m.inputs_as_measured = true;
  m.rig = std::string(rig_models::kCouplingRig);
  m.settings.duration_s = model.settings.duration_s;
  m.settings.thermal_step_s = model.settings.slow_step_s;
  m.settings.sample_rate_Hz = model.settings.sample_rate_Hz;
  m.settings.torque_cell = model.torque_cell;
  m.settings.load_cell = model.load_cell;
  m.rig_params.stick_time = model.params.stick_time;
  return m;
}

}  // namespace shudder::studies
