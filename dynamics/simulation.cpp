#include "dynamics/simulation.hpp"

#include <Eigen/QR>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numeric>
#include <stdexcept>
#include <string>

namespace shudder::dynamics {

namespace odeint = boost::numeric::odeint;

struct Simulation::Forces {
  Eigen::VectorXd tau;             // (n) applied torques, constraint torques excluded
  Eigen::VectorXd acc;             // (n)
  Eigen::VectorXd motor_T;         // (n_motors)
  Eigen::VectorXd motor_dI;        // (n_motors) d/dt of the integral state
  Eigen::VectorXd shaft_T;         // (n_shafts)
  Eigen::VectorXd contact_T;       // (n_contacts) torque on b (−it on a)
  Eigen::VectorXd friction_P;      // (n_contacts) dissipated power, W
  Eigen::VectorXd element_T;       // (n_force_elements)
  std::vector<double> element_dz;  // d/dt of the force elements' states
  double source_P = 0.0, damper_P = 0.0;
  Eigen::VectorXd kkt_rhs, kkt_sol;  // (n + rows) the constraint solve's right-hand side and solution
};

struct Simulation::System {
  const Simulation* sim;
  void operator()(const State& x, State& dxdt, double t) const { sim->derivative(x, dxdt, t); }
};

namespace {
double sign_of(ContactMode m) { return m == ContactMode::kSlipPositive ? 1.0 : -1.0; }
ContactMode slip_mode(double direction) {
  return direction >= 0.0 ? ContactMode::kSlipPositive : ContactMode::kSlipNegative;
}
}  // namespace

Simulation::Simulation(const TorsionalNetwork& network, IntegratorSettings settings) : net_(network), cfg_(settings) {
  net_.validate();
  if (!(cfg_.abs_tol > 0) || !(cfg_.rel_tol > 0) || !(cfg_.max_step_s > 0) || !(cfg_.initial_step_s > 0) ||
      !(cfg_.event_time_tol_s > 0) || !(cfg_.fixed_step_s >= 0) || !std::isfinite(cfg_.fixed_step_s))
    throw std::invalid_argument("integrator tolerances and step limits must be > 0 (a fixed step >= 0)");
  n_ = net_.nodes();
  motor_offset_ = 2 * n_;
  int off = motor_offset_ + static_cast<int>(net_.motors().size());
  element_offset_ = off;
  for (const auto& e : net_.force_elements()) {
    element_state_offset_.push_back(off);
    off += e.law->states();
  }
  element_states_ = off - element_offset_;
  contact_offset_ = off;
  for (const auto& c : net_.contacts()) {
    contact_state_offset_.push_back(off);
    off += c.law->states();
  }
  contact_states_ = off - contact_offset_;
  for (const auto& c : net_.contacts()) {
    channel_offset_.push_back(off);
    off += c.law->heat_channels();
  }
  friction_offset_ = off;
  off += static_cast<int>(net_.contacts().size());
  source_offset_ = off++;
  damper_offset_ = off++;
  size_ = off;
  modes_.assign(net_.contacts().size(), ContactMode::kSlipPositive);
  stick_start_s_.assign(net_.contacts().size(), 0.0);
  impact_loss_J_.assign(net_.contacts().size(), 0.0);
  x_.assign(size_, 0.0);
  stepper_ =
      odeint::make_dense_output(cfg_.abs_tol, cfg_.rel_tol, cfg_.max_step_s, odeint::runge_kutta_dopri5<State>());
}

double Simulation::stick_time(int c, double t) const {
  return modes_[c] == ContactMode::kStuck ? std::max(t - stick_start_s_[c], 0.0) : 0.0;
}

std::vector<int> Simulation::stuck_groups() const {
  if (std::none_of(modes_.begin(), modes_.end(), [](ContactMode m) { return m == ContactMode::kStuck; })) return {};
  // Union–find over nodes plus ground (index n_); the root is the larger index, so ground roots
  // every group it belongs to. Members take the first member's value.
  std::vector<int> parent(n_ + 1);
  std::iota(parent.begin(), parent.end(), 0);
  const auto find = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (std::size_t c = 0; c < net_.contacts().size(); ++c) {
    if (modes_[c] != ContactMode::kStuck) continue;
    const auto& k = net_.contacts()[c];
    const int a = find(k.a), b = find(k.b == kGround ? n_ : k.b);
    if (a != b) parent[std::min(a, b)] = std::max(a, b);
  }
  std::vector<int> first(n_ + 1, -1), same_speed_as(static_cast<std::size_t>(n_), -1);
  for (int i = 0; i < n_; ++i) {
    const int r = find(i);
    if (r == n_) {
      same_speed_as[static_cast<std::size_t>(i)] = n_;
    } else if (first[r] < 0) {
      first[r] = i;
    } else {
      same_speed_as[static_cast<std::size_t>(i)] = first[r];
    }
  }
  return same_speed_as;
}

void Simulation::equalise_stuck_groups(const std::vector<int>& same_speed_as, double* v) const {
  // Nothing stuck (a slipping driveline's every evaluation): nothing to equalise.
  if (same_speed_as.empty()) return;
  for (int i = 0; i < n_; ++i) {
    const int s = same_speed_as[static_cast<std::size_t>(i)];
    if (s == n_) {
      v[i] = 0.0;
    } else if (s >= 0) {
      v[i] = v[s];
    }
  }
}

void Simulation::compute(const State& x, double t, Forces& f) const {
  const auto& J = net_.inertias();
  const auto& shafts = net_.shafts();
  const auto& motors = net_.motors();
  const auto& contacts = net_.contacts();
  const double* th = x.data();
  const double* om = x.data() + n_;
  const auto node_speed = [&](int i) { return i == kGround ? 0.0 : om[i]; };
  const auto node_angle = [&](int i) { return i == kGround ? 0.0 : th[i]; };

  f.tau = Eigen::VectorXd::Zero(n_);
  f.source_P = f.damper_P = 0.0;
  // Shafts.
  f.shaft_T.resize(static_cast<Eigen::Index>(shafts.size()));
  for (std::size_t k = 0; k < shafts.size(); ++k) {
    const auto& s = shafts[k];
    const double dw = node_speed(s.a) - node_speed(s.b);
    const double T = s.stiffness_Nm_per_rad * (node_angle(s.a) - node_angle(s.b)) + s.damping_Nms_per_rad * dw;
    f.shaft_T[k] = T;
    f.tau[s.a] -= T;
    if (s.b != kGround) f.tau[s.b] += T;
    f.damper_P += s.damping_Nms_per_rad * dw * dw;
  }
  // Torque sources.
  for (const auto& s : net_.torque_sources()) {
    const double T = s.torque_at_speed_Nm ? s.torque_at_speed_Nm(t, om[s.node]) : s.torque_Nm(t);
    f.tau[s.node] += T;
    f.source_P += T * om[s.node];
  }
  // Motors: PI speed loop, torque limit, anti-windup by back-calculation (as Modelica's LimPID
  // with N_i = 0.9): while clamped, the integral relaxes towards the value that puts the command
  // on the limit, with time constant N_i K_p/K_i:  dI/dt = e + (T − cmd)/(N_i K_p).
  // This keeps the right-hand side continuous. Conditional integration (dI/dt = 0 while clamped
  // and e pushes further) is discontinuous on the limit: leaving saturation with K_i e > K_p de/dt
  // it chatters there (a sliding mode) and stalls the step-size control. With K_p = 0 the limit
  // does not move with e, nothing chatters, and conditional integration is kept.
  f.motor_T.resize(static_cast<Eigen::Index>(motors.size()));
  f.motor_dI.resize(static_cast<Eigen::Index>(motors.size()));
  for (std::size_t m = 0; m < motors.size(); ++m) {
    const auto& mo = motors[m];
    const double e = mo.speed_ref_rad_s(t) - om[mo.node];
    const double cmd = mo.kp_Nms_per_rad * e + mo.ki_Nm_per_rad * x[motor_offset_ + m];
    const double T = std::clamp(cmd, -mo.torque_limit_Nm, mo.torque_limit_Nm);
    constexpr double kNi = 0.9;
    f.motor_T[m] = T;
    if (mo.kp_Nms_per_rad > 0.0) {
      f.motor_dI[m] = e + (T - cmd) / (kNi * mo.kp_Nms_per_rad);
    } else {
      const bool winding_up = (cmd > mo.torque_limit_Nm && e > 0) || (cmd < -mo.torque_limit_Nm && e < 0);
      f.motor_dI[m] = winding_up ? 0.0 : e;
    }
    f.tau[mo.node] += T;
    f.source_P += T * om[mo.node];
  }
  // Force elements: −T on a, +ρ T on b.
  const auto& elements = net_.force_elements();
  f.element_T.resize(static_cast<Eigen::Index>(elements.size()));
  f.element_dz.assign(static_cast<std::size_t>(element_states_), 0.0);
  for (std::size_t e = 0; e < elements.size(); ++e) {
    const auto& el = elements[e];
    const int z = element_state_offset_[e];
    const auto out = el.law->evaluate(om[el.a], el.ratio * node_speed(el.b), x.data() + z,
                                      f.element_dz.data() + (z - element_offset_));
    f.element_T[e] = out.torque_Nm;
    f.tau[el.a] -= out.torque_Nm;
    if (el.b != kGround) f.tau[el.b] += el.ratio * out.torque_Nm;
    f.damper_P += out.dissipated_W;
  }
  // Slipping contacts: torque −s·T_k on a, +s·T_k on b.
  f.contact_T = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(contacts.size()));
  f.friction_P = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(contacts.size()));
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    if (modes_[c] == ContactMode::kStuck) continue;
    const auto& k = contacts[c];
    const double s = sign_of(modes_[c]);
    const double dw = om[k.a] - node_speed(k.b);
    const double T = s * k.law->kinetic_torque_Nm(std::abs(dw), t, x.data() + contact_state_offset_[c]);
    f.contact_T[c] = T;
    f.friction_P[c] = T * dw;  // exact work rate, also if a stage overshoots the reversal
    f.tau[k.a] -= T;
    if (k.b != kGround) f.tau[k.b] += T;
  }

  // Constraints: gears, differentials, speed sources, stuck contacts; their KKT matrix
  // depends only on which contacts are stuck, so its factorisation is kept per stuck set.
  f.acc.resize(n_);
  const Constraints& k = constraints();
  if (k.rows.empty()) {
    for (int i = 0; i < n_; ++i) f.acc[i] = f.tau[i] / J[i].inertia_kg_m2;
    return;
  }
  const int m = static_cast<int>(k.rows.size());
  f.kkt_rhs.resize(n_ + m);
  f.kkt_rhs.head(n_) = f.tau;
  for (int r = 0; r < m; ++r) {
    const int src = k.rows[static_cast<std::size_t>(r)].speed_source;
    f.kkt_rhs[n_ + r] = src >= 0 ? net_.speed_sources()[static_cast<std::size_t>(src)].acceleration_rad_s2(t) : 0.0;
  }
  f.kkt_sol.noalias() = k.kkt_pinv * f.kkt_rhs;
  f.acc = f.kkt_sol.head(n_);
  for (int r = 0; r < m; ++r) {
    const ConstraintRow& w = k.rows[static_cast<std::size_t>(r)];
    const double mu = f.kkt_sol[n_ + r];
    if (w.contact >= 0) f.contact_T[w.contact] = mu;
    if (w.speed_source >= 0)
      f.source_P += -mu * om[net_.speed_sources()[static_cast<std::size_t>(w.speed_source)].node];
  }
  equalise_stuck_groups(k.same_speed_as, f.acc.data());
}

