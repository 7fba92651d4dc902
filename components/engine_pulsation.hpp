#pragma once
// The engine's firing-order torque pulsation: the driveline's always-present physical
// disturbance, from which an unstable sliding state of the coupling starts to oscillate (without
// it the only seed is the numerical torque step of each slow step, and the onset follows that
// step).
//
//   T_p = A s(ω) sin(k θ)            on the engine node, N m
//   k   = z / 2 pulses per crank revolution (a 4-stroke engine fires each of its z cylinders
//         once every two revolutions; z = 4: the 2nd order, 26.7 Hz at 800 rpm, 100 Hz at 3000)
//   θ   the crank angle, rad, integrated from the engine's speed ω (a state of this element)
//   s   = x² (3 − 2x), x = (ω − ω_stall)/(ω_idle − ω_stall) clamped to [0, 1]: the engine fires
//         only when running (0 below the stall speed, full above idle; engine.hpp's speeds).
//
// A, estimate (the thesis does not model the engine; no public source gives this car's value):
// one cylinder's gas torque (cylinder pressure × piston area × the crank's lever arm) peaks at
// several times the engine's mean torque during its power stroke, so a 4-cylinder petrol
// engine's 2nd-order gas torque at the crank is of the order of the mean, ~100 N m at part load.
// The flywheel and the clutch disc's torsional damper (a dual-mass flywheel in later cars) pass
// a few per cent of it into the gearbox above their ~10 Hz resonance. The model's engine node is
// already the gearbox input (no clutch is modelled), so A is what passes the damper: ~5 % of
// ~100 N m, A = 5 N m — small against the mean torque: a seed, not a load case.
//
// Energy: the element is a source. It keeps the work it has delivered, W (dW/dt = T_p ω), as
// its second state and reports −W as its stored energy, so the network's balance
// (dynamics/network.hpp: T (ω_a − ρ ω_b) = dE/dt + P_diss) holds exactly with P_diss = 0 and
// the pulsation's work appears where it belongs. Over a revolution at steady speed W returns
// to its value: the pulsation adds no mean power. Its modal stiffness is 0 (averaged over a
// revolution it is no spring).

#include "dynamics/network.hpp"

namespace shudder::components {

struct EnginePulsation {
  double amplitude_Nm = 5.0;  // estimate, see header; 0 removes the source
  int cylinders = 4;          // estimate: the 2-litre petrol engine of engine.hpp
};

class EnginePulsationLaw final : public dynamics::ForceLaw {
 public:
  /// Between the engine node (a) and ground. Throws std::invalid_argument for A < 0, fewer than
  /// 1 or more than 16 cylinders, or stall speed >= idle speed (rad/s, > 0).
  EnginePulsationLaw(const EnginePulsation& p, double stall_rad_s, double idle_rad_s);
  int states() const override { return 2; }  // θ (rad), W (J)
  Output evaluate(double omega_engine, double, const double* z, double* dzdt) const override;
  double stored_energy_J(const double* z) const override { return -z[1]; }
  double modal_stiffness_Nm_per_rad() const override { return 0.0; }
  bool is_periodic_forcing() const override { return true; }
  /// T_p on the engine at crank angle θ and speed ω.
  double torque_Nm(double theta_rad, double omega_rad_s) const;

 private:
  EnginePulsation p_;
  double stall_rad_s_, idle_rad_s_;
};

}  // namespace shudder::components
