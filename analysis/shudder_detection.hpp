#pragma once
// Shudder detection from a recorded torque and relative-speed (slip) signal: a verdict, the
// oscillation's amplitude and dominant frequency, when it started and the operating point
// (slip speed, interface temperature, normal force) at that time.
//
// Verdicts (docs/physics.md §6):
//   none        no oscillation above the amplitude threshold;
//   vibration   friction-induced vibration: a (near-)harmonic oscillation while the contact
//               keeps sliding — the slip never reverses and never reaches zero;
//   stick_slip  the relative speed reaches zero periodically: in at least half of the
//               oscillation's cycles a sample is stuck, has |slip| <= zero_slip_rpm, or the
//               slip changes sign between two samples.
//
// Definitions (T torque in N m, uniform sampling at fs, t_0 the first sample time):
//   1. Coarse detrend  x = T − M_W[T], M_W a centred moving mean over W = 2 / f_min, which
//      removes drive-cycle trends (below f_min / 2) but passes every frequency searched.
//   2. Preliminary frequency f_1: peak of the Welch PSD of x (Hann, 50 % overlap, segments of
//      16 periods of f_min or the longest power of two the record holds; the last segment
//      ends at the record's last sample, so a judder that starts late is in it) in
//      [f_min, f_max].
//   3. Spectrogram of x with frames of `periods_per_frame` periods of f_1 (rounded up to a
//      power of two samples, hop a quarter frame, the last frame ending at the record's last
//      sample); band power B_j (N² m²) in f_1 ± 2 bins (the
//      Hann main lobe), in dB: b_j = 10 log10 B_j.
//   4. Oscillating part: the frames with b_j >= max b − oscillating_part_dB (amplitude within
//      a factor 10 of its largest), from the first such frame's start to the last one's end.
//   5. Dominant frequency f_d: interpolated Hann-FFT peak (analysis/spectrum.hpp) of x over
//      the oscillating part, searched within ±20 % of f_1. A stick-slip cycle is no sine and
//      its harmonics can outweigh its fundamental (rig_stick_time_probe: 10 sticks per second,
//      alternating 0.117 / 0.083 s, whose 25 Hz line is 7 % above the 10 Hz one). So if the
//      contact sticks at least min_stick_onsets times in the oscillating part and at a rate
//      f_s = (N − 1)/(t_N − t_1) (t_k the sample times where a stuck phase begins: stuck, or
//      |slip| <= zero_slip_rpm, after a sliding sample) below f_d / 1.5, f_d = f_s: the cycle
//      is one stick and one slip. A rate at or above f_d (several sticks per cycle, or chatter)
//      leaves f_d; peak_frequency_Hz keeps the spectral peak.
//   6. Amplitude A: r = T − M_P[T] with M_P a centred moving mean over exactly one period
//      P = 1/f_d (fractional window), which removes the oscillation's fundamental and its
//      harmonics from the mean whatever the trend; half peak-to-peak (max r − min r)/2 in
//      blocks of `periods_per_block` periods over the oscillating part; A = median of the
//      blocks whose value is >= 80 % of the largest block (the saturated oscillation, not its
//      growth).
//   7. none if A < max(min_amplitude_Nm, min_relative_amplitude · mean |T|).
//   8. Onset (when the oscillation starts), on the band power b_j (dB) before the oscillating
//      part:
//      a. start level b_0: 10 log10 of the mean band power of the first `baseline_frames`
//         frames; if the oscillating part begins with the first frame, the oscillation was
//         there from the start: onset t_0, growth_observed false;
//      b. crossing level L = max(b_0 + onset_rise_dB, max b − onset_below_max_dB) and t_x its
//         last upward crossing before the oscillating part (interpolated in dB between frame
//         centres): the band power leaves its start level for good (the second term keeps
//         the drift of a floor far under the oscillation from counting);
//      c. OnsetDefinition::kGrowthLine (the default, the growth-line onset): if at least
//         `min_growth_frames` frames lie between t_x and the oscillating part, the
//         growth there is fitted by a least-squares line b = b_1 + g t (exponential growth,
//         amplitude ∝ e^{σ t} with σ = g ln10/20, reported as growth_rate_per_s) and the onset
//         is where that line comes up out of the start level: t = (b_0 − b_1)/g (not before
//         t_0); otherwise (an abrupt start, e.g. the first breakaway of a stick-slip) t_x.
//      For an oscillation a e^{σ (t − t_g)} switched on at t_g in a floor of band power P_b
//      (mean square) this is where a² e^{2σ (t − t_g)}/2 = P_b: the time the growing
//      oscillation reaches the floor (= t_g when it starts at the floor), independent of
//      where the thresholds sit. Growth from the first frame gives an onset near t_0. If the
//      growth rate itself rises with time (a ramp into the unstable range), b(t) is convex,
//      the fitted line is a secant and the onset found lies after the instant the growth rate
//      crossed zero; growth_rate_per_s is then the mean σ over the fitted span.
//      d. OnsetDefinition::kGrowthRateZero (for ramps: a slowly varying operating point) instead
//         fits the same frames with a least-squares parabola b = b_1 + g_1 t + g_2 t². Its
//         growth rate σ(t) = (g_1 + 2 g_2 t) ln10/20 is linear in time, and σ' = 2 g_2 ln10/20
//         is reported as growth_acceleration_per_s2. If g_2 > 0 (the growth rate rises) and the
//         vertex lies before the fitted frames, the onset is the vertex t = −g_1/(2 g_2) (not
//         before t_0): the instant the growth rate crossed zero, i.e. where linear theory puts
//         the onset. This comes from the free growth alone, not from where the growth
//         emerges from the floor. That matters because the floor can be a forced response:
//         on the rig, the small torque steps at each thermal step excite the bar mode. A forced
//         floor rises as the damping falls toward zero, so the band power's minimum comes well
//         before the onset. Otherwise (constant or falling growth rate, too few frames) the
//         onset is the growth line's.
//         The vertex is extrapolated back from the fitted 20 dB by σ/σ'. Its precision is set
//         by how well those frames give the curvature. A random floor scatters the band power
//         by ~√(P_floor/P): at 45 dB under the fitted frames the onset is good to ~10 % of the
//         extrapolation, and at 25 dB it is lost (tests/analysis). A deterministic floor of a
//         simulation is smoother. The system must be quasi-static: σ changes little over a frame.
//      e. OnsetDefinition::kThresholdCrossing (what a run reports: studies/recording_detection)
//         instead places the onset where the oscillation's amplitude in the band, a_j = √(2 B_j)
//         (a sinusoid's amplitude from its mean square), last rises through the verdict's
//         threshold (definition 7) before the oscillating part, interpolated in dB between frame
//         centres; the level is capped at the oscillating part's, b_max − oscillating_part_dB,
//         so an oscillation judged on its half peak-to-peak but weaker in its fundamental still
//         has a crossing. t_0 (growth_observed false) if the band never lies under that level
//         before the oscillating part (oscillating from the start). Why: the growth line measures
//         from the start level, the first frames' band power. Where the operating point is
//         unstable from t = 0 the growth leaves the start at once, and the growth line's onset is t_0 plus a
//         fraction of a frame, set by what fills the band in the first frames (the start, the
//         thermal steps' numerical floor), not by physics: rig_shudder_negative_slope gave
//         0.028–0.040 s at thermal steps of 1–10 ms with no trend. The threshold crossing is the instant the
//         oscillation becomes what the verdict calls shudder (the smallest oscillation that
//         counts): it is set by the seed and the growth rate, not by the floor below the
//         threshold; a start transient above the threshold that decays again is skipped (the
//         LAST upward crossing counts). It shares the growth line's assumption that what crosses is the
//         growing oscillation. growth_rate_per_s is still the growth line's fitted σ.
//   9. Operating point at onset: the means of slip (rpm, signed), interface temperature (°C)
//      and normal force (N) over one period P centred at the onset time.
// For `none`, frequency, onset, growth rate and operating point are NaN (peak_frequency_Hz
// still reports the strongest peak examined, amplitude_Nm the measured residual).

