#pragma once
// The Limited Slip Clutch Test Rig (thesis "Method"; Papers B, D) as a torsional network:
//
//   motor+gearbox ══ coupling ══ drive shaft ══ friction disc  ┤clutch├  separators+housing
//   [node 0 "drive": reflected motor, gearbox, coupling, shaft, disc]      [node 1 "housing"]
//        ▲ PI speed loop, |T_m| <= 500 Nm, plus the motor's torque ripple (motor_ripple.hpp)
//                                                                                │ torsion bar
//                                                                             torque cell ─ ground
//
// The coupling is "torsionally rigid" (thesis), so motor, coupling, drive shaft and friction
// disc form one inertia. The torque cell is taken as rigid against the bar and reads the bar
// torque T_cell = k_bar θ_h + c_bar ω_h. The bar stiffness is DERIVED from the target natural
// frequency of the clutch-side mode (the housing on the bar with the clutch slipping), refined
// on the modal analysis so the mode matches the target (modes() of the network).
//
// The rig is written as network components (spec(): nodes `drive` and `housing`, `motor`,
// `clutch`, `torsion_bar`; rig_models/rig_expansion.hpp), assembled by
// components/network_builder.hpp and run by components/network_stepper.hpp, the same code as
// any network scenario; what is the rig's own is its parameters, the bar's tuning and the
// channels it records under the measured-run names.
//
// Unpublished quantities (estimates; overridable in [rig]):
//   drive inertia 0.6 kg m²: servo rotor ~1e-3 kg m² through a ~24:1 gearbox (3000 rpm motor
//       for the rig's 125 rpm maximum) gives ~0.58 kg m², plus ~0.02 kg m² of shaft and disc.
//   housing inertia 0.02 kg m²: separator discs, clutch housing and torque-cell flange, a few kg
//       of steel at 60–90 mm radius.
//   bar damping ratio 1 %: structural damping of a steel bar plus its clamps.
//   speed-loop bandwidth 20 Hz, PI zero at a quarter of it: a typical geared servo drive.

#include <memory>
#include <optional>
#include <string>

#include "clutch/wet_clutch.hpp"
#include "dynamics/network.hpp"
#include "dynamics/recording.hpp"
#include "dynamics/simulation.hpp"
#include "components/clutch_contact.hpp"
#include "components/drive_cycle.hpp"
#include "components/motor_ripple.hpp"
#include "components/network_builder.hpp"
#include "components/network_spec.hpp"

namespace shudder::rig_models {

struct RigParams {
  double drive_inertia_kg_m2 = 0.6;                   // estimate, see header
  double housing_inertia_kg_m2 = 0.02;                // estimate, see header
  double bar_natural_frequency_Hz = 378.0;            // Paper D / thesis: bars of 175 and 378 Hz
  double bar_stiffness_Nm_per_rad = 0.0;              // > 0: given directly instead of the frequency
  double bar_damping_ratio = 0.01;                    // estimate
  double speed_loop_bandwidth_Hz = 20.0;              // estimate
  double motor_torque_limit_Nm = 500.0;               // thesis: geared servo motor, max 500 Nm
  double min_speed_rpm = 0.5, max_speed_rpm = 125.0;  // thesis: 0.5–125 rpm
  bool start_at_rest = false;                         // true: everything at rest, bar unloaded, clutch stuck (a test
                                                      // started from standstill); false: steady sliding at the
                                                      // cycle's first speed with the bar carrying the friction torque
  components::MotorRipple motor_ripple;               // the drive's torque ripple (motor_ripple.hpp); amplitude 0: none
  components::BearingDrag bearing_drag;
  components::LoadCell load_cell;  // records g_F * F as normal_force_N (prescribed_slip.hpp)
  components::StickTimeFriction stick_time;
  // Tolerances: the bar twist is ~1e-3 rad and the slip ~0.1–10 rad/s, so 1e-6 absolute and
  // 1e-5 relative per step keep torques to ~0.1 % while the 100–500 Hz bar mode, not accuracy,
  // sets the step (dopri5's stability limit |λ|·h ≈ 3.3). Events are located to 1e-10 s.
  dynamics::IntegratorSettings integrator{1e-6, 1e-5, 1e-3, 1e-6, 1e-10};
};

struct RigSettings {
  double duration_s = 10.0;
  double thermal_step_s = 0.01;
  double sample_rate_Hz = 1000.0;
  std::vector<double> snapshot_times_s;
};

/// The speed loop's PI gains, tuned from the drive inertia and the loop bandwidth ω_c = 2π f_bw:
/// kp = J ω_c, ki = kp ω_c / 4 (PI zero at a quarter of the bandwidth; estimate, see header).
struct SpeedLoopGains {
  double kp_Nms_per_rad, ki_Nm_per_rad;
};
SpeedLoopGains speed_loop_gains(const RigParams& params);

/// The rig's parameters and what is derived from them (the bar's stiffness from its target
/// frequency, the speed loop's gains), and the rig as network components. A const model: a
/// run or an analysis builds its own network from it (build()).
class LsctrRig {
 public:
  /// Throws std::invalid_argument for invalid parameters. `clutch` must outlive the rig.
  LsctrRig(const RigParams& params, const clutch::WetClutch& clutch, const components::DriveCycle& cycle);

