#pragma once
// A torsional multi-body network: rigid inertias (nodes) joined by shafts (spring–dampers),
// ideal gears, friction contacts; driven by torque sources, speed sources and speed-controlled
// motors. The network is the const MODEL (parameters, topology); the integrator owns the state.
//
// Equations of motion (node angles θ, speeds ω, rad and rad/s):
//
//     J_i dω_i/dt = Σ shaft, source, motor and slipping-contact torques on i  − (Gᵀ μ)_i
//     G dω/dt     = b(t)                       (active kinematic constraints)
//
// Shaft k between a and b:  T = k_s (θ_a − θ_b) + c_s (ω_a − ω_b), acting −T on a, +T on b
//                           (k_s >= 0, c_s >= 0, not both 0: k_s = 0 is a pure damper).
// Gear (a, b, ratio):       ω_a = ratio · ω_b  (constraint row e_a − ratio e_b).
// Differential (c; l, r):   ω_l + ω_r = 2 ω_c  (an open differential without inertia of its own:
//                           constraint row e_l + e_r − 2 e_c; it splits the carrier's torque equally).
// Force element (a, b, ρ):  a nonlinear element with internal states z (e.g. a tyre with its
//                           relaxation, a road load): torque −T on a, +ρ T on b, where
//                           T, dz/dt = law(ω_a, ρ ω_b, z); its power T (ω_a − ρ ω_b) = dE(z)/dt + P_diss
//                           with E the law's stored energy and P_diss what it dissipates (>= 0
//                           but for a law that exchanges energy with a part the network leaves
//                           out, e.g. a tyre's load transfer through the body's pitch).
// Speed source on i:        ω_i = ω_ref(t)      (constraint row e_i, b = dω_ref/dt).
// Stuck contact (a, b):     ω_a = ω_b           (constraint row e_a − e_b); its torque −μ.
// Motor on i (PI speed loop with torque limit and anti-windup by back-calculation):
//     T_m = clamp(K_p e + K_i I, ±T_max),  e = ω_ref(t) − ω_i,
//     dI/dt = e + (T_m − K_p e − K_i I)/(0.9 K_p)   (= e while not clamped; K_p = 0: dI/dt = e,
//     frozen while clamped and e pushes further).
// Node index kGround (−1) is the fixed frame.

#include <Eigen/Dense>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "dynamics/contact_law.hpp"

namespace shudder::dynamics {

inline constexpr int kGround = -1;
using TimeFunction = std::function<double(double t_s)>;

struct Inertia {
  std::string name;
  double inertia_kg_m2 = 0.0;
};
struct Shaft {
  std::string name;
  int a = kGround, b = kGround;
  double stiffness_Nm_per_rad = 0.0;
  double damping_Nms_per_rad = 0.0;
};
struct Gear {
  std::string name;
  int a = kGround, b = kGround;
  double ratio = 1.0;  // ω_a = ratio · ω_b
};
struct Differential {
  std::string name;
  int carrier = kGround, left = kGround, right = kGround;
};

/// Adds a two-node coupling of strength g (a spring's stiffness or a damper's coefficient)
/// between nodes a and b (b may be kGround) to a symmetric n×n matrix.
void stamp_coupling(Eigen::MatrixXd& m, int a, int b, double g);

/// The constitutive law of a ForceElement (see the header).
class ForceLaw {
 public:
  virtual ~ForceLaw() = default;
  virtual int states() const = 0;
  struct Output {
    double torque_Nm = 0.0;     // T, acting −T on a and +ρ T on b
    double dissipated_W = 0.0;  // P_diss (see the header)
  };
  /// `omega_b_at_a` = ρ ω_b; writes dz/dt (states() values) into `dzdt`.
  virtual Output evaluate(double omega_a, double omega_b_at_a, const double* z, double* dzdt) const = 0;
  virtual double stored_energy_J(const double* z) const = 0;
  /// The element as a linear spring between a and b for small motions (modes): dT/dθ at rest.
  virtual double modal_stiffness_Nm_per_rad() const = 0;
  /// The states at the start of a run from the start speeds (default: all 0), e.g. a filter's
  /// state at the speed it filters.
  virtual void initial_states(double /*omega_a*/, double /*omega_b_at_a*/, double* /*z*/) const {}
  /// True for a disturbance prescribed along the motion (e.g. an engine's firing pulsation): it has
  /// no linear part about the mean motion, so linearisation leaves it and its states out.
  virtual bool is_periodic_forcing() const { return false; }
};
struct ForceElement {
  std::string name;
  int a = kGround, b = kGround;  // b may be ground
  double ratio = 1.0;            // ρ
  std::shared_ptr<const ForceLaw> law;
};

struct TorqueSource {
  std::string name;
  int node = kGround;
  TimeFunction torque_Nm;
  /// If set, used instead of torque_Nm: a torque that depends on the node's speed (an engine map).
  std::function<double(double t_s, double omega_rad_s)> torque_at_speed_Nm = nullptr;
};
struct SpeedSource {
  std::string name;
  int node = kGround;
  TimeFunction speed_rad_s;
  TimeFunction acceleration_rad_s2;  // derivative of speed_rad_s
};
struct Motor {
  std::string name;
  int node = kGround;
  TimeFunction speed_ref_rad_s;
  double kp_Nms_per_rad = 0.0;   // proportional gain
  double ki_Nm_per_rad = 0.0;    // integral gain
  double torque_limit_Nm = 0.0;  // |T_m| <= limit
};
struct FrictionContact {
  std::string name;
  int a = kGround, b = kGround;  // Δω = ω_a − ω_b
  std::shared_ptr<const ContactLaw> law;
};

/// Modal data of the undamped system K φ = ω² M φ (gears and constraints eliminated).
struct Modes {
  Eigen::VectorXd frequencies_Hz;       // ascending; rigid-body modes have 0
  Eigen::MatrixXd shapes;               // columns: node amplitudes, max |entry| = 1
  Eigen::VectorXcd damped_eigenvalues;  // of the first-order system, 1/s (sorted by |imag|)
};

class TorsionalNetwork {
 public:
  int add_inertia(Inertia i);
  int add_shaft(Shaft s);
  int add_gear(Gear g);
  int add_torque_source(TorqueSource s);
  int add_speed_source(SpeedSource s);
  int add_motor(Motor m);
  int add_contact(FrictionContact c);
  int add_differential(Differential d);
  int add_force_element(ForceElement e);

