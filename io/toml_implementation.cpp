// toml++'s parser, compiled once, here, into shudder_io: the library is used as a static part of
// the program instead of Debian's libtomlplusplus.so, whose loading and relocation cost ≈ 0.15 ms
// of every process (docs/performance.md). Every file includes toml++ with TOML_HEADER_ONLY=0
// (io/CMakeLists.txt), i.e. declarations only; this one adds the definitions.
#define TOML_IMPLEMENTATION
#include <toml++/toml.h>
