#pragma once
// Anti-shudder indices of a fluid's friction law (docs/physics.md §6; thesis Paper A, "anti-shudder
// performance"), the isothermal slope map dmu/dv(v, T) and the plain-language screening verdict.
//
// Every index is evaluated from a clutch::FrictionLaw at one temperature T (°C) and one normal
// load F (N), exactly as the simulator evaluates the law. Speeds given in rpm are converted to
// the LOCAL sliding speed at the mean radius r (default 46 mm, the test rig's: 1 rpm = 4.817 mm/s,
// as the fluid files convert them; docs/physics.md §4):   v[mm/s] = rpm · 2π/60 · r[mm].
//
//   index                        definition (v in mm/s unless stated)                 risk side
//   mu1/mu50        (Ohtani)     mu(1 rpm) / mu(50 rpm)                                 > 1
//   mu100/mu300     (Ohtani)     mu(100 rpm) / mu(300 rpm); the thesis' Paper A review:
//                                "mu1 is the coefficient of friction at 1 rpm and so on",
//                                so rpm (482 and 1445 mm/s at 46 mm)                    > 1
//   mu1/mu20        (Yoshizawa)  mu(1 cm/s) / mu(20 cm/s) = mu(10) / mu(200)            > 1
//   mu6/mu180       (Miyazaki)   mu(6 mm/s) / mu(180 mm/s)                              > 1
//   dmu/dV(50)      (Murakami)   (mu(50 rpm) − mu(1 rpm)) / (V50 − V1), V in m/s: s/m    < 0
//   dmu/dV(150)     (Murakami)   (mu(150 rpm) − mu(1 rpm)) / (V150 − V1), s/m            < 0
//   2/20 rpm        (Mercon V)   torque ratio T(2 rpm)/T(20 rpm) = mu(2 rpm)/mu(20 rpm)
//                                at equal force and radius; a positive slope needs < 1  > 1
//   40/120 rpm      (Mercon V)   mu(40 rpm) / mu(120 rpm)                               > 1
//   JASO 0.3, 0.9   (M349:2001)  1000 · dp/dv at v = 0.3 and 0.9 m/s, p the least-squares
//                                fifth-degree polynomial of mu(v) (v in m/s) over the law's
//                                speed range; unit 1000 · s/m                           < 0
//
// Data range. A speed outside the law's data range [min_speed_mm_s, max_speed_mm_s] is where
// the law holds mu at its edge value (the Mäki matrix clamps v to 6–590 mm/s; linear lines hold
// beyond their first and last speed). An index that needs such a speed is still evaluated from
// the law as it stands (held mu) and is FLAGGED `clamped`. For JASO the polynomial is fitted over
// the law's speed range only (up to 1500 mm/s, JASO's top speed, if the law has no upper limit)
// and is NOT extrapolated: at an evaluation speed outside the fit range the value is NaN (no
// data there; a quintic's slope beyond or even at the end of its range says nothing about the
// fluid) and flagged. A temperature outside the law's temperature range is flagged separately.
//
// The indices are screening numbers: a positive slope is neither necessary nor sufficient for
// stability on a real driveline (docs/physics.md §6, Cameron); the rig's eigenvalues decide
// (studies/fluid_screening.hpp).

#include <Eigen/Dense>
#include <array>
#include <cstddef>
#include <string>
#include <vector>

#include "clutch/friction_law.hpp"

