#pragma once
// Linear stability of steady sliding for any torsional network (docs/physics.md §6; Papers A, B, D).
//
// Steady sliding: every slipping contact k runs at a constant relative speed Δω_k = ω_a − ω_b
// (rad/s) and transmits the kinetic torque M_k(|Δω_k|, t): −sign(Δω_k) M_k on a, +sign(Δω_k) M_k
// on b. Perturbing the node angles about that motion, θ = θ₀(t) + δθ, and keeping first-order
// terms:
//
//   slipping contact k   d[sign(Δω) M_k(|Δω|)]/dΔω = s_k = dM_k/d|Δω| for either sign of Δω, so
//                        δ(torque on a) = −s_k (δω_a − δω_b), δ(torque on b) = +s_k (δω_a − δω_b):
//                        a DAMPER of coefficient s_k (N m s/rad) between a and b (to ground if
//                        b is ground). s_k is the slope at CONSTANT temperature
//                        (ContactLaw::kinetic_torque_slope_Nms): vibrations grow on time scales
//                        of 0.01–0.1 s on which the interface temperature does not move
//                        (docs/physics.md §6, Van de Velde). For a clutch with n interfaces at mean
//                        radius r under clamp force F, s_k = n F r² dmu/dv (v = r |Δω|); a
//                        falling mu–v curve (s_k < 0) is NEGATIVE damping.
//   stuck contact        constraint δω_a = δω_b (its torque is a reaction); 0 slip or a flag.
//   motor (PI, not       δT = −K_p δω − K_i δθ (dI/dt = ω_ref − ω ⇒ δI = −δθ): a damper K_p and
//     saturated)         a spring K_i to ground — already in the network's stiffness/damping
//                        matrices.
//   shafts               their springs and dampers; gears and speed sources are constraints
//                        ω = N q (TorsionalNetwork::constraint_basis), reducing M, C, K to
//                        M_r = Nᵀ M N etc.
//
//   M_r q̈ + (C_r + Nᵀ S N) q̇ + K_r q = 0,      S = Σ_k s_k (e_a − e_b)(e_a − e_b)ᵀ   (n x n)
//   x = [q; q̇],  ẋ = A x,  A = [0  I; −M_r⁻¹ K_r  −M_r⁻¹ (C_r + Nᵀ S N)]       (2r x 2r)
//
// Each eigenvalue λ = σ ± i ω_d of A (TorsionalNetwork::modes(stuck, S).damped_eigenvalues) is
// a mode growing as e^{σ t} (1/s) and oscillating at ω_d / 2π Hz. The stability MARGIN is the
// largest σ: > 0 unstable, onset where it crosses zero. Free rigid-body directions (null space
// of K_r, e.g. a shaft line held by no spring) each give one eigenvalue λ = 0, the drift of an
// angle no force depends on; the `rigid_body_modes` eigenvalues of smallest |λ| are left out
// of the margin. A free UNDAMPED rigid body gives a second, neutral (≈ 0) eigenvalue that stays
// in; `stable` treats |σ| up to 1e-8 · max|λ| as neutral, i.e. stable.
//
// One degree of freedom (a housing J on a bar k, c driven through the contact at constant
// speed): J δθ̈ + (c + s) δθ̇ + k δθ = 0, unstable iff c + n F r² dmu/dv < 0, growth rate
// −(c + s)/(2J), frequency √(k/J − ((c + s)/2J)²)/2π. In a full driveline the slope sign alone
// does not decide (Cameron, docs/physics.md §6): the eigenvalues of the whole system do.

#include <Eigen/Dense>
#include <vector>

#include "dynamics/network.hpp"

namespace shudder::analysis {

/// The steady motion to linearise about.
struct SteadySliding {
  std::vector<double> slip_rad_s;  // (n_contacts) Δω_k = ω_a − ω_b; exactly 0 ⇒ stuck
  std::vector<bool> stuck;         // (n_contacts) or empty; true ⇒ stuck whatever the slip
  double t_s = 0.0;                // time at which the laws are evaluated (force schedules)
};

/// Result of a linearisation.
struct StabilityPoint {
  double margin_per_s = 0.0;  // largest real part (rigid-body drift excluded), 1/s; > 0 unstable
  double frequency_Hz = 0.0;  // |Im λ|/2π of that mode (0 if it is a real eigenvalue)
  // The oscillatory mode (Im λ ≠ 0) with the largest real part; NaN if there is none.
  double oscillatory_margin_per_s = 0.0;
  double oscillatory_frequency_Hz = 0.0;
  bool stable = true;            // margin_per_s <= 1e-8 · max|λ| (neutral counts as stable)
  int rigid_body_modes = 0;      // zero eigenvalues left out of the margin
  Eigen::VectorXcd eigenvalues;  // (2r) all eigenvalues of A, 1/s (sorted by |Im|)
};

/// The friction-slope damping S (n x n) of the slipping contacts (see the header comment).
/// Throws std::invalid_argument if the slip vector does not match the contacts or a value or
/// a law's slope is not finite.
Eigen::MatrixXd friction_slope_damping(const dynamics::TorsionalNetwork& network, const SteadySliding& steady);

/// Linearises the network about the steady sliding and returns its eigenvalues and margin.
/// The network must be valid (TorsionalNetwork::validate); input errors as above.
StabilityPoint linearise(const dynamics::TorsionalNetwork& network, const SteadySliding& steady);

/// Margin, frequencies and flag from the eigenvalues of A, leaving out the `rigid_body_modes`
/// eigenvalues of smallest modulus (used by linearise; public for callers with their own A).
StabilityPoint stability_from_eigenvalues(const Eigen::VectorXcd& eigenvalues, int rigid_body_modes);

}  // namespace shudder::analysis
