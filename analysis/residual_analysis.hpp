#pragma once
// Statistics of a model–measurement residual used by the diagnosis (analysis/diagnosis.hpp):
// the noise level of a signal, block means, the segments where the residual stands above the
// noise, and which feature of the measured run the residual follows.
//
//   noise     analysis/noise_estimate.hpp.
//   blocks    consecutive samples of ≈ 1/80 of the run (0.05–1 s, at least 5 samples).
//   segment   blocks whose mean residual m satisfies |m| > max(3 sigma/sqrt(n), sigma/2) — three
//             standard errors (not chance) and half a noise sigma (worth telling) — joined
//             while the sign holds; a segment needs two blocks.
//   features  per block, of the MEASURED run: time, temperature_rise (temp − first block),
//             temperature_rate (central difference of block means), sliding_speed (|speed|),
//             speed_change_direction (+1 / −1 / 0 with a 5 % dead band of the largest rate),
//             low_speed_dwell (time since |speed| fell below 10 % of the run's largest),
//             normal_force. Plus "offset": |mean| / rms of the block residual (1 for a pure
//             offset), reported where the residual barely varies and no correlation can exist.

#include <string>
#include <utility>
#include <vector>

#include "analysis/noise_estimate.hpp"

namespace shudder::analysis {

/// Contiguous sample ranges [begin, end) of a run, covering it in time order.
std::vector<std::pair<std::size_t, std::size_t>> residual_blocks(const std::vector<double>& time_s);

/// Named per-block features of one measured run (names as in the file comment).
struct BlockFeatures {
  std::vector<std::string> names;
  std::vector<std::vector<double>> values;  // values[f][block]
};
BlockFeatures block_features(const std::vector<double>& time_s, const std::vector<double>& speed_rpm,
                             const std::vector<double>& temp_C, const std::vector<double>& force_N,
                             const std::vector<std::pair<std::size_t, std::size_t>>& blocks);

std::vector<double> block_means(const std::vector<double>& x,
                                const std::vector<std::pair<std::size_t, std::size_t>>& blocks);

/// Pearson correlation; 0 if either side has no variance (relative 1e-12) or fewer than 3 points.
double pearson(const std::vector<double>& a, const std::vector<double>& b);

struct Segment {
  std::size_t first_sample = 0, end_sample = 0;  // [first, end)
  double mean = 0.0;
};
/// Segments where `residual` stands above the noise `sigma` (see the file comment).
std::vector<Segment> residual_segments(const std::vector<double>& residual, double sigma,
                                       const std::vector<std::pair<std::size_t, std::size_t>>& blocks);

/// Correlation of pooled block residuals with each pooled feature (same block order), strongest
/// |r| first, plus "offset" when the residual is mostly a constant.
std::vector<std::pair<std::string, double>> rank_features(const std::vector<double>& block_residual,
                                                          const BlockFeatures& features);

}  // namespace shudder::analysis