namespace shudder::analysis {

/// The rig's mean friction radius (docs/physics.md §4): 1 rpm = 4.817 mm/s.
inline constexpr double kRigMeanRadius_mm = 46.0;

/// Local sliding speed in mm/s of `rpm` at radius `radius_mm`.
double rpm_to_mm_s(double rpm, double radius_mm = kRigMeanRadius_mm);

enum class Index : std::size_t {
  kMu1OverMu50,
  kMu100OverMu300,
  kYoshizawaMu1OverMu20,
  kMiyazakiMu6OverMu180,
  kMurakamiDmuDV50,
  kMurakamiDmuDV150,
  kMerconV2Over20,
  kMerconV40Over120,
  kJasoDmuDv03,
  kJasoDmuDv09,
};
inline constexpr std::size_t kIndexCount = 10;

/// Static description of an index: how to name, print and judge it.
struct IndexInfo {
  const char* key;    // JSON key, e.g. "mu1_over_mu50"
  const char* label;  // short printed label, e.g. "mu1/mu50 (Ohtani)"
  const char* unit;   // "-" for ratios, "s/m", "1000 s/m"
  bool risk_above;    // true: value > limit is on the risk side; false: value < limit
  double limit;       // 1 for ratios, 0 for slopes
};

/// The table of the ten indices, in Index order.
const std::array<IndexInfo, kIndexCount>& index_info();
const IndexInfo& info(Index index);

/// True if `value` lies on the index's risk side (NaN: false).
bool on_risk_side(Index index, double value);

struct IndexValue {
  double value = 0.0;    // NaN if it cannot be formed (JASO beyond the law's speeds)
  bool clamped = false;  // a speed it needs lies outside the law's data range
};

struct IndexSettings {
  double mean_radius_mm = kRigMeanRadius_mm;  // converts rpm to mm/s
  double load_N = 20000.0;                    // normal load (Paper E: 20 kN)
  int jaso_degree = 5;                        // JASO M349:2001: fifth degree
  int jaso_fit_points = 301;                  // samples, uniform in v over the fit range
  double jaso_top_speed_mm_s = 1500.0;        // fit range end if the law has no upper limit
};

struct AntiShudderIndices {
  double temp_C = 0.0;
  bool temp_outside_data = false;  // T outside the law's temperature range
  std::array<IndexValue, kIndexCount> values;

  const IndexValue& operator[](Index i) const { return values[static_cast<std::size_t>(i)]; }
  IndexValue& operator[](Index i) { return values[static_cast<std::size_t>(i)]; }
};

/// All indices at one temperature. Throws std::invalid_argument for a non-finite temperature,
/// a load or radius that is not finite and > 0, or a JASO degree/point count that cannot fit.
AntiShudderIndices anti_shudder_indices(const clutch::FrictionLaw& law, double temp_C,
                                        const IndexSettings& settings = {});

/// 40, 80 and 120 °C (JASO M349:2001's temperatures), those inside the law's temperature range.
std::vector<double> default_screening_temperatures(const clutch::FrictionLaw& law);

/// A least-squares polynomial mu(v) over [lo, hi] mm/s, stored in the scaled variable
/// x = (2v − lo − hi) / (hi − lo) ∈ [−1, 1] for conditioning.
struct PolynomialFit {
  double lo_mm_s = 0.0, hi_mm_s = 0.0;
  Eigen::VectorXd coefficients;  // (degree + 1) in x, constant term first
  double rms_residual = 0.0;     // of the samples it was fitted to