const Simulation::Constraints& Simulation::constraints() const {
  if (active_constraints_) return *active_constraints_;
  for (const auto& k : constraint_cache_)
    if (k.modes_stuck.size() == modes_.size() &&
        std::equal(modes_.begin(), modes_.end(), k.modes_stuck.begin(),
                   [](ContactMode m, bool stuck) { return (m == ContactMode::kStuck) == stuck; }))
      return *(active_constraints_ = &k);
  // Rows G in a fixed order (gears, differentials, speed sources, stuck contacts), each
  //   g_a ω̇_a + g_b ω̇_b + g_c ω̇_c = b,  and the KKT system [M Gᵀ; G 0] [ω̇; λ] = [τ; b].
  Constraints k;
  for (const auto m : modes_) k.modes_stuck.push_back(m == ContactMode::kStuck);
  struct Coefficients {
    int a;
    double ga;
    int b;
    double gb;
    int c = kGround;
    double gc = 0;
  };
  std::vector<Coefficients> g;
  for (const auto& gear : net_.gears()) {
    g.push_back({gear.a, 1.0, gear.b, -gear.ratio});
    k.rows.push_back({-1, -1});
  }
  for (const auto& d : net_.differentials()) {
    g.push_back({d.left, 1.0, d.right, 1.0, d.carrier, -2.0});
    k.rows.push_back({-1, -1});
  }
  for (std::size_t s = 0; s < net_.speed_sources().size(); ++s) {
    g.push_back({net_.speed_sources()[s].node, 1.0, kGround, 0.0});
    k.rows.push_back({-1, static_cast<int>(s)});
  }
  const auto& contacts = net_.contacts();
  for (std::size_t c = 0; c < contacts.size(); ++c)
    if (modes_[c] == ContactMode::kStuck) {
      g.push_back({contacts[c].a, 1.0, contacts[c].b, -1.0});
      k.rows.push_back({static_cast<int>(c), -1});
    }
  const int m = static_cast<int>(g.size());
  Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n_ + m, n_ + m);
  for (int i = 0; i < n_; ++i) kkt(i, i) = net_.inertias()[static_cast<std::size_t>(i)].inertia_kg_m2;
  for (int r = 0; r < m; ++r) {
    const Coefficients& w = g[static_cast<std::size_t>(r)];
    kkt(n_ + r, w.a) += w.ga;
    kkt(w.a, n_ + r) += w.ga;
    if (w.b != kGround) {
      kkt(n_ + r, w.b) += w.gb;
      kkt(w.b, n_ + r) += w.gb;
    }
    if (w.c != kGround) {
      kkt(n_ + r, w.c) += w.gc;
      kkt(w.c, n_ + r) += w.gc;
    }
  }
  // The pseudo-inverse from a complete orthogonal decomposition: the minimum-norm solution stays
  // defined when rows are dependent (several contacts locking one loop); accelerations are
  // unique regardless. Applied as a matrix (a 20 × 20 product for the driveline) instead of the
  // decomposition's Householder steps per right-hand side (≈ 16 k instructions each, 860 M of a
  // 5 s tight turn; refactorising each time cost 3.8 G more), it rounds differently, at the
  // level of a backward-stable solve (cond(KKT) · ε): docs/performance.md.
  if (m > 0) {
    k.kkt_pinv = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(kkt).pseudoInverse();
    ++counters_.constraint_factorisations;
  }
  k.same_speed_as = stuck_groups();
  constraint_cache_.push_back(std::move(k));
  return *(active_constraints_ = &constraint_cache_.back());
}

