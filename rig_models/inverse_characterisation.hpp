#pragma once
// Model-based characterisation (`shudder characterise --method inverse`, issue 11 part 6).
//
// Why: the sensor method (analysis/friction_characterisation) compensates each sample with the
// temperature a sensor reads, but friction acts at the interface, whose field spans tens of
// kelvin across the radius during a ramp (at 24 kN, 84–125 °C; the inner edge near the start
// temperature) while the thermocouple behind the separator lags and averages it. Here the
// friction law is judged at the SIMULATED interface field instead: every run is replayed
// through the clutch and thermal model (rig_models/replay, the diagnosis' simulator) and the
// law is chosen so that the replayed torque equals the measured one.
//
// Algorithm (defect correction; a fixed point of "fit ∘ replay"):
//   0. L_0 = the sensor method's law (same settings, its own compensation).
//   1. thermal calibration: the oil-flow constants of Paper G eq. 12 (clutch/oil_flow.hpp),
//      the constant fraction e and the slip term a (b = 1), are fitted by Levenberg–Marquardt
//      (analysis/log_parameter_fit) to the measured temperature channel of every run, replayed
//      with the current law: sum over runs and samples of (T_sim − T_meas)² [°C²].
//   2. replay every run with L_k: mu_sim(t) = M_sim / (n F r_eff); refit with
//      Compensation::kModel, i.e. on mu_meas − (mu_sim − L_k(v, T_row, F_row)) → L_{k+1}.
//      Converged when max over rows and node speeds of |L_{k+1} − L_k| < tolerance_mu.
//      At the fixed point mu_sim = mu_meas in the least-squares sense of the law's form.
//   3. steps 1–2 are done twice (the temperature rise depends on the friction heat, so the
//      calibration is repeated with the converged law).
// The contraction of step 2 is the sensitivity of (mu_sim − L(v, T_row)) to the law: the
// temperature field changes with the friction heat (~mu) only in second order, so two to four
// replays suffice (measured: docs/characterisation.md §2).
//
// Errors: std::invalid_argument if the model cannot replay a run; std::runtime_error when a
// replay is not finite or the law does not converge within max_iterations.

#include <vector>

#include "analysis/friction_characterisation.hpp"
#include "clutch/oil_flow.hpp"
#include "rig_models/replay.hpp"

namespace shudder::rig_models {

struct InverseSettings {
  ReplayModel model;             // clutch, thermal defaults and solver settings; its fluid's law is replaced
  int max_iterations = 8;        // replays of every run per pass (step 2)
  double tolerance_mu = 1e-4;    // 0.1 % of a typical mu of 0.1: below the 1 % target by 10×
  bool calibrate_oil_flow = true;
  int thermal_evaluations = 16;  // LM evaluations (each replays every run) per calibration
  unsigned jobs = 1;             // threads replaying runs
};

struct InverseCharacterisation {
  analysis::Characterisation sensor;   // the sensor method (L_0)
  analysis::Characterisation inverse;  // the converged model-based fit
  clutch::OilFlowLaw oil_flow_start, oil_flow;  // before / after calibration
  double temp_rms_start_C = 0.0;   // replay with L_0 and the start oil flow vs the measured channel
  double temp_rms_C = 0.0;         // the final law and oil flow
  double torque_rms_sensor_Nm = 0.0;  // replay with L_0 (calibrated oil flow) vs measured torque
  double torque_rms_Nm = 0.0;         // replay with the final law
  int iterations = 0;                 // law updates over both passes
  int replays = 0;                    // replays of the whole set of runs
  double last_change_mu = 0.0;
};

/// `runs[k]` and `inputs[k]` are the same measured run (inputs carry its metadata and sump
/// channel). `temperature_channel` ("temp_C" or "ir_temp_C") names the replay output compared
/// with runs[k].temp_C in the thermal calibration. `settings` are the sensor method's.
InverseCharacterisation characterise_inverse(const std::vector<analysis::RampRun>& runs,
                                             const std::vector<ReplayInputs>& inputs,
                                             const analysis::CharacterisationSettings& settings,
                                             const std::string& temperature_channel, const InverseSettings& inverse);

}  // namespace shudder::rig_models
