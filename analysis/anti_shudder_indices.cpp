#include "analysis/anti_shudder_indices.hpp"
#include "core/nan.hpp"

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <limits>
#include <numbers>
#include <stdexcept>
#include <string>

namespace shudder::analysis {

namespace {

// Relative slack when deciding whether a speed lies outside the law's data: the fluid files
// and the indices convert rpm at the same radius, but not necessarily by the same operations.
constexpr double kRangeSlack = 1e-9;

void check_settings(const IndexSettings& s) {
  if (!(std::isfinite(s.load_N) && s.load_N > 0))
    throw std::invalid_argument("anti-shudder indices: the normal load must be finite and > 0 N");
  if (!(std::isfinite(s.mean_radius_mm) && s.mean_radius_mm > 0))
    throw std::invalid_argument("anti-shudder indices: the mean radius must be finite and > 0 mm");
  if (s.jaso_degree < 1 || s.jaso_fit_points <= s.jaso_degree)
    throw std::invalid_argument(
        "anti-shudder indices: the JASO fit needs degree >= 1 and more samples than the degree");
  if (!(std::isfinite(s.jaso_top_speed_mm_s) && s.jaso_top_speed_mm_s > 0))
    throw std::invalid_argument("anti-shudder indices: the JASO top speed must be finite and > 0 mm/s");
}

bool outside_speed_data(const clutch::FrictionLaw& law, double v_mm_s) {
  return v_mm_s < law.min_speed_mm_s() * (1.0 - kRangeSlack) || v_mm_s > law.max_speed_mm_s() * (1.0 + kRangeSlack);
}

// mu at one speed and whether that speed is outside the data.
struct Probe {
  double mu = 0.0;
  bool clamped = false;
};

Probe probe(const clutch::FrictionLaw& law, double v_mm_s, double temp_C, double load_N) {
  return {law.mu(v_mm_s, temp_C, load_N), outside_speed_data(law, v_mm_s)};
}

IndexValue ratio(const Probe& num, const Probe& den) { return {num.mu / den.mu, num.clamped || den.clamped}; }

// Murakami: (mu(hi) − mu(lo)) / (V_hi − V_lo), V in m/s.
IndexValue secant_slope(const Probe& lo, double v_lo_mm_s, const Probe& hi, double v_hi_mm_s) {
  return {(hi.mu - lo.mu) / ((v_hi_mm_s - v_lo_mm_s) * 1e-3), lo.clamped || hi.clamped};
}

// Compact number for messages: "10", "2.5", "-40".
std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.4g", x);
  return buf;
}

std::string range_text(double lo, double hi, const char* unit) {
  if (lo == hi) return num(lo) + " " + unit;
  return num(lo) + "\u2013" + num(hi) + " " + unit;
}

}  // namespace

double rpm_to_mm_s(double rpm, double radius_mm) { return rpm * 2.0 * std::numbers::pi / 60.0 * radius_mm; }

const std::array<IndexInfo, kIndexCount>& index_info() {
  static const std::array<IndexInfo, kIndexCount> table = {{
      {"mu1_over_mu50", "mu1/mu50 (Ohtani)", "-", true, 1.0},
      {"mu100_over_mu300", "mu100/mu300 (Ohtani)", "-", true, 1.0},
      {"yoshizawa_mu1_over_mu20", "mu1/mu20 cm/s (Yoshizawa)", "-", true, 1.0},
      {"miyazaki_mu6_over_mu180", "mu6/mu180 mm/s (Miyazaki)", "-", true, 1.0},
      {"murakami_dmu_dV50", "dmu/dV(50) (Murakami)", "s/m", false, 0.0},
      {"murakami_dmu_dV150", "dmu/dV(150) (Murakami)", "s/m", false, 0.0},
      {"mercon_v_2_over_20", "T2/T20 rpm (Mercon V)", "-", true, 1.0},
      {"mercon_v_40_over_120", "T40/T120 rpm (Mercon V)", "-", true, 1.0},
      {"jaso_dmu_dv_0_3", "JASO dmu/dv 0.3 m/s", "1e-3 s/m", false, 0.0},
      {"jaso_dmu_dv_0_9", "JASO dmu/dv 0.9 m/s", "1e-3 s/m", false, 0.0},
  }};
  return table;
}

const IndexInfo& info(Index index) { return index_info()[static_cast<std::size_t>(index)]; }

bool on_risk_side(Index index, double value) {
  const IndexInfo& i = info(index);
  return i.risk_above ? value > i.limit : value < i.limit;  // NaN compares false
}

double PolynomialFit::value(double v_mm_s) const {
  const double x = (2.0 * v_mm_s - lo_mm_s - hi_mm_s) / (hi_mm_s - lo_mm_s);
  double p = 0.0;
  for (Eigen::Index k = coefficients.size() - 1; k >= 0; --k) p = p * x + coefficients[k];
  return p;
}