void Simulation::derivative(const State& x, State& dxdt, double t) const {
  ++counters_.rhs_calls;
  thread_local Forces f;
  compute(x, t, f);
  dxdt.assign(size_, 0.0);
  for (int i = 0; i < n_; ++i) {
    dxdt[i] = x[n_ + i];
    dxdt[n_ + i] = f.acc[i];
  }
  for (Eigen::Index m = 0; m < f.motor_dI.size(); ++m) dxdt[motor_offset_ + m] = f.motor_dI[m];
  std::copy(f.element_dz.begin(), f.element_dz.end(), dxdt.begin() + element_offset_);
  const auto& contacts = net_.contacts();
  for (std::size_t c = 0; c < contacts.size(); ++c) {
    dxdt[friction_offset_ + c] = f.friction_P[c];
    const bool has_states = contacts[c].law->states() > 0;
    if (!has_states && (modes_[c] == ContactMode::kStuck || contacts[c].law->heat_channels() == 0)) continue;
    const double* z = x.data() + contact_state_offset_[c];
    // Stuck: Δω is exactly 0 (a stuck group shares one speed), as the rates must see it.
    const double dw = modes_[c] == ContactMode::kStuck
                          ? 0.0
                          : x[n_ + contacts[c].a] - (contacts[c].b == kGround ? 0.0 : x[n_ + contacts[c].b]);
    if (has_states) contacts[c].law->state_rates(dw, t, z, &dxdt[contact_state_offset_[c]]);
    if (modes_[c] == ContactMode::kStuck || contacts[c].law->heat_channels() == 0) continue;
    contacts[c].law->channel_heat_W(std::abs(dw), t, z, &dxdt[channel_offset_[c]]);
  }
  dxdt[source_offset_] = f.source_P;
  dxdt[damper_offset_] = f.damper_P;
}

