// libFuzzer harness: io::read_measured_run_csv on arbitrary bytes (written to a temporary file).
// Contract: bad input is an io::InputError, nothing else escapes.

#include <cstddef>
#include <cstdint>

#include "fuzz/temp_input.hpp"
#include "io/input_error.hpp"
#include "io/measured_run.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = shudder::fuzz::write_temp_input(data, size, ".csv");
  try {
    (void)shudder::io::read_measured_run_csv(path);
  } catch (const shudder::io::InputError&) {
  }
  return 0;
}
