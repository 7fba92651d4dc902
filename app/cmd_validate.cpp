// `shudder validate`: placeholder replaced below once calibration is done.
#include "app/commands.hpp"
namespace shudder::app {
int validate_command(const ValidateOptions&) { return 1; }
}  // namespace shudder::app
