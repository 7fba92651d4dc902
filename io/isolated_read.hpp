#pragma once
// Reading an HDF5 measured run in a child process, so that a damaged file cannot take the
// command down with it.
//
// Why: Debian's libhdf5 1.10.8 crashes (SIGSEGV, out-of-bounds reads) or hangs inside its own
// global-heap and shared-message decoding on some damaged files (docs/fuzzing.md,
// "Limits"); the stacks have no frame of ours below H5Aread/H5Aexists, so no check in our reader
// can reach them. Re-running 40 of the fuzz campaign's crash and hang inputs through the release
// `shudder characterise`: 32 segmentation faults and 6 hangs. The reader therefore runs in a
// fork()ed child that sends the run (or its InputError) back through a pipe. A child killed by a
// signal, or still reading when the time limit passes (then killed), becomes an io::InputError
// naming the file: exit 2 with one line, as for any other bad input.
//
// Cost: one fork per HDF5 run read (the child shares the parent's pages copy-on-write); measured
// in docs/fuzzing.md. Call it before starting threads (the commands read their runs first): a
// child forked while another thread holds a lock (malloc's, the HDF5 mutex) could wait on it
// forever, which the time limit would then report as a hang.

#include <cstdint>
#include <functional>
#include <string>

#include "io/measured_run.hpp"

namespace shudder::io {

/// The time the child may take: 30 s plus 1 s per 10 MB of file (a valid run reads at
/// ~100 MB/s here; the limit is for hangs, not for slow disks).
double isolated_read_time_limit_s(std::uintmax_t file_bytes);

/// read_measured_run_hdf5(path) in a child process (file comment). Same result and the same
/// InputError messages as the in-process reader; a crash or hang of the child is an InputError.
MeasuredRun read_measured_run_hdf5_isolated(const std::string& path);

namespace detail {
/// The mechanism, for tests: runs `read` in a child, `path` only names the file in messages.
MeasuredRun run_isolated(const std::string& path, double time_limit_s, const std::function<MeasuredRun()>& read);
}  // namespace detail

}  // namespace shudder::io