double Simulation::event_function(int c, const State& x, double t, const Forces& f) const {
  const auto& k = net_.contacts()[c];
  if (modes_[c] == ContactMode::kStuck)
    return k.law->holding_capacity_Nm(t, stick_time(c, t), f.contact_T[c], x.data() + contact_state_offset_[c]) -
           std::abs(f.contact_T[c]);
  const double dw = x[n_ + k.a] - (k.b == kGround ? 0.0 : x[n_ + k.b]);
  return sign_of(modes_[c]) * dw;
}

double Simulation::project_velocities(State& x, double t) {
  // ω' = ω − M⁻¹Gᵀ y with (G M⁻¹ Gᵀ) y = G ω − b: the closest velocities in the kinetic-energy
  // metric that satisfy every active constraint (momentum-conserving for a stuck pair).
  std::vector<Eigen::VectorXd> rows;
  std::vector<double> b;
  const auto add = [&](int a, double ga, int bb, double gb, double rhs) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(n_);
    r[a] += ga;
    if (bb != kGround) r[bb] += gb;
    rows.push_back(r);
    b.push_back(rhs);
  };
  for (const auto& g : net_.gears()) add(g.a, 1.0, g.b, -g.ratio, 0.0);
  for (const auto& d : net_.differentials()) {
    add(d.left, 1.0, d.right, 1.0, 0.0);
    rows.back()[d.carrier] -= 2.0;
  }
  for (const auto& s : net_.speed_sources()) add(s.node, 1.0, kGround, 0.0, s.speed_rad_s(t));
  for (std::size_t c = 0; c < net_.contacts().size(); ++c)
    if (modes_[c] == ContactMode::kStuck) add(net_.contacts()[c].a, 1.0, net_.contacts()[c].b, -1.0, 0.0);
  if (rows.empty()) return 0.0;
  Eigen::MatrixXd G(static_cast<Eigen::Index>(rows.size()), n_);
  for (std::size_t r = 0; r < rows.size(); ++r) G.row(static_cast<Eigen::Index>(r)) = rows[r];
  Eigen::Map<Eigen::VectorXd> om(x.data() + n_, n_);
  const Eigen::VectorXd before = om;
  const Eigen::Map<const Eigen::VectorXd> rhs(b.data(), static_cast<Eigen::Index>(b.size()));
  bool massless = false;
  for (int i = 0; i < n_; ++i) massless = massless || !(net_.inertias()[i].inertia_kg_m2 > 0.0);
  if (!massless) {
    Eigen::VectorXd minv(n_);
    for (int i = 0; i < n_; ++i) minv[i] = 1.0 / net_.inertias()[i].inertia_kg_m2;
    const Eigen::MatrixXd gm = G * minv.asDiagonal();
    const Eigen::VectorXd resid = G * om - rhs;
    const Eigen::VectorXd y = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(gm * G.transpose()).solve(resid);
    om -= gm.transpose() * y;
  } else {
    // A massless node (fixed by a gear or differential): the same closest-in-kinetic-energy
    // projection as the KKT system [M Gᵀ; G 0] [ω; λ] = [M ω₀; b], which needs no M⁻¹.
    const Eigen::Index m = G.rows();
    Eigen::MatrixXd kkt = Eigen::MatrixXd::Zero(n_ + m, n_ + m);
    Eigen::VectorXd r(n_ + m);
    for (int i = 0; i < n_; ++i) {
      kkt(i, i) = net_.inertias()[i].inertia_kg_m2;
      r[i] = kkt(i, i) * om[i];
    }
    kkt.block(n_, 0, m, n_) = G;
    kkt.block(0, n_, n_, m) = G.transpose();
    r.tail(m) = rhs;
    om = Eigen::CompleteOrthogonalDecomposition<Eigen::MatrixXd>(kkt).solve(r).head(n_);
  }
  // Not constraints(): an event's projection must not factorise a KKT system (the counter counts
  // those of the integration); the groups alone are cheap.
  equalise_stuck_groups(stuck_groups(), om.data());
  // Kinetic energy taken out by the projection.
  double lost = 0.0;
  for (int i = 0; i < n_; ++i) lost += 0.5 * net_.inertias()[i].inertia_kg_m2 * (before[i] * before[i] - om[i] * om[i]);
  return lost;
}

