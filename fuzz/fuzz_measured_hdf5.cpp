// libFuzzer harness: io::read_measured_run_hdf5 on arbitrary bytes (written to a temporary
// file). Contract: bad input is an io::InputError, nothing else escapes. HDF5 itself is not
// instrumented (Debian's library), so this exercises our reader's handling of whatever the
// library returns for a damaged file; a crash inside libhdf5 is reported upstream, not fixed here.

#include <cstddef>
#include <cstdint>

#include "fuzz/temp_input.hpp"
#include "io/input_error.hpp"
#include "io/measured_run.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = shudder::fuzz::write_temp_input(data, size, ".h5");
  try {
    (void)shudder::io::read_measured_run_hdf5(path);
  } catch (const shudder::io::InputError&) {
  }
  return 0;
}
