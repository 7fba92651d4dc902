#pragma once
// A NetworkSpec (components/network_spec.hpp) checked and turned into a dynamics::TorsionalNetwork
// with its contact laws, the run-time context of every wet clutch and the initial speeds.
//
// Layout of what is built, in the spec's order within each group:
//   nodes      the inertias, then the vehicles (inertia m r²)
//   contacts   the clutches and brakes, then the freewheels
//   shafts     the shafts without lash; shafts with lash are force elements
//   elements   lash shafts, tyres, then one road load per vehicle, then firing pulsations
//   sources    torque sources, then one grade torque per vehicle with a grade; engines; then
//              each motor's torque ripple (when it has one)
//
// Checks (each a NetworkError naming the component and what to change): unknown nodes (with the
// nearest name), a component joined to itself, a massless node nothing fixes, gears and
// differentials that over-constrain a loop, parts of the network that nothing drives and that
// start at rest, a clutch whose normal force never rises above zero during the run, a
// freewheel that starts overrun in its locking direction.

#include <Eigen/Dense>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "components/network_spec.hpp"
#include "dynamics/network.hpp"
#include "dynamics/simulation.hpp"
#include "components/haldex_coupling_law.hpp"

namespace shudder::components {

/// A network the spec cannot make; `component()` is the component's name ("" for the whole).
class NetworkError : public std::invalid_argument {
 public:
  NetworkError(std::string component, const std::string& message)
      : std::invalid_argument((component.empty() ? "" : "component '" + component + "': ") + message),
        component_(std::move(component)) {}
  const std::string& component() const { return component_; }

 private:
  std::string component_;
};

struct BuiltClutch {
  const ClutchSpec* spec = nullptr;
  int contact = -1;
  double geometry_factor_m = 0.0;                      // torque per unit μ F: plain R, wet n r_mean
  std::shared_ptr<const PlainFrictionLaw> plain;       // plain law
  std::shared_ptr<const clutch::WetClutch> wet;        // wet law: the clutch...
  std::shared_ptr<components::ClutchContext> context;  // ...and the inputs its run holds
  // Haldex law: the coupling's law, the command its control unit sets, the nodes it reads, and
  // where its states (pressure, valve opening) sit in Sample::contact_states.
  std::shared_ptr<const components::HaldexCouplingLaw> haldex;
  std::shared_ptr<components::HaldexCommand> command;
  int front_axle_node = -1, rear_axle_node = -1, state_index = -1;
  /// The normal (clamp) force at a sample, N: the force signal's, or the coupling's hydraulics'.
  double normal_force_N(const dynamics::Sample& s) const;
  /// The same from the force signal alone (plain and wet laws; a Haldex coupling's is a state).
  double scheduled_force_N(double t_s) const;
  const std::string& name() const { return spec->name; }
};

struct BuiltNetwork {
  dynamics::TorsionalNetwork network;
  std::vector<BuiltClutch> clutches;                             // contact c for clutches[c]
  std::vector<int> freewheel_contacts;                           // spec.freewheels[i] is contact freewheel_contacts[i]
  std::vector<int> lash_elements, tyre_elements, road_elements;  // force element indices
  std::vector<int> vehicle_nodes;
  std::vector<int> engine_sources, grade_sources;  // torque source indices
  std::vector<int> pulsation_elements;             // force element indices
  Eigen::VectorXd initial_speed_rad_s, initial_angle_rad;
  Eigen::VectorXd initial_motor_integral;  // ∫(ω_ref − ω) dt per motor at t = 0, rad
  std::vector<int> ripple_sources;         // torque source indices of the motors' ripple
  std::vector<std::string> node_names;
};

/// A wet clutch's pack parameters as the network builds them: the spec's, and for a Haldex
/// coupling with its own oil (volume and cooling flow) unless its [clutch] table gives them.
/// Throws std::invalid_argument for parameters the oil cannot be applied to.
clutch::WetClutchParams pack_params(const ClutchSpec& clutch);

/// How much build_network checks: everything (a spec as a user wrote it), or not the topology
/// (the checks of the header above but the components' own): for a machine that rebuilds a spec
/// whose topology it has built with every check before (the rig's and the car's analyses
/// rebuild their network for each operating point they linearise about).
enum class NetworkChecks { kAll, kSkipTopology };

/// Checks and builds; throws NetworkError. `spec` must outlive the result.
std::unique_ptr<BuiltNetwork> build_network(const NetworkSpec& spec, NetworkChecks checks = NetworkChecks::kAll);

/// A spec and the network built from it, kept together (the built network refers to its
/// spec): what a machine written as components (the rig, the car) hands the analyses that
/// linearise or probe it. The clutch laws are bound to the contexts and commands below, so
/// setting them sets what the network's laws read.
class OwnedNetwork {
 public:
  /// build_network(spec, checks); throws NetworkError.
  explicit OwnedNetwork(NetworkSpec spec, NetworkChecks checks = NetworkChecks::kAll);

  const NetworkSpec& spec() const { return *spec_; }
  const BuiltNetwork& built() const { return *built_; }
  const dynamics::TorsionalNetwork& network() const { return built_->network; }
  /// The held inputs (ring temperatures, clamp force) of clutch `c`, a wet clutch or a Haldex
  /// coupling; std::invalid_argument for another law or an index out of range.
  ClutchContext& clutch_context(std::size_t c = 0) const;
  /// The valve command of clutch `c`, a Haldex coupling; std::invalid_argument otherwise.
  HaldexCommand& command(std::size_t c = 0) const;

 private:
  const BuiltClutch& clutch(std::size_t c) const;
  std::unique_ptr<const NetworkSpec> spec_;
  std::unique_ptr<BuiltNetwork> built_;
};

}  // namespace shudder::components