void Simulation::resolve_contacts(State& x, double t, std::vector<int> sticking, std::vector<int> releasing) {
  Forces f;
  if (!releasing.empty()) compute(x, t, f);
  for (int c : releasing) {
    set_mode(static_cast<std::size_t>(c), slip_mode(f.contact_T[c]));
    ++counters_.breakaway_events;
  }
  for (int c : sticking) {
    set_mode(static_cast<std::size_t>(c), ContactMode::kStuck);
    stick_start_s_[c] = t;
  }
  // The (tiny, root-tolerance sized) impact loss of a stick is heat of a contact that sticks.
  if (!sticking.empty()) impact_loss_J_[sticking.front()] += project_velocities(x, t);
  // Active set: release, one at a time, the stuck contact most over its capacity.
  for (std::size_t guard = 0; guard <= modes_.size(); ++guard) {
    compute(x, t, f);
    int worst = -1;
    double worst_ratio = 1.0 + 1e-12;
    for (std::size_t c = 0; c < modes_.size(); ++c) {
      if (modes_[c] != ContactMode::kStuck) continue;
      const double cap = net_.contacts()[c].law->holding_capacity_Nm(
          t, stick_time(static_cast<int>(c), t), f.contact_T[c], x.data() + contact_state_offset_[c]);
      const double ratio = std::abs(f.contact_T[c]) / std::max(cap, 1e-300);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = static_cast<int>(c);
      }
    }
    if (worst < 0) break;
    set_mode(static_cast<std::size_t>(worst), slip_mode(f.contact_T[worst]));
    const bool was_sticking = std::find(sticking.begin(), sticking.end(), worst) != sticking.end();
    ++(was_sticking ? counters_.reversal_events : counters_.breakaway_events);
    if (was_sticking) sticking.erase(std::find(sticking.begin(), sticking.end(), worst));
  }
  counters_.stick_events += static_cast<long>(sticking.size());
}