double PolynomialFit::derivative_per_mm_s(double v_mm_s) const {
  const double x = (2.0 * v_mm_s - lo_mm_s - hi_mm_s) / (hi_mm_s - lo_mm_s);
  // Horner on dp/dx = Σ k c_k x^(k−1), then dx/dv = 2 / (hi − lo).
  double dp = 0.0;
  for (Eigen::Index k = coefficients.size() - 1; k >= 1; --k) dp = dp * x + static_cast<double>(k) * coefficients[k];
  return dp * 2.0 / (hi_mm_s - lo_mm_s);
}

PolynomialFit least_squares_polynomial(const Eigen::VectorXd& speeds_mm_s, const Eigen::VectorXd& mu, int degree) {
  if (degree < 0) throw std::invalid_argument("polynomial fit: degree must be >= 0");
  if (speeds_mm_s.size() != mu.size())
    throw std::invalid_argument("polynomial fit: speeds and mu must have the same length");
  if (!speeds_mm_s.allFinite() || !mu.allFinite())
    throw std::invalid_argument("polynomial fit: samples must be finite");
  if (speeds_mm_s.size() <= degree) throw std::invalid_argument("polynomial fit: needs more samples than the degree");
  PolynomialFit fit;
  fit.lo_mm_s = speeds_mm_s.minCoeff();
  fit.hi_mm_s = speeds_mm_s.maxCoeff();
  if (!(fit.hi_mm_s > fit.lo_mm_s)) throw std::invalid_argument("polynomial fit: speeds must not all be equal");

  // Vandermonde matrix in the scaled speed x ∈ [−1, 1]  (n x (degree + 1)).
  const Eigen::Index n = speeds_mm_s.size(), m = degree + 1;
  const Eigen::ArrayXd x = (2.0 * speeds_mm_s.array() - fit.lo_mm_s - fit.hi_mm_s) / (fit.hi_mm_s - fit.lo_mm_s);
  Eigen::MatrixXd a(n, m);
  a.col(0).setOnes();
  for (Eigen::Index k = 1; k < m; ++k) a.col(k) = a.col(k - 1).array() * x.matrix().array();

  const auto qr = a.colPivHouseholderQr();
  if (qr.rank() < m) throw std::invalid_argument("polynomial fit: needs more distinct speeds than the degree");
  fit.coefficients = qr.solve(mu);
  fit.rms_residual = std::sqrt((a * fit.coefficients - mu).squaredNorm() / static_cast<double>(n));
  return fit;
}

PolynomialFit fit_law_polynomial(const clutch::FrictionLaw& law, double temp_C, double load_N, double lo_mm_s,
                                 double hi_mm_s, int degree, int n_points) {
  if (!(std::isfinite(lo_mm_s) && std::isfinite(hi_mm_s) && hi_mm_s > lo_mm_s))
    throw std::invalid_argument("polynomial fit: the speed range needs finite lo < hi");
  if (n_points < 2) throw std::invalid_argument("polynomial fit: needs at least 2 samples");
  Eigen::VectorXd v = Eigen::VectorXd::LinSpaced(n_points, lo_mm_s, hi_mm_s), mu(n_points);
  for (Eigen::Index i = 0; i < v.size(); ++i) mu[i] = law.mu(v[i], temp_C, load_N);
  return least_squares_polynomial(v, mu, degree);
}

