#pragma once
// One case of a sweep (or a single run) evaluated both ways:
//   predicted — linear stability (analysis/stability) at the operating points the run passes
//               through (slip, mean interface temperature, force, sampled every
//               `prediction_interval_s`); the case's prediction is its least stable point;
//   simulated — the run itself, classified by analysis/shudder_detection.

#include <limits>
#include <string>

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "components/drive_cycle.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "rig_models/lsctr_rig.hpp"
#include "rig_models/prescribed_slip.hpp"

namespace shudder::studies {

struct CaseOutcome {
  static constexpr double kNaN = std::numeric_limits<double>::quiet_NaN();
  bool predicted_stable = true;
  double predicted_margin_per_s = kNaN;    // largest real part along the run, 1/s
  double predicted_frequency_Hz = kNaN;    // least damped oscillatory mode at that point
  std::string simulated_verdict = "none";  // none / vibration / stick_slip
  double simulated_frequency_Hz = kNaN;
  double amplitude_Nm = 0.0;
  double onset_time_s = kNaN;
};

/// Runs the rig case, records it into `rec`, and evaluates prediction and simulation.
CaseOutcome evaluate_rig_case(const rig_models::RigParams& params, const clutch::WetClutch& clutch,
                              const components::DriveCycle& cycle, const rig_models::RigSettings& settings,
                              dynamics::Recording& rec, double prediction_interval_s = 0.05);

/// Prescribed slip has no torsional dynamics: nothing can vibrate, the prediction is empty.
CaseOutcome evaluate_prescribed_case(const clutch::WetClutch& clutch, const components::DriveCycle& cycle,
                                     const rig_models::PrescribedSlipSettings& settings, dynamics::Recording& rec);

/// The driveline: the run and its coupling judged as `shudder run` judges it (the driveline's own
/// rule: an oscillation counts only if it lasts to the end of the record). No linear prediction
/// yet: predicted_stable stays true with NaN margin and frequency, as for prescribed slip.
CaseOutcome evaluate_driveline_case(const rig_models::DrivelineParams& params, const clutch::WetClutch& clutch,
                                    const rig_models::DrivelineInputs& inputs,
                                    const rig_models::DrivelineSettings& settings, dynamics::Recording& rec);

}  // namespace shudder::studies
