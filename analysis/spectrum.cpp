#include "analysis/spectrum.hpp"

#include <fftw3.h>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "analysis/fftw_wisdom.hpp"
#include "core/units.hpp"

namespace shudder::analysis {

namespace {

using units::kTwoPi;

// FFTW's planner (plan creation and destruction) is not thread-safe; execution is.
std::mutex& planner_mutex() {
  static std::mutex m;
  return m;
}

// Every FftPlan's flags, and the flags the shipped wisdom was made with (fftw_wisdom.hpp):
// FFTW_ESTIMATE does not touch the arrays; FFTW_UNALIGNED lets execute() run on any arrays.
constexpr unsigned kPlannerFlags = FFTW_ESTIMATE | FFTW_UNALIGNED;

// Whether the shipped wisdom was offered to FFTW / accepted (guarded by planner_mutex()).
bool wisdom_offered = false;
bool wisdom_accepted = false;

// Imports the shipped wisdom before the process' first plan. Caller holds planner_mutex().
void offer_shipped_wisdom() {
  if (wisdom_offered) return;
  wisdom_offered = true;
  // 0: another FFTW build made it; FFTW then plans as it would without wisdom.
  wisdom_accepted = fftw_import_wisdom_from_string(kShippedFftwWisdom) != 0;
}

void require_valid(bool ok, const std::string& what) {
  if (!ok) throw std::invalid_argument(what);
}

double sum(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x;
  return s;
}

double sum_of_squares(const std::vector<double>& v) {
  double s = 0.0;
  for (double x : v) s += x * x;
  return s;
}

// e_k of the one-sided spectrum: 2 for interior bins, 1 at DC and (n even) Nyquist.
double one_sided_factor(std::size_t k, std::size_t n) {
  if (k == 0) return 1.0;
  if (n % 2 == 0 && k == n / 2) return 1.0;
  return 2.0;
}

std::vector<double> bin_frequencies(std::size_t n, double fs) {
  std::vector<double> f(n / 2 + 1);
  for (std::size_t k = 0; k < f.size(); ++k) f[k] = static_cast<double>(k) * fs / static_cast<double>(n);
  return f;
}

// Sub-bin offset δ of a tone whose largest bin is k, from the larger neighbour ratio with the
// window's own kernel (see header). mag has the bins' magnitudes (any common scale).
double interpolate_offset(std::span<const double> mag, std::size_t k, Window window) {
  if (k == 0 || k + 1 >= mag.size() || !(mag[k] > 0.0)) return 0.0;
  const bool right = mag[k + 1] >= mag[k - 1];
  const double alpha = (right ? mag[k + 1] : mag[k - 1]) / mag[k];
  double delta = 0.0;
  switch (window) {
    case Window::kRectangular: delta = alpha / (1.0 + alpha); break;
    case Window::kHann: delta = (2.0 * alpha - 1.0) / (alpha + 1.0); break;
  }
  // A peak bin has α <= 1, so δ <= ½; noise can push Hann's δ below 0 (α < ½): clamp.
  delta = std::clamp(delta, 0.0, 0.5);
  return right ? delta : -delta;
}

// Index of the largest value among bins with f_lo <= f_k <= f_hi.
std::size_t argmax_in_band(std::span<const double> f, std::span<const double> v, double lo, double hi) {
  std::size_t best = f.size();
  for (std::size_t k = 0; k < f.size(); ++k) {
    if (f[k] < lo || f[k] > hi) continue;
    if (best == f.size() || v[k] > v[best]) best = k;
  }
  require_valid(best < f.size(), "no spectral bin lies in the band " + std::to_string(lo) + " – " + std::to_string(hi) +
                                     " Hz; widen the band or use a longer record");
  return best;
}

// Windowed copy of x[start, start + n) into buf, optionally less its window-weighted mean
// μ = Σ w x / Σ w. That mean makes bin 0 exactly zero and, unlike the plain mean, is itself
// blind to tones a few bins from DC (the window's leakage), so removing it leaves their
// energy unchanged; the plain mean of a sine over a non-integer number of cycles (~A/(π k))
// would add its square to the windowed energy (2e-4 of it at k ≈ 20).
void windowed_segment(std::span<const double> x, std::size_t start, const std::vector<double>& w, bool remove_mean,
                      std::vector<double>& buf) {
  const std::size_t n = w.size();
  double mean = 0.0;
  if (remove_mean) {
    double sw = 0.0;
    for (std::size_t i = 0; i < n; ++i) {
      mean += w[i] * x[start + i];
      sw += w[i];
    }
    mean /= sw;
  }
  for (std::size_t i = 0; i < n; ++i) buf[i] = w[i] * (x[start + i] - mean);
}

}  // namespace

std::vector<double> window_coefficients(Window window, std::size_t n) {
  require_valid(n >= 1, "a window needs at least 1 sample");
  std::vector<double> w(n, 1.0);
  if (window == Window::kHann)
    for (std::size_t i = 0; i < n; ++i)
      w[i] = 0.5 * (1.0 - std::cos(kTwoPi * static_cast<double>(i) / static_cast<double>(n)));
  return w;
}

double window_transform_magnitude(Window window, std::size_t n, double offset_bins) {
  const std::vector<double> w = window_coefficients(window, n);
  std::complex<double> s = 0.0;
  const double dphi = -kTwoPi * offset_bins / static_cast<double>(n);
  for (std::size_t i = 0; i < n; ++i) s += w[i] * std::polar(1.0, dphi * static_cast<double>(i));
  return std::abs(s);
}

// ---------------------------------------------------------------------------------------------
// FftPlan

FftPlan::FftPlan(std::size_t n) : n_(n) {
  require_valid(n >= 2, "an FFT needs at least 2 samples, got " + std::to_string(n));
  std::lock_guard<std::mutex> lock(planner_mutex());
  offer_shipped_wisdom();
  double* in = fftw_alloc_real(n);
  fftw_complex* out = fftw_alloc_complex(n / 2 + 1);
  plan_ = fftw_plan_dft_r2c_1d(static_cast<int>(n), in, out, kPlannerFlags);
  fftw_free(in);
  fftw_free(out);
  if (plan_ == nullptr) throw std::runtime_error("FFTW could not plan a transform of length " + std::to_string(n));
}

FftPlan::~FftPlan() {
  if (plan_ == nullptr) return;
  std::lock_guard<std::mutex> lock(planner_mutex());
  fftw_destroy_plan(static_cast<fftw_plan>(plan_));
}

FftPlan::FftPlan(FftPlan&& other) noexcept : n_(other.n_), plan_(other.plan_) {
  other.plan_ = nullptr;
  other.n_ = 0;
}

FftPlan& FftPlan::operator=(FftPlan&& other) noexcept {
  if (this != &other) {
    if (plan_ != nullptr) {
      std::lock_guard<std::mutex> lock(planner_mutex());
      fftw_destroy_plan(static_cast<fftw_plan>(plan_));
    }
    n_ = other.n_;
    plan_ = other.plan_;
    other.plan_ = nullptr;
    other.n_ = 0;
  }
  return *this;
}

void FftPlan::execute(std::span<const double> in, std::span<std::complex<double>> out) const {
  require_valid(plan_ != nullptr, "FftPlan used after being moved from");
  require_valid(in.size() == n_ && out.size() == bins(),
                "FftPlan of length " + std::to_string(n_) + " needs " + std::to_string(n_) + " inputs and " +
                    std::to_string(bins()) + " outputs, got " + std::to_string(in.size()) + " and " +
                    std::to_string(out.size()));
  // r2c out-of-place preserves its input (FFTW_PRESERVE_INPUT is the default for r2c), so the
  // const_cast only satisfies the C signature. std::complex<double> is layout-compatible with
  // fftw_complex (FFTW manual §4.1.1).
  fftw_execute_dft_r2c(static_cast<fftw_plan>(plan_), const_cast<double*>(in.data()),
                       reinterpret_cast<fftw_complex*>(out.data()));
}

std::string fftw_wisdom_for_lengths(std::span<const std::size_t> lengths) {
  std::lock_guard<std::mutex> lock(planner_mutex());
  fftw_forget_wisdom();
  wisdom_offered = true;  // forgotten on purpose: later plans plan afresh
  wisdom_accepted = false;
  for (std::size_t n : lengths) {
    require_valid(n >= 2, "an FFT needs at least 2 samples, got " + std::to_string(n));
    double* in = fftw_alloc_real(n);
    fftw_complex* out = fftw_alloc_complex(n / 2 + 1);
    const fftw_plan plan = fftw_plan_dft_r2c_1d(static_cast<int>(n), in, out, kPlannerFlags);
    fftw_free(in);
    fftw_free(out);
    if (plan == nullptr) throw std::runtime_error("FFTW could not plan a transform of length " + std::to_string(n));
    fftw_destroy_plan(plan);
  }
  char* text = fftw_export_wisdom_to_string();
  if (text == nullptr) throw std::runtime_error("FFTW could not export its wisdom");
  std::string wisdom(text);
  fftw_free(text);
  return wisdom;
}

bool shipped_fftw_wisdom_in_use() {
  std::lock_guard<std::mutex> lock(planner_mutex());
  return wisdom_accepted;
}

// ---------------------------------------------------------------------------------------------
// Spectra

Spectrum amplitude_spectrum(const FftPlan& plan, std::span<const double> x, double fs, Window window) {
  require_valid(fs > 0.0, "sample rate must be > 0 Hz");
  const std::size_t n = plan.size();
  require_valid(x.size() == n, "amplitude_spectrum: signal of " + std::to_string(x.size()) +
                                   " samples for a plan of length " + std::to_string(n));
  const std::vector<double> w = window_coefficients(window, n);
  const double s1 = sum(w);
  std::vector<double> buf(n);
  windowed_segment(x, 0, w, false, buf);
  std::vector<std::complex<double>> X(plan.bins());
  plan.execute(buf, X);

  Spectrum s;
  s.window = window;
  s.n_samples = n;
  s.sample_rate_Hz = fs;
  s.bin_width_Hz = fs / static_cast<double>(n);
  s.frequency_Hz = bin_frequencies(n, fs);
  s.amplitude.resize(X.size());
  for (std::size_t k = 0; k < X.size(); ++k) s.amplitude[k] = one_sided_factor(k, n) * std::abs(X[k]) / s1;
  return s;
}

Peak find_peak(const Spectrum& s, double f_lo_Hz, double f_hi_Hz) {
  const std::size_t k = argmax_in_band(s.frequency_Hz, s.amplitude, f_lo_Hz, f_hi_Hz);
  Peak p;
  p.bin = k;
  p.offset_bins = interpolate_offset(s.amplitude, k, s.window);
  p.frequency_Hz = (static_cast<double>(k) + p.offset_bins) * s.bin_width_Hz;
  // Undo the scalloping loss at the interpolated offset: A = A_k S1 / |W(δ)|.
  const double s1 = window_transform_magnitude(s.window, s.n_samples, 0.0);
  p.amplitude = s.amplitude[k] * s1 / window_transform_magnitude(s.window, s.n_samples, p.offset_bins);
  return p;
}

Psd welch_psd(const FftPlan& plan, std::span<const double> x, double fs, const WelchSettings& cfg) {
  require_valid(fs > 0.0, "sample rate must be > 0 Hz");
  require_valid(cfg.overlap >= 0.0 && cfg.overlap < 1.0,
                "Welch overlap must be in [0, 1), got " + std::to_string(cfg.overlap));
  const std::size_t L = plan.size();
  require_valid(x.size() >= L, "Welch PSD: signal of " + std::to_string(x.size()) +
                                   " samples is shorter than one segment (" + std::to_string(L) + ")");
  const std::size_t step =
      std::max<std::size_t>(1, static_cast<std::size_t>(std::lround(static_cast<double>(L) * (1.0 - cfg.overlap))));
  const std::vector<double> w = window_coefficients(cfg.window, L);
  const double s2 = sum_of_squares(w);

  Psd p;
  p.bin_width_Hz = fs / static_cast<double>(L);
  p.frequency_Hz = bin_frequencies(L, fs);
  p.density.assign(plan.bins(), 0.0);
  std::vector<double> buf(L);
  std::vector<std::complex<double>> X(plan.bins());
  const auto add_segment = [&](std::size_t start) {
    windowed_segment(x, start, w, cfg.remove_segment_mean, buf);
    plan.execute(buf, X);
    for (std::size_t k = 0; k < X.size(); ++k) p.density[k] += one_sided_factor(k, L) * std::norm(X[k]);
    ++p.segments;
  };
  std::size_t next = 0;  // start of the first regular segment not taken
  for (; next + L <= x.size(); next += step) add_segment(next);
  // The tail past the last regular segment (it ends at next − step + L): one more segment
  // ending at the record's last sample, so every sample is in the estimate (see header).
  if (next - step + L < x.size()) add_segment(x.size() - L);
  const double scale = 1.0 / (fs * s2 * static_cast<double>(p.segments));
  for (double& d : p.density) d *= scale;
  return p;
}

double peak_frequency_Hz(const Psd& psd, Window window, double f_lo_Hz, double f_hi_Hz) {
  const std::size_t k = argmax_in_band(psd.frequency_Hz, psd.density, f_lo_Hz, f_hi_Hz);
  std::vector<double> mag(psd.density.size());
  for (std::size_t i = 0; i < mag.size(); ++i) mag[i] = std::sqrt(psd.density[i]);
  return (static_cast<double>(k) + interpolate_offset(mag, k, window)) * psd.bin_width_Hz;
}

Spectrogram spectrogram(const FftPlan& plan, std::span<const double> x, double fs, const SpectrogramSettings& cfg,
                        double t0_s) {
  require_valid(fs > 0.0, "sample rate must be > 0 Hz");
  require_valid(cfg.hop >= 1, "spectrogram hop must be >= 1 sample");
  const std::size_t L = plan.size();
  require_valid(x.size() >= L, "spectrogram: signal of " + std::to_string(x.size()) +
                                   " samples is shorter than one frame (" + std::to_string(L) + ")");
  const std::size_t regular = 1 + (x.size() - L) / cfg.hop;
  const bool tail = cfg.end_frame && (regular - 1) * cfg.hop + L < x.size();
  const std::size_t frames = regular + (tail ? 1 : 0);
  const std::vector<double> w = window_coefficients(cfg.window, L);
  const double scale = 1.0 / (fs * sum_of_squares(w));

  Spectrogram s;
  s.bin_width_Hz = fs / static_cast<double>(L);
  s.frequency_Hz = bin_frequencies(L, fs);
  s.times_s.resize(frames);
  s.frame_start.resize(frames);
  s.power.resize(static_cast<Eigen::Index>(frames), static_cast<Eigen::Index>(plan.bins()));
  std::vector<double> buf(L);
  std::vector<std::complex<double>> X(plan.bins());
  for (std::size_t j = 0; j < frames; ++j) {
    const std::size_t start = j < regular ? j * cfg.hop : x.size() - L;
    s.frame_start[j] = start;
    s.times_s[j] = t0_s + (static_cast<double>(start) + 0.5 * static_cast<double>(L - 1)) / fs;
    windowed_segment(x, start, w, cfg.remove_segment_mean, buf);
    plan.execute(buf, X);
    for (std::size_t k = 0; k < X.size(); ++k)
      s.power(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) =
          one_sided_factor(k, L) * std::norm(X[k]) * scale;
  }
  return s;
}

std::vector<double> band_power(const Spectrogram& s, double f_lo_Hz, double f_hi_Hz) {
  std::vector<double> b(s.times_s.size(), 0.0);
  bool any = false;
  for (std::size_t k = 0; k < s.frequency_Hz.size(); ++k) {
    if (s.frequency_Hz[k] < f_lo_Hz || s.frequency_Hz[k] > f_hi_Hz) continue;
    any = true;
    for (std::size_t j = 0; j < b.size(); ++j)
      b[j] += s.power(static_cast<Eigen::Index>(j), static_cast<Eigen::Index>(k)) * s.bin_width_Hz;
  }
  require_valid(any, "band_power: no bin lies in " + std::to_string(f_lo_Hz) + " – " + std::to_string(f_hi_Hz) + " Hz");
  return b;
}

double first_time_at_or_above(std::span<const double> t, std::span<const double> v, double level) {
  require_valid(t.size() == v.size(), "first_time_at_or_above: times and values differ in length");
  for (std::size_t j = 0; j < v.size(); ++j) {
    if (v[j] < level) continue;
    if (j == 0) return t[0];
    const double a = (level - v[j - 1]) / (v[j] - v[j - 1]);
    return t[j - 1] + a * (t[j] - t[j - 1]);
  }
  return std::numeric_limits<double>::quiet_NaN();
}

// ---------------------------------------------------------------------------------------------
// SpectralAnalyzer

const FftPlan& SpectralAnalyzer::plan(std::size_t n) const {
  std::lock_guard<std::mutex> lock(mutex_);
  auto it = plans_.find(n);
  if (it == plans_.end()) it = plans_.emplace(n, std::make_unique<FftPlan>(n)).first;
  return *it->second;
}

std::size_t SpectralAnalyzer::cached_plans() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return plans_.size();
}

Spectrum SpectralAnalyzer::amplitude_spectrum(std::span<const double> x, double fs, Window window) const {
  return analysis::amplitude_spectrum(plan(x.size()), x, fs, window);
}

Psd SpectralAnalyzer::welch_psd(std::span<const double> x, double fs, const WelchSettings& cfg) const {
  return analysis::welch_psd(plan(cfg.segment_length), x, fs, cfg);
}

Spectrogram SpectralAnalyzer::spectrogram(std::span<const double> x, double fs, const SpectrogramSettings& cfg,
                                          double t0_s) const {
  return analysis::spectrogram(plan(cfg.segment_length), x, fs, cfg, t0_s);
}

}  // namespace shudder::analysis
