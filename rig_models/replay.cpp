#include "rig_models/replay.hpp"

#include <algorithm>
#include <cmath>
#include <regex>
#include <stdexcept>
#include <string>
#include <string_view>

#include "clutch/effects.hpp"
#include "core/units.hpp"
#include "dynamics/signal_names.hpp"
#include "rig_models/speed_setpoint.hpp"

namespace shudder::rig_models {

namespace {

// Mean of `x` over consecutive windows of `window_s`, at the windows' mean times.
PiecewiseLinear window_means(const std::vector<double>& t, const std::vector<double>& x, double t0,
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
    if (tq[i] <= t.front()) out[i] = y.front();
    else if (j + 1 >= t.size()) out[i] = y.back();
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
  if (in.oil_flow_ml_min) cp.thermal.supply_flow_m3_s = units::ml_min_to_m3_s(*in.oil_flow_ml_min);
  if (in.thermocouple_r_mm) cp.thermal.thermocouple_r_m = *in.thermocouple_r_mm * 1e-3;
  if (in.thermocouple_z_mm) cp.thermal.thermocouple_z_m = *in.thermocouple_z_mm * 1e-3;
  const clutch::WetClutch clutch(cp, model.fluid);

  DriveCycle cycle;
  // On the rig the measured speed is the drive's; its loop's set point is what drives the model.
  const bool setpoint = model.rig && in.torque_Nm.size() == t.size();
  RigParams rp = model.rig_params;
  rp.bearing_drag = model.settings.bearing_drag;
  cycle.slip_speed_rpm = window_means(
      t, setpoint ? estimate_speed_setpoint(t, in.speed_rpm, in.torque_Nm, rp) : in.speed_rpm, t0,
      in.input_window_s);
  cycle.normal_force_N = window_means(t, in.normal_force_N, t0, in.input_window_s);

  dynamics::Recording rec;
  const double duration = t.back() - t0;
  if (model.rig) {
    RigSettings rs;
    rs.duration_s = duration;
    rs.thermal_step_s = model.settings.thermal_step_s;
    rs.sample_rate_Hz = model.settings.sample_rate_Hz;
    rec = run_rig(rp, clutch, cycle, rs);
  } else {
    PrescribedSlipSettings ps = model.settings;
    ps.duration_s = duration;
    ps.snapshot_times_s.clear();
    rec = run_prescribed_slip(clutch, cycle, ps);
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
  return out;
}

// ---- effect catalogue -------------------------------------------------------------------

namespace {

// Bounds are wide physical limits, not priors; starts span the plausible range so the
// least-squares fit begins in the right basin (a heat capacity of 30 kJ/K would let a missing
// oil flow pass for stored heat, hence the upper bound of 5 kJ/K: the whole rig side of the
// clutch, ~10 kg of steel).
const std::vector<EffectSpec>& catalogue() {
  static const std::vector<EffectSpec> k = {
      {"temperature_dependent_friction", "friction follows the interface temperature", {}, {}},
      {"interface_oil_cooling", "oil through the interface carries heat away (Paper G eq. 12)",
       {{"e", 1e-5, 1.0}}, {{0.016}, {0.004}, {0.064}}},
      {"sump_heating", "the sump warms with the heat carried out (Paper G eq. 7)", {}, {}},
      {"rig_heat_capacity", "rig parts beyond the discs store heat and give it back",
       {{"heat_capacity_J_per_K", 1.0, 5000.0}, {"conductance_W_per_K", 0.01, 1000.0}},
       {{150.0, 10.0}, {600.0, 30.0}, {50.0, 3.0}}},
      {"temperature_sensor_lag", "the temperature sensor lags the disc",
       {{"time_constant_s", 1e-3, 100.0}}, {{0.3}, {1.0}, {3.0}}},
      {"bearing_drag", "the torque cell also carries bearing friction",
       {{"equivalent_mu", 1e-6, 0.1}}, {{0.001}, {0.005}, {0.02}}},
      {"stick_time_static_friction", "breakaway friction grows with the time stuck",
       {{"max_increase", 1e-3, 5.0}, {"time_constant_s", 1e-3, 100.0}},
       {{0.15, 0.05}, {0.15, 0.5}, {0.4, 0.1}}},
      {"viscous_shear", "a viscous torque of the oil film, proportional to viscosity and speed",
       {{"gap_um", 0.01, 1e4}}, {{0.3}, {1.0}, {3.0}}},
      {"load_dependent_friction", "friction depends on the normal force", {}, {}},
  };
  return k;
}

}  // namespace

const EffectSpec& effect_spec(std::string_view name) {
  for (const auto& e : catalogue())
    if (e.name == name) return e;
  std::string list;
  for (const auto& e : catalogue()) list += (list.empty() ? "" : ", ") + e.name;
  throw std::invalid_argument("unknown effect '" + std::string(name) + "'; valid effects are: " + list);
}

bool effect_enabled(const ReplayModel& m, std::string_view name) {
  const auto& th = m.clutch.thermal;
  if (name == "temperature_dependent_friction") return m.clutch.temperature_dependent_friction;
  if (name == "interface_oil_cooling") return th.interface_oil_cooling;
  if (name == "sump_heating") return th.sump_heating;
  if (name == "rig_heat_capacity") return th.rig_heat_capacity;
  if (name == "temperature_sensor_lag") return th.temperature_sensor_lag;
  if (name == "bearing_drag") return m.settings.bearing_drag.enabled;
  if (name == "stick_time_static_friction") return m.rig_params.stick_time.enabled;
  if (name == "viscous_shear") return m.clutch.viscous_shear;
  if (name == "load_dependent_friction") return m.clutch.load_dependent_friction;
  effect_spec(name);  // throws with the valid names
  return false;
}

void enable_effect(ReplayModel& m, std::string_view name, const std::vector<double>& v) {
  const auto& spec = effect_spec(name);
  if (v.size() != spec.parameters.size())
    throw std::invalid_argument("effect " + spec.name + " takes " + std::to_string(spec.parameters.size()) +
                                " parameters, got " + std::to_string(v.size()));
  auto& th = m.clutch.thermal;
  if (name == "temperature_dependent_friction") m.clutch.temperature_dependent_friction = true;
  else if (name == "interface_oil_cooling") {
    th.interface_oil_cooling = true;
    th.oil_flow.e = v[0];
  } else if (name == "sump_heating") th.sump_heating = true;
  else if (name == "rig_heat_capacity") {
    th.rig_heat_capacity = true;
    th.rig_heat_capacity_J_per_K = v[0];
    th.rig_conductance_W_per_K = v[1];
  } else if (name == "temperature_sensor_lag") {
    th.temperature_sensor_lag = true;
    th.sensor_time_constant_s = v[0];
  } else if (name == "bearing_drag") {
    m.settings.bearing_drag.enabled = true;
    m.settings.bearing_drag.equivalent_mu = v[0];
  } else if (name == "stick_time_static_friction") {
    m.rig_params.stick_time.enabled = true;
    m.rig_params.stick_time.max_increase = v[0];
    m.rig_params.stick_time.time_constant_s = v[1];
  } else if (name == "viscous_shear") {
    m.clutch.viscous_shear = true;
    m.clutch.viscous_gap_m = v[0] * 1e-6;
  } else if (name == "load_dependent_friction") m.clutch.load_dependent_friction = true;
}

analysis::Simulator replay_simulator(ReplayModel model, std::vector<ReplayInputs> inputs) {
  return [model = std::move(model), inputs = std::move(inputs)](
             const std::vector<analysis::EffectSetting>& added, std::size_t run) {
    ReplayModel m = model;
    for (const auto& e : added) enable_effect(m, e.effect, e.values);
    ReplayOutput o = replay(m, inputs.at(run));
    return analysis::Prediction{std::move(o.torque_Nm), std::move(o.temp_C), std::move(o.sump_temp_C),
                                std::move(o.ir_temp_C)};
  };
}

std::vector<analysis::EffectCandidate> replay_candidates(const ReplayModel& model,
                                                         std::vector<std::string>* skipped) {
  std::vector<analysis::EffectCandidate> out;
  for (auto name : clutch::kEffectNames) {
    if (effect_enabled(model, name)) continue;
    if (name == "stick_time_static_friction" && !model.rig) {
      if (skipped) skipped->push_back("stick_time_static_friction: the slip is imposed, nothing sticks");
      continue;
    }
    const auto& spec = effect_spec(name);
    analysis::EffectCandidate c;
    c.name = spec.name;
    c.description = spec.description;
    c.starts = spec.starts;
    for (const auto& p : spec.parameters) {
      c.parameter_names.push_back(p.name);
      c.lower.push_back(p.lower);
      c.upper.push_back(p.upper);
    }
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace shudder::rig_models