  double value(double v_mm_s) const;
  /// dp/dv in 1/(mm/s).
  double derivative_per_mm_s(double v_mm_s) const;
};

/// Least-squares polynomial of `degree` through samples (v_i, mu_i), v in mm/s (Eigen's
/// column-pivoting QR). Needs more distinct samples than the degree; throws
/// std::invalid_argument otherwise or for non-finite samples. Also the entry point for fitting
/// measured mu–v points.
PolynomialFit least_squares_polynomial(const Eigen::VectorXd& speeds_mm_s, const Eigen::VectorXd& mu, int degree);

/// The JASO fit of a law at (T, F): `n_points` samples uniform in v over [lo, hi] mm/s.
PolynomialFit fit_law_polynomial(const clutch::FrictionLaw& law, double temp_C, double load_N, double lo_mm_s,
                                 double hi_mm_s, int degree, int n_points);

/// Isothermal slope dmu/dv over speed x temperature at one load.
struct SlopeMap {
  double load_N = 0.0;
  double mean_radius_mm = kRigMeanRadius_mm;
  std::vector<double> speeds_rpm;  // (n_s)
  std::vector<double> temps_C;     // (n_T)
  Eigen::MatrixXd dmu_dv_s_per_m;  // (n_s x n_T) ∂mu/∂v at constant T and F, 1/(m/s)
};

/// Throws std::invalid_argument for non-finite or non-positive speeds, non-finite temperatures,
/// or a bad load/radius.
SlopeMap isothermal_slope_map(const clutch::FrictionLaw& law, const std::vector<double>& speeds_rpm,
                              const std::vector<double>& temps_C, const IndexSettings& settings = {});

/// A run of consecutive grid speeds at one temperature where a condition holds.
struct RegionRun {
  double temp_C = 0.0;
  double from_rpm = 0.0, to_rpm = 0.0;  // first and last grid speed of the run
};

/// Bounding box and size of a region on a speed x temperature grid.
struct RegionExtent {
  int points = 0;       // grid points in the region
  int grid_points = 0;  // grid points evaluated (NaN cells excluded)
  double min_rpm = 0.0, max_rpm = 0.0, min_temp_C = 0.0, max_temp_C = 0.0;  // if points > 0
};

/// Runs of `mask` (n_s x n_T, true = in the region) per temperature, temperatures in order.
std::vector<RegionRun> region_runs(const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C,
                                   const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& mask);
/// Extent of `mask`; `valid` (same shape) marks the cells that were evaluated.
RegionExtent region_extent(const std::vector<double>& speeds_rpm, const std::vector<double>& temps_C,
                           const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& mask,
                           const Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic>& valid);

/// The risky region of a slope map: points with dmu/dv < 0.
Eigen::Array<bool, Eigen::Dynamic, Eigen::Dynamic> negative_slope_mask(const SlopeMap& map);

/// What a stability map on one rig says, for the verdict.
struct RigEvidence {
  std::string label;      // e.g. "rig (378 Hz bar)"
  RegionExtent unstable;  // points with margin > 0; grid_points = points evaluated
};

/// kNotJudged: no index could be computed, so there is no verdict (last: a fluid that could not
/// be judged ranks after every judged one).
enum class RiskLevel { kLow, kCaution, kRisk, kNotJudged };
const char* risk_level_name(RiskLevel level);  // "LOW RISK", "CAUTION", "RISK", "NOT JUDGED"

struct ScreeningVerdict {
  RiskLevel level = RiskLevel::kLow;
  std::string text;  // one line: "LEVEL: reason; reason; ..."
};

/// The screening verdict (docs/screening.md):
///   RISK      a rig is predicted unstable somewhere on its map, or mu1/mu50 > 1 at an evaluated
///             temperature (Ohtani: vibration seen in vehicles), or the slope is negative
///             somewhere and no rig was judged (a rig whose map has no evaluated point, the motor
///             being saturated everywhere, is not judged and is named as such);
///   CAUTION   otherwise, if the isothermal slope is negative somewhere or another index lies on
///             its risk side (the rigs damp it);
///   NOT JUDGED otherwise, if no index was computed (no screening temperature inside the law's
///             data): "safe" needs indices, and the maps alone do not say it;
///   LOW RISK  otherwise: no negative slope on the map and every index on the safe side.
/// Indices computed from held (clamped) speeds count, and are named "(outside data)".
ScreeningVerdict screening_verdict(const std::vector<AntiShudderIndices>& indices, const SlopeMap& slope,
                                   const RegionExtent& negative_slope, const std::vector<RigEvidence>& rigs);

/// "10–100 rpm, 40–120 °C" (or "30 rpm, 80 °C" for a single point).
std::string describe_extent(const RegionExtent& extent);

}  // namespace shudder::analysis
