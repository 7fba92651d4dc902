#include "studies/case_evaluation.hpp"

#include "studies/driveline_judgement.hpp"

#include <cmath>
#include <stdexcept>

#include "analysis/shudder_detection.hpp"
#include "studies/recording_detection.hpp"
#include "studies/rig_stability.hpp"

namespace shudder::studies {

namespace {

// Value of a recorded signal at time t (samples are uniform from 0, so index by rate).
double at(const dynamics::Signal& time, const dynamics::Signal& sig, double t) {
  const auto& ts = time.values;
  if (ts.size() < 2) return sig.values.front();
  const double dt = ts[1] - ts[0];
  const auto i =
      static_cast<std::size_t>(std::clamp(std::round((t - ts[0]) / dt), 0.0, static_cast<double>(ts.size() - 1)));
  return sig.values[i];
}

void fill_simulated(const dynamics::Recording& rec, CaseOutcome& o) {
  // The run's own judgement (recording_detection.hpp), so a sweep's case and `shudder run` of
  // the same scenario report the same onset.
  const analysis::ShudderResult r = judge_recording(*recording_detection(rec));
  o.simulated_verdict = std::string(analysis::to_string(r.verdict));
  o.amplitude_Nm = r.amplitude_Nm;
  o.simulated_frequency_Hz = r.verdict == analysis::Verdict::kNone ? CaseOutcome::kNaN : r.frequency_Hz;
  o.onset_time_s = r.verdict == analysis::Verdict::kNone ? CaseOutcome::kNaN : r.onset_time_s;
}

}  // namespace

CaseOutcome evaluate_rig_case(const rig_models::RigParams& params, const clutch::WetClutch& clutch,
                              const components::DriveCycle& cycle, const rig_models::RigSettings& settings,
                              dynamics::Recording& rec, double interval_s) {
  rec = rig_models::run_rig(params, clutch, cycle, settings);
  CaseOutcome o;
  fill_simulated(rec, o);

  // Prediction: linearise about steady sliding at the operating points the run passes through
  // (reference slip, mean interface temperature, force), every interval_s; keep the worst.
  const rig_models::LsctrRig rig(params, clutch, cycle);
  const auto* time = rec.find("time_s");
  const auto* temp = rec.find("interface_mean_temp_C");
  double worst = -std::numeric_limits<double>::infinity();
  for (double t = 0.0; t <= settings.duration_s + 1e-12; t += interval_s) {
    const double slip = cycle.slip_speed_rpm(t);
    const components::ClutchHeldInputs held{
        Eigen::VectorXd::Constant(clutch.thermal().radial_cells(), at(*time, *temp, t)), cycle.normal_force_N};
    analysis::StabilityPoint p;
    try {
      p = rig_stability(rig, held, slip, t);
    } catch (const std::invalid_argument&) {
      continue;  // steady sliding impossible (motor saturated): no linearisation there
    }
    if (p.margin_per_s > worst) {
      worst = p.margin_per_s;
      o.predicted_margin_per_s = p.margin_per_s;
      // The frequency a shudder would have: the least damped OSCILLATORY mode (the largest
      // real part overall often belongs to the drive loop's real, non-oscillating mode).
      o.predicted_frequency_Hz = p.oscillatory_frequency_Hz;
      o.predicted_stable = p.stable;
    }
  }
  return o;
}

CaseOutcome evaluate_prescribed_case(const clutch::WetClutch& clutch, const components::DriveCycle& cycle,
                                     const rig_models::PrescribedSlipSettings& settings, dynamics::Recording& rec) {
  rec = rig_models::run_prescribed_slip(clutch, cycle, settings);
  CaseOutcome o;
  o.amplitude_Nm = 0.0;
  return o;
}

CaseOutcome evaluate_driveline_case(const rig_models::DrivelineParams& params, const clutch::WetClutch& clutch,
                                    const rig_models::DrivelineInputs& inputs,
                                    const rig_models::DrivelineSettings& settings, dynamics::Recording& rec) {
  rec = rig_models::run_driveline(params, clutch, inputs, settings);
  add_driveline_judgement(params, clutch, inputs, settings, rec);
  CaseOutcome o;
  // The run's own verdict (coupling_verdict_code), with the onset from the same judgement.
  const auto verdict =
      static_cast<analysis::Verdict>(static_cast<int>(rec.find_scalar("coupling_verdict_code")->value));
  o.simulated_verdict = std::string(analysis::to_string(verdict));
  if (verdict == analysis::Verdict::kNone) return o;
  o.simulated_frequency_Hz = rec.find_scalar("coupling_oscillation_frequency_Hz")->value;
  o.amplitude_Nm = rec.find_scalar("coupling_oscillation_amplitude_Nm")->value;
  o.onset_time_s = judge_recording(*recording_detection(rec)).onset_time_s;
  return o;
}

}  // namespace shudder::studies
