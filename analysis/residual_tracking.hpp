#pragma once
// Where and how a model's residual disagrees with measured runs (analysis/diagnosis.hpp,
// "segments" and "tracks"), from the statistics of analysis/residual_analysis.hpp: the
// segments of each run where the residual stands above the noise, and the features of the
// measured runs the block-mean residual follows (pooled over the runs given predictions).

#include <string>
#include <utility>
#include <vector>

#include "analysis/diagnosis.hpp"
#include "analysis/misfit.hpp"

namespace shudder::analysis {

/// Features the torque (or temp_C) residual follows, pooled over the runs with a prediction,
/// strongest first.
std::vector<std::pair<std::string, double>> pooled_tracking(const std::vector<DiagnosisRun>& runs, const Predictions& p,
                                                            bool torque);
/// Disagreeing segments of torque then temp_C in every run (every run must have a prediction).
std::vector<Disagreement> disagreements(const std::vector<DiagnosisRun>& runs, const Predictions& p,
                                        double sigma_torque_Nm, double sigma_temp_C);
/// Feature correlations of every run (and all runs pooled, with several), torque then temp_C.
std::vector<Tracking> tracking(const std::vector<DiagnosisRun>& runs, const Predictions& p);

}  // namespace shudder::analysis
