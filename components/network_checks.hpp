#pragma once
// The checks of a network as it is built (components/network_builder.hpp), each a NetworkError
// naming the component and what to change.

#include <set>
#include <utility>
#include <vector>

#include "components/network_builder.hpp"

namespace shudder::components {

/// What the assembly records for the checks: every two-node link (a, b) (b may be ground), the
/// nodes a source, motor, engine, grade or speed source drives, and the nodes whose speed a gear,
/// differential or speed source ties.
struct Topology {
  std::vector<std::pair<int, int>> links;
  std::set<int> driven_nodes, fixed_nodes;
};

/// A clutch judged on a shaft's torque names a shaft of the network (nearest name when misspelt).
void check_judged_on(const NetworkSpec& spec);

/// A massless inertia has its speed fixed by a gear, a differential or a speed source.
void check_massless_nodes(const NetworkSpec& spec, const Topology& topology);

/// Gears, differentials and speed sources are independent (a row that adds no rank closes a loop
/// the others already fix), gears alone leave every node free to turn (a loop whose ratios
/// disagree locks it), and the mass on the free motions is positive definite.
void check_constraints(const NetworkSpec& spec, const BuiltNetwork& built);

/// Every part of the network is driven or starts moving (union-find over the links).
void check_connected(const BuiltNetwork& built, const Topology& topology);

}  // namespace shudder::components
