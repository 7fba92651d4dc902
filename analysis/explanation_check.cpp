#include "analysis/explanation_check.hpp"

#include <cmath>
#include <cstdio>

namespace shudder::analysis {

namespace {

std::string number(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

bool among(const std::string& name, std::initializer_list<const char*> names) {
  for (const char* n : names)
    if (name == n) return true;
  return false;
}

// The parameter of `c` at a bound (index, bound), or -1: the test of CandidateFitter::parameter_at_bound.
int at_bound(const EffectCandidate& c, const std::vector<double>& values, double margin_fraction, double& bound) {
  for (std::size_t j = 0; j < values.size(); ++j) {
    const bool linear = !c.linear.empty() && c.linear[j];
    const auto space = [linear](double v) { return linear ? v : std::log(v); };
    const double margin = margin_fraction * (space(c.upper[j]) - space(c.lower[j]));
    const double to_lower = space(values[j]) - space(c.lower[j]), to_upper = space(c.upper[j]) - space(values[j]);
    if (to_lower < margin || to_upper < margin) {
      bound = to_lower < to_upper ? c.lower[j] : c.upper[j];
      return static_cast<int>(j);
    }
  }
  return -1;
}

}  // namespace

std::string likely_cause_at_bound(const std::string& effect) {
  if (among(effect, {"torque_sensor_gain", "torque_sensor_offset", "load_sensor_gain", "friction_drift", "bearing_drag",
                     "viscous_shear", "load_dependent_friction", "temperature_dependent_friction",
                     "stick_time_static_friction"}))
    return "the friction law does not match these runs: a law characterised at another friction radius "
           "(M = mu F r_eff n: the thesis' 46 mm against the model's 47.8 mm is 4 %) or from other runs, or torque "
           "or force logged in other units (kN, N cm)";
  if (among(effect, {"interface_oil_cooling", "sump_heating", "rig_heat_capacity", "temperature_sensor_lag",
                     "thermocouple_offset"}))
    return "the thermal model's form differs from the rig's (oil flow, geometry, sensor place), or a temperature "
           "logged in other units (K, °F)";
  return {};
}

std::vector<UnexplainedEffect> unexplained_effects(const Config& full, const CandidateFitter& fitter,
                                                   const std::vector<ChannelFit>& channels,
                                                   const DiagnosisOptions& opt) {
  std::vector<UnexplainedEffect> out;
  if (full.empty()) return out;
  bool any_at_bound = false;
  for (const auto& e : full) {
    const auto& c = fitter.candidate(e.effect);
    UnexplainedEffect u;
    u.effect = e.effect;
    for (std::size_t j = 0; j < e.values.size(); ++j) u.parameters.emplace_back(c.parameter_names[j], e.values[j]);
    double bound = 0.0;
    if (const int j = at_bound(c, e.values, opt.bound_margin, bound); j >= 0) {
      any_at_bound = true;
      u.parameter = c.parameter_names[static_cast<std::size_t>(j)];
      u.bound = bound;
      u.reason = "the data pull " + e.effect + "'s " + u.parameter + " to its bound " + number(bound) + " (fitted " +
                 number(e.values[static_cast<std::size_t>(j)]) + ")";
      u.likely_cause = likely_cause_at_bound(e.effect);
    }
    out.push_back(std::move(u));
  }
  if (any_at_bound) {
    for (auto& u : out)
      if (u.reason.empty()) u.reason = "fitted together with an effect the data pull to its bound";
    return out;
  }
  // The gap left with every added effect on.
  const bool tolerance = !opt.tolerance.empty();
  const double allowed = tolerance ? opt.found_gap_factor : opt.noise_tolerance;
  const ChannelFit* worst = nullptr;
  for (const auto& ch : channels)
    if (!worst || ch.final_misfit > worst->final_misfit) worst = &ch;
  if (!worst || std::sqrt(worst->final_misfit) <= allowed) return {};
  std::string names;
  for (const auto& e : full) names += (names.empty() ? "" : " + ") + e.effect;
  for (auto& u : out) {
    u.reason = "with " + names + " the " + worst->signal + " gap stays at " + number(std::sqrt(worst->final_misfit)) +
               "x its error scale (found needs <= " + number(allowed) + "x)";
    u.likely_cause = tolerance ? "the model's form differs from the data's by more than the tolerance given"
                               : "no --tolerance given: a model-form gap (another thermal model or friction law) "
                                 "cannot be told from a missing effect; read a tolerance off runs with nothing "
                                 "hidden (docs/diagnosis.md \"Choosing a tolerance\")";
  }
  return out;
}

}  // namespace shudder::analysis
