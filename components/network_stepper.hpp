#pragma once
// A network (components/network_builder.hpp) built and set at its start, advanced in pieces:
// what components/network_run.hpp runs to the scenario's duration in one piece, and what the
// network FMU (fmu/network_fmu.cpp) advances one communication step at a time.
//
// Contents: the built network, one thermal state per wet clutch (the multi-rate coupling,
// components/multirate_clutch.hpp, advances them every thermal step with the friction heat
// their contacts accumulated), each Haldex coupling's control unit (its command set at the
// start, at its instants and, with the oil, after every thermal step), each wet clutch's
// friction data tally, and the simulation (dopri5, or the fixed-step RK4 of
// settings.integrator.fixed_step_s > 0) started at t = 0 from the built initial state. The
// stepper restarts at every jump of an input signal and every control instant up to `end_s`.
//
// `end_s` is the scenario's duration for a run (samples at its sample rate up to it), or
// infinity for an FMU (no samples delivered, no end; thermal steps end at the run's instants;
// the signals' jumps are then those up to the scenario's duration, the control units' instants
// go on past it, added a duration's worth at a time as advance_to reaches them).

#include <functional>
#include <limits>
#include <memory>
#include <vector>

#include "clutch/friction_data_range.hpp"
#include "components/haldex_control.hpp"
#include "components/network_builder.hpp"
#include "dynamics/simulation.hpp"
#include "components/multirate_clutch.hpp"

namespace shudder::components {

class NetworkStepper {
 public:
  /// Builds `spec` (which must outlive the stepper); throws NetworkError for a bad network.
  explicit NetworkStepper(const NetworkSpec& spec, double end_s);
  ~NetworkStepper();
  NetworkStepper(const NetworkStepper&) = delete;
  NetworkStepper& operator=(const NetworkStepper&) = delete;

  /// Advances to min(t_s, end): `on_sample` at every sample time passed, `after_step` after
  /// every thermal step completed (the control units already updated with its oil).
  void advance_to(double t_s, const std::function<void(const dynamics::Sample&)>& on_sample = {},
                  const std::function<void(const components::SlowStep&)>& after_step = {});

  const BuiltNetwork& built() const { return *built_; }
  BuiltNetwork& built() { return *built_; }
  dynamics::Simulation& simulation() { return *sim_; }
  const dynamics::Simulation& simulation() const { return *sim_; }
  /// Every wet clutch's thermal state, in clutch order.
  const std::vector<clutch::ThermalState>& thermal() const { return thermal_; }
  /// Clutch c's index into thermal() (-1: a plain clutch).
  const std::vector<int>& wet_index() const { return wet_index_; }
  /// Each wet clutch's friction data tally, in the order of thermal().
  const std::vector<clutch::FrictionDataRange>& data_ranges() const { return ranges_; }

 private:
  std::unique_ptr<BuiltNetwork> built_;
  std::vector<clutch::ThermalState> thermal_;
  std::vector<int> wet_index_;
  std::vector<HaldexControlUnit> units_;
  std::vector<std::size_t> unit_wet_;  // each unit's coupling's index into thermal_
  std::vector<clutch::FrictionDataRange> ranges_;
  std::unique_ptr<dynamics::Simulation> sim_;
  std::unique_ptr<components::MultirateCoupling> coupling_;
  double instants_until_s_ = 0.0;  // the control units' instants are the coupling's breaks up to here
  double instants_chunk_s_ = 0.0;  // how far each addition reaches (the scenario's duration)
};

}  // namespace shudder::components
