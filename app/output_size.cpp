#include "app/output_size.hpp"

#include <cmath>
#include <variant>

namespace shudder::app {

namespace {

// Thermal snapshots the runner stores: explicit times in the scenario (rig, prescribed slip);
// the driveline stores none.
std::uint64_t snapshot_count(const rig_models::Model& model) {
  return std::visit(
      [](const auto& m) -> std::uint64_t {
        if constexpr (requires { m.settings.snapshot_times_s; })
          return m.settings.snapshot_times_s.size();
        else
          return 0;
      },
      model);
}

}  // namespace

std::uint64_t estimated_samples(const io::Scenario& scenario) {
  const auto [duration, rate] = std::visit(
      [](const auto& m) {
        return std::pair{m.settings.duration_s, m.settings.sample_rate_Hz};
      },
      scenario.model);
  return static_cast<std::uint64_t>(std::floor(duration * rate)) + 1;
}

std::uint64_t recorded_channels(const io::Scenario& scenario) {
  return std::holds_alternative<rig_models::DrivelineModel>(scenario.model) ? kDrivelineRecordedChannels
                                                                            : kRecordedChannels;
}

std::uint64_t estimated_run_bytes(const io::Scenario& scenario) {
  const auto& th = scenario.clutch.thermal;
  const auto cells = static_cast<std::uint64_t>(th.radial_cells) *
                     static_cast<std::uint64_t>(th.separator.cells + th.lining.cells + th.core.cells);
  return 8 * (estimated_samples(scenario) * recorded_channels(scenario) + snapshot_count(scenario.model) * cells);
}

std::uint64_t estimated_sweep_bytes(const io::Scenario& case_scenario, std::uint64_t cases) {
  return 8 * cases * estimated_samples(case_scenario) * kSweepKeptChannels;
}

}  // namespace shudder::app
