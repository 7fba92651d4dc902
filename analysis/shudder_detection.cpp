#include "analysis/shudder_detection.hpp"

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>
#include <string_view>
#include <utility>

#include "core/median.hpp"
#include "dynamics/signal_names.hpp"
#include "core/nan.hpp"

namespace shudder::analysis {

namespace {

constexpr std::size_t kMinSamples = 64;

void require(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

std::size_t next_pow2(double x) {
  std::size_t p = 1;
  while (static_cast<double>(p) < x) p *= 2;
  return p;
}

std::size_t prev_pow2(std::size_t n) {
  std::size_t p = 1;
  while (2 * p <= n) p *= 2;
  return p;
}

// Largest 2^a 3^b 5^c <= n: FFT lengths FFTW handles fast, and few distinct ones, so the plan
// cache stays small when record lengths vary.
std::size_t nice_length(std::size_t n) {
  std::size_t best = 1;
  for (std::size_t p5 = 1; p5 <= n; p5 *= 5)
    for (std::size_t p3 = p5; p3 <= n; p3 *= 3) best = std::max(best, p3 * prev_pow2(n / p3));
  return best;
}

// Centred moving mean over a window of `width` samples (real, >= 1) of the zero-order-hold
// signal (sample i covers [i, i + 1)), via the cumulative sum with fractional ends; near the
// record's ends the window is clipped to the record. The overall mean is taken out first so
// the cumulative sum keeps its precision.
std::vector<double> moving_mean(std::span<const double> x, double width) {
  const std::size_t n = x.size();
  double offset = 0.0;
  for (double v : x) offset += v;
  offset /= static_cast<double>(n);
  std::vector<double> c(n + 1, 0.0);
  for (std::size_t i = 0; i < n; ++i) c[i + 1] = c[i] + (x[i] - offset);
  const auto cum = [&](double u) {
    u = std::clamp(u, 0.0, static_cast<double>(n));
    const auto i = std::min(static_cast<std::size_t>(u), n - 1);
    return c[i] + (u - static_cast<double>(i)) * (x[i] - offset);
  };
  width = std::clamp(width, 1.0, static_cast<double>(n));
  std::vector<double> m(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double centre = static_cast<double>(i) + 0.5;
    const double lo = std::max(0.0, centre - 0.5 * width), hi = std::min(static_cast<double>(n), centre + 0.5 * width);
    m[i] = offset + (cum(hi) - cum(lo)) / (hi - lo);
  }
  return m;
}

// Mean of v over samples [i0, i1) (NaN for an empty signal).
double mean_over(std::span<const double> v, std::size_t i0, std::size_t i1) {
  if (v.empty() || i1 <= i0) return kNaN;
  double s = 0.0;
  for (std::size_t i = i0; i < i1; ++i) s += v[i];
  return s / static_cast<double>(i1 - i0);
}

double to_dB(double power) { return 10.0 * std::log10(std::max(power, 1e-300)); }

void check_input(const DetectionInput& in) {
  const std::size_t n = in.time_s.size();
  require(n >= kMinSamples, "shudder detection needs at least " + std::to_string(kMinSamples) +
                                " samples of time_s, got " + std::to_string(n));
  const auto same = [n](std::span<const double> s, const char* name, bool optional) {
    if (optional && s.empty()) return;
    require(s.size() == n, std::string("shudder detection: signal ") + name + " has " + std::to_string(s.size()) +
                               " samples, time_s has " + std::to_string(n));
  };
  same(in.torque_Nm, "torque_Nm", false);
  same(in.slip_rpm, "slip_rpm", false);
  same(in.stuck, "stuck", true);
  same(in.interface_temp_C, "interface temperature", true);
  same(in.normal_force_N, "normal_force_N", true);
  const double dt = (in.time_s[n - 1] - in.time_s[0]) / static_cast<double>(n - 1);
  require(dt > 0.0, "shudder detection: time_s must increase");
  // The message is built only for a failing step (building it for every sample cost more than
  // the rest of the detection on a 1000-sample run).
  for (std::size_t i = 1; i < n; ++i)
    if (!(std::abs(in.time_s[i] - in.time_s[i - 1] - dt) <= 1e-3 * dt))
      require(false, "shudder detection needs uniform sampling: time_s steps by " +
                         std::to_string(in.time_s[i] - in.time_s[i - 1]) + " s at t = " + std::to_string(in.time_s[i]) +
                         " s against a mean step of " + std::to_string(dt) + " s; resample first");
}

// Stuck phases per second over samples [i_a, i_b) (header, step 5): the mean rate between the
// first and the last sample where a stuck phase begins; 0 with fewer than min_stick_onsets.
double stick_rate_Hz(const DetectionInput& in, std::size_t i_a, std::size_t i_b, const DetectionSettings& cfg) {
  const auto stuck_at = [&](std::size_t i) {
    return (!in.stuck.empty() && in.stuck[i] > 0.5) || std::abs(in.slip_rpm[i]) <= cfg.zero_slip_rpm;
  };
  std::size_t onsets = 0, first = 0, last = 0;
  for (std::size_t i = std::max<std::size_t>(i_a, 1); i < i_b; ++i)
    if (stuck_at(i) && !stuck_at(i - 1)) {
      if (onsets++ == 0) first = i;
      last = i;
    }
  if (onsets < static_cast<std::size_t>(cfg.min_stick_onsets)) return 0.0;
  return static_cast<double>(onsets - 1) / (in.time_s[last] - in.time_s[first]);
}

// Definition 6: the amplitude, half peak-to-peak of T minus its one-period moving mean, in
// blocks of periods_per_block periods over [i_a, i_b); the median of the blocks within 80 % of
// the largest (0 when no block fits).
double block_amplitude_Nm(std::span<const double> T, std::size_t i_a, std::size_t i_b, double period,
                          const DetectionSettings& cfg) {
  const std::size_t n = T.size();
  const std::vector<double> mean_P = moving_mean(T, period);
  const auto half = static_cast<std::size_t>(std::ceil(0.5 * period));
  const std::size_t k0 = std::max(i_a, half), k1 = std::min(i_b, n > half ? n - half : 0);
  const auto block = std::max<std::size_t>(2, static_cast<std::size_t>(std::lround(cfg.periods_per_block * period)));
  std::vector<double> blocks;
  for (std::size_t start = k0; start < k1; start += block) {
    const std::size_t end = std::min(k1, start + block);
    if (end - start < block / 2 && !blocks.empty()) break;  // a short tail block is not a full measure
    double lo = std::numeric_limits<double>::infinity(), hi = -lo;
    for (std::size_t i = start; i < end; ++i) {
      lo = std::min(lo, T[i] - mean_P[i]);
      hi = std::max(hi, T[i] - mean_P[i]);
    }
    blocks.push_back(0.5 * (hi - lo));
  }
  if (blocks.empty()) return 0.0;
  const double largest = *std::max_element(blocks.begin(), blocks.end());
  std::vector<double> strong;
  for (double v : blocks)
    if (v >= 0.8 * largest) strong.push_back(v);
  return core::median(strong);
}

// Definition 7's split: the share of one-period cycles of [i_a, i_b) in which the slip reaches
// zero (a stuck sample, |slip| <= zero_slip_rpm, or a sign change).
double stick_cycle_share(const DetectionInput& in, std::size_t i_a, std::size_t i_b, double period,
                         const DetectionSettings& cfg) {
  const auto reaches_zero = [&](std::size_t i) {
    if (!in.stuck.empty() && in.stuck[i] > 0.5) return true;
    if (std::abs(in.slip_rpm[i]) <= cfg.zero_slip_rpm) return true;
    return i > 0 && in.slip_rpm[i] * in.slip_rpm[i - 1] < 0.0;
  };
  const auto cycles = std::max<std::size_t>(1, static_cast<std::size_t>(static_cast<double>(i_b - i_a) / period));
  std::size_t touched = 0;
  for (std::size_t c = 0; c < cycles; ++c) {
    const auto c0 = i_a + static_cast<std::size_t>(std::lround(static_cast<double>(c) * period));
    const auto c1 = std::min(i_b, i_a + static_cast<std::size_t>(std::lround(static_cast<double>(c + 1) * period)));
    for (std::size_t i = c0; i < c1; ++i)
      if (reaches_zero(i)) {
        ++touched;
        break;
      }
  }
  return static_cast<double>(touched) / static_cast<double>(cycles);
}

// The band power in dB per spectrogram frame, and the frames of the oscillating part.
struct BandTrace {
  std::span<const double> times_s;  // (frames) frame centres
  std::vector<double> dB;           // (frames)
  double max_dB = 0.0;
  std::size_t ja = 0;  // first frame of the oscillating part
};

// The time `level` is crossed upwards between frame j (at or below it) and j + 1 (above it),
// interpolated in dB.
double crossing_time_s(const BandTrace& b, std::size_t j, double level) {
  const double w = std::clamp((level - b.dB[j]) / (b.dB[j + 1] - b.dB[j]), 0.0, 1.0);
  return b.times_s[j] + w * (b.times_s[j + 1] - b.times_s[j]);
}

// Definition 8, growth line and growth-rate zero: the onset from the band power's rise before
// the oscillating part. Start level b0: mean band power of the first frames before it (none:
// the oscillation was there from the start). Crossing level L = max(b0 + rise, b_max −
// below_max); its last upward crossing before the oscillating part; then the least-squares
// growth line through the frames between L and the oscillating part, extrapolated down to b0
// (or, for kGrowthRateZero, the vertex of a parabola through them).
void growth_onset(const BandTrace& b, std::span<const double> band_power, double t0, const DetectionSettings& cfg,
                  ShudderResult& r) {
  const std::size_t frames = b.dB.size(), ja = b.ja;
  const std::size_t nb = std::min<std::size_t>(static_cast<std::size_t>(cfg.baseline_frames), ja);
  std::size_t j_x = frames;  // last frame before the oscillating part at or below L
  double b0 = kNaN, level = kNaN;
  if (nb > 0) {
    double p0 = 0.0;
    for (std::size_t j = 0; j < nb; ++j) p0 += band_power[j];
    b0 = to_dB(p0 / static_cast<double>(nb));
    level = std::max(b0 + cfg.onset_rise_dB, b.max_dB - cfg.onset_below_max_dB);
    for (std::size_t j = 0; j < ja; ++j)
      if (b.dB[j] <= level) j_x = j;
  }
  r.growth_observed = j_x < frames;
  r.onset_time_s = t0;
  r.growth_rate_per_s = r.growth_acceleration_per_s2 = kNaN;
  if (!r.growth_observed) return;
  r.onset_time_s = crossing_time_s(b, j_x, level);
  const std::size_t count = ja - j_x - 1;
  if (count < static_cast<std::size_t>(cfg.min_growth_frames)) return;
  // Exponential growth: the least-squares line through (t_j, b_j), j_x < j < ja.
  double st = 0, sb = 0, stt = 0, stb = 0;
  for (std::size_t j = j_x + 1; j < ja; ++j) {
    st += b.times_s[j];
    sb += b.dB[j];
    stt += b.times_s[j] * b.times_s[j];
    stb += b.times_s[j] * b.dB[j];
  }
  const double c = static_cast<double>(count);
  const double slope_dB_per_s = (c * stb - st * sb) / (c * stt - st * st);
  if (slope_dB_per_s > 0.0) {
    const double intercept = (sb - slope_dB_per_s * st) / c;
    r.growth_rate_per_s = slope_dB_per_s * std::log(10.0) / 20.0;  // amplitude ∝ e^{σ t}
    r.onset_time_s = std::max(t0, (b0 - intercept) / slope_dB_per_s);
  }
  if (cfg.onset_definition != OnsetDefinition::kGrowthRateZero) return;
  // Least-squares parabola b = c0 + c1 u + c2 u², u = t − t_mean (centred for conditioning),
  // over the same frames; its vertex is where the growth rate is zero.
  const double t_mean = st / c;
  double s2 = 0, s3 = 0, s4 = 0, y0 = 0, y1 = 0, y2 = 0;
  for (std::size_t j = j_x + 1; j < ja; ++j) {
    const double u = b.times_s[j] - t_mean, u2 = u * u;
    s2 += u2;
    s3 += u2 * u;
    s4 += u2 * u2;
    y0 += b.dB[j];
    y1 += u * b.dB[j];
    y2 += u2 * b.dB[j];
  }
  // Normal equations [n 0 s2; 0 s2 s3; s2 s3 s4] (c0 c1 c2)ᵀ = (y0 y1 y2)ᵀ (Σu = 0).
  Eigen::Matrix3d m;
  m << c, 0.0, s2, 0.0, s2, s3, s2, s3, s4;
  const Eigen::Vector3d coef = m.ldlt().solve(Eigen::Vector3d(y0, y1, y2));
  const double c1 = coef(1), c2 = coef(2);
  const double vertex = t_mean - c1 / (2.0 * c2);
  if (c2 > 0.0 && std::isfinite(vertex) && vertex < b.times_s[j_x + 1]) {
    r.onset_time_s = std::max(t0, vertex);
    r.growth_acceleration_per_s2 = 2.0 * c2 * std::log(10.0) / 20.0;
  }
}

// Definition 8, threshold crossing: the last upward crossing of the verdict's threshold (as
// band power: a²/2) before the oscillating part, the level capped at the oscillating part's.
void threshold_onset(const BandTrace& b, double t0, const DetectionSettings& cfg, ShudderResult& r) {
  const std::size_t frames = b.dB.size();
  const double level_e = std::min(to_dB(0.5 * r.threshold_Nm * r.threshold_Nm), b.max_dB - cfg.oscillating_part_dB);
  std::size_t j_e = frames;
  for (std::size_t j = 0; j < b.ja; ++j)
    if (b.dB[j] <= level_e) j_e = j;
  r.growth_observed = j_e < frames;
  r.onset_time_s = t0;
  r.growth_acceleration_per_s2 = kNaN;
  if (r.growth_observed) r.onset_time_s = crossing_time_s(b, j_e, level_e);  // frame j_e + 1 <= ja lies above
}

}  // namespace

std::string_view to_string(Verdict v) {
  switch (v) {
    case Verdict::kNone: return "none";
    case Verdict::kVibration: return "vibration";
    case Verdict::kStickSlip: return "stick_slip";
  }
  return "none";
}

Verdict verdict_from_string(std::string_view name) {
  for (const Verdict v : kVerdicts)
    if (to_string(v) == name) return v;
  return Verdict::kNone;
}

ShudderDetector::ShudderDetector(const DetectionSettings& s) : settings_(s) {
  require(s.min_frequency_Hz > 0 && s.max_frequency_Hz > s.min_frequency_Hz,
          "detection band needs 0 < min_frequency_Hz < max_frequency_Hz");
  require(s.min_amplitude_Nm >= 0 && s.min_relative_amplitude >= 0, "amplitude thresholds must be >= 0");
  require(s.zero_slip_rpm >= 0, "zero_slip_rpm must be >= 0");
  require(s.min_stick_onsets >= 2, "min_stick_onsets must be >= 2 (a rate needs two stuck phases)");
  require(s.stick_cycle_fraction > 0 && s.stick_cycle_fraction <= 1, "stick_cycle_fraction must be in (0, 1]");
  require(s.oscillating_part_dB > 0 && s.onset_rise_dB > 0 && s.onset_below_max_dB > s.oscillating_part_dB,
          "oscillating_part_dB and onset_rise_dB must be > 0 and onset_below_max_dB > oscillating_part_dB");
  require(s.baseline_frames >= 1 && s.min_growth_frames >= 2, "baseline_frames must be >= 1, min_growth_frames >= 2");
  require(s.periods_per_frame >= 2 && s.periods_per_block >= 1,
          "periods_per_frame must be >= 2 and periods_per_block >= 1");
}

ShudderResult ShudderDetector::detect(const DetectionInput& in) const {
  check_input(in);
  const DetectionSettings& cfg = settings_;
  const std::size_t n = in.time_s.size();
  const double t0 = in.time_s[0];
  const double fs = static_cast<double>(n - 1) / (in.time_s[n - 1] - t0);
  const double f_max = std::min(cfg.max_frequency_Hz, 0.45 * fs);
  require(f_max > cfg.min_frequency_Hz, "sample rate " + std::to_string(fs) +
                                            " Hz is too low for the detection band from " +
                                            std::to_string(cfg.min_frequency_Hz) + " Hz");
  const std::span<const double> T = in.torque_Nm;

  ShudderResult r;
  for (double v : T) r.mean_torque_Nm += std::abs(v);
  r.mean_torque_Nm /= static_cast<double>(n);

  // 1. Coarse detrend over two periods of the lowest frequency searched.
  const std::vector<double> trend = moving_mean(T, 2.0 * fs / cfg.min_frequency_Hz);
  std::vector<double> x(n);
  for (std::size_t i = 0; i < n; ++i) x[i] = T[i] - trend[i];

  // 2. Preliminary frequency from the Welch PSD.
  WelchSettings welch;
  welch.segment_length = std::min(next_pow2(16.0 * fs / cfg.min_frequency_Hz), prev_pow2(n));
  const Psd psd = spectra_.welch_psd(x, fs, welch);
  const double f1 = peak_frequency_Hz(psd, Window::kHann, cfg.min_frequency_Hz, f_max);

  // 3. Spectrogram and band power around f1.
  SpectrogramSettings sg;
  sg.segment_length = std::clamp<std::size_t>(next_pow2(cfg.periods_per_frame * fs / f1), 16, prev_pow2(n));
  sg.hop = std::max<std::size_t>(1, sg.segment_length / 4);
  sg.end_frame = true;  // a judder growing in the last hop of the record is seen too
  const Spectrogram spec = spectra_.spectrogram(x, fs, sg, t0);
  r.band_times_s = spec.times_s;
  r.band_power = band_power(spec, f1 - 2.0 * spec.bin_width_Hz, f1 + 2.0 * spec.bin_width_Hz);
  const std::size_t frames = r.band_power.size();
  std::vector<double> b(frames);
  for (std::size_t j = 0; j < frames; ++j) b[j] = to_dB(r.band_power[j]);

  // 4. Oscillating part: frames within oscillating_part_dB of the largest band power.
  const double b_max = *std::max_element(b.begin(), b.end());
  std::size_t ja = 0, jb = 0;
  while (b[ja] < b_max - cfg.oscillating_part_dB) ++ja;
  for (std::size_t j = 0; j < frames; ++j)
    if (b[j] >= b_max - cfg.oscillating_part_dB) jb = j;
  const std::size_t i_a = spec.frame_start[ja], i_b = std::min(n, spec.frame_start[jb] + sg.segment_length);
  r.oscillating_from_s = in.time_s[i_a];
  r.oscillating_to_s = in.time_s[i_b - 1];

  // 5. Dominant frequency: interpolated Hann-FFT peak over the oscillating part.
  const std::size_t m = nice_length(i_b - i_a);
  const Spectrum s = spectra_.amplitude_spectrum(std::span<const double>(x).subspan(i_a, m), fs, Window::kHann);
  const double df = s.bin_width_Hz;
  const Peak peak = find_peak(s, std::max(cfg.min_frequency_Hz, std::min(0.8 * f1, f1 - 2 * df)),
                              std::min(f_max, std::max(1.2 * f1, f1 + 2 * df)));
  r.peak_frequency_Hz = peak.frequency_Hz;
  const double f_stick = stick_rate_Hz(in, i_a, i_b, cfg);
  const double fd = f_stick > 0.0 && f_stick < peak.frequency_Hz / 1.5 ? f_stick : peak.frequency_Hz;

  // 6. Amplitude, in blocks of periods.
  const double period = fs / fd;  // samples
  r.amplitude_Nm = block_amplitude_Nm(T, i_a, i_b, period, cfg);

  // 7. Verdict none below the amplitude threshold; else stick-slip or vibration by the share
  // of cycles that reach zero slip.
  r.threshold_Nm = std::max(cfg.min_amplitude_Nm, cfg.min_relative_amplitude * r.mean_torque_Nm);
  if (!(r.amplitude_Nm >= r.threshold_Nm)) {
    r.verdict = Verdict::kNone;
    r.frequency_Hz = r.onset_time_s = r.growth_rate_per_s = r.growth_acceleration_per_s2 = kNaN;
    r.at_onset = {kNaN, kNaN, kNaN, kNaN};
    return r;
  }
  r.frequency_Hz = fd;
  r.stick_cycle_fraction = stick_cycle_share(in, i_a, i_b, period, cfg);
  r.verdict = r.stick_cycle_fraction >= cfg.stick_cycle_fraction ? Verdict::kStickSlip : Verdict::kVibration;

  // 8. Onset. The growth line is fitted under every definition (its rate is reported); the
  // threshold crossing then places the onset itself.
  const BandTrace trace{spec.times_s, std::move(b), b_max, ja};
  growth_onset(trace, r.band_power, t0, cfg, r);
  if (cfg.onset_definition == OnsetDefinition::kThresholdCrossing) threshold_onset(trace, t0, cfg, r);

  // 9. Operating point: means over one period centred at the onset.
  const double u = (r.onset_time_s - t0) * fs;
  const auto p0 = static_cast<std::size_t>(std::clamp(std::lround(u - 0.5 * period), 0L, static_cast<long>(n - 1)));
  const auto p1 = static_cast<std::size_t>(
      std::clamp(std::lround(u + 0.5 * period), static_cast<long>(p0 + 1), static_cast<long>(n)));
  r.at_onset.time_s = r.onset_time_s;
  r.at_onset.slip_rpm = mean_over(in.slip_rpm, p0, p1);
  r.at_onset.interface_temp_C = mean_over(in.interface_temp_C, p0, p1);
  r.at_onset.normal_force_N = mean_over(in.normal_force_N, p0, p1);
  return r;
}

ShudderResult ShudderDetector::detect(const dynamics::Recording& rec) const {
  const auto required = [&](std::string_view name) {
    const auto* s = rec.find(name);
    require(s != nullptr, "shudder detection needs the signal '" + std::string(name) +
                              "' in the recording (a rig or prescribed-slip run records it)");
    return std::span<const double>(s->values);
  };
  const auto optional = [&](std::string_view name) {
    const auto* s = rec.find(name);
    return s ? std::span<const double>(s->values) : std::span<const double>();
  };
  namespace sn = dynamics::signal_names;
  DetectionInput in;
  in.time_s = required(sn::kTime);
  in.torque_Nm = required(sn::kTorque);
  in.slip_rpm = required(sn::kSlip);
  in.stuck = optional(sn::kStuck);
  in.interface_temp_C = optional(sn::kInterfaceMeanTemp);
  in.normal_force_N = optional(sn::kNormalForce);
  return detect(in);
}

ShudderResult detect_shudder(const dynamics::Recording& recording, const DetectionSettings& settings) {
  return ShudderDetector(settings).detect(recording);
}

ShudderResult detect_shudder(const DetectionInput& input, const DetectionSettings& settings) {
  return ShudderDetector(settings).detect(input);
}

}  // namespace shudder::analysis
