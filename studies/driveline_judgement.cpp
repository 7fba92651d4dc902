#include "studies/driveline_judgement.hpp"

#include <limits>
#include <stdexcept>

#include "analysis/shudder_detection.hpp"
#include "studies/driveline_stability.hpp"
#include "studies/recording_detection.hpp"

namespace shudder::studies {

namespace {

analysis::ShudderResult judge_coupling(const dynamics::Recording& rec) {
  const RecordingDetection detection = *recording_detection(rec);
  analysis::ShudderResult judder;
  try {
    judder = judge_recording(detection);
  } catch (const std::invalid_argument&) {
    judder.verdict = analysis::Verdict::kNone;  // too short a record to judge (< 64 samples)
    judder.frequency_Hz = judder.amplitude_Nm = std::numeric_limits<double>::quiet_NaN();
  }
  return judder;
}

}  // namespace

void add_driveline_judgement(const rig_models::DrivelineParams& params, const clutch::WetClutch& clutch,
                             const rig_models::DrivelineInputs& inputs, const rig_models::DrivelineSettings& settings,
                             dynamics::Recording& rec) {
  const rig_models::HaldexDriveline dl(params, clutch, inputs);
  const LockedShuffle shuffle = run_shuffle_mode(dl, clutch, rec, settings.duration_s);
  const analysis::ShudderResult judder = judge_coupling(rec);
  rec.scalars.push_back({"coupling_verdict_code", "1", static_cast<double>(judder.verdict)});
  rec.scalars.push_back({"coupling_oscillation_frequency_Hz", "Hz", judder.frequency_Hz});
  rec.scalars.push_back({"coupling_oscillation_amplitude_Nm", "N m", judder.amplitude_Nm});
  rec.scalars.push_back({"shuffle_frequency_Hz", "Hz", shuffle.frequency_Hz});
  rec.scalars.push_back({"shuffle_damping_ratio", "1", shuffle.damping_ratio});
}

}  // namespace shudder::studies
