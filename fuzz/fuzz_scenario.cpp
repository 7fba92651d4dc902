// libFuzzer harness: io::load_scenario_text on arbitrary bytes, then the clutch it describes.
// Contract (io/input_error.hpp): bad input is an io::InputError, nothing else escapes, no
// sanitizer report. The scenario is named as if it lay in the shipped scenarios/ folder so
// that `fluid = "fluids/..."` in the seeds resolves to the shipped fluid files.

#include <cstddef>
#include <cstdint>
#include <string>

#include "io/input_error.hpp"
#include "io/scenario.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    const auto scenario = shudder::io::load_scenario_text(text, SHUDDER_FUZZ_SCENARIO_DIR "/fuzz.toml");
    (void)scenario.make_clutch();
  } catch (const shudder::io::InputError&) {
  }
  return 0;
}
