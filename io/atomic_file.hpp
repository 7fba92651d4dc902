#pragma once
// Temp-file-then-rename for output files (docs/formats/run_output.md: a reader never sees half a file).
// A writer fills `temp_path_for(path)`, closes it, then calls commit_temp_file(); on any failure
// before that it calls discard_temp_file(). The rename is atomic, so a reader, and a crash of
// shudder itself, sees either the old file or the complete new one at `path`.
//
// Durability against a power cut or an operating-system crash needs more: the data on disk
// (fsync) before the rename. That costs 0.5–12 ms of wall time per file on this machine (the
// disk's flush, longer while others write), from a tenth to all of a short run's time, so it is
// off by default (a simulation's output can be made again; ext4 with its default auto_da_alloc
// flushes a file that replaces another before the rename anyway). SHUDDER_FSYNC=1 in the
// environment turns it on (docs/formats/run_output.md).

#include <string>

namespace shudder::io {

/// The temporary name written first: `path + ".tmp.<pid>.<n>"`, unique per process and write
/// (n counts this process' writes), so two processes writing the same output never fill the
/// same temporary and one cannot rename the other's half-written file into place.
std::string temp_path_for(const std::string& path);

/// Removes the temporaries a killed writer of `path` left behind: in `path`'s directory, the
/// files named `path + ".tmp"` (the name before per-process temporaries) and `path +
/// ".tmp.<pid>.<n>"` whose process no longer runs. Files of live writers and any other name
/// are left alone. Called at the start of every atomic write of `path`; never throws.
void remove_stale_temp_files(const std::string& path) noexcept;

/// Whether outputs are flushed to disk before their rename: SHUDDER_FSYNC=1 yes; unset, empty or
/// 0 no. Any other value is an InputError naming the variable and the allowed values.
bool output_fsync_requested();

/// Renames `tmp` to `path` (replacing an existing file), after fsync()ing it if
/// output_fsync_requested(). On failure removes `tmp` and throws InputError naming `path` and
/// the system's reason (or the bad SHUDDER_FSYNC value).
void commit_temp_file(const std::string& tmp, const std::string& path);

/// Removes `tmp` if it exists; never throws.
void discard_temp_file(const std::string& tmp) noexcept;

/// Writes `text` to `path` through the temporary name; InputError naming `path` on failure.
void write_text_file_atomically(const std::string& path, const std::string& text);

}  // namespace shudder::io