void Simulation::initialize(double t0, const Eigen::VectorXd& theta, const Eigen::VectorXd& omega,
                            const Eigen::VectorXd& motor_integral, double stick_speed_tol) {
  if (theta.size() != n_ || omega.size() != n_)
    throw std::invalid_argument("initial angles and speeds need one value per node");
  x_.assign(size_, 0.0);
  for (int i = 0; i < n_; ++i) {
    x_[i] = theta[i];
    x_[n_ + i] = omega[i];
  }
  for (Eigen::Index m = 0; m < motor_integral.size() && m < static_cast<Eigen::Index>(net_.motors().size()); ++m)
    x_[motor_offset_ + m] = motor_integral[m];
  for (std::size_t c = 0; c < net_.contacts().size(); ++c)
    net_.contacts()[c].law->initial_states(&x_[contact_state_offset_[c]]);
  t_ = t0;
  // Classify the contacts on the given speeds, then project those onto the gears and speed
  // sources (no contact stuck yet), then let the candidates stick (projecting again).
  std::vector<int> sticking;
  for (std::size_t c = 0; c < net_.contacts().size(); ++c) {
    const auto& k = net_.contacts()[c];
    const double dw = omega[k.a] - (k.b == kGround ? 0.0 : omega[k.b]);
    set_mode(c, slip_mode(dw));
    if (!(std::abs(dw) > stick_speed_tol)) sticking.push_back(static_cast<int>(c));
  }
  project_velocities(x_, t_);
  resolve_contacts(x_, t_, sticking, {});
  // Force elements' states from the projected start speeds.
  for (std::size_t k = 0; k < net_.force_elements().size(); ++k) {
    const auto& el = net_.force_elements()[k];
    const double wa = x_[n_ + el.a], wb = el.b == kGround ? 0.0 : x_[n_ + el.b];
    el.law->initial_states(wa, el.ratio * wb, &x_[element_state_offset_[k]]);
  }
  // Projection losses at the start are not part of the run's energy account.
  std::fill(impact_loss_J_.begin(), impact_loss_J_.end(), 0.0);
  counters_ = {};
  const EnergyAccount e = energy();
  initial_kinetic_J_ = e.kinetic_J;
  initial_elastic_J_ = e.elastic_J;
  last_dt_ = cfg_.initial_step_s;
  restart();
}

void Simulation::restart() { stepper_.initialize(x_, t_, std::min(last_dt_, cfg_.max_step_s)); }

