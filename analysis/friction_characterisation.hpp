#pragma once
// From measured speed ramps to a friction law (the thesis' method, docs/physics.md §2, §7):
//
//   1. ramps   analysis/ramp_detection finds the up- and down-ramps of every run.
//   2. mu      mu = (M / (n F r_eff)) − mu_bearing, M the torque cell, F the normal force, n the
//              sliding interfaces, r_eff the effective friction radius (one definition of both
//              conversions: clutch/friction_radius.hpp):
//                model (default of the command): the clutch model's own radius, sum r_i A_i /
//                                               sum A_i over its rings (47.839 mm for Paper G's
//                                               annulus), at which a model reproduces the torque;
//                uniform wear (the thesis):     r_eff = the stated mean radius (46 mm),
//                uniform pressure (Paper G):    r_eff = 2/3 (ro³ − ri³)/(ro² − ri²) (47.8 mm
//                                               for 38.1–56.4 mm, docs/physics.md §9);
//              the sliding speed at the same radius, v = ω r_eff (1 rpm = 4.82 mm/s at 46 mm).
//              mu_bearing is the bearing drag as an equivalent friction coefficient at r_eff
//              (thesis: "bearing losses equivalent to mu = 0.005").
//   3. rows    one row per load x reference temperature. A ramp's reference temperature is its
//              start temperature; a down-ramp takes that of the up-ramp before it in the same
//              run (one Paper D cycle: both belong to the cycle's start temperature). Loads
//              within ±load_tolerance and temperatures within ±temp_tolerance_C join.
//   3b. hot row (CharacterisationSettings::hot_row; Mäki and table laws, a compensation other
//              than none): when the ramps heat the temperature channel beyond the top row by
//              more than temp_tolerance_C, one more row at the hottest reading, made of the top
//              row's ramps compensated up to it. Without it the law holds the top row's mu above
//              it, where the hottest runs heat the clutch (a replay misses there).
//   4. compensation to the row temperature T_row, sample by sample at temperature T:
//              none       mu as measured (the bias the thesis removes);
//              linear     mu − alpha (T − T_row) (Papers B/C), alpha given or fitted as the
//                         within-group slope of mu on T, groups = load x narrow speed bin;
//              quadratic  mu + q_k(T_row) − q_k(T) with q_k(T) = a + bT + cT² fitted at every
//                         node speed k (Paper D: 1, 5, 10, …, 100 rpm) over all ramps of the load
//                         (value and temperature read where each ramp crosses the node), linear
//                         in ln v between nodes;
//              piecewise  mu + f(v, T_row) − f(v, T), f the load's surface piecewise linear in T
//                         between knots at the rows, fitted to all its samples at once
//                         (analysis/temperature_surface.hpp: follows a matrix law's kinks).
//   5. fit     maki:   Paper G eq. 13 per row, weighted least squares on the row's speed-binned
//                      means by variable projection: C2 searched on a log grid and refined by
//                      golden section, C1, C3, C4 linear least squares for each C2 (exact
//                      optimum of the separable problem; no start values needed);
//              linear: mu_k(T) = alpha_k T + beta_k per node over the rows at one load
//                      (Paper E: 20 kN);
//              table:  the rows' compensated curves at the node speeds (each a quadratic in
//                      ln v over the row's bin means within ±30 % of the node, read at it).
//              A ramp's samples include up to 1 s of the hold at its low end (Paper D's N0).
//
// Errors: bad input (a run without a usable ramp, a row with too few ramps, a missing cell of
// the grid, a requested temperature no ramp reaches) throws CharacterisationInputError naming
// the file or row; a fit that fails numerically throws std::runtime_error.

#include <array>
#include <limits>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "analysis/ramp_detection.hpp"
#include "clutch/friction_law.hpp"
#include "clutch/friction_radius.hpp"

namespace shudder::analysis {

class CharacterisationInputError : public std::invalid_argument {
 public:
  CharacterisationInputError(std::string file, const std::string& message)
      : std::invalid_argument(message), file_(std::move(file)) {}
  const std::string& file() const { return file_; }

