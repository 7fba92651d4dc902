#pragma once
// The hydraulics of a first-generation Haldex limited-slip coupling (Gen I, VW Golf IV 4motion /
// Audi TT quattro, 1998; the same principle in Gen II): what clamps the disc pack. Generation I
// only — no electric pre-charge pressure, no accumulator, no preload spring of the later ones.
//
// Sources (public, medium reliability; docs/driveline.md):
//   [P1] US 5,405,293 (Haldex): an annular control piston driven through control pins by a cam
//        curve on the other shaft oscillates "with a frequency directly proportional to the
//        rotational speed differential": the pump delivers a fixed volume per relative turn.
//   [P2] US 5,979,631 (Haldex): ring-shaped pistons, check valves, oil removed via an overflow valve.
//   [S1] VW Self-Study Programme 206 "Four-wheel drive with Haldex coupling" (1998): the control
//        unit sets the pressure through a throttle (regulating) valve on the return to the
//        reservoir, from wheel speeds and the accelerator pedal; a pressure-limiting valve;
//        "no strain on the clutch when parking and manoeuvring".
//   [W1] awdwiki.com "Haldex": Gen I–II are reactive: the pump needs slip, the electronics can
//        only lower the pressure, "just 1/4 of a wheel turn is needed to engage".
//
// The pressure chamber behind the clutch piston (one lumped volume):
//
//   C dp/dt = D |Δω| − Q_v(p, u) − G(T) p − Q_r(p),     p_cap = min(p_relief, p_set)
//   Q_v = C_d u a_max √(2 p/ρ)          p >= p_lam   (turbulent, the sharp-edged orifice)
//   Q_v = C_d u a_max √(2/ρ) p/√p_lam   p <  p_lam   (laminar: linear through zero)
//   τ_v du/dt = u_cmd − u                (the valve follows the control unit's command)
//   C = V/β + A²/k_pack                                     (oil and pack compliance)
//   F_clamp = F_preload + A p
//
//   D        pump displacement per radian of relative rotation of the coupling's halves [P1]
//   u        throttle-valve opening 0..1 [S1]; a_max its full flow area; the sharp-edged orifice
//            equation with discharge coefficient C_d. Below p_lam = 0.01 bar the flow turns
//            laminar (the transition every hydraulic library puts at a critical pressure or
//            Reynolds number): without it √p has an infinite slope at p = 0, which an explicit
//            integrator meets as a stiff, non-Lipschitz right-hand side.
//   u_cmd    the opening the control unit commands (components/haldex_controller.hpp); the Gen I
//            unit turns the regulating valve with a servomotor [S1], so the valve lags the
//            command with τ_v (estimate, valve_time_constant_ms)
//   G(T)     laminar leakage (piston seals, check valves), G_40 ν(40 °C)/ν(T) (laminar flow ∝ 1/ν)
//   p_relief the pressure-limiting valve [S1, P2]: it opens in proportion to the pressure above
//            its setting, Q_r = (C/τ_r)(p − p_cap)⁺ with τ_r = 1 ms (estimate: a poppet valve's
//            response), so the pressure overrides the setting by Q τ_r / C (0.07 bar at
//            10 rad/s of slip with the defaults) and falls to a lowered setting within
//            milliseconds; a rate continuous in p, which an explicit integrator steps over at
//            full step size (an ideal cap's switch it can only resolve with ever shorter steps)
//   p_set    an optional raw pressure setting (scenario key valve_pressure_bar), an ideal cap
//   V, β     chamber volume and effective bulk modulus of the oil (air and housing included)
//   A        piston area; k_pack the pack's axial stiffness: the piston's travel as the pressure
//            squeezes the discs' waviness and linings displaces A²/k_pack per pascal
//
// The defaults (each an estimate, reasoning in docs/driveline.md) give full pressure after a
// quarter turn of the WHEEL ([W1]): the coupling turns i_r = 2.6 times the rear wheel, so the pump
// sweeps D i_r π/2 = C p_relief (test). Units: SI inside; bar, cm³, mm² at the interface.
//
// Integration: p and u are states of the coupling's contact law (components/haldex_coupling_law.hpp),
// integrated with the torsional states, so the clamp force follows the slip that pumps it within
// every integrator step. Holding p over a thermal step instead made the force a staircase that
// set the driveline's verdicts (they changed with the thermal step). Time scales: C/(dQ_v/dp)
// ≈ 2 ms at p_lam up to ≈ 35 ms at 1 bar with the valve open, against the integrator's ≤ 1 ms steps.