EnergyAccount Simulation::energy() const {
  EnergyAccount e;
  for (int i = 0; i < n_; ++i) e.kinetic_J += 0.5 * net_.inertias()[i].inertia_kg_m2 * x_[n_ + i] * x_[n_ + i];
  for (const auto& s : net_.shafts()) {
    const double d = x_[s.a] - (s.b == kGround ? 0.0 : x_[s.b]);
    e.elastic_J += 0.5 * s.stiffness_Nm_per_rad * d * d;
  }
  for (std::size_t k = 0; k < net_.force_elements().size(); ++k)
    e.elastic_J += net_.force_elements()[k].law->stored_energy_J(x_.data() + element_state_offset_[k]);
  for (std::size_t c = 0; c < net_.contacts().size(); ++c) e.friction_heat_J += friction_work_J(static_cast<int>(c));
  e.source_work_J = x_[source_offset_];
  e.damper_loss_J = x_[damper_offset_];
  e.initial_kinetic_J = initial_kinetic_J_;
  e.initial_elastic_J = initial_elastic_J_;
  return e;
}

Sample Simulation::evaluate(const State& x, double t) const {
  Forces f;
  compute(x, t, f);
  Sample s;
  s.t_s = t;
  s.theta_rad = Eigen::Map<const Eigen::VectorXd>(x.data(), n_);
  s.omega_rad_s = Eigen::Map<const Eigen::VectorXd>(x.data() + n_, n_);
  s.motor_torque_Nm = f.motor_T;
  s.shaft_torque_Nm = f.shaft_T;
  s.contact_torque_Nm = f.contact_T;
  s.element_torque_Nm = f.element_T;
  s.element_states = Eigen::Map<const Eigen::VectorXd>(x.data() + element_offset_, element_states_);
  s.contact_states = Eigen::Map<const Eigen::VectorXd>(x.data() + contact_offset_, contact_states_);
  s.contact_slip_rad_s.resize(static_cast<Eigen::Index>(net_.contacts().size()));
  for (std::size_t c = 0; c < net_.contacts().size(); ++c) {
    const auto& k = net_.contacts()[c];
    s.contact_slip_rad_s[c] = x[n_ + k.a] - (k.b == kGround ? 0.0 : x[n_ + k.b]);
  }
  s.modes = modes_;
  return s;
}

void Simulation::advance_fixed(double t_end, const std::vector<double>& samples, const SampleCallback& cb) {
  const double h = cfg_.fixed_step_s;
  const double t_start = t_;
  const double span = t_end - t_start;
  if (!(span > 0.0)) return;
  // Equal steps no longer than h; a span that is a whole number of steps (to round-off) takes h.
  const long steps = std::max(1L, static_cast<long>(std::ceil(span / h - 1e-9)));
  const double dt = span / static_cast<double>(steps);
  const double on_step_s = 1e-9 * dt;  // a sample this close to a step's end is taken there
  auto next = std::upper_bound(samples.begin(), samples.end(), t_);
  const int nc = static_cast<int>(net_.contacts().size());
  thread_local Forces f;
  thread_local std::vector<double> g0;
  thread_local State x1, xs;
  g0.resize(static_cast<std::size_t>(nc));
  compute(x_, t_, f);
  for (int c = 0; c < nc; ++c) g0[c] = event_function(c, x_, t_, f);
  for (long k = 1; k <= steps; ++k) {
    const double t1 = k == steps ? t_end : t_start + static_cast<double>(k) * dt;
    // Samples strictly inside the step: a sub-step from the step's start (header).
    for (; next != samples.end() && *next < t1 - on_step_s; ++next) {
      xs = x_;
      fixed_stepper_.do_step(System{this}, xs, t_, *next - t_);
      if (cb) cb(evaluate(xs, *next));
    }
    x1 = x_;
    fixed_stepper_.do_step(System{this}, x1, t_, t1 - t_);
    ++counters_.steps;
    for (double v : x1)
      if (!std::isfinite(v))
        throw std::runtime_error("integration produced a non-finite state at t = " + std::to_string(t1) + " s");
    x_ = x1;
    t_ = t1;
    for (; next != samples.end() && *next <= t1 + on_step_s; ++next)
      if (cb) cb(evaluate(x_, t_));
    // Events at the step's end (header): the contacts whose event function changed sign.
    compute(x_, t_, f);
    std::vector<int> sticking, releasing;
    for (int c = 0; c < nc; ++c) {
      const double g1 = event_function(c, x_, t_, f);
      if (g1 < 0.0 && !(g0[c] <= 0.0 && g1 > -1e-13))
        (modes_[c] == ContactMode::kStuck ? releasing : sticking).push_back(c);
      g0[c] = g1;
    }
    if (sticking.empty() && releasing.empty()) continue;
    resolve_contacts(x_, t_, sticking, releasing);
    compute(x_, t_, f);
    for (int c = 0; c < nc; ++c) g0[c] = event_function(c, x_, t_, f);
  }
}

