#pragma once
// Linearisation of a TorsionalNetwork about an operating point, WITH the internal states of its
// force elements (e.g. a tyre's relaxation), the speed dependence of its torque sources (an
// engine's torque–speed slope) and the friction slope of its slipping contacts. The undamped
// `TorsionalNetwork::modes` treats force elements as springs; this keeps their dynamics.
//
// Node speeds ω = N v, angles θ = N q (N = constraint_basis(stuck), n x r: gears, differentials,
// speed sources and stuck contacts eliminated). Perturbing about (ω₀, z₀) at time t:
//
//   shafts, motors      −K N δq − C N δv               (K, C: shafts' springs and dampers, the
//                                                       motors' K_i and K_p; no force elements)
//   slipping contact k  damper s_k = dM_k/d|Δω| (ContactLaw::kinetic_torque_slope_Nms at |Δω₀|)
//                       between a and b: a falling friction curve is negative damping
//                       (analysis/stability.hpp, docs/physics.md §6)
//   torque source       δT = (∂T/∂ω) δω_node for a source with torque_at_speed_Nm (engine map)
//   force element e     T = T(ω_a, ρ ω_b, z), ż = g(ω_a, ρ ω_b, z); torque −T on a, +ρ T on b:
//       δT = T_a δω_a + T_b ρ δω_b + T_z δz,   δż = g_a δω_a + g_b ρ δω_b + g_z δz
//
//   contact law c with internal states z_c (an actuator's pressure and valve, dynamics/contact_law.hpp):
//       δż_c = f_Δω δΔω + f_z δz_c,  and while slipping δM_c = M_z δz_c beside its slope
//
//   x = [δq (r); δv (r); δz (m); δz_c (m_c)],  ẋ = A x:
//     δq̇ = δv
//     M_r δv̇ = −K_r δq − (C_r + Nᵀ(S + D_src)N) δv + Σ_e Nᵀ(−e_a + ρ e_b) δT_e
//     δż = ...                                                   (M_r = NᵀMN, K_r = NᵀKN, ...)
//
// The force elements' and torque-at-speed sources' partial derivatives are central differences
// of their laws (steps 1e-6 relative, ≥ 1e-7 absolute: ~1e-8 relative accuracy for laws smooth on
// that scale; the brush tyre's kinks at full sliding and the transport speed's switch between
// |ω_a r| and |ρ ω_b r| are where a difference straddles a kink). The contacts' slope is the law's own.
// Rigid-body directions (null space of K_r: angles no force depends on) give exact zero
// eigenvalues; `rigid_body_modes` counts them.

#include <Eigen/Dense>
#include <string>
#include <vector>

#include "dynamics/network.hpp"

namespace shudder::dynamics {

/// The motion to linearise about.
struct LinearOperatingPoint {
  double t_s = 0.0;
  Eigen::VectorXd omega_rad_s;     // (n) node speeds
  Eigen::VectorXd element_states;  // (Σ states of the force elements, in element order; periodic forcings left out)
  std::vector<bool> stuck;         // (n_contacts) or empty = all slipping
  /// Contact laws' internal states (Sample::contact_states' layout) at the operating point; they
  /// are linearised with the motion. Empty: each law's start values.
  Eigen::VectorXd contact_states;
  /// Extra node damping (n x n, may be empty), e.g. a thermal admittance's equivalent damper.
  Eigen::MatrixXd extra_damping;
};

/// ẋ = A x with x = [δq; δv; δz; δz_c] (see the header).
struct LinearSystem {
  Eigen::MatrixXd a;                      // (2r + m) x (2r + m)
  Eigen::MatrixXd basis;                  // N (n x r)
  int reduced_dofs = 0;                   // r
  int element_states = 0;                 // m
  int contact_states = 0;                 // m_c: the contact laws' internal states, after the elements'
  int rigid_body_modes = 0;               // r − rank(K_r)
  std::vector<double> contact_slope_Nms;  // (n_contacts) s_k used (0 for stuck contacts)
  /// Node speeds (n) of an eigenvector of A (its δv part mapped through N).
  Eigen::VectorXcd node_speeds(const Eigen::VectorXcd& eigenvector) const;
};

/// Throws std::invalid_argument for vectors of the wrong size or non-finite values/slopes.
LinearSystem linearise_network(const TorsionalNetwork& network, const LinearOperatingPoint& op);

/// One eigenvalue of A with its shape.
struct LinearMode {
  std::complex<double> eigenvalue;  // 1/s
  double frequency_Hz = 0.0;        // |Im λ| / 2π
  double damping_ratio = 0.0;       // −Re λ / |λ| (1 for a real decaying root)
  Eigen::VectorXd node_amplitude;   // (n) |node speed|, largest = 1
  Eigen::VectorXd node_phase_rad;   // (n) phase of each node's speed relative to the largest
};

/// The eigenvalues of A (each oscillatory pair once, Im λ > 0; real roots all, except the
/// rigid-body zeros), sorted by frequency then real part. Without `shapes` the eigenvectors are
/// not computed (node_amplitude and node_phase_rad stay empty; about half the work): the
/// eigenvalues are the same to the bit (the same Hessenberg and Schur steps on A).
std::vector<LinearMode> linear_modes(const LinearSystem& sys, bool shapes = true);

}  // namespace shudder::dynamics
