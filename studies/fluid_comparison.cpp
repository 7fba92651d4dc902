#include "studies/fluid_comparison.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numeric>
#include <array>

namespace shudder::studies {

namespace {

constexpr double kMarginResolution_per_s = 0.5;
constexpr double kRatioResolution = 0.005;  // relative, on mu1/mu50
constexpr double kBreakawayResolution = 0.01;

std::string g(double x) {
  char buf[48];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

// The ranking keys, each rounded to its resolution so that fluids the data cannot separate get
// equal keys (rounding makes the order a strict weak order; a tolerance would not be transitive).
std::array<long, 4> rank_key(const FluidComparison& f) {
  const double margin = std::isfinite(f.worst_margin_per_s) ? f.worst_margin_per_s : 0.0;
  return {long(f.screen.verdict.level), std::lround(margin / kMarginResolution_per_s),
          std::lround(std::log(f.worst_mu1_over_mu50) / kRatioResolution),
          std::lround(f.breakaway_ratio / kBreakawayResolution)};
}

// What separates a from b (a ranked before or with b).
std::string separation(const FluidComparison& a, const FluidComparison& b) {
  const auto ka = rank_key(a), kb = rank_key(b);
  if (ka[0] != kb[0])
    return std::string("verdict ") + analysis::risk_level_name(a.screen.verdict.level) + " vs " +
           analysis::risk_level_name(b.screen.verdict.level);
  if (ka[1] != kb[1])
    return "largest clutch-mode margin " + g(a.worst_margin_per_s) + " vs " + g(b.worst_margin_per_s) +
           " 1/s (lower is better)";
  if (ka[2] != kb[2])
    return "largest mu1/mu50 " + g(a.worst_mu1_over_mu50) + " vs " + g(b.worst_mu1_over_mu50) + " (lower is better)";
  if (ka[3] != kb[3])
    return "breakaway ratio " + g(a.breakaway_ratio) + " vs " + g(b.breakaway_ratio) + " (lower is better)";
  return "tie: verdict, margins (" + g(kMarginResolution_per_s) + " 1/s), mu1/mu50 (" + g(100 * kRatioResolution) +
         " %) and breakaway ratio (" + g(kBreakawayResolution) + ") agree within their resolution";
}

// The largest margin of the clutch-side (oscillatory) mode over the map points inside the law's
// data. Outside them the law holds its edge value, its slope is zero and the mode's margin is the
// rig's own damping (−ζω of the bar: −6.28 1/s on the 100 Hz bar for every fluid), and the drive
// loop's slow real mode, which leads the map's overall margin where the clutch damps well, does
// not depend on the fluid either. NaN when no rig has a judged point there.
double largest_margin_inside_data(const ScreeningReport& screen, const clutch::FrictionLaw& law,
                                  double mean_radius_mm) {
  const double v_lo = law.min_speed_mm_s(), v_hi = law.max_speed_mm_s();
  const auto [t_lo, t_hi] = law.temp_range_C();
  double worst = std::numeric_limits<double>::quiet_NaN();
  for (const auto& rig : screen.rigs) {
    const StabilityMap& m = rig.map;
    for (std::size_t i = 0; i < m.speeds_rpm.size(); ++i) {
      const double v = analysis::rpm_to_mm_s(m.speeds_rpm[i], mean_radius_mm);
      if (v < v_lo || v > v_hi) continue;
      for (std::size_t j = 0; j < m.temps_C.size(); ++j) {
        if (m.temps_C[j] < t_lo || m.temps_C[j] > t_hi) continue;
        const double margin = m.oscillatory_margin_per_s(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j));
        if (std::isfinite(margin)) worst = std::isfinite(worst) ? std::max(worst, margin) : margin;
      }
    }
  }
  return worst;
}

}  // namespace

double temperature_at_viscosity(double nu40_cSt, double nu100_cSt, double cSt) {
  const clutch::WaltherViscosity nu(nu40_cSt, nu100_cSt);
  double lo = -40.0, hi = 250.0;
  if (nu.kinematic_cSt(lo) < cSt || nu.kinematic_cSt(hi) > cSt) return std::numeric_limits<double>::quiet_NaN();
  for (int k = 0; k < 60; ++k) (nu.kinematic_cSt(0.5 * (lo + hi)) > cSt ? lo : hi) = 0.5 * (lo + hi);
  return 0.5 * (lo + hi);
}

Comparison compare_fluids(const std::vector<std::pair<std::string, clutch::Fluid>>& fluids,
                          const ComparisonOptions& options) {
  Comparison out;
  ScreeningOptions so = options.screening;
  if (so.temps_C.empty()) so.temps_C = {30.0, 60.0, 90.0};
  out.temps_C = so.temps_C;
  out.load_N = so.indices.load_N;
  out.viscosity_cSt = options.viscosity_cSt;
  for (const auto& [file, fluid] : fluids) {
    FluidComparison f;
    f.file = file;
    f.name = fluid.name;
    f.screen = screen_fluid(fluid, so);
    f.equal_viscosity_temp_C = temperature_at_viscosity(fluid.nu40_cSt, fluid.nu100_cSt, options.viscosity_cSt);
    if (std::isfinite(f.equal_viscosity_temp_C))
      f.at_equal_viscosity = analysis::anti_shudder_indices(*fluid.friction, f.equal_viscosity_temp_C, so.indices);
    else
      for (auto& v : f.at_equal_viscosity.values) v.value = std::numeric_limits<double>::quiet_NaN();
    f.breakaway_ratio = fluid.breakaway_ratio;
    const double v50 = analysis::rpm_to_mm_s(50.0, so.indices.mean_radius_mm);
    for (const auto& at : f.screen.indices) {
      f.mu50.push_back(fluid.friction->mu(v50, at.temp_C, so.indices.load_N));
      f.worst_mu1_over_mu50 = std::max(f.worst_mu1_over_mu50, at[analysis::Index::kMu1OverMu50].value);
    }
    f.worst_margin_per_s = largest_margin_inside_data(f.screen, *fluid.friction, so.indices.mean_radius_mm);
    out.fluids.push_back(std::move(f));
  }
  // Rank by the rounded keys; a fluid with its predecessor's keys shares its place.
  std::vector<std::size_t> idx(out.fluids.size());
  std::iota(idx.begin(), idx.end(), 0);
  std::stable_sort(idx.begin(), idx.end(),
                   [&](auto a, auto b) { return rank_key(out.fluids[a]) < rank_key(out.fluids[b]); });
  for (std::size_t k = 0; k < idx.size(); ++k) {
    FluidComparison& f = out.fluids[idx[k]];
    if (k == 0) {
      f.rank = 1;
      continue;
    }
    const FluidComparison& prev = out.fluids[idx[k - 1]];
    f.rank = rank_key(prev) == rank_key(f) ? prev.rank : int(k) + 1;
    out.separations.push_back(prev.name + " / " + f.name + ": " + separation(prev, f));
  }
  return out;
}

}  // namespace shudder::studies
