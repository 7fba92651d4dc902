// Spectra (analysis/spectrum): FFT convention, windowed amplitude spectrum with sub-bin peak
// interpolation, Welch PSD against Parseval, spectrogram timing, FFTW plan reuse.
//
//   x_n = Σ_i A_i sin(2π f_i n/fs + φ_i),  f_i = (k_i + δ_i) df off-bin,  df = fs/N
//   Hann: |X_{k±1}|/|X_k| = (1 ± δ)/(2 ∓ δ)  ⇒  δ = (2α − 1)/(α + 1)   (exact for one tone, N → ∞)
//         A = A_k · S1/|W(δ)|   (undo the scalloping loss, up to 15 % at δ = ½)
//   Welch: Σ_k P_k df = Σ_n (w_n x_n)²/Σ_n w_n²  (per segment, exact)
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <cmath>
#include <complex>
#include <cstdio>
#include <numbers>
#include <random>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include "analysis/spectrum.hpp"
#include "core/units.hpp"
#include "tests/support/record_property.hpp"

namespace {

using namespace shudder::analysis;
using ::testing::HasSubstr;

using shudder::units::kTwoPi;

using shudder::test::record;

struct Tone {
  double f_Hz, amplitude, phase;
};

std::vector<double> tones(const std::vector<Tone>& ts, std::size_t n, double fs, double offset = 0.0) {
  std::vector<double> x(n, offset);
  for (std::size_t i = 0; i < n; ++i)
    for (const auto& t : ts) x[i] += t.amplitude * std::sin(kTwoPi * t.f_Hz * static_cast<double>(i) / fs + t.phase);
  return x;
}

// The FFT convention X_k = Σ x_n e^{-2πi kn/N} against a direct DFT (odd and even lengths).
TEST(SpectrumFft, MatchesDirectDftForOddAndEvenLengths) {
  for (std::size_t n : {12u, 15u}) {
    SCOPED_TRACE(n);
    std::mt19937 rng(7);
    std::uniform_real_distribution<double> u(-1.0, 1.0);
    std::vector<double> x(n);
    for (double& v : x) v = u(rng);
    const FftPlan plan(n);
    std::vector<std::complex<double>> X(plan.bins());
    plan.execute(x, X);
    ASSERT_EQ(X.size(), n / 2 + 1);
    for (std::size_t k = 0; k < X.size(); ++k) {
      std::complex<double> d = 0.0;
      for (std::size_t i = 0; i < n; ++i)
        d += x[i] * std::polar(1.0, -kTwoPi * static_cast<double>(k * i) / static_cast<double>(n));
      EXPECT_NEAR(std::abs(X[k] - d), 0.0, 1e-12);  // round-off of a length-15 sum of O(1) terms
    }
  }
}

// A sum of off-bin sines (and a DC offset) through the Hann window: every tone's frequency
// within 0.1 bin and amplitude within 1 %. Reachable because the interpolation uses the Hann
// kernel's exact neighbour ratio and the amplitude undoes the scalloping loss at the
// interpolated offset; what is left is leakage of the other tones and of each tone's
// negative-frequency image through the Hann sidelobes (falling as 1/Δk³: ≲ 1e-6 at the
// tones' >= 200-bin separations), so the measured errors are ~6e-8 bin and ~1e-8 relative,
// far inside the spec. The raw peak bin alone is off by up to the scalloping loss (15 % at
// δ = ½), shown for the tone placed near half a bin.
TEST(SpectrumFft, SumOfOffBinSinesGivesFrequencyWithinATenthBinAndAmplitudeWithinOnePercent) {
  const double fs = 10000.0;
  const std::size_t n = 8192;
  const double df = fs / static_cast<double>(n);
  const std::vector<Tone> ts = {{(101 + 0.31) * df, 1.0, 0.3},
                                {(310 + 0.49) * df, 0.25, 1.1},
                                {(828 + 0.77) * df, 3.0, -0.7},
                                {(1500 + 0.05) * df, 0.5, 2.0}};
  const auto x = tones(ts, n, fs, 5.0);
  const FftPlan plan(n);
  const Spectrum s = amplitude_spectrum(plan, x, fs, Window::kHann);
  ASSERT_DOUBLE_EQ(s.bin_width_Hz, df);
  double worst_f = 0.0, worst_a = 0.0;
  for (const auto& t : ts) {
    SCOPED_TRACE(t.f_Hz);
    const Peak p = find_peak(s, t.f_Hz - 10 * df, t.f_Hz + 10 * df);
    const double ef = std::abs(p.frequency_Hz - t.f_Hz) / df, ea = std::abs(p.amplitude / t.amplitude - 1.0);
    worst_f = std::max(worst_f, ef);
    worst_a = std::max(worst_a, ea);
    EXPECT_LT(ef, 0.1);
    EXPECT_LT(ea, 0.01);
  }
  record("hann_sum_of_sines", "worst frequency error %.2e bin, worst amplitude error %.2e", worst_f, worst_a);
  // The DC offset reads as itself at bin 0 (factor 1, not 2), to the tones' leakage.
  EXPECT_NEAR(s.amplitude[0], 5.0, 1e-3);
  // Without the scalloping correction the tone at δ = 0.49 reads ~15 % low.
  const Peak p = find_peak(s, ts[1].f_Hz - 10 * df, ts[1].f_Hz + 10 * df);
  EXPECT_LT(s.amplitude[p.bin] / ts[1].amplitude, 0.86);
}

// Rectangular window, one off-bin tone: the same ratio rule with |W| ∝ |sinc ν| gives
// δ = α/(1 + α). Its sidelobes fall only as 1/Δk, so the negative-frequency image (2k bins
// away) leaks ~1/(2π k) ≈ 3e-4 of the amplitude at k ≈ 500: frequency within 0.1 bin and
// amplitude within 1 % still hold for a lone tone far from DC.
TEST(SpectrumFft, RectangularWindowSingleToneWithinATenthBinAndOnePercent) {
  const double fs = 4096.0;
  const std::size_t n = 4096;
  const Tone t{523.37, 2.0, 0.4};
  const FftPlan plan(n);
  const Spectrum s = amplitude_spectrum(plan, tones({t}, n, fs), fs, Window::kRectangular);
  const Peak p = find_peak(s, 500.0, 550.0);
  record("rectangular_single_tone", "frequency error %.2e bin, amplitude error %.2e", std::abs(p.frequency_Hz - t.f_Hz),
         p.amplitude / t.amplitude - 1.0);
  EXPECT_LT(std::abs(p.frequency_Hz - t.f_Hz) / s.bin_width_Hz, 0.1);
  EXPECT_NEAR(p.amplitude / t.amplitude, 1.0, 0.01);
}

// The window transform at zero offset is the coherent gain S1 (N and N/2), and Hann's
// scalloping loss at half a bin is (2/π)/(3/4) = 0.8488 for large N.
TEST(SpectrumWindow, CoherentGainAndHannScallopingLoss) {
  const std::size_t n = 4096;
  EXPECT_NEAR(window_transform_magnitude(Window::kRectangular, n, 0.0), 4096.0, 1e-9);
  EXPECT_NEAR(window_transform_magnitude(Window::kHann, n, 0.0), 2048.0, 1e-9);
  // Finite-N departure from the N → ∞ kernel is O(1/N²) ~ 1e-7.
  EXPECT_NEAR(window_transform_magnitude(Window::kHann, n, 0.5) / 2048.0, (2.0 / std::numbers::pi) / 0.75, 1e-6);
}

// Welch PSD and Parseval. (a) Deterministic: off-bin sines have mean square Σ A²/2; the
// window-weighted mean square per segment differs from it only through the Hann² transform at
// twice a tone's frequency or at the tones' difference frequencies (> 38 bins, falling as
// 1/Δk⁵: < 1e-7) and by removing each segment's window-weighted mean (Hann leakage from
// > 19 bins: ~1e-8 of the energy): relative 1e-6 (measured 1.5e-9). (b) Seeded white noise (2^20 samples, 1024-sample
// segments, 50 % overlap): Σ P df equals the segments' window-weighted mean square to round-off (1e-12), and the
// record's plain mean square within statistics: per segment the relative std is
// √(2 Σw⁴/(Σw²)²) = √(3.89/L) = 6.2 %, over 2047 segments (adjacent overlap correlation 3/35)
// 0.15 %, plus the record's own √(2/n) = 0.14 %: 1e-2 is > 4 standard deviations. The level
// itself is the one-sided white density 2σ²/fs within the same statistics (1e-2).
TEST(SpectrumWelch, ParsevalForSinesAndWhiteNoise) {
  const double fs = 20000.0;
  WelchSettings cfg;
  cfg.segment_length = 1024;
  cfg.overlap = 0.5;
  const FftPlan plan(cfg.segment_length);
  {
    const std::vector<Tone> ts = {{378.3, 2.0, 0.1}, {1234.5, 0.7, 0.9}, {4001.1, 0.3, 2.5}};
    const auto x = tones(ts, 200000, fs);
    const Psd p = welch_psd(plan, x, fs, cfg);
    double power = 0.0, ms = 0.0;
    for (double d : p.density) power += d * p.bin_width_Hz;
    for (const auto& t : ts) ms += 0.5 * t.amplitude * t.amplitude;
    record("welch_parseval_sines", "sum(P) df = %.8f, mean square %.8f, rel %.2e, %zu segments", power, ms,
           power / ms - 1.0, p.segments);
    EXPECT_NEAR(power / ms, 1.0, 1e-6);
    EXPECT_NEAR(peak_frequency_Hz(p, Window::kHann, 300.0, 450.0), 378.3, 0.1 * p.bin_width_Hz);
  }
  {
    const std::size_t n = 1u << 20;
    const double sigma = 0.7;
    std::mt19937_64 rng(12345);
    std::normal_distribution<double> g(0.0, sigma);
    std::vector<double> x(n);
    for (double& v : x) v = g(rng);
    cfg.remove_segment_mean = false;
    const Psd p = welch_psd(plan, x, fs, cfg);
    double power = 0.0, ms = 0.0, weighted = 0.0;
    for (double d : p.density) power += d * p.bin_width_Hz;
    for (double v : x) ms += v * v;
    ms /= static_cast<double>(n);
    const auto w = window_coefficients(Window::kHann, cfg.segment_length);
    double s2 = 0.0;
    for (double v : w) s2 += v * v;
    for (std::size_t start = 0; start + cfg.segment_length <= n; start += cfg.segment_length / 2)
      for (std::size_t i = 0; i < cfg.segment_length; ++i) weighted += std::pow(w[i] * x[start + i], 2) / s2;
    weighted /= static_cast<double>(p.segments);
    double level = 0.0;
    for (std::size_t k = 1; k + 1 < p.density.size(); ++k) level += p.density[k];
    level /= static_cast<double>(p.density.size() - 2);
    record("welch_parseval_noise",
           "sum(P) df / mean square - 1 = %.3e, vs weighted %.3e, level / (2 sigma^2/fs) - 1 = %.3e", power / ms - 1.0,
           power / weighted - 1.0, level / (2 * sigma * sigma / fs) - 1.0);
    EXPECT_EQ(p.segments, 2047u);
    EXPECT_NEAR(power / weighted, 1.0, 1e-12);
    EXPECT_NEAR(power / ms, 1.0, 1e-2);
    EXPECT_NEAR(level / (2 * sigma * sigma / fs), 1.0, 1e-2);
  }
}

// A sine switched on at t_s: the Hann frame centred at t_s holds exactly half of the steady
// windowed energy (the window is symmetric), so the band power crosses half its steady level
// at t_s; frames are one hop apart, so the interpolated crossing lies within one hop of t_s.
TEST(SpectrumSpectrogram, LocatesTheStartOfASineWithinOneHop) {
  const double fs = 8000.0, t_s = 0.61234, f = 250.3;
  const std::size_t n = 12000;
  std::vector<double> x(n, 0.0);
  for (std::size_t i = 0; i < n; ++i) {
    const double t = static_cast<double>(i) / fs;
    if (t >= t_s) x[i] = std::sin(kTwoPi * f * t);
  }
  SpectrogramSettings cfg;
  cfg.segment_length = 512;
  cfg.hop = 64;
  SpectralAnalyzer sa;
  const double t0 = 1.5;  // time of sample 0 shifts every frame centre
  const Spectrogram s = sa.spectrogram(x, fs, cfg, t0);
  ASSERT_EQ(s.times_s.size(), 1 + (n - 512) / 64);
  EXPECT_DOUBLE_EQ(s.times_s[0], t0 + 255.5 / fs);
  EXPECT_EQ(s.power.rows(), static_cast<Eigen::Index>(s.times_s.size()));
  EXPECT_EQ(s.power.cols(), 257);
  const auto bp = band_power(s, f - 3 * s.bin_width_Hz, f + 3 * s.bin_width_Hz);
  const double steady = bp.back();
  EXPECT_NEAR(steady, 0.5, 0.01);  // mean square of a unit sine; 3 bins each side hold > 99.9 %
  const double t_on = first_time_at_or_above(s.times_s, bp, 0.5 * steady) - t0;
  const double hop_s = 64.0 / fs;
  record("spectrogram_start", "found %.5f s for %.5f s: error %.2f hop", t_on, t_s, (t_on - t_s) / hop_s);
  EXPECT_LE(std::abs(t_on - t_s), hop_s);
}

// The same plan used for many transforms gives bit-identical results, from one thread or two
// sharing it; the analyser makes one plan per length and reuses it.
TEST(SpectrumPlan, ReusedPlanGivesIdenticalResultsAndTheAnalyserCachesOnePlanPerLength) {
  const std::size_t n = 4096;
  std::mt19937 rng(3);
  std::normal_distribution<double> g;
  std::vector<std::vector<double>> xs(40, std::vector<double>(n));
  for (auto& x : xs)
    for (double& v : x) v = g(rng);
  const FftPlan plan(n);
  std::vector<std::complex<double>> first(plan.bins()), again(plan.bins()), other(plan.bins());
  plan.execute(xs[0], first);
  for (const auto& x : xs) plan.execute(x, other);
  plan.execute(xs[0], again);
  EXPECT_EQ(first, again);
  // A second plan of the same length computes the same numbers.
  FftPlan original(n);
  const FftPlan moved(std::move(original));
  moved.execute(xs[0], other);
  EXPECT_EQ(first, other);

  // Two threads executing the shared plan on their own arrays.
  std::vector<std::vector<std::complex<double>>> serial(xs.size()), parallel(xs.size());
  for (std::size_t i = 0; i < xs.size(); ++i) {
    serial[i].resize(plan.bins());
    parallel[i].resize(plan.bins());
    plan.execute(xs[i], serial[i]);
  }
  const auto worker = [&](std::size_t from) {
    for (std::size_t i = from; i < xs.size(); i += 2) plan.execute(xs[i], parallel[i]);
  };
  std::thread a(worker, 0), b(worker, 1);
  a.join();
  b.join();
  EXPECT_EQ(serial, parallel);

  SpectralAnalyzer sa;
  const Spectrum s1 = sa.amplitude_spectrum(xs[0], 1000.0);
  for (const auto& x : xs) sa.amplitude_spectrum(x, 1000.0);
  const Spectrum s2 = sa.amplitude_spectrum(xs[0], 1000.0);
  EXPECT_EQ(s1.amplitude, s2.amplitude);
  EXPECT_EQ(sa.cached_plans(), 1u);
  EXPECT_EQ(&sa.plan(n), &sa.plan(n));
  sa.amplitude_spectrum(std::span<const double>(xs[0]).first(1000), 1000.0);
  EXPECT_EQ(sa.cached_plans(), 2u);
}

TEST(SpectrumInput, BadArgumentsAreRejectedWithTheirReason) {
  const FftPlan plan(64);
  const std::vector<double> x(32, 1.0);
  EXPECT_THAT([&] { amplitude_spectrum(plan, x, 100.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("plan of length 64")));
  EXPECT_THAT([&] { welch_psd(plan, x, 100.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("shorter than one segment")));
  EXPECT_THAT([] { FftPlan p(1); }, ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("at least 2")));
  const Spectrum s = amplitude_spectrum(plan, std::vector<double>(64, 1.0), 64.0);
  EXPECT_THAT([&] { find_peak(s, 40.0, 50.0); },
              ::testing::ThrowsMessage<std::invalid_argument>(HasSubstr("no spectral bin")));
}

}  // namespace
