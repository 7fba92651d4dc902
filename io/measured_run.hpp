#pragma once
// Strict reader of a measured rig run (docs/formats/measured_run.md), as CSV or as its
// HDF5 form, and the writer of the HDF5 form. A file that breaks a rule is rejected with an
// io::InputError naming the file, the place (CSV: line number; HDF5: the dataset or attribute
// and the row index) and the reason, never repaired. docs/formats/run_output.md lists the rules.
//
// HDF5 form: group /measurement; one 1-D float64 dataset per column, named as the column, in
// column order (the group tracks creation order), each with a string attribute `units`; the
// metadata as variable-length UTF-8 string attributes of /measurement, in file order (also
// tracked). Keys name HDF5 places as "/measurement/<column>" and "/measurement@<attribute>".

#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "dynamics/recording.hpp"

namespace shudder::io {

/// The only `format` this reader accepts.
inline constexpr std::string_view measured_run_format = "shudder-measurement/1";

/// The columns every measured run has, in the order the writers put them.
inline constexpr std::string_view measured_run_required[] = {"time_s", "speed_rpm", "normal_force_N", "torque_Nm",
                                                             "temp_C"};

/// Fewest data rows a measured run may have.
inline constexpr std::size_t measured_run_min_rows = 10;

struct MeasuredRun {
  std::string path;                                           // as given to the reader
  std::vector<std::pair<std::string, std::string>> metadata;  // in file order, `format` included
  std::vector<dynamics::Signal> columns;                      // in file order, equal lengths

  /// The column's values; nullptr if there is no such column.
  const std::vector<double>* column(std::string_view name) const;
  /// A column the reader guarantees (measured_run_required); std::logic_error if absent.
  const std::vector<double>& required(std::string_view name) const;
  /// The first metadata value under `key`.
  std::optional<std::string> meta(std::string_view key) const;
  std::size_t rows() const;
  /// time_s last - first.
  double duration_s() const;
};

/// Unit of a column from its name's suffix (_s -> "s", _rpm -> "rpm", _N -> "N", _Nm -> "N m",
/// _C -> "degC"); "" for other names.
std::string measured_run_units(std::string_view column_name);

/// Reads `path` as HDF5 if it starts with the HDF5 signature (\x89HDF\r\n\x1a\n), else as CSV.
/// The HDF5 form is read in a child process (io/isolated_read.hpp): a damaged file that crashes
/// or hangs libhdf5 is an InputError. Call before starting threads.
MeasuredRun read_measured_run(const std::string& path);

/// CSV: `# key: value` metadata lines, one header line, comma-separated rows; \r\n accepted,
/// blank lines only at the end, a UTF-8 byte-order mark at the start ignored.
MeasuredRun read_measured_run_csv(const std::string& path);

/// HDF5 form (file comment), in this process. Integer datasets are read as double; a dataset
/// without `units` gets measured_run_units(name).
MeasuredRun read_measured_run_hdf5(const std::string& path);

/// Writes `run` in the HDF5 form to `path + ".tmp"`, renamed to `path` when complete. Refuses
/// (InputError naming `path`, nothing left on disk) what read_measured_run_hdf5 would reject,
/// and column names or metadata keys that are empty, duplicated or (columns) contain '/'.
void write_measured_run_hdf5(const std::string& path, const MeasuredRun& run);

namespace detail {
/// For tests of the reader's rejections: writes `run` as write_measured_run_hdf5 does but
/// without any check, and adds each of `number_attributes` to /measurement as a float64
/// attribute (which the reader must reject). Throws InputError only if HDF5 fails.
void write_measured_run_hdf5_unchecked(const std::string& path, const MeasuredRun& run,
                                       const std::vector<std::pair<std::string, double>>& number_attributes = {});
}  // namespace detail

}  // namespace shudder::io
