#pragma once
// A run's recorded output: sampled signals, thermal-field snapshots and summary scalars.
// Produced by the models (rig_models/), written by io/ (HDF5, CSV), read by analysis/.
// Plain data, no behaviour beyond lookup.

#include <Eigen/Dense>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shudder::dynamics {

/// One sampled channel. `name` follows FORMATS.md (`time_s`, `torque_Nm`, `temp_C`, ...);
/// `units` is the unit string written as the HDF5 `units` attribute.
struct Signal {
  std::string name;
  std::string units;
  std::vector<double> values;
};

/// The temperature field at one instant: rows are axial cells (z from the separator's back
/// face), columns radial cells. Shape (n_z x n_r), degrees Celsius.
struct ThermalSnapshot {
  double time_s = 0.0;
  Eigen::MatrixXd temp_C;
};

/// A named scalar result (e.g. torque at t = 10 s) with its unit.
struct Scalar {
  std::string name;
  std::string units;
  double value = 0.0;
};

struct Recording {
  std::vector<Signal> signals;            // equal lengths; `time_s` first
  std::vector<double> grid_r_m;           // (n_r) cell-centre radii of the thermal grid
  std::vector<double> grid_z_m;           // (n_z) cell-centre axial positions
  std::vector<ThermalSnapshot> snapshots; // thermal field at chosen times
  std::vector<Scalar> scalars;            // summary values

  Signal& add_signal(std::string name, std::string units) {
    signals.push_back(Signal{std::move(name), std::move(units), {}});
    return signals.back();
  }
  const Signal* find(std::string_view name) const {
    for (const auto& s : signals)
      if (s.name == name) return &s;
    return nullptr;
  }
  const Scalar* find_scalar(std::string_view name) const {
    for (const auto& s : scalars)
      if (s.name == name) return &s;
    return nullptr;
  }
};

}  // namespace shudder::dynamics
