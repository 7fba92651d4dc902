#include "dynamics/linearisation.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

namespace shudder::dynamics {

namespace {

// Central-difference step for a speed x (see the header); states use max(1e-9, 1e-6 |z|).
double fd_step(double x) { return std::max(1e-7, 1e-6 * std::abs(x)); }

}  // namespace

Eigen::VectorXcd LinearSystem::node_speeds(const Eigen::VectorXcd& eigenvector) const {
  return basis.cast<std::complex<double>>() * eigenvector.segment(reduced_dofs, reduced_dofs);
}

LinearSystem linearise_network(const TorsionalNetwork& net, const LinearOperatingPoint& op) {
  const int n = net.nodes();
  int m_states = 0;
  for (const auto& e : net.force_elements())
    if (!e.law->is_periodic_forcing()) m_states += e.law->states();
  if (op.omega_rad_s.size() != n || !op.omega_rad_s.allFinite())
    throw std::invalid_argument("linearisation: node speeds must be " + std::to_string(n) + " finite values");
  if (op.element_states.size() != m_states || !op.element_states.allFinite())
    throw std::invalid_argument("linearisation: force-element states must be " + std::to_string(m_states) +
                                " finite values");
  if (!op.stuck.empty() && op.stuck.size() != net.contacts().size())
    throw std::invalid_argument("linearisation: one stuck flag per contact (or none)");
  if (op.extra_damping.size() != 0 && (op.extra_damping.rows() != n || op.extra_damping.cols() != n))
    throw std::invalid_argument("linearisation: extra damping must be n x n");

  LinearSystem sys;
  std::vector<bool> stuck = op.stuck;
  stuck.resize(net.contacts().size(), false);
  sys.basis = net.constraint_basis(stuck);
  const Eigen::MatrixXd& nb = sys.basis;
  const int r = static_cast<int>(nb.cols());
  sys.reduced_dofs = r;
  sys.element_states = m_states;

  // Springs: shafts and motors only (force elements enter through their states).
  Eigen::MatrixXd k = Eigen::MatrixXd::Zero(n, n);
  for (const auto& s : net.shafts()) stamp_coupling(k, s.a, s.b, s.stiffness_Nm_per_rad);
  for (const auto& mo : net.motors()) k(mo.node, mo.node) += mo.ki_Nm_per_rad;
  Eigen::MatrixXd c = net.damping_matrix();
  if (op.extra_damping.size() != 0) c += op.extra_damping;

  // Slipping contacts: the friction slope as a damper.
  sys.contact_slope_Nms.assign(net.contacts().size(), 0.0);
  const Eigen::VectorXd contact_z = op.contact_states.size() != 0 ? op.contact_states : net.initial_contact_states();
  const std::vector<int> contact_z_at = net.contact_state_indices();
  for (std::size_t i = 0; i < net.contacts().size(); ++i) {
    if (stuck[i]) continue;
    const auto& ct = net.contacts()[i];
    const double slip = op.omega_rad_s[ct.a] - (ct.b == kGround ? 0.0 : op.omega_rad_s[ct.b]);
    const double s = ct.law->kinetic_torque_slope_Nms(std::abs(slip), op.t_s, contact_z.data() + contact_z_at[i]);
    if (!std::isfinite(s))
      throw std::invalid_argument("linearisation: friction slope of contact '" + ct.name + "' is not finite");
    sys.contact_slope_Nms[i] = s;
    stamp_coupling(c, ct.a, ct.b, s);
  }
  // Torque sources that depend on speed: δT = (∂T/∂ω) δω is a damper −∂T/∂ω.
  for (const auto& src : net.torque_sources()) {
    if (!src.torque_at_speed_Nm) continue;
    const double w = op.omega_rad_s[src.node], h = fd_step(w);
    const double slope = (src.torque_at_speed_Nm(op.t_s, w + h) - src.torque_at_speed_Nm(op.t_s, w - h)) / (2 * h);
    c(src.node, src.node) -= slope;
  }

  const Eigen::MatrixXd mr = nb.transpose() * net.mass_matrix() * nb;
  const Eigen::MatrixXd kr = nb.transpose() * k * nb;
  const Eigen::MatrixXd cr = nb.transpose() * c * nb;
  const Eigen::LLT<Eigen::MatrixXd> llt(mr);

  const int mc_states = static_cast<int>(contact_z.size());
  sys.contact_states = mc_states;
  const int dim = 2 * r + m_states + mc_states;
  sys.a = Eigen::MatrixXd::Zero(dim, dim);
  sys.a.block(0, r, r, r).setIdentity();
  sys.a.block(r, 0, r, r) = -llt.solve(kr);
  sys.a.block(r, r, r, r) = -llt.solve(cr);

  // Force elements: partial derivatives of T and ż by central differences.
  int z_off = 0;
  for (const auto& e : net.force_elements()) {
    if (e.law->is_periodic_forcing()) continue;  // no linear part about the mean motion
    const int ns = e.law->states();
    const double wa = op.omega_rad_s[e.a];
    const double wb = e.b == kGround ? 0.0 : e.ratio * op.omega_rad_s[e.b];
    std::vector<double> z(op.element_states.data() + z_off, op.element_states.data() + z_off + ns);
    std::vector<double> dz_p(static_cast<std::size_t>(ns)), dz_m(static_cast<std::size_t>(ns));
    // Column j of the local Jacobian: inputs (ω_a, ρω_b, z_0..z_{ns-1}) → outputs (T, ż_0..).
    const int inputs = 2 + ns;
    Eigen::MatrixXd jac(1 + ns, inputs);
    for (int j = 0; j < inputs; ++j) {
      double a_p = wa, a_m = wa, b_p = wb, b_m = wb;
      std::vector<double> z_p = z, z_m = z;
      double h;
      if (j == 0) {
        h = fd_step(wa);
        a_p += h;
        a_m -= h;
      } else if (j == 1) {
        h = fd_step(wb);
        b_p += h;
        b_m -= h;
      } else {
        h = std::max(1e-9, 1e-6 * std::abs(z[static_cast<std::size_t>(j - 2)]));
        z_p[j - 2] += h;
        z_m[j - 2] -= h;
      }
      const double tp = e.law->evaluate(a_p, b_p, z_p.data(), dz_p.data()).torque_Nm;
      const double tm = e.law->evaluate(a_m, b_m, z_m.data(), dz_m.data()).torque_Nm;
      jac(0, j) = (tp - tm) / (2 * h);
      for (int s = 0; s < ns; ++s) jac(1 + s, j) = (dz_p[s] - dz_m[s]) / (2 * h);
    }
    // δω_a = e_aᵀ N δv, ρ δω_b = ρ e_bᵀ N δv.
    Eigen::RowVectorXd da = nb.row(e.a);
    Eigen::RowVectorXd db = e.b == kGround ? Eigen::RowVectorXd::Zero(r) : Eigen::RowVectorXd(e.ratio * nb.row(e.b));
    // Generalised force direction of T: Nᵀ(−e_a + ρ e_b).
    Eigen::VectorXd g = -nb.row(e.a).transpose();
    if (e.b != kGround) g += e.ratio * nb.row(e.b).transpose();
    const Eigen::VectorXd minv_g = llt.solve(g);
    const Eigen::RowVectorXd dt_dv = jac(0, 0) * da + jac(0, 1) * db;
    sys.a.block(r, r, r, r) += minv_g * dt_dv;
    for (int s = 0; s < ns; ++s) {
      sys.a.block(r, 2 * r + z_off + s, r, 1) += minv_g * jac(0, 2 + s);
      sys.a.block(2 * r + z_off + s, r, 1, r) += jac(1 + s, 0) * da + jac(1 + s, 1) * db;
      for (int s2 = 0; s2 < ns; ++s2) sys.a(2 * r + z_off + s, 2 * r + z_off + s2) += jac(1 + s, 2 + s2);
    }
    z_off += ns;
  }
  // Contact laws' internal states (an actuator's pressure and valve): z_c at their values in the
  // operating point; ż_c = f(Δω, t, z_c) and, while slipping, the torque M(|Δω|, t, z_c) acting
  // −s M on a and +s M on b (s the slip's sign). Central differences as for the force elements;
  // a stuck contact's δΔω is 0 in the basis, so its states only decay on their own.
  for (std::size_t ci = 0; ci < net.contacts().size(); ++ci) {
    const auto& ct = net.contacts()[ci];
    const int ns = ct.law->states();
    if (ns == 0) continue;
    const int row0 = 2 * r + m_states + contact_z_at[ci];
    const double slip = stuck[ci] ? 0.0 : op.omega_rad_s[ct.a] - (ct.b == kGround ? 0.0 : op.omega_rad_s[ct.b]);
    const double sign = slip >= 0 ? 1.0 : -1.0;
    std::vector<double> z(contact_z.data() + contact_z_at[ci], contact_z.data() + contact_z_at[ci] + ns);
    std::vector<double> dz_p(static_cast<std::size_t>(ns)), dz_m(static_cast<std::size_t>(ns));
    const Eigen::RowVectorXd dslip_dv =
        ct.b == kGround ? Eigen::RowVectorXd(nb.row(ct.a)) : Eigen::RowVectorXd(nb.row(ct.a) - nb.row(ct.b));
    Eigen::VectorXd g = -nb.row(ct.a).transpose();
    if (ct.b != kGround) g += nb.row(ct.b).transpose();
    const Eigen::VectorXd minv_g = llt.solve(sign * g);
    // With respect to the slip (only while slipping; stuck, δΔω = 0).
    if (!stuck[ci]) {
      const double h = fd_step(slip);
      ct.law->state_rates(slip + h, op.t_s, z.data(), dz_p.data());
      ct.law->state_rates(slip - h, op.t_s, z.data(), dz_m.data());
      for (int s = 0; s < ns; ++s) sys.a.block(row0 + s, r, 1, r) += (dz_p[s] - dz_m[s]) / (2 * h) * dslip_dv;
    }
    // With respect to each state: the rates, and the torque while slipping.
    for (int j = 0; j < ns; ++j) {
      const double h = std::max(1e-9, 1e-6 * std::abs(z[static_cast<std::size_t>(j)]));
      std::vector<double> z_p = z, z_m = z;
      z_p[j] += h;
      z_m[j] -= h;
      ct.law->state_rates(slip, op.t_s, z_p.data(), dz_p.data());
      ct.law->state_rates(slip, op.t_s, z_m.data(), dz_m.data());
      for (int s = 0; s < ns; ++s) sys.a(row0 + s, row0 + j) += (dz_p[s] - dz_m[s]) / (2 * h);
      if (!stuck[ci]) {
        const double dm = (ct.law->kinetic_torque_Nm(std::abs(slip), op.t_s, z_p.data()) -
                           ct.law->kinetic_torque_Nm(std::abs(slip), op.t_s, z_m.data())) /
                          (2 * h);
        sys.a.block(r, row0 + j, r, 1) += minv_g * dm;
      }
    }
  }
  if (!sys.a.allFinite()) throw std::invalid_argument("linearisation: the linear system is not finite");

  // Rigid-body directions: the null space of K_r.
  Eigen::FullPivLU<Eigen::MatrixXd> lu(kr);
  lu.setThreshold(1e-10);
  sys.rigid_body_modes = r - static_cast<int>(lu.rank());
  return sys;
}

std::vector<LinearMode> linear_modes(const LinearSystem& sys, bool shapes) {
  Eigen::EigenSolver<Eigen::MatrixXd> es(sys.a, shapes);
  const Eigen::VectorXcd ev = es.eigenvalues();
  // The rigid-body zeros: the `rigid_body_modes` eigenvalues of smallest modulus.
  std::vector<Eigen::Index> order(static_cast<std::size_t>(ev.size()));
  for (Eigen::Index i = 0; i < ev.size(); ++i) order[static_cast<std::size_t>(i)] = i;
  std::sort(order.begin(), order.end(), [&](auto x, auto y) { return std::abs(ev[x]) < std::abs(ev[y]); });
  const double scale = std::max(1.0, ev.cwiseAbs().maxCoeff());
  std::vector<LinearMode> out;
  for (std::size_t k = static_cast<std::size_t>(sys.rigid_body_modes); k < order.size(); ++k) {
    const Eigen::Index i = order[k];
    std::complex<double> l = ev[i];
    if (std::abs(l.imag()) < 1e-9 * scale) l.imag(0.0);
    if (l.imag() < 0) continue;
    LinearMode md;
    md.eigenvalue = l;
    md.frequency_Hz = l.imag() / (2.0 * std::numbers::pi);
    md.damping_ratio = std::abs(l) > 0 ? -l.real() / std::abs(l) : 0.0;
    if (!shapes) {
      out.push_back(std::move(md));
      continue;
    }
    const Eigen::VectorXcd w = sys.node_speeds(es.eigenvectors().col(i));
    Eigen::Index imax = 0;
    w.cwiseAbs().maxCoeff(&imax);
    const std::complex<double> ref = w[imax];
    md.node_amplitude.resize(w.size());
    md.node_phase_rad.resize(w.size());
    for (Eigen::Index j = 0; j < w.size(); ++j) {
      const std::complex<double> rel = std::abs(ref) > 0 ? w[j] / ref : std::complex<double>(0.0);
      md.node_amplitude[j] = std::abs(rel);
      md.node_phase_rad[j] = std::abs(rel) > 1e-12 ? std::arg(rel) : 0.0;
    }
    out.push_back(std::move(md));
  }
  std::sort(out.begin(), out.end(), [](const LinearMode& x, const LinearMode& y) {
    return x.frequency_Hz != y.frequency_Hz ? x.frequency_Hz < y.frequency_Hz
                                            : x.eigenvalue.real() > y.eigenvalue.real();
  });
  return out;
}

}  // namespace shudder::dynamics
