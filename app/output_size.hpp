#pragma once
// What a run or a sweep will write, estimated from the scenario before simulating, so that a
// mistaken rate or duration is refused in a second instead of after hours (a
// `sample_rate_Hz = 1e6` run once wrote 3.6 GB with no warning). The figure is the data before
// compression: (duration x rate + 1) samples x channels x 8 bytes, plus the thermal snapshots
// (n_snap x n_r x n_z x 8 bytes). Compression only makes the file smaller, so the estimate is
// an upper figure for the data; HDF5's own overhead (a few kB) is not counted.

#include <cstdint>

#include "io/scenario.hpp"

namespace shudder::app {

/// Channels the rig and prescribed-slip runners record (docs/formats/run_output.md: 15).
constexpr std::uint64_t kRecordedChannels = 15;
/// Channels the driveline records: its 15 and per wheel speed and tyre force, the road load, and
/// the coupling's thermocouple and oil temperatures.
constexpr std::uint64_t kDrivelineRecordedChannels = 27;
/// The channels a run of this scenario records.
std::uint64_t recorded_channels(const io::Scenario& scenario);
/// Signals a sweep keeps per case (time, speed, slip, torque, temperature; cmd_sweep.cpp).
constexpr std::uint64_t kSweepKeptChannels = 5;

/// Samples the recording will hold: floor(duration x rate) + 1.
std::uint64_t estimated_samples(const io::Scenario& scenario);

/// Bytes of a run file's data: samples x recorded_channels(scenario) x 8 + snapshots.
std::uint64_t estimated_run_bytes(const io::Scenario& scenario);

/// Bytes of a sweep file's data: for each case, samples x kSweepKeptChannels x 8.
std::uint64_t estimated_sweep_bytes(const io::Scenario& case_scenario, std::uint64_t cases);

}  // namespace shudder::app
