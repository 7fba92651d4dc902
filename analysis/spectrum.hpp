#pragma once
// Spectra of uniformly sampled signals with FFTW: windowed amplitude spectrum, Welch power
// spectral density, peak frequency with sub-bin interpolation, short-time spectra
// (spectrogram) and band power over time.
//
// Conventions (N samples x_n at rate fs, window w_n, DFT X_k = Σ_n w_n x_n e^{-2πi kn/N},
// bins k = 0 … N/2, bin width df = fs/N, frequency f_k = k df):
//
//   Windows (periodic, "DFT-even", so 50 % overlapped Hann segments sum to a constant):
//     rectangular  w_n = 1
//     Hann         w_n = ½ (1 − cos(2π n/N))
//     coherent gain S1 = Σ w_n (N, N/2), power sum S2 = Σ w_n² (N, 3N/8).
//
//   Single-sided amplitude spectrum (window amplitude correction):
//     A_k = c_k |X_k| / S1,  c_k = 2 for 0 < k < N/2, 1 at DC and (N even) Nyquist,
//     so a sine A sin(2π f_k t + φ) exactly on bin k reads A_k = A (for any window).
//
//   Welch power spectral density (Welch 1967), segments of length L with overlap, each
//   windowed (Hann by default) and optionally less its window-weighted mean Σwx/Σw (which
//   zeroes bin 0 and leaves tones a few bins off DC untouched), one-sided density, unit²/Hz:
//     P_k = mean over segments of  e_k |X_k|² / (fs S2),
//     e_k = 2 for 0 < k < L/2, 1 at DC and (L even) Nyquist; df = fs/L.
//   Parseval holds per segment exactly:  Σ_k P_k df = Σ_n (w_n x_n)² / S2, the window-weighted
//   mean square, which for a stationary signal is the mean square Σ x_n²/N (in expectation).
//   Segments start at 0, step, 2 step, … (step = round(L (1 − overlap))); when the last of
//   these ends short of the record's end, one more segment ends at the last sample (it overlaps
//   its neighbour by more than `overlap`). Why: the records judged here are transients, not
//   stationary noise: a judder that grows late in a run lives in the tail, and the regular
//   segments alone can leave up to L − 1 samples out (a 12.0 s record with 8.192 s segments
//   put only its first 8.19 s into the estimate). Welch (1967) averages K segments placed
//   anywhere: each modified periodogram has the same expectation for a stationary signal, so
//   the average stays unbiased and its normalisation per segment is unchanged; only the
//   variance reduction of the last pair is a little smaller (more overlap, more correlation).
//   SciPy's welch (padded=False, boundary=None) drops the tail instead; zero-padding the tail
//   (its stft with padded=True) would bias that segment's density low by the missing energy.
//   A record whose regular segments already reach its end is analysed exactly as before.
//
//   Peak with sub-bin interpolation. A tone at f = (k + δ) df, |δ| ≤ ½, puts |X_k| ∝ |W(δ)| in
//   its largest bin, with W(ν) = Σ_n w_n e^{-2πi ν n/N} the window's transform. From the ratio
//   α = |X_{k±1}| / |X_k| of the larger neighbour (k±1) to the peak bin (the window's own
//   kernel, exact for a single tone as N → ∞; Grandke 1983 for Hann):
//     rectangular  |W(ν)| ∝ |sinc ν|           ⇒  δ = ± α / (1 + α)
//     Hann         |W(ν)| ∝ |sinc ν| / (1 − ν²) ⇒  δ = ± (2α − 1) / (α + 1)
//   and the amplitude follows from the scalloping loss at that offset, evaluated exactly for
//   the finite window:  A = A_k · S1 / |W(δ)|.  For Hann the neighbour leakage of other tones
//   and of the negative-frequency image falls as 1/Δk³, so tones ~100 bins apart and from DC
//   are measured to ~1e-7 bin and ~1e-8 relative amplitude (tests/analysis/test_spectrum.cpp);
//   a plain 3-point parabola would leave up to a few hundredths of a bin, and the uncorrected
//   scalloping loss is up to 15 % (Hann at δ = ½: (2/π)/(3/4) = 0.849). With the rectangular
//   window the leakage falls only as 1/Δk (a lone tone k bins from DC: ~1/(2πk)).
//   Peaks closer than ~3 bins to each other are not separated by either window.
//
//   Spectrogram: frames of length L every `hop` samples, frame j starting at sample j·hop,
//   time centre t_0 + (j·hop + (L − 1)/2)/fs, each frame's one-sided PSD as above
//   (n_frames x n_bins). With end_frame (the shudder detector's choice), when the last regular
//   frame ends short of the record's end (by < hop samples) one more frame ends at the last
//   sample, so an oscillation in the record's last samples is seen; frame times are then not
//   uniform at the end (plots, which need a uniform grid, leave it off). Band power b_j = Σ_{f_lo ≤ f_k ≤ f_hi} P_jk df
//   is the mean square of the part of the signal in that band (unit²), the quantity used to find when an oscillation
//   starts.
//
// FFTW: an FftPlan is one r2c plan for one length (FFTW_ESTIMATE | FFTW_UNALIGNED, so it can
// be executed on any caller-owned arrays). FFTW's planner is not thread-safe: plan creation
// and destruction take a process-wide mutex; fftw_execute_dft_r2c on distinct arrays is
// thread-safe, so one plan may be shared by threads. SpectralAnalyzer caches one plan per
// length: repeated transforms of equal length reuse it.

