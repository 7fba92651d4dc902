// libFuzzer harness: io::load_fluid on arbitrary bytes (written to a temporary file: the loader
// reads a path). Contract: bad input is an io::InputError, nothing else escapes.

#include <cstddef>
#include <cstdint>

#include "fuzz/temp_input.hpp"
#include "io/fluid_loader.hpp"
#include "io/input_error.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const auto path = shudder::fuzz::write_temp_input(data, size, ".toml");
  try {
    (void)shudder::io::load_fluid(path);
  } catch (const shudder::io::InputError&) {
  }
  return 0;
}