  int nodes() const { return static_cast<int>(inertias_.size()); }
  const std::vector<Inertia>& inertias() const { return inertias_; }
  const std::vector<Shaft>& shafts() const { return shafts_; }
  const std::vector<Gear>& gears() const { return gears_; }
  const std::vector<TorqueSource>& torque_sources() const { return torque_sources_; }
  const std::vector<SpeedSource>& speed_sources() const { return speed_sources_; }
  const std::vector<Motor>& motors() const { return motors_; }
  const std::vector<FrictionContact>& contacts() const { return contacts_; }
  const std::vector<Differential>& differentials() const { return differentials_; }
  const std::vector<ForceElement>& force_elements() const { return force_elements_; }

  /// Mass, stiffness and damping matrices over the nodes (n x n). Motors count as a spring
  /// K_i and damper K_p to ground (their linear, unsaturated loop); contacts add nothing; force
  /// elements their modal stiffness.
  Eigen::MatrixXd mass_matrix() const;
  Eigen::MatrixXd stiffness_matrix() const;
  Eigen::MatrixXd damping_matrix() const;
  /// Modes with the given contacts stuck (others slipping, i.e. no stiffness).
  /// `extra_damping` (n x n, may be empty) adds e.g. friction-slope terms.
  Modes modes(const std::vector<bool>& stuck = {}, const Eigen::MatrixXd& extra_damping = {}) const;
  /// Basis N (n x r) of the node speeds allowed by gears, speed sources (ω fixed → 0) and the
  /// stuck contacts: ω = N q.
  Eigen::MatrixXd constraint_basis(const std::vector<bool>& stuck) const;

  /// Throws std::invalid_argument naming the element if a node index or parameter is invalid.
  void validate() const;

  /// Every contact law's internal states at their start values, in contact order (the layout of
  /// Sample::contact_states), and where contact c's start in it.
  Eigen::VectorXd initial_contact_states() const;
  std::vector<int> contact_state_indices() const;

 private:
  void check_node(int node, const std::string& what, bool ground_ok) const;
  std::vector<Inertia> inertias_;
  std::vector<Shaft> shafts_;
  std::vector<Gear> gears_;
  std::vector<TorqueSource> torque_sources_;
  std::vector<SpeedSource> speed_sources_;
  std::vector<Motor> motors_;
  std::vector<FrictionContact> contacts_;
  std::vector<Differential> differentials_;
  std::vector<ForceElement> force_elements_;
};

}  // namespace shudder::dynamics
