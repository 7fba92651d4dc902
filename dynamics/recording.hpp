#pragma once
// A run's recorded output: sampled signals, thermal-field snapshots, summary scalars, 2-D
// maps (e.g. a stability map over slip speed x interface temperature) and result blocks (e.g.
// the shudder verdict).
// Produced by the models (rig_models/), written by io/ (HDF5, CSV), read by analysis/.
// Plain data, no behaviour beyond lookup.

#include <Eigen/Dense>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace shudder::dynamics {

/// One sampled channel. `name` follows docs/formats/measured_run.md (`time_s`, `torque_Nm`, `temp_C`, ...);
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

/// A quantity sampled on a rectangular grid over two variables, e.g. the stability margin over
/// slip speed x interface temperature. `layers` are the quantities on that grid (all (n_x x n_y),
/// row i at x[i], column j at y[j]); `scalars` are constants of the whole map (e.g. the normal
/// force it was computed at). Written under /analysis/<name>/ (io/hdf5_run.hpp).
struct Map2D {
  struct Layer {
    std::string name;        // e.g. "margin_per_s"
    std::string units;       // e.g. "1/s"
    Eigen::MatrixXd values;  // (n_x x n_y); NaN where undefined
  };
  std::string name;         // e.g. "stability_map"
  std::string description;  // one line: what the map is and how it was computed
  std::string x_name, x_units;
  std::vector<double> x;  // (n_x), increasing
  std::string y_name, y_units;
  std::vector<double> y;  // (n_y), increasing
  std::vector<Layer> layers;
  std::vector<Scalar> scalars;

  const Layer* find(std::string_view layer) const {
    for (const auto& l : layers)
      if (l.name == layer) return &l;
    return nullptr;
  }
  const Scalar* find_scalar(std::string_view scalar) const {
    for (const auto& s : scalars)
      if (s.name == scalar) return &s;
    return nullptr;
  }
};

/// A named block of results that is neither a signal nor a map: scalars with units and text
/// (e.g. the run's shudder verdict: its name, the channels judged). Written as the group
/// /analysis/<name>/ (io/hdf5_run.hpp): each scalar a dataset with `units`, each text an
/// attribute.
struct ResultBlock {
  struct Text {
    std::string name;
    std::string value;
  };
  std::string name;         // e.g. "verdict"
  std::string description;  // one line: what the block is
  std::vector<Text> texts;
  std::vector<Scalar> scalars;

  const Scalar* find_scalar(std::string_view scalar) const {
    for (const auto& s : scalars)
      if (s.name == scalar) return &s;
    return nullptr;
  }
  const Text* find_text(std::string_view text) const {
    for (const auto& t : texts)
      if (t.name == text) return &t;
    return nullptr;
  }
};

struct Recording {
  std::vector<Signal> signals;             // equal lengths; `time_s` first
  std::vector<double> grid_r_m;            // (n_r) cell-centre radii of the thermal grid
  std::vector<double> grid_z_m;            // (n_z) cell-centre axial positions
  std::vector<ThermalSnapshot> snapshots;  // thermal field at chosen times
  std::vector<Scalar> scalars;             // summary values
  std::vector<Map2D> maps;                 // 2-D results (e.g. "stability_map")
  std::vector<ResultBlock> blocks;         // other results (e.g. "verdict")

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
  const Map2D* find_map(std::string_view name) const {
    for (const auto& m : maps)
      if (m.name == name) return &m;
    return nullptr;
  }
  const ResultBlock* find_block(std::string_view name) const {
    for (const auto& b : blocks)
      if (b.name == name) return &b;
    return nullptr;
  }
};

}  // namespace shudder::dynamics
