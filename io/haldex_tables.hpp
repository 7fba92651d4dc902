#pragma once
// The Haldex coupling's hydraulics and control-unit tables, read the same way wherever a coupling
// is described: a driveline scenario's [driveline.hydraulics] / [driveline.controller] and a
// network's haldex_coupling component's `hydraulics` / `controller` tables. Every key is
// optional; defaults, meanings and units are those of components/haldex_hydraulics.hpp and
// components/haldex_controller.hpp (docs/driveline.md lists them).

#include "io/toml_reader.hpp"
#include "components/haldex_controller.hpp"
#include "components/haldex_hydraulics.hpp"

namespace shudder::io {

/// Reads the hydraulics keys present in `h` over `p` and finishes the table.
void read_haldex_hydraulics(TomlTable& h, components::HaldexHydraulicsParams& p);
/// Reads the control unit's keys present in `c` over `p` and finishes the table.
void read_haldex_controller(TomlTable& c, components::HaldexControllerParams& p);

}  // namespace shudder::io