AntiShudderIndices anti_shudder_indices(const clutch::FrictionLaw& law, double temp_C, const IndexSettings& s) {
  check_settings(s);
  if (!std::isfinite(temp_C))
    throw std::invalid_argument("anti-shudder indices: the temperature must be finite (degC)");
  const double F = s.load_N;
  const auto rpm = [&](double n) { return rpm_to_mm_s(n, s.mean_radius_mm); };
  const auto at = [&](double v_mm_s) { return probe(law, v_mm_s, temp_C, F); };

  AntiShudderIndices out;
  out.temp_C = temp_C;
  const auto [t_lo, t_hi] = law.temp_range_C();
  out.temp_outside_data = temp_C < t_lo || temp_C > t_hi;

  // Ratios at speeds in rpm (Ohtani, Mercon V), cm/s (Yoshizawa) and mm/s (Miyazaki).
  const Probe mu1 = at(rpm(1)), mu50 = at(rpm(50)), mu150 = at(rpm(150));
  out[Index::kMu1OverMu50] = ratio(mu1, mu50);
  out[Index::kMu100OverMu300] = ratio(at(rpm(100)), at(rpm(300)));
  out[Index::kYoshizawaMu1OverMu20] = ratio(at(10.0), at(200.0));
  out[Index::kMiyazakiMu6OverMu180] = ratio(at(6.0), at(180.0));
  out[Index::kMerconV2Over20] = ratio(at(rpm(2)), at(rpm(20)));
  out[Index::kMerconV40Over120] = ratio(at(rpm(40)), at(rpm(120)));

  // Murakami: secant slopes from 1 rpm, s/m.
  out[Index::kMurakamiDmuDV50] = secant_slope(mu1, rpm(1), mu50, rpm(50));
  out[Index::kMurakamiDmuDV150] = secant_slope(mu1, rpm(1), mu150, rpm(150));

  // JASO: quintic over the law's speed range, slope at 0.3 and 0.9 m/s inside it, × 1000.
  const double lo = law.min_speed_mm_s();
  const double hi = std::isfinite(law.max_speed_mm_s()) ? law.max_speed_mm_s() : s.jaso_top_speed_mm_s;
  const Index jaso[] = {Index::kJasoDmuDv03, Index::kJasoDmuDv09};
  const double jaso_speed_mm_s[] = {300.0, 900.0};
  for (const Index j : jaso) out[j] = {kNaN, true};
  if (hi > lo) {  // one speed only: no mu–v curve to fit
    const PolynomialFit fit = fit_law_polynomial(law, temp_C, F, lo, hi, s.jaso_degree, s.jaso_fit_points);
    for (int k = 0; k < 2; ++k) {
      const double v = jaso_speed_mm_s[k];
      // Not extrapolated: outside the fit range the value stays NaN (and flagged).
      if (v < lo * (1.0 - kRangeSlack) || v > hi * (1.0 + kRangeSlack)) continue;
      // per mm/s -> per m/s (× 1000), then JASO's × 1000.
      out[jaso[k]] = {fit.derivative_per_mm_s(std::clamp(v, lo, hi)) * 1e6, outside_speed_data(law, v)};
    }
  }
  return out;
}

std::vector<double> default_screening_temperatures(const clutch::FrictionLaw& law) {
  const auto [lo, hi] = law.temp_range_C();
  std::vector<double> temps;
  for (double T : {40.0, 80.0, 120.0})
    if (T >= lo && T <= hi) temps.push_back(T);
  return temps;
}

SlopeMap isothermal_slope_map(const clutch::FrictionLaw& law, const std::vector<double>& speeds_rpm,
                              const std::vector<double>& temps_C, const IndexSettings& s) {
  check_settings(s);
  for (double n : speeds_rpm)
    if (!(std::isfinite(n) && n > 0)) throw std::invalid_argument("slope map: speeds must be finite and > 0 rpm");
  for (double T : temps_C)
    if (!std::isfinite(T)) throw std::invalid_argument("slope map: temperatures must be finite (degC)");
  SlopeMap map;
  map.load_N = s.load_N;
  map.mean_radius_mm = s.mean_radius_mm;
  map.speeds_rpm = speeds_rpm;
  map.temps_C = temps_C;
  const auto ns = static_cast<Eigen::Index>(speeds_rpm.size()), nt = static_cast<Eigen::Index>(temps_C.size());
  map.dmu_dv_s_per_m.resize(ns, nt);
  for (Eigen::Index j = 0; j < nt; ++j)
    for (Eigen::Index i = 0; i < ns; ++i)
      map.dmu_dv_s_per_m(i, j) =
          1e3 * law.dmu_dv_per_mm_s(rpm_to_mm_s(speeds_rpm[static_cast<std::size_t>(i)], s.mean_radius_mm),
                                    temps_C[static_cast<std::size_t>(j)], s.load_N);
  return map;
}

std::vector<RegionRun> region_runs(const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C,
                                   const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& mask) {
  std::vector<RegionRun> runs;
  for (Eigen::Index j = 0; j < mask.cols(); ++j) {
    for (Eigen::Index i = 0; i < mask.rows();) {
      if (!mask(i, j)) {
        ++i;
        continue;
      }
      // Extend the run while the mask holds.
      Eigen::Index k = i;
      while (k + 1 < mask.rows() && mask(k + 1, j)) ++k;
      runs.push_back({temps_C[static_cast<std::size_t>(j)], speeds_rpm[static_cast<std::size_t>(i)],
                      speeds_rpm[static_cast<std::size_t>(k)]});
      i = k + 1;
    }
  }
  return runs;
}

