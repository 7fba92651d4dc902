#pragma once
// Comparing fluids (docs/characterisation.md "Comparing fluids"):
//
//   per fluid   the screening of studies/fluid_screening (anti-shudder indices at the chosen
//               temperatures, stability margins on the chosen rigs, the verdict);
//               the indices at EQUAL VISCOSITY: at the temperature where the fluid's Walther
//               viscosity equals `viscosity_cSt` (Paper E Table 5: 10 cSt);
//               the static/dynamic (breakaway) ratio Paper F ranks additives by;
//               the dynamic friction level mu(50 rpm) at the chosen temperatures (Paper F: high
//               dynamic friction wanted).
//   ranking     lexicographic, each key compared only beyond its resolution so that fluids the
//               data cannot separate share a place ("tie"):
//                 1. verdict level (LOW RISK < CAUTION < RISK < NOT JUDGED),
//                 2. the largest margin of the clutch-side mode over the rigs' maps where the
//                    law has data (1/s, lower is better; resolution 0.5 1/s, about the maps' own
//                    step effect; outside the data the law's slope is zero and the margin is the
//                    rig's own damping, the same for every fluid),
//                 3. the largest mu1/mu50 over the chosen temperatures (Ohtani: lower is
//                    further from shudder; resolution 0.5 %, the characterisation's accuracy),
//                 4. the breakaway ratio (Paper F: lower is better; resolution 0.01).

#include <string>
#include <vector>

#include "studies/fluid_screening.hpp"

namespace shudder::studies {

struct ComparisonOptions {
  ScreeningOptions screening;   // temps_C (empty: 30, 60, 90 °C), load, rigs
  double viscosity_cSt = 10.0;  // Paper E Table 5's equal viscosity
};

struct FluidComparison {
  std::string name, file;
  ScreeningReport screen;
  double equal_viscosity_temp_C = 0.0;  // NaN if the viscosity is not reached in −40…250 °C
  analysis::AntiShudderIndices at_equal_viscosity;
  double breakaway_ratio = 1.0;
  std::vector<double> mu50;          // mu at 50 rpm at each screening temperature
  double worst_mu1_over_mu50 = 0.0;  // largest over the screening temperatures
  double worst_margin_per_s = 0.0;   // clutch-side mode, largest over the rigs' maps inside the
                                     // law's data (NaN: no judged point there)
  int rank = 0;                      // 1 = best; equal ranks = not separated by the data
};

struct Comparison {
  std::vector<double> temps_C;
  double load_N = 0.0, viscosity_cSt = 0.0;
  std::vector<FluidComparison> fluids;   // in the order given
  std::vector<std::string> separations;  // one line per neighbouring pair in the ranking: what separates them, or "tie"
};

/// Throws std::invalid_argument like screen_fluid.
Comparison compare_fluids(const std::vector<std::pair<std::string, clutch::Fluid>>& fluids,
                          const ComparisonOptions& options);

/// The temperature where the Walther viscosity of (nu40, nu100) equals `cSt`, by bisection over
/// −40…250 °C (the viscosity falls monotonically with temperature); NaN outside that range.
double temperature_at_viscosity(double nu40_cSt, double nu100_cSt, double cSt);

}  // namespace shudder::studies
