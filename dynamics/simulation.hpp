#pragma once
// Time integration of a TorsionalNetwork with stick/slip friction contacts.
//
// Stepper: Boost.Odeint's runge_kutta_dopri5 in a dense-output driver. Why: an explicit
// 5th-order pair with error control and a free 4th-order interpolant (FSAL), so events (stick,
// breakaway, slip reversal) are located by root finding on the interpolant between accepted
// steps rather than by a sign test between steps. The networks here are not stiff once the
// "torsionally rigid" coupling is lumped; the bar mode (100–500 Hz) sets the step.
//
// Hybrid modes per contact: slipping with a fixed direction s = ±1 (so the right-hand side is
// smooth within a mode) or stuck. Event functions, located to `event_time_tol_s` by bisection
// on the dense output:
//   slipping: g = s·Δω            (reaches 0: stick if the holding torque is below capacity,
//                                  otherwise slip on in the other direction)
//   stuck:    g = capacity − |λ|  (reaches 0: breakaway in the direction λ pushes)
// A stuck contact is a kinematic constraint ω_a = ω_b solved with the other constraints (gears,
// speed sources) in one KKT system by complete orthogonal decomposition, which stays well
// defined when constraints are dependent (e.g. contacts that lock together). Members of a stuck
// group receive bitwise-identical accelerations, so their relative speed stays exactly zero.
//
// Fixed-step mode (IntegratorSettings::fixed_step_s = h > 0): the same right-hand side advanced by
// classical RK4 with steps of h (each advance() span cut into equal steps no longer than h, so
// a span that is a whole number of steps takes exactly h). Why RK4: the networks' fastest modes
// (a 100–500 Hz torsion bar) sit at ωh ≈ 0.06–0.3 for h = 0.1 ms, inside RK4's stability region
// (|λh| < 2.8), with numerical damping (ωh)⁶/144 and phase error (ωh)⁵/120 per step (a 378 Hz
// bar: 1.2e-6 and 6e-6): an explicit fourth-order method is cheaper and more accurate there than
// a semi-implicit first-order one. Events are tested at the step ends and handled there (no root
// finding, a fixed cost per step): a contact whose slip changed sign within the step sticks at
// the step's end, the network's speeds projected onto the new constraint (a stuck pair meets at
// its common momentum speed; the kinetic energy removed counts as that contact's heat), or slips
// on reversed if it cannot hold; a stuck contact whose holding torque exceeds its capacity breaks
// away there. Event times are so located to within one step, an O(h) error against the adaptive
// run's located events. A sample between step ends is taken by an extra RK4 sub-step from the
// last step end, which does not alter the trajectory.
//
// Force elements' internal states (e.g. a tyre's deflection) follow the motors' integrals; their
// stored energy counts as elastic, their dissipation with the dampers'. Contact laws' internal
// states (e.g. a coupling's hydraulic pressure, dynamics/contact_law.hpp) follow them; they are not
// mechanical energy (the actuator's own power is outside the account, as a motor's electrics are).
// Extra integrated states make coupling and energy exact: the heat of every contact channel
// (e.g. clutch rings, handed to a thermal step), each contact's total friction work, the work
// of all sources and the damper losses.

#include <Eigen/Dense>
#include <boost/numeric/odeint.hpp>
#include <deque>
#include <functional>
#include <vector>

#include "dynamics/network.hpp"

namespace shudder::dynamics {

struct IntegratorSettings {
  double abs_tol = 1e-9;     // absolute error per step (rad, rad/s, J)
  double rel_tol = 1e-8;     // relative error per step
  double max_step_s = 1e-3;  // upper bound on the step (keeps sampling and events honest)
  double initial_step_s = 1e-6;
  double event_time_tol_s = 1e-12;  // width of the bracket left by event root finding
  /// > 0: the fixed-step mode (below) at this step, s; 0: the adaptive dopri5 run.
  double fixed_step_s = 0.0;
};

enum class ContactMode { kSlipPositive, kSlipNegative, kStuck };

/// Everything derived from the state at one instant.
struct Sample {
  double t_s = 0.0;
  Eigen::VectorXd theta_rad, omega_rad_s;  // (n)
  Eigen::VectorXd motor_torque_Nm;         // (n_motors)
  Eigen::VectorXd shaft_torque_Nm;         // (n_shafts) k Δθ + c Δω, as carried by the shaft
  Eigen::VectorXd contact_torque_Nm;       // (n_contacts) torque transmitted from a to b
  Eigen::VectorXd contact_slip_rad_s;      // (n_contacts) Δω = ω_a − ω_b
  Eigen::VectorXd element_torque_Nm;       // (n_force_elements) T of each force element
  Eigen::VectorXd element_states;          // (all force elements' states, in element order)
  Eigen::VectorXd contact_states;          // (all contact laws' internal states, in contact order)
  std::vector<ContactMode> modes;
};

struct EnergyAccount {
  double source_work_J = 0.0;  // torque/speed sources and motors
  double kinetic_J = 0.0, initial_kinetic_J = 0.0;
  double elastic_J = 0.0, initial_elastic_J = 0.0;
  double friction_heat_J = 0.0;  // all contacts, incl. the tiny losses of stick impacts
  double damper_loss_J = 0.0;    // dampers and the force elements' dissipation
  /// source work − Δkinetic − Δelastic − friction heat − damper losses
  double imbalance_J() const {
    return source_work_J - (kinetic_J - initial_kinetic_J) - (elastic_J - initial_elastic_J) - friction_heat_J -
           damper_loss_J;
  }
};

struct Counters {
  long steps = 0, rhs_calls = 0, stick_events = 0, breakaway_events = 0, reversal_events = 0;
  long constraint_factorisations = 0;  // KKT factorisations: one per stuck set met (cached)
};

class Simulation {
 public:
  using SampleCallback = std::function<void(const Sample&)>;

