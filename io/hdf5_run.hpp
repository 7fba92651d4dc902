#pragma once
// One simulation run <-> one HDF5 file (docs/formats/run_output.md).
//
// Layout written:
//   /signals/<name>            1-D double (n_samples), attribute `units`; `time_s` first
//   /thermal/r_m, /thermal/z_m  1-D double (n_r), (n_z) cell centres        [if grid non-empty]
//   /thermal/times_s           1-D double (n_snap)                          [if snapshots]
//   /thermal/temp_C            3-D double (n_snap x n_z x n_r), row-major    [if snapshots]
//   /analysis/summary/<name>   scalar double, attribute `units`
//   /analysis/<block>/         one group per dynamics::ResultBlock (e.g. `verdict`): each
//                              scalar a scalar double with `units`, each text and the
//                              `description` a string attribute              [if blocks]
//   /analysis/<map>/           one group per dynamics::Map2D, attributes `x`, `y` (names of the
//                              axis datasets) and `description`; in it the axes <x> (n_x),
//                              <y> (n_y), each layer (n_x x n_y, row-major) and the map's
//                              scalars, all with `units`              [if maps]
//   root attributes            `scenario`, `fluid` (the fluid file's text; omitted when
//                              not given), `shudder_version`, `created_utc` (ISO 8601, UTC)
// Datasets of >= 65536 values are chunked (<= 16384 values per chunk, along the first axis),
// shuffled and deflated (level 4); readers decompress transparently.
// Strings are variable-length UTF-8 (h5py reads them as str). Groups track link creation
// order, so the reader returns signals and scalars in the order they were written.
//
// The file is written to `path + ".tmp"` and renamed to `path` only when complete and closed:
// a reader never sees half a file, and on any failure the temp file is removed, nothing is
// created at `path` and io::InputError is thrown naming the file.

#include <string>

#include "dynamics/recording.hpp"

namespace shudder::io {

/// Writes `rec` and the scenario text. Rejects (InputError) signals of unequal length, empty,
/// duplicate or '/'-containing names, snapshots whose shape differs from each other or from
/// the grid, and maps named "summary", with empty axes, no layers or layers not (n_x x n_y),
/// result blocks named "summary" or like a map, or with duplicate or '/'-containing scalar names
/// or duplicate text names. An existing file at `path` is replaced atomically.
/// Signals are deflated (RunCompression::kDeflate) unless the file is a scratch copy read back at
/// once (a sweep's part files: kNone, where deflate costs ~25 % of a short case's time).
enum class RunCompression { kDeflate, kNone };
void write_run_hdf5(const std::string& path, const dynamics::Recording& rec, const std::string& scenario_text,
                    const std::string& fluid_text = "", RunCompression compression = RunCompression::kDeflate);

/// Reads a file written by write_run_hdf5 (or any file with the same layout). Signals come in
/// file order with `time_s` moved first; a missing `units` attribute reads as "". Throws
/// InputError for a missing or non-HDF5 file, a file without /signals, a signal that is not
/// 1-D, signals of unequal length, or inconsistent thermal or map datasets. Groups under
/// /analysis without the map attributes (other than the summary) are read as result blocks:
/// their scalar numeric datasets and string attributes (texts in name order), the rest skipped.
dynamics::Recording read_run_hdf5(const std::string& path);

/// A root string attribute of a run file (`scenario`, `fluid`, `shudder_version`, `created_utc`); ""
/// when absent. Throws InputError like read_run_hdf5.
std::string read_run_attribute(const std::string& path, const std::string& name);

namespace detail {
/// Number of HDF5 identifiers (files, groups, datasets, attributes, dataspaces, datatypes,
/// property lists) currently open in this process, including the library's predefined ones.
/// For leak tests: the count must be the same before and after a write or read.
long open_hdf5_identifiers();
}  // namespace detail

}  // namespace shudder::io