  const components::ClutchContact& clutch_contact() const { return contact_; }
  /// Every ring at the clutch's start temperature, the cycle's clamp force.
  components::ClutchHeldInputs start_inputs() const { return contact_.start_inputs(force_N_); }
  /// The rig as network components (rig_models/rig_expansion.hpp), run with `settings`. The spec
  /// holds copies of the clutch's parameters and fluid and stands alone; with `share_clutch` its
  /// networks take this rig's clutch itself instead of building their own (which must then
  /// outlive them).
  components::NetworkSpec spec(const RigSettings& settings, bool share_clutch = false) const;
  /// The network of spec(RigSettings{}): what a run integrates and an analysis linearises
  /// (node kDrive and kHousing, contact kClutch, shaft kBar, motor 0 the drive's). With
  /// `bar_damping_ratio` the bar's damping replaced (its stiffness held). Its clutch context
  /// holds start_inputs().
  components::OwnedNetwork build(std::optional<double> bar_damping_ratio = std::nullopt) const;
  const RigParams& params() const { return p_; }
  double bar_stiffness_Nm_per_rad() const { return k_bar_; }
  double bar_damping_Nms_per_rad() const { return c_bar_; }
  double motor_kp() const { return kp_; }
  double motor_ki() const { return ki_; }
  /// Frequency of the clutch-side (housing) mode with the clutch slipping, Hz.
  double clutch_side_frequency_Hz() const;

  static constexpr int kDrive = 0, kHousing = 1, kClutch = 0, kBar = 0;

 private:
  components::NetworkSpec spec_with_bar(double k_bar, double c_bar, const RigSettings& settings,
                                        bool share_clutch) const;
  components::OwnedNetwork build_with_bar(
      double k_bar, double c_bar, components::NetworkChecks checks = components::NetworkChecks::kSkipTopology) const;
  RigParams p_;
  const clutch::WetClutch* clutch_;
  components::ClutchContact contact_;
  components::DriveCycle cycle_;
  components::PiecewiseLinear force_N_;
  double k_bar_ = 0, c_bar_ = 0, kp_ = 0, ki_ = 0;
  // Stiffness the network is built with: k_bar_ itself unless the tuning loop ran out of
  // iterations (then k_bar_ holds the next correction, as it always has).
  double k_network_ = 0;
  double clutch_side_Hz_ = -1.0;  // from the tuning's modal analysis; < 0: not computed
};

/// Simulates the rig on the cycle: its network (spec()) run by components::NetworkStepper, the
/// clutch's thermal model coupled multi-rate, recorded as the rig's sensors
/// (docs/formats/measured_run.md names) plus internal signals.
dynamics::Recording run_rig(const RigParams& params, const clutch::WetClutch& clutch,
                            const components::DriveCycle& cycle, const RigSettings& settings);

}  // namespace shudder::rig_models
