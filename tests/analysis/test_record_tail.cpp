// Every sample of a record counts: the Welch PSD's last segment and, with
// end_frame, the spectrogram's last frame end at the record's last sample
// (analysis/spectrum.hpp), so a judder that grows late in a run decides its verdict.
//
// Closed-form record (torque, N m; t in s):
//   T(t) = T_0 + B e^{−t/τ} sin(2π f_t t) + A e(t) sin(2π f t),
//   e(t) = g/√(1 + g²), g = ε e^{σ (t − t_g)} for t >= t_g, else 0,
// a decaying low-frequency start transient (a take-up) and a sine that grows from ε A at t_g and
// saturates at A, starting in the last ~30 % of the record, after the last whole regular Welch
// segment has ended (so the old segmentation had no sample of it). Slip is a steady 30 rpm, so
// the verdict is a vibration. Onset (threshold crossing): the amplitude A e(t) reaches the verdict's
// threshold a* = max(0.5 N m, 1 % mean |T|) at g* = (a*/A)/√(1 − (a*/A)²):
//   t* = t_g + ln(g*/ε)/σ.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <string>
#include <vector>

#include "analysis/shudder_detection.hpp"
#include "analysis/spectrum.hpp"
#include "core/units.hpp"
#include "tests/support/record_property.hpp"

namespace {

using namespace shudder::analysis;
using shudder::units::kTwoPi;

using shudder::test::record;

struct LateJudder {
  double fs_Hz, duration_s;
  double B_Nm, tau_s, f_t_Hz;                      // start transient
  double A_Nm, f_Hz, t_g_s, epsilon, sigma_per_s;  // late growing sine
  double T0_Nm = 40.0;
};

struct Record {
  std::vector<double> t, T, slip;
  double threshold_Nm = 0.0, onset_s = 0.0;
};

Record make(const LateJudder& c) {
  Record r;
  const auto n = static_cast<std::size_t>(std::lround(c.duration_s * c.fs_Hz)) + 1;
  double mean_abs = 0.0;
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / c.fs_Hz;
    const double g = t >= c.t_g_s ? c.epsilon * std::exp(c.sigma_per_s * (t - c.t_g_s)) : 0.0;
    const double T = c.T0_Nm + c.B_Nm * std::exp(-t / c.tau_s) * std::sin(kTwoPi * c.f_t_Hz * t) +
                     c.A_Nm * g / std::sqrt(1.0 + g * g) * std::sin(kTwoPi * c.f_Hz * t);
    r.t.push_back(t);
    r.T.push_back(T);
    r.slip.push_back(30.0);
    mean_abs += std::abs(T);
  }
  r.threshold_Nm = std::max(0.5, 0.01 * mean_abs / static_cast<double>(n));
  const double q = r.threshold_Nm / c.A_Nm;
  r.onset_s = c.t_g_s + std::log(q / std::sqrt(1.0 - q * q) / c.epsilon) / c.sigma_per_s;
  return r;
}

// The driveline's detection band (from 2 Hz: 8.192 s Welch segments at 1 kHz) on a 12.0 s record
// (one whole regular segment, 0–8.19 s, before the fix), and two other shapes: a 20 s record
// at 500 Hz (three regular 8.19 s segments, the last ending at 16.38 s) with a 17 Hz judder from
// 16.5 s, and 11.5 s at 2 kHz (one regular segment of 16384 samples, 0–8.19 s) with 55 Hz from
// 8.3 s.
class DetectionRecordTail : public ::testing::TestWithParam<LateJudder> {};