namespace shudder::components {

struct HaldexHydraulicsParams {
  double relief_pressure_bar = 30.0;           // [S1]-type pressure-limiting valve; "order 10–30 bar" (public)
  double piston_area_cm2 = 60.0;               // estimate: annulus under the discs' 38–56 mm friction ring
  double pump_displacement_cm3_per_rev = 2.5;  // estimate: 2 annular pistons × 5 cm² × 1.25 mm × 2 cam lobes
  double chamber_volume_cm3 = 40.0;            // estimate: piston chamber (60 cm² × ~5 mm) and passages
  double bulk_modulus_bar = 10000.0;           // estimate: mineral oil 1.5 GPa, ~1 GPa with air and housing
  double pack_stiffness_N_per_mm = 72000.0;    // estimate: set so the quarter wheel turn [W1] holds (header)
  double valve_area_mm2 = 0.3;                 // estimate: fully open throttle, a ~0.6 mm orifice
  double discharge_coefficient = 0.7;          // sharp-edged orifice, 0.6–0.7 (textbook)
  double leak_cm3_s_per_bar = 0.005;           // estimate at 40 °C: holds the pressure ~10 s with the valve shut
  double oil_density_kg_m3 = 870.0;            // mineral ATF/Haldex oil
  double preload_torque_Nm = 0.0;              // Gen I has no preload spring [W1]; later generations ~80 N m
  double valve_time_constant_ms = 50.0;  // estimate: a servomotor-driven regulating valve [S1], ~0.1–0.2 s end to end
};

class HaldexHydraulics {
 public:
  /// `pack_torque_per_newton_m` = n μ_nom r_eff of the disc pack (N m per N of clamp force),
  /// used only to turn the preload torque into a force.
  /// Throws std::invalid_argument for non-positive or non-finite parameters.
  HaldexHydraulics(const HaldexHydraulicsParams& params, double pack_torque_per_newton_m);

  /// dp/dt in bar/s at pressure `pressure_bar`, slip |Δω| `abs_slip_rad_s`, the throttle valve
  /// open by `opening` (0–1), the pressure capped at `setting_bar` (≥ relief: no cap but the
  /// relief valve), the leakage scaled by `leak_scale` (ν(40 °C)/ν(T) of the oil).
  double pressure_rate_bar_s(double pressure_bar, double abs_slip_rad_s, double opening, double setting_bar,
                             double leak_scale = 1.0) const;
  /// The steady pressure at a constant |Δω| and valve opening: where pressure_rate_bar_s vanishes
  /// (D|Δω| = Q_v(p, u) + G p + Q_r(p)), with the cap `setting_bar` (≥ relief: the relief valve).
  double steady_pressure_bar(double slip_rad_s, double opening, double leak_scale = 1.0,
                             double setting_bar = 1e9) const;
  double clamp_force_N(double pressure_bar) const;
  /// The pressure that gives a clamp force (0 below the preload), bar.
  double pressure_for_force_bar(double force_N) const;
  /// The laminar–turbulent transition pressure of the valve, bar.
  static constexpr double kLaminarPressure_bar = 0.01;
  /// The relief valve's time constant τ_r (its flow (C/τ_r)(p − p_cap)⁺), s.
  static constexpr double kReliefTime_s = 1e-3;
  double piston_area_m2() const { return area_m2_; }
  double preload_force_N() const { return preload_N_; }
  /// D: pump delivery per radian of relative rotation, m³/rad.
  double displacement_m3_per_rad() const { return displacement_m3_per_rad_; }
  /// C = V/β + A²/k_pack, m³/Pa.
  double compliance_m3_per_Pa() const { return compliance_m3_per_Pa_; }
  /// Laminar leakage at 40 °C, m³/s per Pa.
  double leak_m3_s_per_Pa() const { return leak_m3_s_per_Pa_; }
  /// C_d a_max √(2/ρ): the fully open valve's flow per √Pa.
  double valve_flow_coefficient() const { return valve_k_; }
  const HaldexHydraulicsParams& params() const { return p_; }

 private:
  HaldexHydraulicsParams p_;
  double area_m2_ = 0, preload_N_ = 0, displacement_m3_per_rad_ = 0, compliance_m3_per_Pa_ = 0;
  double leak_m3_s_per_Pa_ = 0, valve_k_ = 0;
};

}  // namespace shudder::components
