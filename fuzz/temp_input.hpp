#pragma once
// The fuzzers' bridge to readers that take a path: the input bytes written to one file per
// process and suffix in /dev/shm (memory, no disk I/O; $TMPDIR where there is no /dev/shm),
// removed at exit. The readers run unchanged, their own open, size and type checks included.
// libFuzzer runs inputs one after another in a single thread, so one file per suffix suffices.

#include <cstddef>
#include <cstdint>
#include <string>

namespace shudder::fuzz {

/// Writes `data` to this process's input file for `suffix` (".toml", ".csv", ".h5") and returns
/// its path.
std::string write_temp_input(const std::uint8_t* data, std::size_t size, const std::string& suffix);

}  // namespace shudder::fuzz