 private:
  std::string file_;
};

enum class RadiusRule { kUniformWear, kUniformPressure, kModel };
enum class Compensation { kNone, kLinear, kQuadratic, kPiecewise };
enum class LawKind { kMaki, kLinear, kTable };
const char* compensation_name(Compensation c);  // "none", "linear", "quadratic", "piecewise"
const char* law_name(LawKind k);                // "maki", "linear", "table"

/// The Mäki rate C2's search range, per mm/s (fit_maki_curve), and the fraction of its log range
/// within which a fitted C2 counts as on its bound (Characterisation::warnings): 2 %, the margin
/// the diagnosis allows its parameters (analysis/diagnosis.hpp bound_margin), a factor 1.26.
inline constexpr double kMakiC2Min = 1e-5, kMakiC2Max = 1.0, kMakiBoundMargin = 0.02;

struct FrictionConversion {
  RadiusRule rule = RadiusRule::kUniformWear;
  double mean_radius_mm = 46.0;   // thesis: uniform wear at the mean radius 46 mm
  double inner_radius_mm = 38.1;  // Paper G's annulus (uniform pressure)
  double outer_radius_mm = 56.4;
  double model_radius_mm = 0.0;  // kModel: the clutch model's radius (WetClutch::mean_radius_m)
  int interfaces = 1;            // sliding interfaces n (Paper G simulates one)
  double bearing_drag_mu = 0.0;  // subtracted; thesis rig: 0.005
  std::string source;            // where the radius comes from, for the outputs ("" : the rule's name)
  double effective_radius_mm() const;
  /// The convention recorded with the law: kModel is uniform pressure (on the model's rings).
  clutch::RadiusConvention convention() const;
};

struct CharacterisationSettings {
  FrictionConversion conversion;
  RampSettings ramps;
  Compensation compensation = Compensation::kQuadratic;
  std::optional<double> alpha_per_C;  // linear compensation: given instead of fitted
  LawKind law = LawKind::kMaki;
  double temp_tolerance_C = 3.0;    // reference temperatures within this join one row
  double load_tolerance = 0.05;     // loads within ±5 % join one row
  int min_ramps_per_row = 2;        // one up and one down, or two up
  std::vector<double> node_rpm;     // empty: Paper D's 1, 5, 10, …, 100 rpm
  std::vector<double> row_temps_C;  // empty: the clusters of the data
  double linear_load_N = 20000.0;   // the linear law's load (Paper E: 20 kN); nearest row
  int speed_bins = 48;              // log-spaced bins per row for the fit
  bool hot_row = false;             // a row at the hottest temperature reached (file comment, 3b)
};

struct QuadraticNode {
  double load_N = 0.0, rpm = 0.0;
  double a = 0.0, b = 0.0, c = 0.0;  // mu = a + b T + c T², T in °C
  int ramps = 0;
  double rms = 0.0;  // residual of the ramps' node values
};

struct PiecewiseSurfaceInfo {  // --compensation piecewise, per load
  double load_N = 0.0;
  std::vector<double> temp_knots_C;
  double rms = 0.0;  // surface against the samples
};

struct RowFit {
  std::size_t i_temp = 0, i_load = 0;
  double load_N = 0.0, temp_C = 0.0;
  int ramps_up = 0, ramps_down = 0;
  double min_speed_mm_s = 0.0, max_speed_mm_s = 0.0;                  // data range of the row
  double min_temp_C = 0.0, max_temp_C = 0.0;                          // temperature channel over its ramps
  std::vector<double> bin_speed_mm_s, bin_mu_raw, bin_mu, bin_count;  // binned means
  std::vector<double> up_raw, down_raw, up_comp, down_comp;           // means at the node speeds (NaN: none)
  double up_down_gap_raw = 0.0, up_down_gap_comp = 0.0;               // mean |up − down| over the nodes
  std::vector<double> node_mu;                                        // compensated curve at the nodes
  std::array<double, 4> maki{}, maki_se{};                            // C1..C4 and standard errors
  double rms_residual = 0.0, max_residual = 0.0;                      // law − bin means
};

struct LinearLine {
  double rpm = 0.0, alpha_per_C = 0.0, beta = 0.0, alpha_se = 0.0, beta_se = 0.0;
};

struct Characterisation {
  double effective_radius_mm = 0.0;
  std::vector<Ramp> used;
  std::vector<double> used_ref_temp_C;
  std::vector<RejectedRamp> rejected;
  std::vector<double> loads_N, temps_C;  // the grid's axes
  std::vector<double> node_rpm, node_speeds_mm_s;
  std::vector<RowFit> rows;  // every cell that has ramps, temp-major
  double alpha_per_C = 0.0;  // linear compensation
  bool alpha_fitted = false;
  std::vector<QuadraticNode> quadratic;
  std::vector<PiecewiseSurfaceInfo> piecewise;
  std::vector<LinearLine> lines;  // linear law
  double linear_load_N = 0.0;
  double min_speed_mm_s = 0.0, max_speed_mm_s = 0.0;  // the law's speed range
  double min_temp_C = 0.0, max_temp_C = 0.0;          // temperature channel, all used ramps
  std::shared_ptr<const clutch::FrictionLaw> law;
  std::vector<std::string> warnings;  // fitted parameters on a search bound (printed by the command)
  double hot_row_temp_C = std::numeric_limits<double>::quiet_NaN();  // the hot row's, if one was added
};

/// `runs` in the order given (their names appear in errors and in `used`/`rejected`).
Characterisation characterise(const std::vector<RampRun>& runs, const CharacterisationSettings& settings);

/// Paper G eq. 13 fitted to (v, mu) with weights w by variable projection (file comment).
/// Returns C1..C4; `se` (if given) gets their standard errors with the residual variance
/// `sigma2`. Throws std::runtime_error if no finite fit exists.
std::array<double, 4> fit_maki_curve(const std::vector<double>& v_mm_s, const std::vector<double>& mu,
                                     const std::vector<double>& weight, double sigma2 = 0.0,
                                     std::array<double, 4>* se = nullptr);

}  // namespace shudder::analysis
