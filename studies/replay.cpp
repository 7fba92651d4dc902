#include "studies/replay.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <stdexcept>
#include <string>
#include <string_view>

#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "studies/speed_setpoint.hpp"

namespace shudder::studies {

namespace {

constexpr int kCouplingStepsPerStep = 10;

// Mean of `x` over consecutive windows of `window_s`, at the windows' mean times.
components::PiecewiseLinear window_means(const std::vector<double>& t, const std::vector<double>& x, double t0,
                                         double window_s) {
  std::vector<double> times, values;
  for (std::size_t b = 0; b < t.size();) {
    std::size_t e = b;
    double st = 0, sx = 0;
    while (e < t.size() && t[e] < t[b] + window_s) {
      st += t[e];
      sx += x[e];
      ++e;
    }
    const double n = static_cast<double>(e - b);
    const double tm = st / n - t0;
    if (times.empty() || tm > times.back()) {
      times.push_back(tm);
      values.push_back(sx / n);
    }
    b = e;
  }
  return {times, values};
}

// `x` at its own sample times (relative to t0), joined linearly: a measured signal that is
// continuous and sampled finely enough for its motion (a coupling's clamp force and slip, which the
// driveline integrates with the motion and records at 1 kHz). Repeated times keep the first.
components::PiecewiseLinear samples_as_measured(const std::vector<double>& t, const std::vector<double>& x, double t0) {
  std::vector<double> times, values;
  for (std::size_t i = 0; i < t.size(); ++i)
    if (times.empty() || t[i] - t0 > times.back()) {
      times.push_back(t[i] - t0);
      values.push_back(x[i]);
    }
  return {times, values};
}

double start_mean(const std::vector<double>& t, const std::vector<double>& x) {
  double s = 0;
  std::size_t n = 0;
  for (; n < x.size() && (n < 5 || t[n] - t.front() < 0.1); ++n) s += x[n];
  return s / static_cast<double>(n);
}

// Linear interpolation of (t, y) at the increasing query times tq (held beyond the ends).
std::vector<double> interpolate(const std::vector<double>& t, const std::vector<double>& y,
                                const std::vector<double>& tq) {
  std::vector<double> out(tq.size());
  std::size_t j = 0;
  for (std::size_t i = 0; i < tq.size(); ++i) {
    while (j + 1 < t.size() && t[j + 1] < tq[i]) ++j;
    if (tq[i] <= t.front())
      out[i] = y.front();
    else if (j + 1 >= t.size())
      out[i] = y.back();
    else {
      const double w = (tq[i] - t[j]) / (t[j + 1] - t[j]);
      out[i] = y[j] + w * (y[j + 1] - y[j]);
    }
  }
  return out;
}

const std::vector<double>& signal(const dynamics::Recording& rec, std::string_view name) {
  const auto* s = rec.find(name);
  if (!s) throw std::logic_error("replay: the model did not record " + std::string(name));
  return s->values;
}

}  // namespace

void parse_temp_sensor(const std::string& value, ReplayInputs& in) {
  static const std::regex r_mm(R"(r_mm\s*=\s*([-+0-9.eE]+))"), z_mm(R"(z_mm\s*=\s*([-+0-9.eE]+))");
  std::smatch m;
  if (std::regex_search(value, m, r_mm)) in.thermocouple_r_mm = std::stod(m[1]);
  if (std::regex_search(value, m, z_mm)) in.thermocouple_z_mm = std::stod(m[1]);
}

ReplayOutput replay(const ReplayModel& model, const ReplayInputs& in) {
  const auto& t = in.time_s;
  if (t.size() < 2) throw std::invalid_argument("replay needs at least two samples");
  const double t0 = t.front();

  clutch::WetClutchParams cp = model.clutch;
  cp.start_temp_C = start_mean(t, in.temp_C);
  cp.sump_start_temp_C = in.sump_temp_C.size() == t.size() ? start_mean(t, in.sump_temp_C) : cp.start_temp_C;
  // A thermocouple reading dT too much would carry its offset into the start temperature and
  // hide it: under that hypothesis the discs start at the sump's reading (oil and discs at rest
  // together), or without a sump channel at the reading less dT.
  if (cp.thermal.thermocouple_offset)
    cp.start_temp_C =
        in.sump_temp_C.size() == t.size() ? cp.sump_start_temp_C : cp.start_temp_C - cp.thermal.thermocouple_offset_K;
  if (cp.thermal.thermocouple_offset && in.sump_temp_C.size() != t.size()) cp.sump_start_temp_C = cp.start_temp_C;
  if (in.oil_flow_ml_min) cp.thermal.supply_flow_m3_s = units::ml_min_to_m3_s(*in.oil_flow_ml_min);
  if (in.thermocouple_r_mm) cp.thermal.thermocouple_r_m = *in.thermocouple_r_mm * 1e-3;
  if (in.thermocouple_z_mm) cp.thermal.thermocouple_z_m = *in.thermocouple_z_mm * 1e-3;
  const clutch::WetClutch clutch(cp, model.fluid);

  components::DriveCycle cycle;
  // A coupling's slip and clamp force are continuous (its hydraulics are integrated with the
  // motion, rig_models/haldex_driveline.hpp) and recorded finely: imposed as measured. A rig's
  // inputs are averaged over windows of `input_window_s` against the sensors' noise.
  const bool coupling = model.inputs_as_measured;
  const double window_s = in.input_window_s;
  // On the rig the measured speed is the drive's; its loop's set point is what drives the model.
  const bool setpoint = model.kind == ModelKind::kRig && in.torque_Nm.size() == t.size();
  rig_models::RigParams rp = model.rig_params;
  rp.bearing_drag = model.settings.bearing_drag;
  cycle.slip_speed_rpm =
      coupling ? samples_as_measured(t, in.speed_rpm, t0)
               : window_means(t, setpoint ? estimate_speed_setpoint(t, in.speed_rpm, in.torque_Nm, rp) : in.speed_rpm,
                              t0, window_s);
  // A load cell reading g_F too much: the clutch was pressed with F_rec / g_F.
  std::vector<double> force_N = in.normal_force_N;
  for (auto& f : force_N) f = model.settings.load_cell.true_N(f);
  cycle.normal_force_N = coupling ? samples_as_measured(t, force_N, t0) : window_means(t, force_N, t0, window_s);

  dynamics::Recording rec;
  const double duration = t.back() - t0;
  if (model.kind == ModelKind::kRig) {
    rig_models::RigSettings rs;
    rs.duration_s = duration;
    rs.thermal_step_s = model.settings.thermal_step_s;
    rs.sample_rate_Hz = model.settings.sample_rate_Hz;
    rec = rig_models::run_rig(rp, clutch, cycle, rs);
  } else {
    rig_models::PrescribedSlipSettings ps = model.settings;
    ps.duration_s = duration;
    // Prescribed slip records its step ends and interpolates between them: a tenth of the
    // coupling's thermal step puts them within a millisecond of every measured sample.
    if (coupling) ps.thermal_step_s = model.settings.thermal_step_s / kCouplingStepsPerStep;
    ps.snapshot_times_s.clear();
    rec = rig_models::run_prescribed_slip(clutch, cycle, ps);
  }
  std::vector<double> tq(t.size());
  for (std::size_t i = 0; i < t.size(); ++i) tq[i] = t[i] - t0;
  namespace sn = dynamics::signal_names;
  const auto& time = signal(rec, sn::kTime);
  ReplayOutput out;
  out.torque_Nm = interpolate(time, signal(rec, sn::kTorque), tq);
  out.temp_C = interpolate(time, signal(rec, sn::kTemp), tq);
  out.sump_temp_C = interpolate(time, signal(rec, sn::kSumpTemp), tq);
  out.ir_temp_C = interpolate(time, signal(rec, sn::kIrTemp), tq);
  out.speed_rpm = interpolate(time, signal(rec, sn::kSpeed), tq);
  out.interface_mean_temp_C = interpolate(time, signal(rec, sn::kInterfaceMeanTemp), tq);
  return out;
}

// ---- effects (from the registry) -------------------------------------------------------

namespace {

const rig_models::EffectDefinition& known_effect(std::string_view name) {
  if (const auto* e = rig_models::find_effect(name)) return *e;
  throw std::invalid_argument("unknown effect '" + std::string(name) +
                              "'; valid effects are: " + rig_models::effect_names_list());
}

// Why the effect cannot be a candidate: inert in the model's kind, or, for a driveline's
// coupling, inert in the prescribed slip it is replayed with (nothing sticks).
std::optional<std::string_view> candidate_inert_reason(const rig_models::EffectDefinition& effect,
                                                       const ReplayModel& m) {
  if (const auto why = rig_models::inert_reason(effect, m.kind)) return why;
  return m.kind == ModelKind::kDriveline ? rig_models::inert_reason(effect, ModelKind::kPrescribedSlip) : std::nullopt;
}

}  // namespace

rig_models::EffectTarget effect_target(ReplayModel& m) {
  return {m.clutch,
          m.settings.bearing_drag,
          m.rig_params.stick_time,
          m.settings.torque_cell,
          m.settings.load_cell,
          m.settings.friction_drift};
}

rig_models::ConstEffectTarget effect_target(const ReplayModel& m) {
  return {m.clutch,
          m.settings.bearing_drag,
          m.rig_params.stick_time,
          m.settings.torque_cell,
          m.settings.load_cell,
          m.settings.friction_drift};
}

bool effect_enabled(const ReplayModel& m, std::string_view name) {
  return known_effect(name).enabled(effect_target(m));
}

void enable_effect(ReplayModel& m, std::string_view name, const std::vector<double>& v) {
  const auto& effect = known_effect(name);
  const auto fitted = rig_models::fitted_parameters(effect);
  if (v.size() != fitted.size())
    throw std::invalid_argument("effect " + effect.name + " takes " + std::to_string(fitted.size()) +
                                " parameters, got " + std::to_string(v.size()));
  auto target = effect_target(m);
  effect.enabled(target) = true;
  for (std::size_t i = 0; i < fitted.size(); ++i) fitted[i]->member(target) = v[i] * fitted[i]->scale.to_si;
}

analysis::Simulator replay_simulator(ReplayModel model, std::vector<ReplayInputs> inputs) {
  return [model = std::move(model), inputs = std::move(inputs)](const std::vector<analysis::EffectSetting>& added,
                                                                std::size_t run) {
    ReplayModel m = model;
    for (const auto& e : added) enable_effect(m, e.effect, e.values);
    ReplayOutput o = replay(m, inputs.at(run));
    return analysis::Prediction{std::move(o.torque_Nm), std::move(o.temp_C), std::move(o.sump_temp_C),
                                std::move(o.ir_temp_C), std::move(o.speed_rpm)};
  };
}

analysis::Reproducer replay_reproducer(ReplayModel model, std::vector<ReplayInputs> inputs) {
  return [model = std::move(model), inputs = std::move(inputs)](const analysis::DiagnosisRun& pseudo, std::size_t run) {
    ReplayInputs in = inputs.at(run);
    in.speed_rpm = pseudo.speed_rpm;
    in.temp_C = pseudo.temp_C;
    if (!in.torque_Nm.empty()) in.torque_Nm = pseudo.torque_Nm;
    if (!in.sump_temp_C.empty()) in.sump_temp_C = pseudo.sump_temp_C;
    in.normal_force_N = pseudo.normal_force_N;  // with its own noise (analysis/diagnosis.cpp pseudo_run)
    ReplayOutput o = replay(model, in);
    return analysis::Prediction{std::move(o.torque_Nm), std::move(o.temp_C), std::move(o.sump_temp_C),
                                std::move(o.ir_temp_C), std::move(o.speed_rpm)};
  };
}

std::vector<analysis::EffectCandidate> replay_candidates(const ReplayModel& model, std::vector<std::string>* skipped) {
  const auto target = effect_target(model);
  std::vector<analysis::EffectCandidate> out;
  for (const auto& effect : rig_models::effect_registry()) {
    if (effect.enabled(target)) continue;
    if (const auto why = candidate_inert_reason(effect, model)) {
      if (skipped) skipped->push_back(effect.name + ": " + std::string(*why));
      continue;
    }
    analysis::EffectCandidate c;
    c.name = effect.name;
    c.description = effect.description;
    const auto fitted = rig_models::fitted_parameters(effect);
    for (const auto* p : fitted) {
      c.parameter_names.push_back(p->key);
      c.lower.push_back(p->fit->lower);
      c.upper.push_back(p->fit->upper);
      c.linear.push_back(p->fit->linear);
    }
    // Start j of the effect is the j-th start of each fitted parameter.
    const std::size_t starts = fitted.empty() ? 0 : fitted.front()->fit->starts.size();
    for (std::size_t j = 0; j < starts; ++j) {
      std::vector<double> start;
      for (const auto* p : fitted) start.push_back(p->fit->starts.at(j));
      c.starts.push_back(std::move(start));
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace shudder::studies
