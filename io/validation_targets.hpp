#pragma once
// The cases and targets of `shudder validate`, read from a data file beside the scenarios
// (scenarios/validation.toml; schema in docs/formats/validation_targets.md). Reading is strict like the
// scenario loader: unknown keys, a target naming no case, a kind without its times, or bounds
// out of order are io::InputError naming the file, line and key.

#include <optional>
#include <string>
#include <vector>

namespace shudder::io {

struct ValidationCase {
  std::string scenario;  // file stem in the scenarios folder
  std::string label;     // as printed in the tables
};

/// How a target's value is taken from a recording:
///   value          signal at time_s
///   mean           time mean of the signal over [from_s, to_s]
///   rise           signal(to_s) − signal(from_s)
///   percent_below  100 (1 − v / v_ref), v and v_ref the signal at time_s of this case and `reference`
///   percent_above  100 (v / v_ref − 1)
enum class TargetKind { kValue, kMean, kRise, kPercentBelow, kPercentAbove };

struct ValidationTarget {
  std::size_t case_index = 0;                  // into ValidationSpec::cases
  std::optional<std::size_t> reference_index;  // percent_* kinds
  std::string quantity;                        // as printed
  TargetKind kind = TargetKind::kValue;
  std::string signal;  // docs/formats/measured_run.md signal name
  double time_s = 0.0, from_s = 0.0, to_s = 0.0;
  std::string unit;  // the signal's unit as printed ("Nm", "°C")
  // Pass band on the value (percent for percent_* kinds): min <= v <= max, v > greater_than.
  // None of them: reported without a target.
  std::optional<double> min, max, greater_than;

  bool has_band() const { return min || max || greater_than; }
};

struct ValidationSpec {
  std::vector<ValidationCase> cases;
  std::vector<ValidationTarget> targets;
  std::size_t ramp_case = 0;  // the up/down-ramp case: its own table, sump curve and plot
  std::string ramp_plot_file;
  std::vector<std::pair<std::size_t, std::string>> comparison;  // (case, label) on one plot
  std::string comparison_title, comparison_heading, comparison_file;
};

ValidationSpec load_validation_spec(const std::string& path);

}  // namespace shudder::io