#include <Eigen/Dense>
#include <complex>
#include <cstddef>
#include <map>
#include <memory>
#include <mutex>
#include <span>
#include <vector>

namespace shudder::analysis {

enum class Window { kRectangular, kHann };

/// Periodic window coefficients w_0 … w_{n-1} (see header). n >= 1.
std::vector<double> window_coefficients(Window window, std::size_t n);

/// |W(ν)| = |Σ_n w_n e^{-2πi ν n/n_samples}| for a frequency offset ν in bins (ν = 0: S1).
double window_transform_magnitude(Window window, std::size_t n, double offset_bins);

/// One FFTW real-to-complex plan for one transform length, created once and reused (RAII).
class FftPlan {
 public:
  /// Throws std::invalid_argument for n < 2.
  explicit FftPlan(std::size_t n);
  ~FftPlan();
  FftPlan(const FftPlan&) = delete;
  FftPlan& operator=(const FftPlan&) = delete;
  FftPlan(FftPlan&& other) noexcept;
  FftPlan& operator=(FftPlan&& other) noexcept;

  std::size_t size() const { return n_; }
  std::size_t bins() const { return n_ / 2 + 1; }

  /// out_k = Σ_n in_n e^{-2πi kn/N}, k = 0 … N/2. `in` has size() values (left unchanged:
  /// FFTW preserves the input of out-of-place r2c transforms), `out` bins() values.
  /// Thread-safe for distinct `out` arrays. Throws std::invalid_argument on wrong sizes.
  void execute(std::span<const double> in, std::span<std::complex<double>> out) const;