#include <array>
#include <cstddef>
#include <span>
#include <string_view>
#include <vector>

#include "analysis/spectrum.hpp"
#include "dynamics/recording.hpp"

namespace shudder::analysis {

enum class Verdict { kNone, kVibration, kStickSlip };

/// Every verdict, in code order (the integer a verdict is stored as: 0, 1, 2).
inline constexpr std::array<Verdict, 3> kVerdicts = {Verdict::kNone, Verdict::kVibration, Verdict::kStickSlip};

/// How the onset time is placed on the growth (definition 8 in the header comment).
enum class OnsetDefinition {
  kGrowthLine,         // c: the fitted exponential growth extrapolated down to the start level
  kGrowthRateZero,     // d (ramps): where the growth rate, fitted as linear in time, crosses zero
  kThresholdCrossing,  // e (runs' verdicts): the band amplitude's last rise through the verdict threshold
};

/// "none", "vibration", "stick_slip" (the names written to outputs).
std::string_view to_string(Verdict verdict);
/// The verdict of a name to_string gives; kNone for any other text.
Verdict verdict_from_string(std::string_view name);

struct DetectionSettings {
  // Band searched. 5 Hz: the driveline's lowest shudder modes (~5–50 Hz, docs/architecture.md); the
  // rig's clutch-side modes are 100–500 Hz and its stick-slip ~100–300 Hz. 2 kHz covers the
  // rig's modes and a few harmonics; it is capped at 0.45 fs (below Nyquist, where the
  // one-sided spectrum has no neighbour bin to interpolate with).
  double min_frequency_Hz = 5.0;
  double max_frequency_Hz = 2000.0;
  // Amplitude threshold max(0.5 N m, 1 % of mean |T|): 0.5 N m is a torque-cell resolution
  // level on the rig's 0–1000 N m range; 1 % of the mean torque is the ripple a quasi-static
  // friction test tolerates (the rig's no-shudder check, tests/rig_models).
  double min_amplitude_Nm = 0.5;
  double min_relative_amplitude = 0.01;
  // |slip| at or below this counts as stuck, rpm: a fifth of the rig's slowest drive speed
  // (0.5 rpm), far below the slip excursions of a vibration at tens of rpm.
  double zero_slip_rpm = 0.1;
  // Stuck phases needed before their rate may replace the spectral f_d (step 5): 4 onsets
  // give 3 whole cycles, the fewest whose mean is a rate rather than one interval.
  int min_stick_onsets = 4;
  // Fraction of the oscillation's cycles that must reach zero slip for stick_slip: "most
  // cycles" while tolerating a few cycles missed between samples.
  double stick_cycle_fraction = 0.5;
  // Oscillating part: band power within 20 dB (amplitude within a factor 10) of its largest.
  double oscillating_part_dB = 20.0;
  // Onset: band power 6 dB (amplitude doubled) above its starting level — clear of the
  // ±1–2 dB scatter of a noise floor's band power, small against the tens of dB of growth.
  double onset_rise_dB = 6.0;
  // ... or, if higher, 40 dB under the largest band power (amplitude 1 % of the largest): a
  // start level far under the oscillation may drift by more than 6 dB without meaning
  // anything (the rig's stick-slip run: the bar's smooth wind-up carries numerical wiggles
  // 80 dB under the stick-slip that rise 10 dB before the first breakaway).
  double onset_below_max_dB = 40.0;
  // Frames needed to fit the growth line (at a hop of 2 periods: 16 periods of growth).
  int min_growth_frames = 8;
  // Start level: mean band power of the first 8 frames (2 frame lengths of signal: the
  // overlapping frames are not independent), short against a growth from the start.
  int baseline_frames = 8;
  // Spectrogram frames of 8 periods: frequency resolution ~f/8..f/16, time resolution a
  // quarter frame (2 periods) per hop.
  double periods_per_frame = 8.0;
  double periods_per_block = 4.0;
  // Onset definition: the growth line (constant operating point), the growth rate's zero (slow
  // ramp into instability) or the threshold crossing (the oscillation reaching the verdict's
  // threshold; what runs report).
  OnsetDefinition onset_definition = OnsetDefinition::kGrowthLine;
};

/// Plain-vector input. time_s, torque_Nm and slip_rpm are required (equal lengths, uniform
/// sampling); stuck (1 = stuck), interface_temp_C and normal_force_N may be empty.
struct DetectionInput {
  std::span<const double> time_s;
  std::span<const double> torque_Nm;
  std::span<const double> slip_rpm;
  std::span<const double> stuck;
  std::span<const double> interface_temp_C;
  std::span<const double> normal_force_N;
};

struct OperatingPoint {
  double time_s = 0.0;
  double slip_rpm = 0.0;          // signed mean over one period
  double interface_temp_C = 0.0;  // NaN if not recorded
  double normal_force_N = 0.0;    // NaN if not recorded
};

struct ShudderResult {
  Verdict verdict = Verdict::kNone;
  double amplitude_Nm = 0.0;       // half peak-to-peak of T − moving mean (definition 6)
  double threshold_Nm = 0.0;       // amplitude threshold applied (definition 7)
  double frequency_Hz = 0.0;       // dominant frequency f_d; NaN for none
  double peak_frequency_Hz = 0.0;  // strongest peak examined (f_d, also for none)
  double onset_time_s = 0.0;       // definition 8; NaN for none
  bool growth_observed =
      false;  // the band power rose from its starting level (threshold crossing: through the threshold)
  double growth_rate_per_s = 0.0;  // σ of the fitted growth (the growth line); NaN if not fitted
  // dσ/dt of the parabola of kGrowthRateZero, 1/s²; NaN unless that definition placed the onset.
  double growth_acceleration_per_s2 = 0.0;
  OperatingPoint at_onset;                                  // definition 9; NaN fields for none
  double mean_torque_Nm = 0.0;                              // mean |T| over the record
  double stick_cycle_fraction = 0.0;                        // cycles of the oscillating part that reached zero slip
  double oscillating_from_s = 0.0, oscillating_to_s = 0.0;  // definition 4
  std::vector<double> band_times_s;                         // (n_frames) spectrogram frame centres
  std::vector<double> band_power;                           // (n_frames) band power around f_1, N² m²
};

/// Runs definitions 1–9. Holds a SpectralAnalyzer so repeated detections on records of equal
/// length reuse their FFT plans; detect() is const and thread-safe.
class ShudderDetector {
 public:
  /// Throws std::invalid_argument for inconsistent settings.
  explicit ShudderDetector(const DetectionSettings& settings = {});

  /// Throws std::invalid_argument for missing, unequal-length, too short (< 64 samples) or
  /// non-uniformly sampled signals, naming the signal.
  ShudderResult detect(const DetectionInput& input) const;

  /// From a run's recording: time_s, torque_Nm, slip_rpm (required), stuck,
  /// interface_mean_temp_C, normal_force_N (used when present).
  ShudderResult detect(const dynamics::Recording& recording) const;

  const DetectionSettings& settings() const { return settings_; }
  const SpectralAnalyzer& spectra() const { return spectra_; }

 private:
  DetectionSettings settings_;
  SpectralAnalyzer spectra_;
};

/// One-off detection (plans are not kept between calls).
ShudderResult detect_shudder(const dynamics::Recording& recording, const DetectionSettings& settings = {});
ShudderResult detect_shudder(const DetectionInput& input, const DetectionSettings& settings = {});

}  // namespace shudder::analysis
