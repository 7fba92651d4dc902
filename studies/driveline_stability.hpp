#pragma once
// Linear stability and modes of the Haldex driveline (rig_models/haldex_driveline.hpp) about an
// operating point, with the coupling slipping or locked (docs/physics.md §6, §8).
//
// The network is linearised by dynamics/linearisation.hpp with every element's own dynamics:
//   coupling (slipping)  damper s = dM/d|Δω| = n r F dμ/d|Δω| at the point's slip, clamp force
//                        F and interface temperature T, all rings at T (the ISOTHERMAL slope:
//                        temperature held, docs/physics.md §6); a falling μ–v curve is negative damping.
//                        Locked: the constraint ω_in = ω_out instead.
//   tyres                the relaxation state u of each wheel (components/tyre.hpp):
//                        δF = F'(κ')/σ δu, δu̇ = r(δω_w − ρ δω_v) − (V_t/σ) δu − κ' δV_t —
//                        at speed V a spring C_κ r²/σ in series with a damper C_κ r²/V
//                        (the slip's damping falls with speed; at rest a pure spring).
//   engine               −dT/dω of the throttle map as a damper (0 for a raw torque schedule).
//   road load            dF/dv r² as a damper on the car.
//
// The operating point: the car's speed V, the coupling's slip Δω = ω_in − ω_out, clamp force,
// interface temperature and the four tyre forces (the deflections u = σ κ' that carry them, from
// the brush curve; a force at or beyond μ F_z is taken at 0.999 μ F_z, the curve's edge). Node
// speeds: every part rolling with V (rolling_speed_ratios), the rear group (coupling_out to the
// rear wheels) scaled so the coupling slips by Δω — or the node speeds of a simulated sample.

#include <array>
#include <complex>
#include <limits>
#include <vector>

#include "analysis/stability.hpp"
#include "dynamics/linearisation.hpp"
#include "dynamics/recording.hpp"
#include "dynamics/simulation.hpp"
#include "rig_models/haldex_driveline.hpp"
#include "studies/run_verdict.hpp"

