#pragma once
// A Haldex coupling's control unit in a network run (a haldex_coupling component): what the
// driveline scenario's car does for its one coupling, for any coupling of any network.
//
// Every control period T_c (components/haldex_controller.hpp) the unit reads the two axle nodes'
// mean speeds over the period just ended (the angle each turned over T_c, as a pulse-counting
// wheel-speed sensor gives it), low-passes them with τ_f, and sets the throttle valve's opening
// it holds until the next instant:
//   vehicle speed  v = r min(ω_front / ρ̄_f, ω_rear / ρ̄_r)   (the slower axle, as an ABS reference does)
//   reading        front and rear axle rpm, the turn's ρ̄_f / ρ̄_r, the pedal 0–1
//   opening        HaldexController::valve_opening(reading), or a raw opening schedule, or shut
//                  under a raw pressure setting.
// The coupling's leakage follows its oil's viscosity: leak_scale = ν(40 °C) / ν(T_sump) (Walther's
// law of the pack's fluid), set from the pack's thermal state after every thermal step.

#include <vector>

#include "clutch/fluid.hpp"
#include "clutch/thermal_model.hpp"
#include "components/network_builder.hpp"
#include "dynamics/simulation.hpp"
#include "components/haldex_controller.hpp"

namespace shudder::components {

class HaldexControlUnit {
 public:
  /// For a built clutch of law kHaldex; throws std::invalid_argument for bad controller values.
  explicit HaldexControlUnit(const BuiltClutch& coupling);
  /// At t = 0 (every angle 0): signals steady at the nodes' start speeds, the first command set
  /// from them (before the simulation takes the valve's start opening from the command), the
  /// leakage at the pack's start temperature.
  void start(const Eigen::VectorXd& speed_rad_s, const clutch::ThermalState& pack);
  /// The unit's instants k·T_c (k >= 1) in [from, until), each end to 1e-12 s, on the clock
  /// the run started at 0: [0, duration) for a run, then [duration, ...) piece by piece for an
  /// FMU, whose clock starts at 0 at the master's start time.
  std::vector<double> instants(double from_s, double until_s) const;
  /// At a restart time t with the simulation's sample there: acts if t is its next instant.
  void at(double t_s, const dynamics::Sample& s);
  /// After a thermal step of the pack.
  void update_oil(const clutch::ThermalState& pack);
  /// The reading the unit makes of axle speeds (rad/s) at time t.
  components::ControllerReading reading(double t_s, double front_rad_s, double rear_rad_s) const;
  /// The opening it commands for them.
  double commanded_opening(double t_s, double front_rad_s, double rear_rad_s) const;

 private:
  const BuiltClutch& c_;
  const HaldexSpec& h_;
  components::HaldexController controller_;
  clutch::WaltherViscosity viscosity_;
  double nu40_cSt_ = 0, period_s_ = 0, filter_s_ = 0;
  components::SampledSpeedSignal front_, rear_;
  long next_ = 1;  // the next instant is next_ · T_c
};

}  // namespace shudder::components
