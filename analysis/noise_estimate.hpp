#pragma once
// The noise level of a sampled signal from the data alone.
//
//   sigma = 1.4826 · MAD(d2) / sqrt(6),   d2_i = x_{i+1} − 2 x_i + x_{i−1}
//
// For white noise of standard deviation sigma, Var(d2) = (1 + 4 + 1) sigma² and 1.4826 · MAD is
// the standard deviation of a Gaussian; the median makes rare steps (stick-slip jumps, a ramp's
// kink) irrelevant. A smooth signal adds its second difference, ~x''·dt², which is negligible
// at 100 Hz–1 kHz sampling.

#include <vector>

namespace shudder::analysis {

/// sigma of one sample (0 for fewer than 3 samples).
double estimate_noise_sigma(const std::vector<double>& x);

/// The noise of one signal over several runs: the root of the sample-count-weighted mean of
/// each run's sigma², at least `floor` (noise-free data would otherwise give 0).
double pooled_noise_sigma(const std::vector<const std::vector<double>*>& runs, double floor);

}  // namespace shudder::analysis
