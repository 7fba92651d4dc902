#pragma once
// The fuzzers' bridge to readers that take a path: the input bytes written to one file per
// process (libFuzzer runs inputs one after another in a single thread, so one file suffices),
// under $TMPDIR, removed at exit.

#include <cstddef>
#include <cstdint>
#include <string>

namespace shudder::fuzz {

/// Writes `data` to this process's temporary file (name ending in `suffix`) and returns its path.
std::string write_temp_input(const std::uint8_t* data, std::size_t size, const std::string& suffix);

}  // namespace shudder::fuzz
