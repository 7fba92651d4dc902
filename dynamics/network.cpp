#include "dynamics/network.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/SVD>
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shudder::dynamics {

int TorsionalNetwork::add_inertia(Inertia i) {
  inertias_.push_back(std::move(i));
  return nodes() - 1;
}
int TorsionalNetwork::add_shaft(Shaft s) {
  shafts_.push_back(std::move(s));
  return static_cast<int>(shafts_.size()) - 1;
}
int TorsionalNetwork::add_gear(Gear g) {
  gears_.push_back(std::move(g));
  return static_cast<int>(gears_.size()) - 1;
}
int TorsionalNetwork::add_torque_source(TorqueSource s) {
  torque_sources_.push_back(std::move(s));
  return static_cast<int>(torque_sources_.size()) - 1;
}
int TorsionalNetwork::add_speed_source(SpeedSource s) {
  speed_sources_.push_back(std::move(s));
  return static_cast<int>(speed_sources_.size()) - 1;
}
int TorsionalNetwork::add_motor(Motor m) {
  motors_.push_back(std::move(m));
  return static_cast<int>(motors_.size()) - 1;
}
int TorsionalNetwork::add_contact(FrictionContact c) {
  contacts_.push_back(std::move(c));
  return static_cast<int>(contacts_.size()) - 1;
}

int TorsionalNetwork::add_differential(Differential d) {
  differentials_.push_back(std::move(d));
  return static_cast<int>(differentials_.size()) - 1;
}
int TorsionalNetwork::add_force_element(ForceElement e) {
  force_elements_.push_back(std::move(e));
  return static_cast<int>(force_elements_.size()) - 1;
}

void TorsionalNetwork::check_node(int node, const std::string& what, bool ground_ok) const {
  if (node == kGround && ground_ok) return;
  if (node < 0 || node >= nodes())
    throw std::invalid_argument(what + " refers to node " + std::to_string(node) + ", but the network has nodes 0.." +
                                std::to_string(nodes() - 1));
}

void TorsionalNetwork::validate() const {
  const auto positive = [](double x) { return std::isfinite(x) && x > 0.0; };
  const auto non_negative = [](double x) { return std::isfinite(x) && x >= 0.0; };
  // A massless node is allowed where a gear, differential or speed source fixes its speed (the
  // KKT system then has its row); anywhere else its acceleration would be undefined.
  std::vector<bool> tied(inertias_.size(), false);
  const auto tie = [&](int node) {
    if (node >= 0 && node < nodes()) tied[static_cast<std::size_t>(node)] = true;
  };
  for (const auto& g : gears_) tie(g.a), tie(g.b);
  for (const auto& d : differentials_) tie(d.carrier), tie(d.left), tie(d.right);
  for (const auto& s : speed_sources_) tie(s.node);
  for (std::size_t i = 0; i < inertias_.size(); ++i) {
    const double j = inertias_[i].inertia_kg_m2;
    if (!(positive(j) || (j == 0.0 && tied[i])))
      throw std::invalid_argument(
          "inertia '" + inertias_[i].name +
          "' must be > 0 kg m^2 (0 only where a gear, differential or speed source fixes its speed)");
  }
  for (const auto& s : shafts_) {
    check_node(s.a, "shaft '" + s.name + "'", false);
    check_node(s.b, "shaft '" + s.name + "'", true);
    if (!non_negative(s.stiffness_Nm_per_rad))
      throw std::invalid_argument("shaft '" + s.name + "' stiffness must be >= 0 N m/rad");
    if (!non_negative(s.damping_Nms_per_rad))
      throw std::invalid_argument("shaft '" + s.name + "' damping must be >= 0 N m s/rad");
    // A pure damper (k = 0, e.g. a tyre's slip) is a shaft; neither is nothing.
    if (!(s.stiffness_Nm_per_rad > 0 || s.damping_Nms_per_rad > 0))
      throw std::invalid_argument("shaft '" + s.name + "' needs a stiffness or a damping > 0");
  }
  for (const auto& g : gears_) {
    check_node(g.a, "gear '" + g.name + "'", false);
    check_node(g.b, "gear '" + g.name + "'", false);
    if (!std::isfinite(g.ratio) || g.ratio == 0.0)
      throw std::invalid_argument("gear '" + g.name + "' ratio must be finite and non-zero");
  }
  for (const auto& d : differentials_) {
    for (int node : {d.carrier, d.left, d.right}) check_node(node, "differential '" + d.name + "'", false);
    if (d.carrier == d.left || d.carrier == d.right || d.left == d.right)
      throw std::invalid_argument("differential '" + d.name + "' needs three different nodes");
  }
  for (const auto& e : force_elements_) {
    check_node(e.a, "force element '" + e.name + "'", false);
    check_node(e.b, "force element '" + e.name + "'", true);
    if (!e.law) throw std::invalid_argument("force element '" + e.name + "' has no law");
    if (!std::isfinite(e.ratio) || e.ratio == 0.0)
      throw std::invalid_argument("force element '" + e.name + "' ratio must be finite and non-zero");
  }
  for (const auto& s : torque_sources_) check_node(s.node, "torque source '" + s.name + "'", false);
  for (const auto& s : speed_sources_) check_node(s.node, "speed source '" + s.name + "'", false);
  for (const auto& m : motors_) {
    check_node(m.node, "motor '" + m.name + "'", false);
    if (!non_negative(m.kp_Nms_per_rad) || !non_negative(m.ki_Nm_per_rad) || !positive(m.torque_limit_Nm))
      throw std::invalid_argument("motor '" + m.name + "' needs gains >= 0 and a torque limit > 0");
  }
  for (const auto& c : contacts_) {
    check_node(c.a, "contact '" + c.name + "'", false);
    check_node(c.b, "contact '" + c.name + "'", true);
    if (!c.law) throw std::invalid_argument("contact '" + c.name + "' has no friction law");
  }
}

Eigen::MatrixXd TorsionalNetwork::mass_matrix() const {
  Eigen::MatrixXd m = Eigen::MatrixXd::Zero(nodes(), nodes());
  for (int i = 0; i < nodes(); ++i) m(i, i) = inertias_[i].inertia_kg_m2;
  return m;
}

void stamp_coupling(Eigen::MatrixXd& m, int a, int b, double g) {
  m(a, a) += g;
  if (b == kGround) return;
  m(b, b) += g;
  m(a, b) -= g;
  m(b, a) -= g;
}

Eigen::MatrixXd TorsionalNetwork::stiffness_matrix() const {
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(nodes(), nodes());
  for (const auto& s : shafts_) stamp_coupling(k, s.a, s.b, s.stiffness_Nm_per_rad);
  for (const auto& m : motors_) k(m.node, m.node) += m.ki_Nm_per_rad;
  // T = k_e (θ_a − ρ θ_b): K += k_e v vᵀ with v = e_a − ρ e_b.
  for (const auto& e : force_elements_) {
    const double ke = e.law->modal_stiffness_Nm_per_rad();
    k(e.a, e.a) += ke;
    if (e.b == kGround) continue;
    k(e.b, e.b) += ke * e.ratio * e.ratio;
    k(e.a, e.b) -= ke * e.ratio;
    k(e.b, e.a) -= ke * e.ratio;
  }
  return k;
}

Eigen::MatrixXd TorsionalNetwork::damping_matrix() const {
  Eigen::MatrixXd c = Eigen::MatrixXd::Zero(nodes(), nodes());
  for (const auto& s : shafts_) stamp_coupling(c, s.a, s.b, s.damping_Nms_per_rad);
  for (const auto& m : motors_) c(m.node, m.node) += m.kp_Nms_per_rad;
  return c;
}

Eigen::MatrixXd TorsionalNetwork::constraint_basis(const std::vector<bool>& stuck) const {
  std::vector<Eigen::VectorXd> rows;
  const auto row = [&](int a, double ga, int b, double gb) {
    Eigen::VectorXd r = Eigen::VectorXd::Zero(nodes());
    r[a] += ga;
    if (b != kGround) r[b] += gb;
    rows.push_back(r);
  };
  for (const auto& g : gears_) row(g.a, 1.0, g.b, -g.ratio);
  for (const auto& d : differentials_) {
    row(d.left, 1.0, d.right, 1.0);
    rows.back()[d.carrier] -= 2.0;
  }
  for (const auto& s : speed_sources_) row(s.node, 1.0, kGround, 0.0);
  for (std::size_t c = 0; c < contacts_.size(); ++c)
    if (c < stuck.size() && stuck[c]) row(contacts_[c].a, 1.0, contacts_[c].b, -1.0);
  if (rows.empty()) return Eigen::MatrixXd::Identity(nodes(), nodes());
  Eigen::MatrixXd g(static_cast<Eigen::Index>(rows.size()), nodes());
  for (std::size_t i = 0; i < rows.size(); ++i) g.row(static_cast<Eigen::Index>(i)) = rows[i];
  // Null space from the SVD: right singular vectors of (numerically) zero singular values.
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(g, Eigen::ComputeFullV);
  const auto& sv = svd.singularValues();
  const double tol = 1e-12 * std::max(1.0, sv.size() ? sv[0] : 1.0);
  int rank = 0;
  for (Eigen::Index i = 0; i < sv.size(); ++i) rank += sv[i] > tol;
  return svd.matrixV().rightCols(nodes() - rank);
}

Modes TorsionalNetwork::modes(const std::vector<bool>& stuck, const Eigen::MatrixXd& extra_damping) const {
  const Eigen::MatrixXd n = constraint_basis(stuck);
  const Eigen::MatrixXd m = n.transpose() * mass_matrix() * n;
  const Eigen::MatrixXd k = n.transpose() * stiffness_matrix() * n;
  Eigen::MatrixXd c = damping_matrix();
  if (extra_damping.size() > 0) c += extra_damping;
  c = n.transpose() * c * n;
  const Eigen::Index r = m.rows();
  Modes out;
  if (r == 0) return out;

  Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> ges(k, m);
  out.frequencies_Hz.resize(r);
  for (Eigen::Index i = 0; i < r; ++i)
    out.frequencies_Hz[i] = std::sqrt(std::max(ges.eigenvalues()[i], 0.0)) / (2.0 * std::numbers::pi);
  out.shapes = n * ges.eigenvectors();
  for (Eigen::Index j = 0; j < out.shapes.cols(); ++j) {
    Eigen::Index imax = 0;
    out.shapes.col(j).cwiseAbs().maxCoeff(&imax);
    out.shapes.col(j) /= out.shapes(imax, j);
  }

  // First-order form x = [q; q'], A = [0 I; -M⁻¹K -M⁻¹C].
  Eigen::MatrixXd a = Eigen::MatrixXd::Zero(2 * r, 2 * r);
  a.topRightCorner(r, r).setIdentity();
  const Eigen::LLT<Eigen::MatrixXd> llt(m);
  a.bottomLeftCorner(r, r) = -llt.solve(k);
  a.bottomRightCorner(r, r) = -llt.solve(c);
  Eigen::EigenSolver<Eigen::MatrixXd> es(a, false);
  Eigen::VectorXcd ev = es.eigenvalues();
  std::vector<std::complex<double>> sorted(ev.data(), ev.data() + ev.size());
  std::sort(sorted.begin(), sorted.end(), [](const auto& x, const auto& y) {
    return std::abs(x.imag()) != std::abs(y.imag()) ? std::abs(x.imag()) < std::abs(y.imag()) : x.imag() > y.imag();
  });
  out.damped_eigenvalues = Eigen::Map<Eigen::VectorXcd>(sorted.data(), static_cast<Eigen::Index>(sorted.size()));
  return out;
}

std::vector<int> TorsionalNetwork::contact_state_indices() const {
  std::vector<int> at;
  int n = 0;
  for (const auto& c : contacts_) {
    at.push_back(n);
    n += c.law->states();
  }
  return at;
}

Eigen::VectorXd TorsionalNetwork::initial_contact_states() const {
  int n = 0;
  for (const auto& c : contacts_) n += c.law->states();
  Eigen::VectorXd z = Eigen::VectorXd::Zero(n);
  const auto at = contact_state_indices();
  for (std::size_t c = 0; c < contacts_.size(); ++c)
    if (contacts_[c].law->states() > 0) contacts_[c].law->initial_states(z.data() + at[c]);
  return z;
}

}  // namespace shudder::dynamics
