#pragma once
// Temp-file-then-rename for output files (FORMATS.md: "a reader never sees half a file").
// A writer fills `temp_path_for(path)`, closes it, then calls commit_temp_file(); on any failure
// before that it calls discard_temp_file(). commit flushes the data to disk (fsync) before the
// rename, so even a crash leaves either the old file or the complete new one at `path`.

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

/// fsync()s `tmp` and renames it to `path` (replacing an existing file). On failure removes
/// `tmp` and throws InputError naming `path` and the system's reason.
void commit_temp_file(const std::string& tmp, const std::string& path);

/// Removes `tmp` if it exists; never throws.
void discard_temp_file(const std::string& tmp) noexcept;

/// Writes `text` to `path` through the temporary name; InputError naming `path` on failure.
void write_text_file_atomically(const std::string& path, const std::string& text);

}  // namespace shudder::io
