#pragma once
// Wet clutch: boundary friction on radial rings coupled both ways with the thermal field.
//
//   p      = F / A                         uniform nominal pressure on the model annulus (Pa)
//   v_i    = r_i * |Δω|                    local sliding speed of ring i (m/s; mm/s for mu)
//   mu_i   = mu(v_i, T_i, F)               boundary friction (Paper G eq. 13) at the ring's
//                                          interface temperature
//   M      = n * sum_i r_i * p * mu_i * A_i * sign(Δω)  (+ viscous shear)   torque, N m
//   q_i    = |Δω| * r_i * p * mu_i * A_i   heat into ring i of ONE interface (Paper G eq. 4), W
//
// For a uniform mu, M = mu F r_eff n with r_eff = sum(r_i A_i)/sum(A_i) (mean_radius_m): the
// model's friction radius (clutch/friction_radius.hpp). A fluid whose law was fitted at another
// radius (Fluid::friction_radius_mm) is converted to this one when the clutch is built.
// n = number of sliding interfaces (Paper G simulates one). Each interface has the same
// thermal domain by symmetry, so one ThermalModel serves them all.
//
// Effect switches handled here (docs/formats/diagnosis_json.md):
//   temperature_dependent_friction  off: every ring uses the clutch start temperature
//   load_dependent_friction         off: friction evaluated at reference_load_N
//   viscous_shear                   adds the Couette torque of the film,
//                                   M_v = n * sum_i eta(T_i) * r_i|Δω| / h_v * r_i * A_i,
//                                   eta = rho * nu(T) (Walther), and its heat.
// The thermal ones (oil cooling, sump, rig mass, sensor lag) live in ThermalModel.

#include <Eigen/Dense>
#include <vector>

#include "clutch/fluid.hpp"
#include "clutch/thermal_model.hpp"

namespace shudder::clutch {

struct WetClutchParams {
  int sliding_interfaces = 1;       // Paper G: one
  double start_temp_C = 20.0;       // discs and inner boundary at t = 0
  double sump_start_temp_C = 20.0;  // sump (outer boundary) at t = 0
  ThermalParams thermal;
  bool temperature_dependent_friction = true;
  bool load_dependent_friction = true;
  double reference_load_N = 20000.0;  // used when load_dependent_friction is off (Paper E load)
  bool viscous_shear = false;
  double viscous_gap_m = 10e-6;  // estimate: Paper G's mean film thickness h_mean
};

/// Every ring's friction at held temperatures and one load, as a function of slip only: built
/// once per thermal step so the fast dynamics evaluate the clutch cheaply (ring_torque_Nm of a
/// frozen state equals the direct evaluation to round-off).
///   mu_i(v) = Σ_k rate_weight(i, k) tanh(rates[k] v) + power_weight_i v^0.1 + offset_i,
///   v = r_i |Δω| clamped to [min_speed_mm_s, max_speed_mm_s]
/// is ring i's SpeedCurve with its terms regrouped over the rates of all rings (a weight is 0
/// where a ring's curve lacks that rate), so one pass over the rings at one slip takes each
/// rate's tanh along the rings once (ring_torque_Nm).
struct FrozenFriction {
  std::vector<SpeedCurve> curves;  // (n_r); empty if the law has no SpeedCurve form
  Eigen::VectorXd ring_temp_C;     // (n_r) held temperatures
  Eigen::VectorXd viscous_Nms;     // (n_r) viscous torque per rad/s of slip, per ring
  Eigen::VectorXd radius_pow;      // (n_r) (r_i in mm)^0.1: v_i^0.1 = r_i^0.1 · |Δω|^0.1
  double load_N = 0.0;             // load at which mu was frozen
  // The curves regrouped (empty with `curves`):
  std::vector<double> rates;                          // distinct b_j of all rings, 1/(mm/s)
  Eigen::MatrixXd rate_weight;                        // (n_r, rates) a_j of ring i at rates[k]
  Eigen::VectorXd power_weight, offset;               // (n_r) c and d of each ring
  double min_speed_mm_s = 0.0, max_speed_mm_s = 0.0;  // the speed clamp, one for every ring
};

class WetClutch {
 public:
  /// Throws std::invalid_argument for invalid parameters.
  WetClutch(WetClutchParams params, Fluid fluid);