 private:
  std::size_t n_ = 0;
  void* plan_ = nullptr;  // fftw_plan (kept opaque so the header does not need fftw3.h)
};

/// Single-sided amplitude spectrum (unit of the signal), see header.
struct Spectrum {
  Window window = Window::kHann;
  std::size_t n_samples = 0;
  double sample_rate_Hz = 0.0;
  double bin_width_Hz = 0.0;
  std::vector<double> frequency_Hz;  // (n/2+1)
  std::vector<double> amplitude;     // (n/2+1)
};

/// A spectral peak: interpolated frequency and amplitude, the bin it was found in and the
/// interpolated offset from it (bins, |δ| ≤ ½).
struct Peak {
  double frequency_Hz = 0.0;
  double amplitude = 0.0;
  std::size_t bin = 0;
  double offset_bins = 0.0;
};

struct WelchSettings {
  std::size_t segment_length = 1024;
  double overlap = 0.5;  // fraction of a segment shared with the next, [0, 1)
  Window window = Window::kHann;
  bool remove_segment_mean = true;
};

/// One-sided power spectral density, unit²/Hz.
struct Psd {
  double bin_width_Hz = 0.0;
  std::size_t segments = 0;
  std::vector<double> frequency_Hz;  // (L/2+1)
  std::vector<double> density;       // (L/2+1)
};

struct SpectrogramSettings {
  std::size_t segment_length = 1024;
  std::size_t hop = 256;  // samples between frame starts, >= 1
  Window window = Window::kHann;
  bool remove_segment_mean = true;
  bool end_frame = false;  // one more frame ending at the last sample when hops stop short
};

struct Spectrogram {
  double bin_width_Hz = 0.0;
  std::vector<double> times_s;           // (n_frames) frame centres
  std::vector<std::size_t> frame_start;  // (n_frames) index of each frame's first sample
  std::vector<double> frequency_Hz;      // (n_bins)
  Eigen::MatrixXd power;                 // (n_frames x n_bins) one-sided PSD, unit²/Hz
};

/// Amplitude spectrum of x (x.size() == plan.size()). Throws std::invalid_argument on a size
/// mismatch or fs <= 0.
Spectrum amplitude_spectrum(const FftPlan& plan, std::span<const double> x, double sample_rate_Hz,
                            Window window = Window::kHann);

/// Largest amplitude bin with f_lo <= f_k <= f_hi, interpolated (see header). Throws
/// std::invalid_argument if no bin lies in the band.
Peak find_peak(const Spectrum& spectrum, double f_lo_Hz, double f_hi_Hz);

/// Welch PSD with segments of plan.size() samples (settings.segment_length is ignored here),
/// the last one aligned to the record's end when the regular ones stop short (see header).
/// Throws std::invalid_argument if x is shorter than one segment or the overlap is outside [0, 1).
Psd welch_psd(const FftPlan& plan, std::span<const double> x, double sample_rate_Hz,
              const WelchSettings& settings = {});

/// Frequency of the largest PSD bin in [f_lo, f_hi], interpolated on sqrt(P) with the window's
/// ratio rule (a segment-averaged tone keeps its |X| ratios).
double peak_frequency_Hz(const Psd& psd, Window window, double f_lo_Hz, double f_hi_Hz);

/// Spectrogram with frames of plan.size() samples (settings.segment_length is ignored here);
/// time of sample 0 is t0_s. Throws std::invalid_argument if x is shorter than one frame or
/// hop == 0.
Spectrogram spectrogram(const FftPlan& plan, std::span<const double> x, double sample_rate_Hz,
                        const SpectrogramSettings& settings = {}, double t0_s = 0.0);

/// Mean square of the band f_lo <= f <= f_hi per frame: Σ_k P_jk df (n_frames), unit².
std::vector<double> band_power(const Spectrogram& spectrogram, double f_lo_Hz, double f_hi_Hz);

/// First time at which `values` reaches `level`, linearly interpolated between the two
/// samples around the crossing; NaN if it never does. times and values have equal length.
double first_time_at_or_above(std::span<const double> times, std::span<const double> values, double level);

/// Caches one FftPlan per transform length and runs the spectra above with them. plan() is
/// thread-safe; references to plans stay valid for the analyser's lifetime.
class SpectralAnalyzer {
 public:
  const FftPlan& plan(std::size_t n) const;
  std::size_t cached_plans() const;

  Spectrum amplitude_spectrum(std::span<const double> x, double sample_rate_Hz, Window window = Window::kHann) const;
  Psd welch_psd(std::span<const double> x, double sample_rate_Hz, const WelchSettings& settings = {}) const;
  Spectrogram spectrogram(std::span<const double> x, double sample_rate_Hz, const SpectrogramSettings& settings = {},
                          double t0_s = 0.0) const;

 private:
  mutable std::mutex mutex_;
  mutable std::map<std::size_t, std::unique_ptr<FftPlan>> plans_;
};

}  // namespace shudder::analysis