namespace shudder::studies {

struct DrivelineOperatingPoint {
  double t_s = 0.0;                  // time the engine's map or schedule is read at
  double vehicle_speed_m_s = 0.0;    // V of the rear axle centre
  double coupling_slip_rad_s = 0.0;  // Δω = ω_in − ω_out
  double clamp_force_N = 0.0;
  double interface_temp_C = 40.0;        // every ring of the pack
  std::array<double, 4> tyre_force_N{};  // FL, FR, RL, RR, driving > 0
  Eigen::VectorXd node_speeds_rad_s;     // (kNodes) if given, used instead of V and Δω
};

/// The quasi-static operating point a manoeuvre starts towards: V = the start speed, Δω = the
/// turn's kinematic slip (at least `min_slip_rpm`), the clamp force the hydraulics reach holding
/// that slip for 100 s against the valve's setting at t = 0 (the pump–leak balance or the valve),
/// the clutch's start temperature, and tyre forces from each group's torque balance with the car
/// accelerating as one body (engine torque at t = 0 and the coupling's kinetic torque there).
/// A finite `clamp_force_N` replaces the hydraulics' (an onset search over the clamp force).
DrivelineOperatingPoint quasi_static_operating_point(const rig_models::HaldexDriveline& dl,
                                                     const clutch::WetClutch& clutch,
                                                     const rig_models::DrivelineInputs& inputs,
                                                     double min_slip_rpm = 1.0,
                                                     double clamp_force_N = std::numeric_limits<double>::quiet_NaN());

/// The operating point of a simulated sample (its node speeds, tyre torques and time) with the
/// clamp force and interface temperature held at that time.
DrivelineOperatingPoint sample_operating_point(const rig_models::HaldexDriveline& dl, const dynamics::Sample& s,
                                               double clamp_force_N, double interface_temp_C);

/// The mean operating point of a driveline recording over [from_s, to_s] (vehicle speed,
/// coupling slip, clamp force, mean interface temperature, tyre forces; t = to_s). Throws
/// std::invalid_argument if a channel is missing or the window holds no sample.
DrivelineOperatingPoint recorded_operating_point(const dynamics::Recording& rec, double from_s, double to_s);

struct DrivelineStability {
  dynamics::LinearSystem system;
  std::vector<dynamics::LinearMode> modes;  // oscillatory pairs once, real roots, no rigid-body zeros
  analysis::StabilityPoint point;           // margin and frequency of the least-damped mode
  double coupling_slope_Nms = 0.0;          // s (0 when locked)
  std::vector<std::string> node_names;      // (kNodes) for the mode shapes
};

/// Linearises `dl` at `op` with the coupling locked or slipping. `extra_damping` (kNodes x
/// kNodes, may be empty) adds node dampers (e.g. the thermal feedback's). Throws
/// std::invalid_argument for a non-finite point or a clamp force <= 0.
DrivelineStability driveline_stability(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                       const DrivelineOperatingPoint& op, bool coupling_locked,
                                       const Eigen::MatrixXd& extra_damping = {});

/// The driveline's lowest oscillating mode with the coupling locked (the shuffle mode, from
/// 0.5 Hz: below it the car's rolling), linearised about a recording's mean operating point over
/// [0, to_s] (driveline_stability.hpp's recorded_operating_point and driveline_stability).
/// NaN frequency and damping when the recording has no such point (e.g. no clamp force).
struct LockedShuffle {
  double frequency_Hz, damping_ratio;
};
LockedShuffle run_shuffle_mode(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                               const dynamics::Recording& rec, double to_s);

/// The slipping coupling's least-damped oscillatory mode: its growth rate σ (1/s, > 0 grows),
/// frequency and damping ratio. NaN if no mode oscillates.
struct CouplingMode {
  double growth_per_s = 0.0, frequency_Hz = 0.0, damping_ratio = 0.0;
};
CouplingMode least_damped_mode(const DrivelineStability& st);
/// least_damped_mode(driveline_stability(dl, clutch, op, false, extra_damping)) to the bit,
/// without the mode shapes and the stability point it does not read (about half the work; the
/// stability maps, the onset search and the thermal rounds call it per point).
CouplingMode least_damped_slipping_mode(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                        const DrivelineOperatingPoint& op, const Eigen::MatrixXd& extra_damping = {});

/// The interface temperature's feedback on the coupling's torque at an oscillation of angular
/// frequency ω (the isothermal slope leaves it out). Per interface (n of them,
/// area A, torque M/n, heat flux q'' = (M/n)|Δω|/A into the discs, all of it: an upper bound):
///   δM_i = s_i δΔω + g_i δT,   δT = Z(iω) δq'' = Z (M_i δΔω + |Δω| δM_i)/A   (g_i = dM_i/dT)
///   ⇒ s_eff = n (s_i + g_i Z M_i/A) / (1 − g_i Z |Δω|/A)
/// with Z the interface's thermal impedance (clutch/interface_thermal_impedance.hpp) and g from
/// the friction law (torque at T ± 0.5 K). Re(s_eff) − s is the damping the temperature adds
/// (< 0 when μ falls with temperature: it destabilises); Im(s_eff)/ω a stiffness (left out).
struct ThermalFeedback {
  double frequency_Hz = 0.0;
  std::complex<double> impedance_m2K_per_W;
  double torque_temperature_slope_Nm_per_K = 0.0;  // dM/dT of the pack
  double coupling_torque_Nm = 0.0;                 // M at the point
  double isothermal_slope_Nms = 0.0;               // s
  std::complex<double> effective_slope_Nms;        // s_eff
  double added_damping_Nms = 0.0;                  // Re(s_eff) − s
};
ThermalFeedback coupling_thermal_feedback(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                          const DrivelineOperatingPoint& op, double frequency_Hz);

/// The least-damped slipping mode with the thermal feedback at that mode's frequency added as a
/// damper across the coupling (one fixed-point round on the frequency, then a second).
CouplingMode least_damped_mode_with_thermal(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                                            const DrivelineOperatingPoint& op);

/// The clamp force (N) in [lo_N, hi_N] at which the least-damped slipping mode of the
/// manoeuvre's quasi-static operating point (at that clamp force) crosses zero growth, by
/// bisection to 1e-6 relative (isothermal, or with the thermal feedback). NaN if the growth has
/// the same sign at both ends.
double onset_clamp_force_N(const rig_models::HaldexDriveline& dl, const clutch::WetClutch& clutch,
                           const rig_models::DrivelineInputs& inputs, double lo_N, double hi_N, bool thermal = false);

/// Stability maps of the slipping coupling over slip × interface temperature, one per clamp
/// force (named `coupling_stability_map_<k>`, k = 1, 2, ... with the scalar normal_force_N):
/// the least-damped oscillatory mode's growth rate (1/s, > 0 judder) and frequency at the
/// operating point `op` with its slip, temperature and clamp force replaced (every part rolling
/// with V, the tyre forces of `op`). Layers: growth_per_s, frequency_Hz, damping_ratio.
std::vector<dynamics::Map2D> coupling_stability_maps(const rig_models::HaldexDriveline& dl,
                                                     const clutch::WetClutch& clutch, const DrivelineOperatingPoint& op,
                                                     const std::vector<double>& slips_rpm,
                                                     const std::vector<double>& temps_C,
                                                     const std::vector<double>& forces_N);

/// The run's prediction (run_verdict.hpp) at the judged window's mean operating point of a
/// driveline recording: the coupling slipping, isothermal slope. "not predicted" if the coupling
/// was stuck over the window (|mean slip| < 0.1 rpm), unloaded, or the point is not finite.
Prediction predict_driveline(const rig_models::DrivelineParams& params, const clutch::WetClutch& clutch,
                             const rig_models::DrivelineInputs& inputs, const dynamics::Recording& rec,
                             const OperatingWindow& w);

}  // namespace shudder::studies