void Simulation::advance(double t_end, const std::vector<double>& samples, const SampleCallback& cb) {
  if (cfg_.fixed_step_s > 0.0) {
    advance_fixed(t_end, samples, cb);
    return;
  }
  auto next = std::upper_bound(samples.begin(), samples.end(), t_);
  const int nc = static_cast<int>(net_.contacts().size());
  std::vector<double> g0(nc);
  const auto refresh_g0 = [&] {
    Forces f;
    compute(x_, t_, f);
    for (int c = 0; c < nc; ++c) g0[c] = event_function(c, x_, t_, f);
  };
  refresh_g0();
  State xs(size_);
  Forces f;
  int events_at_same_time = 0;
  double last_event_t = -std::numeric_limits<double>::infinity();

  while (t_ < t_end) {
    const auto [t0, t1] = stepper_.do_step(System{this});
    ++counters_.steps;
    last_dt_ = stepper_.current_time_step();
    const State& x1 = stepper_.current_state();
    for (double v : x1)
      if (!std::isfinite(v))
        throw std::runtime_error("integration produced a non-finite state at t = " + std::to_string(t1) + " s");

    // Locate the earliest event in (t0, t1] by bisection on the dense output.
    compute(x1, t1, f);
    double t_event = std::numeric_limits<double>::infinity();
    std::vector<std::pair<int, double>> roots;
    for (int c = 0; c < nc; ++c) {
      const double g1 = event_function(c, x1, t1, f);
      // A contact released exactly at t0 starts at g = 0; only a clear sign change counts.
      if (!(g1 < 0.0) || (g0[c] <= 0.0 && g1 > -1e-13)) continue;
      double lo = t0, hi = t1;
      while (hi - lo > cfg_.event_time_tol_s) {
        const double mid = 0.5 * (lo + hi);
        if (mid <= lo || mid >= hi) break;  // adjacent doubles (large t): cannot shrink further
        stepper_.calc_state(mid, xs);
        Forces fm;
        compute(xs, mid, fm);
        (event_function(c, xs, mid, fm) < 0.0 ? hi : lo) = mid;
      }
      roots.emplace_back(c, hi);
      t_event = std::min(t_event, hi);
    }
    const bool event = t_event <= t_end;
    const double t_stop = event ? t_event : std::min(t1, t_end);

    for (; next != samples.end() && *next <= t_stop; ++next) {
      stepper_.calc_state(*next, xs);
      if (cb) cb(evaluate(xs, *next));
    }

    if (event) {
      stepper_.calc_state(t_event, xs);
      std::vector<int> sticking, releasing;
      for (const auto& [c, tc] : roots) {
        if (tc > t_event + 1e3 * cfg_.event_time_tol_s) continue;  // later: found again after restart
        (modes_[c] == ContactMode::kStuck ? releasing : sticking).push_back(c);
      }
      x_ = xs;
      t_ = t_event;
      resolve_contacts(x_, t_, sticking, releasing);
      events_at_same_time = (t_ - last_event_t <= 1e3 * cfg_.event_time_tol_s) ? events_at_same_time + 1 : 0;
      last_event_t = t_;
      if (events_at_same_time > 100)
        throw std::runtime_error("contact '" + net_.contacts()[roots.front().first].name +
                                 "' keeps switching between stick and slip at t = " + std::to_string(t_) + " s");
      restart();
      refresh_g0();
    } else if (t1 > t_end) {
      stepper_.calc_state(t_end, xs);
      x_ = xs;
      t_ = t_end;
      restart();
      refresh_g0();
    } else {
      x_ = x1;
      t_ = t1;
      for (int c = 0; c < nc; ++c) g0[c] = event_function(c, x1, t1, f);
    }
  }
}

}  // namespace shudder::dynamics