RegionExtent region_extent(const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C,
                           const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& mask,
                           const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& valid) {
  RegionExtent e;
  for (Eigen::Index j = 0; j < mask.cols(); ++j) {
    for (Eigen::Index i = 0; i < mask.rows(); ++i) {
      if (!valid(i, j)) continue;
      ++e.grid_points;
      if (!mask(i, j)) continue;
      const double n = speeds_rpm[static_cast<std::size_t>(i)], T = temps_C[static_cast<std::size_t>(j)];
      if (e.points == 0) {
        e.min_rpm = e.max_rpm = n;
        e.min_temp_C = e.max_temp_C = T;
      }
      e.min_rpm = std::min(e.min_rpm, n);
      e.max_rpm = std::max(e.max_rpm, n);
      e.min_temp_C = std::min(e.min_temp_C, T);
      e.max_temp_C = std::max(e.max_temp_C, T);
      ++e.points;
    }
  }
  return e;
}

Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> negative_slope_mask(const SlopeMap& map) {
  return map.dmu_dv_s_per_m.array() < 0.0;
}

const char* risk_level_name(RiskLevel level) {
  switch (level) {
    case RiskLevel::kLow: return "LOW RISK";
    case RiskLevel::kNotJudged: return "NOT JUDGED";
    case RiskLevel::kCaution: return "CAUTION";
    case RiskLevel::kRisk: return "RISK";
  }
  return "RISK";
}

std::string describe_extent(const RegionExtent& e) {
  return range_text(e.min_rpm, e.max_rpm, "rpm") + ", " + range_text(e.min_temp_C, e.max_temp_C, "\u00b0C");
}

ScreeningVerdict screening_verdict(const std::vector<AntiShudderIndices>& indices, const SlopeMap& slope,
                                   const RegionExtent& negative_slope, const std::vector<RigEvidence>& rigs) {
  std::vector<std::string> risk, caution;

  // Rigs with no evaluated point (motor saturated everywhere) are no evidence either way.
  bool any_unstable = false, any_judged = false;
  for (const auto& r : rigs) {
    any_unstable = any_unstable || r.unstable.points > 0;
    any_judged = any_judged || r.unstable.grid_points > 0;
    if (r.unstable.grid_points == 0)
      caution.push_back(r.label + " not judged: no steady sliding anywhere (clutch torque above the motor's limit)");
  }

  // The isothermal slope: evidence of risk by itself only when no rig was judged.
  if (negative_slope.points > 0) {
    std::string why = "negative isothermal slope at " + describe_extent(negative_slope);
    if (!any_judged)
      risk.push_back(why);
    else if (any_unstable)
      risk.push_back(why);
    else
      caution.insert(caution.begin(), why + ", but every rig is predicted stable");
  }
  for (const auto& r : rigs)
    if (r.unstable.points > 0) risk.push_back(r.label + " predicted unstable at " + describe_extent(r.unstable));

  // Indices on their risk side, with the temperatures where they are.
  for (std::size_t k = 0; k < kIndexCount; ++k) {
    const auto idx = static_cast<Index>(k);
    std::string temps;
    bool clamped = false;
    for (const auto& at : indices) {
      if (!on_risk_side(idx, at[idx].value)) continue;
      temps += (temps.empty() ? "" : ", ") + num(at.temp_C);
      clamped = clamped || at[idx].clamped;
    }
    if (temps.empty()) continue;
    const IndexInfo& i = info(idx);
    std::string why = std::string(i.label) + (i.risk_above ? " > " : " < ") + num(i.limit) + " at " + temps +
                      " \u00b0C" + (clamped ? " (outside data)" : "");
    (idx == Index::kMu1OverMu50 ? risk : caution).push_back(why);
  }

  ScreeningVerdict v;
  v.level = !risk.empty()      ? RiskLevel::kRisk
            : !caution.empty() ? RiskLevel::kCaution
            : indices.empty()  ? RiskLevel::kNotJudged
                               : RiskLevel::kLow;
  v.text = risk_level_name(v.level);
  if (v.level == RiskLevel::kNotJudged) {
    v.text +=
        ": no anti-shudder index was computed (no screening temperature inside the law's data; give "
        "--temps inside it); the slope map and the rigs found no risk, which alone is no verdict";
    return v;
  }
  v.text += ": ";
  if (v.level == RiskLevel::kLow) {
    std::string grid = "no negative isothermal slope";
    if (!slope.speeds_rpm.empty() && !slope.temps_C.empty()) {
      const auto [s_lo, s_hi] = std::minmax_element(slope.speeds_rpm.begin(), slope.speeds_rpm.end());
      const auto [t_lo, t_hi] = std::minmax_element(slope.temps_C.begin(), slope.temps_C.end());
      grid += " over " + range_text(*s_lo, *s_hi, "rpm") + ", " + range_text(*t_lo, *t_hi, "\u00b0C");
    }
    v.text += grid + "; every index on its safe side (mu1/mu50 <= 1)";
    if (!rigs.empty()) v.text += "; every rig predicted stable";
    return v;
  }
  bool first = true;
  for (const auto* list : {&risk, &caution})
    for (const auto& why : *list) {
      v.text += (first ? "" : "; ") + why;
      first = false;
    }
  return v;
}

}  // namespace shudder::analysis
