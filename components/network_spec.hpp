#pragma once
// A drivetrain described by its components and the nodes they join (docs/formats/network_file.md):
// the plain description a scenario file is read into (io/network_scenario.hpp) and a network is
// built from (components/network_builder.hpp). Nodes are the inertias, named by the user;
// "ground" is the fixed frame. Units SI (rad/s, N m, N, kg m², m); files use rpm where engineers
// do and say so in the key.

#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "clutch/fluid.hpp"
#include "clutch/wet_clutch.hpp"
#include "components/plain_friction.hpp"
#include "components/signal.hpp"
#include "dynamics/simulation.hpp"
#include "components/clutch_contact.hpp"
#include "components/engine.hpp"
#include "components/engine_pulsation.hpp"
#include "components/haldex_controller.hpp"
#include "components/haldex_hydraulics.hpp"
#include "components/motor_ripple.hpp"
#include "components/tyre.hpp"

namespace shudder::components {

inline constexpr const char* kGroundNode = "ground";

struct InertiaSpec {
  std::string name;
  double inertia_kg_m2 = 0.0;  // >= 0; 0 only where a gear or differential fixes its speed
  double speed_rad_s = 0.0;    // at t = 0
  double angle_rad = 0.0;      // at t = 0 (a shaft's start twist is the difference of its ends')
};
/// T = k (θ_a − θ_b) + c (ω_a − ω_b) from a to b; with lash > 0 a dead zone of that total width
/// (components/lash_shaft.hpp).
struct ShaftSpec {
  std::string name, a, b;
  double stiffness_Nm_per_rad = 0.0, damping_Nms_per_rad = 0.0, lash_rad = 0.0;
};
/// ω_input = ratio · ω_output (ideal, lossless).
struct GearSpec {
  std::string name, input, output;
  double ratio = 1.0;
};
/// ω_left + ω_right = 2 ω_carrier (open, massless, equal torque split).
struct DifferentialSpec {
  std::string name, carrier, left, right;
};
/// A wet clutch's pack: the clutch, its fluid, the effects outside the clutch (bearing drag,
/// stick-time static friction), as a scenario's [clutch] and [effects] give them.
struct WetPackSpec {
  std::string fluid_path, fluid_text;
  clutch::Fluid fluid;
  clutch::WetClutchParams clutch;
  components::BearingDrag bearing_drag;
  components::StickTimeFriction stick_time;
  std::vector<std::string> enabled_effects;
  bool oil_volume_given = false, oil_flow_given = false;  // the [clutch] table's oil.sump_volume_ml, supply_flow_ml_min
  // The clutch already built from `clutch` (with the pack's oil applied) and `fluid`, which a
  // machine that writes itself as a network from its own clutch hands over: the builder then
  // takes it instead of building its own (building one assembles the thermal model's grid).
  std::shared_ptr<const clutch::WetClutch> prebuilt;
};
/// A Haldex limited-slip coupling's own parts beside its wet pack (components/haldex_coupling_law.hpp):
/// the hydraulics that clamp the pack (F = F_preload + A p, p a state of the run) and the control
/// unit that sets their throttle valve every control period from two axle speeds, sampled and
/// filtered as a real unit reads them (components/haldex_controller.hpp), or raw valve schedules.
struct HaldexSpec {
  components::HaldexHydraulicsParams hydraulics;
  components::HaldexControllerParams controller;
  double nominal_friction = 0.12;  // μ_nom of the preload's force (estimate: wet clutch)
  // The pack's own oil, shared by its interfaces unless the [clutch] table's oil says otherwise
  // (components/pack_oil.hpp).
  double pack_oil_volume_ml = 600.0, pack_cooling_flow_ml_min = 300.0;
  std::string front_axle, rear_axle;  // nodes whose speeds the unit reads (each axle's carrier)
  // ρ̄ of each axle: its wheels' mean path over the vehicle's in a steady turn (1 straight); the
  // unit takes the difference they explain as geometry, not slip.
  double front_path_ratio = 1.0, rear_path_ratio = 1.0;
  double wheel_radius_m = 0.0;               // maps an axle's speed to the vehicle speed the unit estimates
  Signal pedal = Signal::constant(0.0);      // accelerator pedal 0–1 the unit reads
  std::optional<Signal> valve_opening;       // raw opening schedule (0 shut – 1 open) instead of the unit
  std::optional<Signal> valve_pressure_bar;  // raw pressure setting (valve shut below it) instead of the unit
};
/// A clutch between a and b, or a brake (b = "ground"). Normal force F = max_force_N · max(u, 0),
/// or, for a Haldex coupling, the clamp force of its hydraulics.
struct ClutchSpec {
  enum class Law { kPlain, kWet, kHaldex };
  std::string name, a, b;
  Law law = Law::kPlain;
  double max_force_N = 0.0;
  Signal force_signal = Signal::constant(1.0);
  PlainFrictionParams plain;  // law kPlain (its max_force_N is this one's)
  WetPackSpec wet;            // law kWet and kHaldex: the pack
  HaldexSpec haldex;          // law kHaldex
  std::string judged_on;      // a shaft whose torque the verdict is judged on; "" = the clutch's own
};
/// A one-way clutch: carries torque from `driving` to `driven` when driving would turn faster;
/// driven may overrun driving (components/one_way_clutch.hpp). `driven` may be ground (a backstop).
struct FreewheelSpec {
  std::string name, driving, driven;
  double drag_Nm = 0.0;
};
struct TorqueSourceSpec {
  std::string name, node;
  Signal torque_Nm = Signal::constant(0.0);  // on the node, positive along its speed
};
struct SpeedSourceSpec {
  std::string name, node;
  Signal speed_rpm = Signal::constant(0.0);
};
struct MotorSpec {
  std::string name, node;
  Signal speed_rpm = Signal::constant(0.0);  // the speed loop's set point
  double kp_Nms_per_rad = 0.0, ki_Nm_per_rad = 0.0, torque_limit_Nm = 0.0;
  double start_torque_Nm = 0.0;  // the integrator's torque at t = 0 (ki ∫e = start torque)
  components::MotorRipple ripple{0.0,
                                 576.0};  // the drive's torque ripple A sin(2π N rev) (motor_ripple.hpp); A = 0: none
};
/// components/engine.hpp's torque map on a node, driven by a throttle signal (0–1).
struct EngineSpec {
  std::string name, node;
  components::EngineParams params;
  Signal throttle = Signal::constant(0.0);
};
/// The car's translational mass as a node of inertia m r² (speed ω = v / r) with its road load
/// (rolling resistance, drag) and grade to ground.
struct VehicleSpec {
  std::string name;
  double mass_kg = 0.0, wheel_radius_m = 0.0, speed_m_s = 0.0, grade_percent = 0.0;
  double cg_height_m = 0.0;                                  // h; 0: no load transfer
  std::optional<double> wheelbase_m, front_axle_load_share;  // required by tyres with an axle
  components::RoadLoadParams road;                           // rolling_resistance_N from f_r m g cos θ when not given
};
/// A tyre between a wheel node and a vehicle node (components/tyre.hpp).
struct TyreSpec {
  std::string name, wheel, vehicle;
  components::TyreParams params;  // vertical_load_N and load_transfer set by the builder for an axle
  double path_ratio = 1.0;        // ρ: the wheel's path over the vehicle's in a steady turn (1 straight)
  enum class Axle { kNone, kFront, kRear } axle = Axle::kNone;
};
/// An engine's firing-order torque pulsation on a node (components/engine_pulsation.hpp).
struct FiringPulsationSpec {
  std::string name, node;
  components::EnginePulsation params;
  double stall_speed_rpm = 0.0, idle_speed_rpm = 0.0;
};

struct NetworkSettings {
  double duration_s = 1.0;
  double sample_rate_Hz = 1000.0;
  double thermal_step_s = 0.01;  // wet clutches' thermal step (the multi-rate coupling)
  dynamics::IntegratorSettings integrator{1e-7, 1e-6, 1e-3, 1e-6, 1e-10};
};

struct NetworkSpec {
  std::vector<InertiaSpec> inertias;
  std::vector<ShaftSpec> shafts;
  std::vector<GearSpec> gears;
  std::vector<DifferentialSpec> differentials;
  std::vector<ClutchSpec> clutches;
  std::vector<FreewheelSpec> freewheels;
  std::vector<TorqueSourceSpec> torque_sources;
  std::vector<SpeedSourceSpec> speed_sources;
  std::vector<MotorSpec> motors;
  std::vector<EngineSpec> engines;
  std::vector<VehicleSpec> vehicles;
  std::vector<TyreSpec> tyres;
  std::vector<FiringPulsationSpec> firing_pulsations;
  NetworkSettings settings;
};

}  // namespace shudder::components
