#pragma once
// A simulated run written as a measured rig run (docs/formats/measured_run.md), so the
// tools that read real LSCTR data can read simulations too, optionally with sensor noise. The
// same content can be written in the format's HDF5 form (io/measured_run.hpp).
//
// Columns: time_s, speed_rpm, normal_force_N, torque_Nm, temp_C (required; the recording must
// have them), then sump_temp_C and ir_temp_C when the recording has them. Other signals are
// model internals and are not written. Metadata lines: format, rig, fluid (when given),
// temp_sensor, oil_flow_ml_min, and this writer's additions sample_rate_Hz, noise (on|off) and
// seed (when noise is on); docs/formats/run_output.md explains them.
//
// Resampling: linear interpolation at t0 + k / rate over [t0, t_end] of the recording's time_s.
// Noise: independent Gaussian per sample and channel with sigma = half the stated sensor
// accuracy, i.e. the stated bound is read as a ~95 % (2 sigma) bound. The generator is
// std::mt19937_64 seeded with `seed` plus our own Box-Muller transform (std::normal_distribution
// differs between standard libraries), so a seed gives the same file everywhere. A noisy normal
// force is clipped at 0 N (the format forbids negative force; only matters near zero load).
//
// The file is written to `path + ".tmp"` and renamed when complete; on failure nothing is left
// and io::InputError is thrown. The writer refuses to produce what the format's reader rejects:
// missing required signals, non-finite values, time not strictly increasing, negative normal
// force, fewer than 10 rows.

#include <string>

#include "clutch/wet_clutch.hpp"
#include "dynamics/recording.hpp"
#include "io/measured_run.hpp"
#include "rig_models/rig_names.hpp"

namespace shudder::io {

/// Stated accuracy (a +- bound, in the channel's unit) of each LSCTR channel.
/// Source: docs/physics.md §4 (thesis Method; Papers B, D).
struct SensorAccuracy {
  static constexpr double full_scale_fraction = 0.0025;  // torque and force: "< 0.25 % F.S."
  static constexpr double torque_full_scale_Nm = 500.0;  // assumed = drive's max torque, 500 Nm
  static constexpr double force_full_scale_N = 30e3;     // cylinder's max normal force, 30 kN
  static constexpr double torque_Nm = full_scale_fraction * torque_full_scale_Nm;     // 1.25
  static constexpr double normal_force_N = full_scale_fraction * force_full_scale_N;  // 75
  static constexpr double thermocouple_C = 0.67;  // separator thermocouple (temp_C, sump_temp_C)
  static constexpr double ir_C = 1.5;             // IR pyrometer (ir_temp_C)
  static constexpr double speed_rpm = 0.01;       // NOT stated: estimate, drive-encoder resolution
  /// Noise sigma = this x accuracy: the bound is taken as 2 sigma (~95 % of samples inside).
  static constexpr double sigma_per_accuracy = 0.5;
};

struct MeasurementOptions {
  double sample_rate_Hz = 0;                             // 0 = the recording's own samples; else (0, 1e6] Hz
  bool noise = false;                                    // add Gaussian sensor noise (see SensorAccuracy)
  unsigned seed = 1;                                     // noise generator seed
  std::string rig = std::string(rig_models::kLsctrRig);  // metadata `rig` (omitted when empty)
  std::string fluid;                                     // metadata `fluid` (omitted when empty)
  std::string clutch;  // metadata `clutch`: the network clutch the run is of (omitted when empty)
  std::string temp_sensor = "separator_thermocouple r_mm=48 z_mm=0.5";  // metadata `temp_sensor`
  double oil_flow_ml_min = 200;                                         // metadata `oil_flow_ml_min`, >= 0
};

/// What the writers below write, in memory: time_s then the sensor columns (units from
/// measured_run_units), resampled and with noise added, at full precision; the metadata in file
/// order. `path` is the output named in errors (and the run's `path`). Throws like the writers.
MeasuredRun make_measurement(const std::string& path, const dynamics::Recording& rec, const MeasurementOptions& opt);

/// Writes `rec` as a measured-run CSV at `path`; see the file comment.
void write_measurement_csv(const std::string& path, const dynamics::Recording& rec, const MeasurementOptions& opt);

/// Writes `run` (time_s first) as a measured-run CSV: metadata lines, header, rows, as above.
void write_measured_run_csv(const std::string& path, const MeasuredRun& run);

/// write_measurement_csv, or, when `path` ends in `.h5` or `.hdf5` (any case), the same run in
/// the HDF5 form (write_measured_run_hdf5), its values at full precision instead of printed.
void write_measurement(const std::string& path, const dynamics::Recording& rec, const MeasurementOptions& opt);

/// The metadata a wet clutch's run carries: its fluid's name, its oil flow and its thermocouple
/// (`separator_thermocouple r_mm=R z_mm=Z`); the rig, rate, noise and seed are the caller's.
void describe_clutch(MeasurementOptions& opt, const clutch::WetClutchParams& clutch, const std::string& fluid_name);

}  // namespace shudder::io
