#include "studies/fluid_screening.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

namespace shudder::studies {

namespace {

constexpr double kMapTempStep_C = 5.0;

std::string default_label(double frequency_Hz) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "rig (%.0f Hz bar)", frequency_Hz);
  return buf;
}

RigScreen screen_rig(const ScreeningRig& spec, const clutch::Fluid& fluid, double load_N,
                     const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C) {
  const clutch::WetClutch clutch(spec.clutch, fluid);
  RigScreen out;
  // The bar's actual clutch-side frequency (the stiffness may be given directly).
  const components::DriveCycle cycle{components::PiecewiseLinear({0.0}, {speeds_rpm.front()}),
                                     components::PiecewiseLinear({0.0}, {load_N})};
  out.clutch_side_frequency_Hz = rig_models::LsctrRig(spec.params, clutch, cycle).clutch_side_frequency_Hz();
  out.label = spec.label.empty() ? default_label(out.clutch_side_frequency_Hz) : spec.label;
  out.map = stability_map(spec.params, clutch, load_N, speeds_rpm, temps_C);

  const auto& m = out.map.margin_per_s;
  const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> valid = m.array().isFinite();
  const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> unstable = valid && (m.array() > 0.0);
  out.unstable = analysis::region_runs(speeds_rpm, temps_C, unstable);
  out.unstable_extent = analysis::region_extent(speeds_rpm, temps_C, unstable, valid);
  out.saturated_points = static_cast<int>((!valid).count());

  // Largest finite margin.
  bool found = false;
  for (Eigen::Index j = 0; j < m.cols(); ++j)
    for (Eigen::Index i = 0; i < m.rows(); ++i) {
      if (!valid(i, j) || (found && m(i, j) <= out.max_margin_per_s)) continue;
      found = true;
      out.max_margin_per_s = m(i, j);
      out.max_margin_rpm = speeds_rpm[static_cast<std::size_t>(i)];
      out.max_margin_temp_C = temps_C[static_cast<std::size_t>(j)];
      out.max_margin_frequency_Hz = out.map.frequency_Hz(i, j);
    }
  if (!found)
    out.max_margin_per_s = out.max_margin_rpm = out.max_margin_temp_C = out.max_margin_frequency_Hz =
        std::numeric_limits<double>::quiet_NaN();
  return out;
}

}  // namespace

std::vector<ScreeningRig> default_screening_rigs() {
  std::vector<ScreeningRig> rigs;
  for (double f : {100.0, 300.0, 500.0}) {
    ScreeningRig r;
    r.params.bar_natural_frequency_Hz = f;
    rigs.push_back(r);
  }
  return rigs;
}

std::vector<double> default_map_temperatures(const clutch::FrictionLaw& law, const std::vector<double>& temps_C) {
  auto [lo, hi] = law.temp_range_C();
  if (!std::isfinite(lo)) lo = 40.0;
  if (!std::isfinite(hi)) hi = 120.0;
  for (double T : temps_C) {
    lo = std::min(lo, T);
    hi = std::max(hi, T);
  }
  if (hi == lo) return {lo};
  const int steps = std::max(1, static_cast<int>(std::ceil((hi - lo) / kMapTempStep_C - 1e-9)));
  std::vector<double> out;
  for (int k = 0; k <= steps; ++k) out.push_back(lo + (hi - lo) * k / steps);
  return out;
}

ScreeningReport screen_fluid(const clutch::Fluid& fluid, const ScreeningOptions& opt) {
  if (!fluid.friction) throw std::invalid_argument("screening: the fluid has no friction law");
  const clutch::FrictionLaw& law = *fluid.friction;
  for (double T : opt.temps_C)
    if (!std::isfinite(T)) throw std::invalid_argument("screening: temperatures must be finite (degC)");

  // rpm are read at the radius the law was fitted at when the fluid records one (a
  // characterised fluid: 1 rpm then means what it meant on the rig), else at the rig's
  // (clutch/friction_radius.hpp); the rigs' clutches convert the law to their own radius.
  analysis::IndexSettings indices = opt.indices;
  if (fluid.friction_radius_mm > 0.0) indices.mean_radius_mm = fluid.friction_radius_mm;
  ScreeningReport rep;
  rep.fluid_name = fluid.name;
  rep.load_N = indices.load_N;
  rep.mean_radius_mm = indices.mean_radius_mm;
  rep.law_temp_range_C = law.temp_range_C();
  rep.law_speed_range_mm_s = {law.min_speed_mm_s(), law.max_speed_mm_s()};

  // 1. Indices per screening temperature.
  const std::vector<double> temps = opt.temps_C.empty() ? analysis::default_screening_temperatures(law) : opt.temps_C;
  for (double T : temps) rep.indices.push_back(analysis::anti_shudder_indices(law, T, indices));

  // 2. Slope map and its negative region on the speed x temperature grid.
  std::vector<double> speeds = opt.map_speeds_rpm;
  if (speeds.empty())
    for (int n = 1; n <= 120; ++n) speeds.push_back(n);
  const std::vector<double> map_temps =
      opt.map_temps_C.empty() ? default_map_temperatures(law, temps) : opt.map_temps_C;
  rep.slope = analysis::isothermal_slope_map(law, speeds, map_temps, indices);
  const auto negative = analysis::negative_slope_mask(rep.slope);
  const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> all =
      Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>::Constant(negative.rows(), negative.cols(), true);
  rep.negative_slope = analysis::region_runs(speeds, map_temps, negative);
  rep.negative_slope_extent = analysis::region_extent(speeds, map_temps, negative, all);

  // 3. Stability maps on the rigs.
  const std::vector<ScreeningRig> rigs = opt.rigs.empty() ? default_screening_rigs() : opt.rigs;
  std::vector<analysis::RigEvidence> evidence;
  for (const auto& spec : rigs) {
    rep.rigs.push_back(screen_rig(spec, fluid, indices.load_N, speeds, map_temps));
    evidence.push_back({rep.rigs.back().label, rep.rigs.back().unstable_extent});
  }

  // 4. Verdict.
  rep.verdict = analysis::screening_verdict(rep.indices, rep.slope, rep.negative_slope_extent, evidence);
  return rep;
}

}  // namespace shudder::studies