  ThermalState initial_state() const;
  const ThermalModel& thermal() const { return thermal_; }
  const Fluid& fluid() const { return fluid_; }
  const WetClutchParams& params() const { return p_; }

  double pressure_Pa(double force_N) const { return force_N / thermal_.contact_area_m2(); }
  /// Area-weighted mean radius r_eff = sum(r_i A_i) / sum(A_i), m: the model's friction radius.
  double mean_radius_m() const;

  /// What a caller keeps across ring_mu / ring_torque_Nm / ring_heat_W calls so that calls at
  /// the same slip reuse the friction law's speed-only work (FrictionLaw::mu_at_load); the
  /// results are the same bit for bit with or without it. Without it nothing is allocated.
  struct RingScratch {
    std::vector<double> speed_mm_s, temp_C;
    SpeedTerms terms;
  };
  /// Friction coefficient per ring (n_r) at the given slip, force and ring temperatures.
  void ring_mu(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C, Eigen::VectorXd& mu,
               RingScratch* scratch = nullptr) const;
  /// Total torque of all sliding interfaces, signed like slip_rad_s, N m.
  double torque_Nm(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C) const;
  /// Heat power into each ring of one interface's domain (n_r), W, >= 0.
  void ring_heat_W(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C, Eigen::VectorXd& heat,
                   RingScratch* scratch = nullptr) const;

  /// Freezes the friction of every ring at the given temperatures and force.
  FrozenFriction freeze(const Eigen::VectorXd& ring_temp_C, double force_N) const;
  /// Load at which mu is evaluated for a clamp force (the reference load when
  /// load_dependent_friction is off). The one place that switch is read.
  double friction_load_N(double force_N) const { return p_.load_dependent_friction ? force_N : p_.reference_load_N; }
  /// Temperature at which a ring's mu is evaluated (the clutch start temperature when
  /// temperature_dependent_friction is off). The one place that switch is read.
  double friction_temp_C(double ring_temp_C) const {
    return p_.temperature_dependent_friction ? ring_temp_C : p_.start_temp_C;
  }
  /// Torque per ring of ONE interface (n_r), N m, at |slip| with a frozen state.
  void ring_torque_Nm(const FrozenFriction& frozen, double abs_slip_rad_s, double force_N,
                      Eigen::VectorXd& torque) const;
  /// The same for two frozen states at one force (the ends of a ring-temperature ramp):
  /// `torque_a` of `a` and `torque_b` of `b`, each equal bit for bit to ring_torque_Nm of that
  /// state. The work that depends on the speed only is done once per ring: v_i^0.1, and
  /// tanh(C2 v_i) for every rate C2 of either state (both ends of a ramp lie in one bracket of
  /// the friction matrix almost always, and then share every rate). Allocates nothing once the
  /// outputs have n_r entries.
  void ring_torque_pair_Nm(const FrozenFriction& a, const FrozenFriction& b, double abs_slip_rad_s, double force_N,
                           Eigen::VectorXd& torque_a, Eigen::VectorXd& torque_b) const;
  /// Torque per ring of ONE interface (n_r), N m, for |slip| (>= 0 whatever slip's sign):
  /// torque_Nm is copysign(sliding_interfaces * sum, slip) of it, ring_heat_W it times |slip|.
  void ring_torque_Nm(double slip_rad_s, double force_N, const Eigen::VectorXd& ring_temp_C, Eigen::VectorXd& torque,
                      RingScratch* scratch = nullptr) const;

 private:
  WetClutchParams p_;
  Fluid fluid_;
  ThermalModel thermal_;
  WaltherViscosity viscosity_;
  Eigen::VectorXd ring_radius_area_m3_;  // (n_r) r_i A_i
  // Spacing of the ring centres r_i = r_0 + i Δr, m; 0 if they are not equally spaced (then
  // tanh is taken ring by ring, wet_clutch.cpp).
  double ring_pitch_m_ = 0.0;
  bool rings_increasing_ = false;  // r_i strictly increasing: the end rings bound the speeds
};

}  // namespace shudder::clutch