// Frequency tolerance: the dominant frequency is the Hann-interpolated peak over the
// oscillating part (≥ 2.5 s here, bins ≤ 0.4 Hz); the ratio rule is exact for a steady tone and
// the growing head of the envelope biases it (measured 0.01–0.07 bin here): 0.15 bin. Onset
// tolerance: band power is a Hann-weighted mean over a frame (8 periods) and frames are a
// quarter frame apart; for e^{2σt} growth the frame mean leads its centre by
// ln(1 + 2σ² var_Hann)/(2σ) (var_Hann = 0.0327 frame², < 0.02 s here) and the dB-linear
// interpolation between frames is exact for exponential growth: one hop.
TEST_P(DetectionRecordTail, LateJudderAfterAStartTransientIsJudgedAtItsFrequencyAndOnset) {
  const LateJudder& c = GetParam();
  const Record rec = make(c);
  DetectionSettings cfg;
  cfg.min_frequency_Hz = 2.0;
  cfg.max_frequency_Hz = 400.0;
  cfg.onset_definition = OnsetDefinition::kThresholdCrossing;
  const ShudderResult r = detect_shudder(DetectionInput{rec.t, rec.T, rec.slip, {}, {}, {}}, cfg);
  const double period_samples = c.fs_Hz / c.f_Hz;
  const double frame_samples = std::exp2(std::ceil(std::log2(cfg.periods_per_frame * period_samples)));
  const double hop_s = 0.25 * frame_samples / c.fs_Hz;
  // The FFT spans the largest 2^a 3^b 5^c samples within the oscillating part (>= 90 % of it
  // at these lengths): its bin is at most fs / (0.9 × span).
  const double span = (r.oscillating_to_s - r.oscillating_from_s) * c.fs_Hz;
  const double bin_Hz = c.fs_Hz / (0.9 * span);
  record("record_tail_" + std::to_string(static_cast<int>(c.f_Hz)),
         "%s %.4f Hz (true %.4f, bin >= %.3f Hz), onset %.4f s (closed form %.4f, hop %.4f s), A %.3f N m, "
         "oscillating %.3f-%.3f s",
         std::string(to_string(r.verdict)).c_str(), r.frequency_Hz, c.f_Hz, bin_Hz, r.onset_time_s, rec.onset_s, hop_s,
         r.amplitude_Nm, r.oscillating_from_s, r.oscillating_to_s);
  EXPECT_EQ(r.verdict, Verdict::kVibration);
  EXPECT_NEAR(r.frequency_Hz, c.f_Hz, 0.15 * bin_Hz);
  EXPECT_NEAR(r.onset_time_s, rec.onset_s, hop_s);
  EXPECT_NEAR(r.amplitude_Nm, c.A_Nm, 0.05 * c.A_Nm);  // the saturated sine: e(t) > 0.995 at the end
}

INSTANTIATE_TEST_SUITE_P(Shapes, DetectionRecordTail,
                         ::testing::Values(LateJudder{1000.0, 12.0, 10.0, 1.5, 2.5, 8.0, 31.0, 8.6, 0.01, 5.0},
                                           LateJudder{500.0, 20.0, 6.0, 2.0, 3.0, 6.0, 17.0, 16.5, 0.02, 4.0},
                                           LateJudder{2000.0, 11.5, 8.0, 1.0, 2.2, 10.0, 55.0, 8.3, 0.01, 6.0}));

// White noise of variance σ² on a record whose regular 1024-sample segments (50 % overlap)
// end 188 samples short of the record's end: 2048 regular segments and one more ending at the last
// sample. Σ_k P_k df equals the mean of the 2049 segments' window-weighted mean squares to
// round-off (Parseval per segment, the same normalisation for the extra one), and the level is
// the one-sided white density 2σ²/fs within statistics (per segment 6.2 % relative std, over
// ~2049 partly correlated segments ~0.15 %, plus the record's own √(2/n) = 0.14 %: 1e-2 is
// > 4 standard deviations).
TEST(SpectrumWelchTail, WhiteNoiseWithATailKeepsParsevalAndItsLevel) {
  const double fs = 20000.0, sigma = 0.7;
  const std::size_t L = 1024, n = (1u << 20) + 700;
  std::mt19937_64 rng(777);
  std::normal_distribution<double> g(0.0, sigma);
  std::vector<double> x(n);
  for (double& v : x) v = g(rng);
  WelchSettings cfg;
  cfg.segment_length = L;
  cfg.remove_segment_mean = false;
  const FftPlan plan(L);
  const Psd p = welch_psd(plan, x, fs, cfg);
  ASSERT_EQ(p.segments, 2049u);

  const auto w = window_coefficients(Window::kHann, L);
  double s2 = 0.0;
  for (double v : w) s2 += v * v;
  std::vector<std::size_t> starts;
  for (std::size_t s = 0; s + L <= n; s += L / 2) starts.push_back(s);
  starts.push_back(n - L);
  double weighted = 0.0;
  for (std::size_t s : starts)
    for (std::size_t i = 0; i < L; ++i) weighted += std::pow(w[i] * x[s + i], 2) / s2;
  weighted /= static_cast<double>(starts.size());
  double power = 0.0, level = 0.0;
  for (double d : p.density) power += d * p.bin_width_Hz;
  for (std::size_t k = 1; k + 1 < p.density.size(); ++k) level += p.density[k];
  level /= static_cast<double>(p.density.size() - 2);
  record("welch_tail_noise", "sum(P) df / weighted - 1 = %.3e, level / (2 sigma^2/fs) - 1 = %.3e",
         power / weighted - 1.0, level / (2 * sigma * sigma / fs) - 1.0);
  EXPECT_NEAR(power / weighted, 1.0, 1e-12);
  EXPECT_NEAR(level / (2 * sigma * sigma / fs), 1.0, 1e-2);
}

