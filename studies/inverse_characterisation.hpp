#pragma once
// Model-based characterisation (`shudder characterise --method inverse`).
//
// Why: the sensor method (analysis/friction_characterisation) compensates each sample with the
// temperature a sensor reads, but friction acts at the interface, whose field spans tens of
// kelvin across the radius during a ramp (at 24 kN, 84–125 °C; the inner edge near the start
// temperature) while the thermocouple behind the separator lags and averages it. Here the
// friction law is judged at the SIMULATED interface field instead: every run is replayed
// through the clutch and thermal model (studies/replay, the diagnosis' simulator), its oil
// flow calibrated on the measured temperature channel, and each sample is compensated with the
// model's interface temperature. The replayed torque with each method's law is reported.
//
// Algorithm:
//   0. L_0 = the sensor method's law (same settings).
//   1. thermal calibration: the oil-flow constant fraction e of Paper G eq. 12
//      (clutch/oil_flow.hpp; its slip and temperature terms keep the model's values) is fitted
//      by Levenberg–Marquardt (analysis/log_parameter_fit) to the measured temperature channel
//      of every run, replayed with the current law: sum over runs and samples of
//      (T_sim − T_meas)² [°C²].
//   2. replay every run with L_k and refit with the SAME compensation and law settings, but
//      with the replay's area-mean interface temperature in place of the sensor's, on the
//      sensor method's rows (--row-temps = its row temperatures) → L_{k+1}. Converged when
//      max over rows and node speeds of |L_{k+1} − L_k| < tolerance_mu. The law enters only
//      through the friction heat, so the map contracts strongly (2–3 updates, measured).
//   3. steps 1–2 are done twice (the temperature rise depends on the friction heat, so the
//      calibration is repeated with the converged law; the second calibration starts from the
//      first and is given a third of the evaluations).
// Tried and dropped: defect correction on the replayed torque (L_{k+1} = fit of
// mu_meas − mu_sim[L_k] + L_k(v, T_row)) converges for a law global in T (linear) but diverges
// for row-wise laws (Mäki matrix, table): a row's hot samples are explained by the rows above
// it, so the row-by-row update is a Jacobi iteration on a non-diagonally-dominant system.
//
// Errors: std::invalid_argument if the model cannot replay a run; std::runtime_error when a
// replay is not finite or the law does not converge within max_iterations.

#include <vector>

#include "analysis/friction_characterisation.hpp"
#include "clutch/oil_flow.hpp"
#include "studies/replay.hpp"

namespace shudder::studies {

struct InverseSettings {
  ReplayModel model;           // clutch, thermal defaults and solver settings; its fluid's law is replaced
  int max_iterations = 8;      // replays of every run per pass (step 2)
  double tolerance_mu = 1e-4;  // 0.1 % of a typical mu of 0.1: below the 1 % target by 10×
  bool calibrate_oil_flow = true;
  int thermal_evaluations = 12;  // LM evaluations (each replays every run) in the first calibration
  unsigned jobs = 1;             // threads replaying runs
};

struct InverseCharacterisation {
  analysis::Characterisation sensor;            // the sensor method (L_0)
  analysis::Characterisation inverse;           // the converged model-based fit
  clutch::OilFlowLaw oil_flow_start, oil_flow;  // before / after calibration
  double temp_rms_start_C = 0.0;                // replay with L_0 and the start oil flow vs the measured channel
  double temp_rms_C = 0.0;                      // the final law and oil flow
  double torque_rms_sensor_Nm = 0.0;            // replay with L_0 (calibrated oil flow) vs measured torque
  double torque_rms_Nm = 0.0;                   // replay with the final law
  analysis::CharacterisationSettings settings;  // the inverse fit's (rows fixed to the sensor's)
  int iterations = 0;                           // law updates over both passes
  int replays = 0;                              // replays of the whole set of runs
  double last_change_mu = 0.0;
};

/// `runs[k]` and `inputs[k]` are the same measured run (inputs carry its metadata and sump
/// channel). `temperature_channel` ("temp_C" or "ir_temp_C") names the replay output compared
/// with runs[k].temp_C in the thermal calibration. `settings` are the sensor method's.
InverseCharacterisation characterise_inverse(const std::vector<analysis::RampRun>& runs,
                                             const std::vector<ReplayInputs>& inputs,
                                             const analysis::CharacterisationSettings& settings,
                                             const std::string& temperature_channel, const InverseSettings& inverse);

}  // namespace shudder::studies