  /// The network must outlive the simulation. Throws std::invalid_argument for a bad network.
  Simulation(const TorsionalNetwork& network, IntegratorSettings settings = {});

  /// Sets the state at t0. Contacts with |Δω| below `stick_speed_tol` start stuck if they can
  /// hold, otherwise slipping in the direction of Δω (or of the holding torque). Speeds that
  /// violate a gear, a speed source or a starting stick are projected onto the constraints
  /// (closest in kinetic energy); the energy account starts after that projection.
  void initialize(double t0_s, const Eigen::VectorXd& theta_rad, const Eigen::VectorXd& omega_rad_s,
                  const Eigen::VectorXd& motor_integral = {}, double stick_speed_tol = 0.0);

  /// Integrates to t_end; calls `on_sample` for each time of `sample_times_s` in (t, t_end].
  void advance(double t_end_s, const std::vector<double>& sample_times_s = {}, const SampleCallback& on_sample = {});

  /// The right-hand side changed (a contact law's held inputs were updated): restart the
  /// stepper from the current state.
  void restart();

  double time_s() const { return t_; }
  Sample sample() const { return evaluate(x_, t_); }
  ContactMode mode(int contact) const { return modes_[contact]; }
  /// Heat accumulated in channel `ch` of contact `c` since the start, J.
  double channel_heat_J(int c, int ch) const { return x_[channel_offset_[c] + ch]; }
  double friction_work_J(int c) const { return x_[friction_offset_ + c] + impact_loss_J_[c]; }
  EnergyAccount energy() const;
  const Counters& counters() const { return counters_; }
  const TorsionalNetwork& network() const { return net_; }
  /// Where contact `c`'s internal states start in Sample::contact_states.
  int contact_state_index(int c) const { return contact_state_offset_[static_cast<std::size_t>(c)] - contact_offset_; }

 private:
  using State = std::vector<double>;
  struct Forces;
  struct System;
  /// One row of the constraint system: the stuck contact it locks or the speed source it
  /// prescribes (its right-hand side, the source's acceleration), else -1.
  struct ConstraintRow {
    int contact = -1, speed_source = -1;
  };
  /// The constraint rows and the KKT matrix's pseudo-inverse for one set of stuck contacts: the
  /// matrix depends on nothing else, so each set is factorised once per run and every
  /// right-hand side costs one matrix–vector product.
  struct Constraints {
    std::vector<bool> modes_stuck;
    std::vector<ConstraintRow> rows;
    Eigen::MatrixXd kkt_pinv;  // (n + rows)²
    // The stuck groups, which also depend on the stuck set only: per node, -1 (keeps its own
    // value: free, or the first node of its group), n (held by ground: 0) or the group's first
    // node, whose value it takes. Empty when nothing is stuck.
    std::vector<int> same_speed_as;
  };

  Sample evaluate(const State& x, double t) const;
  void compute(const State& x, double t, Forces& f) const;
  void derivative(const State& x, State& dxdt, double t) const;
  double event_function(int c, const State& x, double t, const Forces& f) const;
  double stick_time(int c, double t) const;
  double project_velocities(State& x, double t);
  void advance_fixed(double t_end_s, const std::vector<double>& sample_times_s, const SampleCallback& on_sample);
  void resolve_contacts(State& x, double t, std::vector<int> sticking, std::vector<int> releasing);
  /// Constraints::same_speed_as of the current modes.
  std::vector<int> stuck_groups() const;
  void equalise_stuck_groups(const std::vector<int>& same_speed_as, double* v) const;
  /// The constraint system of the current modes: built (and factorised) the first time a stuck
  /// set is met, then found by pointer until a contact changes mode (set_mode).
  const Constraints& constraints() const;
  void set_mode(std::size_t c, ContactMode m) {
    modes_[c] = m;
    active_constraints_ = nullptr;
  }

  const TorsionalNetwork& net_;
  IntegratorSettings cfg_;
  int n_ = 0;
  int motor_offset_ = 0, element_offset_ = 0, friction_offset_ = 0, source_offset_ = 0, damper_offset_ = 0, size_ = 0;
  std::vector<int> channel_offset_;
  std::vector<int> element_state_offset_;  // per force element, into the state
  int element_states_ = 0;                 // all force elements' states
  int contact_offset_ = 0;                 // first contact-law state
  std::vector<int> contact_state_offset_;  // per contact, into the state
  int contact_states_ = 0;                 // all contact laws' states
  std::vector<ContactMode> modes_;
  std::vector<double> stick_start_s_;
  std::vector<double> impact_loss_J_;
  State x_;
  double t_ = 0.0;
  double initial_kinetic_J_ = 0.0, initial_elastic_J_ = 0.0;
  mutable Counters counters_;
  using Stepper = boost::numeric::odeint::dense_output_runge_kutta<
      boost::numeric::odeint::controlled_runge_kutta<boost::numeric::odeint::runge_kutta_dopri5<State>>>;
  Stepper stepper_;
  boost::numeric::odeint::runge_kutta4<State> fixed_stepper_;
  double last_dt_ = 0.0;
  // Factorised constraint systems, one per stuck set met so far (a handful per run).
  mutable std::deque<Constraints> constraint_cache_;
  mutable const Constraints* active_constraints_ = nullptr;  // the entry of modes_ (deque: stable)
};

}  // namespace shudder::dynamics