// A record that is zero except for a tone in its last 100 samples (past every regular segment):
// the PSD holds exactly the end segment's windowed energy over the segment count; before the
// fix it was identically zero. A record the regular segments cover exactly gets no extra one.
TEST(SpectrumWelchTail, ToneInTheLastSamplesIsInTheEstimateAndAnExactFitGetsNoExtraSegment) {
  const double fs = 1000.0;
  const std::size_t L = 256, n = 3 * 128 + 256 + 100;  // regular segments end 100 samples short
  std::vector<double> x(n, 0.0);
  for (std::size_t i = n - 100; i < n; ++i) x[i] = std::sin(kTwoPi * 97.0 * static_cast<double>(i) / fs);
  WelchSettings cfg;
  cfg.segment_length = L;
  cfg.remove_segment_mean = false;
  const FftPlan plan(L);
  const Psd p = welch_psd(plan, x, fs, cfg);
  ASSERT_EQ(p.segments, 5u);
  const auto w = window_coefficients(Window::kHann, L);
  double s2 = 0.0, end_energy = 0.0;
  for (double v : w) s2 += v * v;
  for (std::size_t i = 0; i < L; ++i) end_energy += std::pow(w[i] * x[n - L + i], 2);
  double power = 0.0;
  for (double d : p.density) power += d * p.bin_width_Hz;
  EXPECT_GT(end_energy, 0.0);
  EXPECT_NEAR(power, end_energy / s2 / 5.0, 1e-12 * end_energy / s2);

  const std::vector<double> exact(4 * 128 + 256, 1.0);  // regular segments end at its last sample
  EXPECT_EQ(welch_psd(plan, exact, fs, cfg).segments, 5u);
}

// Spectrogram with end_frame: frames at j·hop as before, plus one starting at n − L when the
// regular frames stop short; a sine switched on in the record's last hop shows only there.
TEST(SpectrumSpectrogramTail, EndFrameEndsAtTheLastSampleAndSeesASineStartingThere) {
  const double fs = 8000.0, f = 250.3, t0 = 0.25;
  const std::size_t L = 512, hop = 128, n = 4000;  // regular frames end at 3968
  std::vector<double> x(n, 0.0);
  for (std::size_t i = n - 30; i < n; ++i) x[i] = std::sin(kTwoPi * f * static_cast<double>(i) / fs);
  SpectrogramSettings cfg;
  cfg.segment_length = L;
  cfg.hop = hop;
  SpectralAnalyzer sa;
  const Spectrogram plain = sa.spectrogram(x, fs, cfg, t0);
  cfg.end_frame = true;
  const Spectrogram s = sa.spectrogram(x, fs, cfg, t0);
  const std::size_t regular = 1 + (n - L) / hop;
  ASSERT_EQ(plain.times_s.size(), regular);
  ASSERT_EQ(s.times_s.size(), regular + 1);
  EXPECT_EQ(s.frame_start.back(), n - L);
  EXPECT_EQ(s.frame_start[regular - 1], (regular - 1) * hop);
  EXPECT_DOUBLE_EQ(s.times_s.back(), t0 + (static_cast<double>(n - L) + 0.5 * (L - 1)) / fs);
  const auto bp_plain = band_power(plain, f - 3 * s.bin_width_Hz, f + 3 * s.bin_width_Hz);
  const auto bp = band_power(s, f - 3 * s.bin_width_Hz, f + 3 * s.bin_width_Hz);
  for (double v : bp_plain) EXPECT_EQ(v, 0.0);
  EXPECT_GT(bp.back(), 0.0);
  // The frames both have are identical.
  for (std::size_t j = 0; j < regular; ++j) EXPECT_EQ(bp[j], bp_plain[j]);
}

}  // namespace
