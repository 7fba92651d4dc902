#pragma once
// Screening a fluid's friction data for vibration risk (docs/screening.md):
//
//   1. the anti-shudder indices at each screening temperature (analysis/anti_shudder_indices.hpp);
//   2. the isothermal slope map dmu/dv over slip speed x temperature and its negative region;
//   3. the stability map of steady sliding on one or more test rigs (rig_stability.hpp) over the
//      same grid: margin > 0 is where friction-induced vibration grows;
//   4. a plain verdict combining them (analysis::screening_verdict).
//
// The fluid enters only through its FrictionLaw (and viscosity for the rig's viscous shear), so
// a law fitted to measured rig logs slots in unchanged. The rigs are the LSCTR model with the
// screened fluid in its clutch: by default RigParams{} and WetClutchParams{} with 100, 300 and
// 500 Hz torsion bars (the rig's 100–500 Hz range, docs/physics.md §4), or a rig scenario's [rig]
// and [clutch] with its fluid replaced.

#include <string>
#include <vector>

#include "analysis/anti_shudder_indices.hpp"
#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "studies/rig_stability.hpp"

namespace shudder::studies {

struct ScreeningRig {
  std::string label;  // empty: "rig (<clutch-side frequency> Hz bar)"
  rig_models::RigParams params;
  clutch::WetClutchParams clutch;
};

/// RigParams{} and WetClutchParams{} with bars of 100, 300 and 500 Hz.
std::vector<ScreeningRig> default_screening_rigs();

struct ScreeningOptions {
  analysis::IndexSettings indices;     // load (default 20 kN) and mean radius (46 mm)
  std::vector<double> temps_C;         // empty: 40/80/120 °C inside the law's temperature range
  std::vector<double> map_speeds_rpm;  // empty: 1, 2, ..., 120 rpm
  std::vector<double> map_temps_C;     // empty: default_map_temperatures()
  std::vector<ScreeningRig> rigs;      // empty: default_screening_rigs()
};

/// The map's temperatures: the law's temperature range if finite, else 40–120 °C, widened to
/// include every screening temperature, in steps of at most 5 °C (ends included).
std::vector<double> default_map_temperatures(const clutch::FrictionLaw& law, const std::vector<double>& temps_C);

struct RigScreen {
  std::string label;
  double clutch_side_frequency_Hz = 0.0;  // the rig's housing-on-bar mode, clutch slipping
  StabilityMap map;                       // margin > 0: unstable; NaN: motor saturated
  std::vector<analysis::RegionRun> unstable;
  analysis::RegionExtent unstable_extent;
  int saturated_points = 0;
  // The most unstable (or least stable) point of the map.
  double max_margin_per_s = 0.0, max_margin_rpm = 0.0, max_margin_temp_C = 0.0, max_margin_frequency_Hz = 0.0;
};

struct ScreeningReport {
  std::string fluid_name;
  double load_N = 0.0;
  double mean_radius_mm = 0.0;
  std::pair<double, double> law_temp_range_C;         // the law's data temperatures
  std::pair<double, double> law_speed_range_mm_s;     // the law's data speeds
  std::vector<analysis::AntiShudderIndices> indices;  // one per screening temperature
  analysis::SlopeMap slope;
  std::vector<analysis::RegionRun> negative_slope;  // the risky region: dmu/dv < 0
  analysis::RegionExtent negative_slope_extent;
  std::vector<RigScreen> rigs;
  analysis::ScreeningVerdict verdict;
};

/// Runs the screening. Throws std::invalid_argument for a bad load, radius, temperature or
/// speed, or invalid rig/clutch parameters.
ScreeningReport screen_fluid(const clutch::Fluid& fluid, const ScreeningOptions& options);

}  // namespace shudder::studies
