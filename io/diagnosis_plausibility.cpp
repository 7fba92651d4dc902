#include "io/diagnosis_plausibility.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>

#include "core/median.hpp"
#include "dynamics/signal_names.hpp"
#include "io/input_error.hpp"

namespace shudder::io {

namespace {

std::string fmt(double v) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", v);
  return buf;
}

void check_units(const MeasuredRun& run, std::vector<std::string>& warnings) {
  namespace sn = dynamics::signal_names;
  for (const auto name : {sn::kTemp, sn::kSumpTemp, sn::kIrTemp}) {
    const auto* c = run.column(name);
    if (!c || c->empty()) continue;
    const double m = core::median(*c);
    if (m > 200.0)
      throw InputError(run.path, 0, std::string(name),
                       "the temperatures have a median of " + fmt(m) +
                           ", which looks like kelvin (the rig runs its oil at 20-150 C); give degrees Celsius");
  }
  if (const auto* f = run.column(sn::kNormalForce); f && !f->empty()) {
    double top = 0;
    for (double x : *f) top = std::max(top, std::abs(x));
    if (top < 100.0)
      throw InputError(
          run.path, 0, std::string(sn::kNormalForce),
          "the largest force is " + fmt(top) + " N, which looks like kN (the rig applies 1-30 kN); give newtons");
    if (top < 500.0)
      warnings.push_back(run.path + ": the largest normal force is " + fmt(top) +
                         " N, far below the rig's 1-30 kN; is normal_force_N in newtons?");
  }
}

bool same_data(const MeasuredRun& a, const MeasuredRun& b) {
  namespace sn = dynamics::signal_names;
  for (const auto name : {sn::kTime, sn::kTorque, sn::kTemp}) {
    const auto* x = a.column(name);
    const auto* y = b.column(name);
    if (!x || !y || *x != *y) return false;
  }
  return true;
}

// The slowest time constant of the thermal effects the model has on (s; 0 if none).
double slowest_time_constant_s(const studies::ReplayModel& model) {
  const auto& th = model.clutch.thermal;
  double tau = 0;
  if (th.rig_heat_capacity && th.rig_conductance_W_per_K > 0)
    tau = std::max(tau, th.rig_heat_capacity_J_per_K / th.rig_conductance_W_per_K);
  if (th.temperature_sensor_lag) tau = std::max(tau, th.sensor_time_constant_s);
  return tau;
}

}  // namespace

void check_plausibility(const std::vector<MeasuredRun>& runs, const studies::ReplayModel& model,
                        double statistics_block_s, std::vector<std::string>& warnings) {
  double total_s = 0;
  for (std::size_t i = 0; i < runs.size(); ++i) {
    const auto& run = runs[i];
    check_units(run, warnings);
    for (std::size_t j = 0; j < i; ++j)
      if (same_data(run, runs[j]))
        throw InputError(run.path, 0, "",
                         "this run has the same time, torque and temperature columns as " + runs[j].path +
                             "; the hold-out would be fit data; give different runs");
    const double min_s = 20.0 * model.settings.thermal_step_s;
    if (run.duration_s() < min_s)
      throw InputError(run.path, 0, "",
                       "the run lasts " + fmt(run.duration_s()) + " s, shorter than 20 of the model's thermal steps (" +
                           fmt(min_s) + " s); give a longer run");
    // Half-overlapping blocks: a run of D s holds 2D/L − 1 of them; the jitter needs 5.
    if (model.kind == ModelKind::kRig && run.duration_s() < 3.0 * statistics_block_s - 1e-9)
      warnings.push_back(run.path + ": the run lasts " + fmt(run.duration_s()) +
                         " s, under 3 torque statistics blocks of " + fmt(statistics_block_s) +
                         " s; the block jitter is not estimated and the torque scale is the noise alone");
    total_s += run.duration_s();
  }
  if (const double tau = slowest_time_constant_s(model); tau > 0 && total_s < 3.0 * tau)
    warnings.push_back("the runs last " + fmt(total_s) + " s together, under 3 x the model's slowest time constant (" +
                       fmt(tau) + " s); its parameters are poorly constrained");
}

}  // namespace shudder::io
