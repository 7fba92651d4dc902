#include "analysis/stability.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "core/units.hpp"

namespace shudder::analysis {

namespace {

using units::kTwoPi;
// A mode is a rigid-body one if its undamped frequency is below this fraction of the highest:
// the generalised eigenvalues ω² carry round-off ~1e-16 · ω²_max, i.e. ~1e-8 · ω_max.
constexpr double kRigidFrequencyFraction = 1e-6;
// Real parts up to this fraction of max|λ| count as neutral: a double zero eigenvalue (free
// undamped body) splits by ~√ε · scale ≈ 1.5e-8 · scale in the eigen-solver.
constexpr double kNeutralFraction = 1e-8;

bool is_stuck(const SteadySliding& s, std::size_t k) {
  return (k < s.stuck.size() && s.stuck[k]) || s.slip_rad_s[k] == 0.0;
}

void check_input(const dynamics::TorsionalNetwork& net, const SteadySliding& s) {
  const std::size_t n = net.contacts().size();
  if (s.slip_rad_s.size() != n)
    throw std::invalid_argument("steady sliding gives " + std::to_string(s.slip_rad_s.size()) +
                                " contact slips, but the network has " + std::to_string(n) +
                                " contacts; give one slip (rad/s, 0 = stuck) per contact");
  if (!s.stuck.empty() && s.stuck.size() != n)
    throw std::invalid_argument("steady sliding gives " + std::to_string(s.stuck.size()) + " stuck flags for " +
                                std::to_string(n) + " contacts; give one per contact or none");
  if (!std::isfinite(s.t_s)) throw std::invalid_argument("steady sliding time must be finite");
  for (std::size_t k = 0; k < n; ++k)
    if (!std::isfinite(s.slip_rad_s[k]))
      throw std::invalid_argument("slip of contact '" + net.contacts()[k].name + "' must be finite (rad/s)");
}

}  // namespace

Eigen::MatrixXd friction_slope_damping(const dynamics::TorsionalNetwork& net, const SteadySliding& s) {
  check_input(net, s);
  Eigen::MatrixXd d = Eigen::MatrixXd::Zero(net.nodes(), net.nodes());
  // Contact laws' own states (an actuator's pressure) at their start values.
  const Eigen::VectorXd z = net.initial_contact_states();
  const std::vector<int> z_at = net.contact_state_indices();
  for (std::size_t k = 0; k < net.contacts().size(); ++k) {
    if (is_stuck(s, k)) continue;
    const auto& c = net.contacts()[k];
    const double slope = c.law->kinetic_torque_slope_Nms(std::abs(s.slip_rad_s[k]), s.t_s, z.data() + z_at[k]);
    if (!std::isfinite(slope))
      throw std::invalid_argument("friction law of contact '" + c.name + "' gives a non-finite slope at slip " +
                                  std::to_string(s.slip_rad_s[k]) + " rad/s");
    // Damper s between a and b (or a and ground).
    d(c.a, c.a) += slope;
    if (c.b == dynamics::kGround) continue;
    d(c.b, c.b) += slope;
    d(c.a, c.b) -= slope;
    d(c.b, c.a) -= slope;
  }
  return d;
}

StabilityPoint stability_from_eigenvalues(const Eigen::VectorXcd& ev, int rigid_body_modes) {
  StabilityPoint out;
  out.eigenvalues = ev;
  out.rigid_body_modes = rigid_body_modes;
  // Leave out the rigid-body drift: the `rigid_body_modes` eigenvalues nearest zero.
  std::vector<Eigen::Index> order(static_cast<std::size_t>(ev.size()));
  for (Eigen::Index i = 0; i < ev.size(); ++i) order[static_cast<std::size_t>(i)] = i;
  std::stable_sort(order.begin(), order.end(),
                   [&](Eigen::Index x, Eigen::Index y) { return std::abs(ev[x]) < std::abs(ev[y]); });
  const std::size_t skip = std::min(order.size(), static_cast<std::size_t>(std::max(rigid_body_modes, 0)));

  const double nan = std::numeric_limits<double>::quiet_NaN();
  out.margin_per_s = -std::numeric_limits<double>::infinity();
  out.oscillatory_margin_per_s = nan;
  out.oscillatory_frequency_Hz = nan;
  double scale = 0.0;
  for (std::size_t j = skip; j < order.size(); ++j) {
    const std::complex<double> l = ev[order[j]];
    scale = std::max(scale, std::abs(l));
    if (l.real() > out.margin_per_s) {
      out.margin_per_s = l.real();
      out.frequency_Hz = std::abs(l.imag()) / kTwoPi;
    }
    // Eigen's real Schur form gives real eigenvalues an imaginary part of exactly 0.
    if (l.imag() != 0.0 && !(l.real() <= out.oscillatory_margin_per_s)) {
      out.oscillatory_margin_per_s = l.real();
      out.oscillatory_frequency_Hz = std::abs(l.imag()) / kTwoPi;
    }
  }
  if (skip == order.size()) {  // nothing but rigid-body drift: neutral
    out.margin_per_s = 0.0;
    out.frequency_Hz = 0.0;
  }
  out.stable = out.margin_per_s <= kNeutralFraction * scale;
  return out;
}

StabilityPoint linearise(const dynamics::TorsionalNetwork& net, const SteadySliding& s) {
  const Eigen::MatrixXd slope_damping = friction_slope_damping(net, s);
  std::vector<bool> stuck(net.contacts().size());
  for (std::size_t k = 0; k < stuck.size(); ++k) stuck[k] = is_stuck(s, k);
  const dynamics::Modes m = net.modes(stuck, slope_damping);

  // Rigid-body directions: undamped frequency ~0 against the highest.
  int rigid = 0;
  const double f_max = m.frequencies_Hz.size() > 0 ? m.frequencies_Hz.maxCoeff() : 0.0;
  for (Eigen::Index i = 0; i < m.frequencies_Hz.size(); ++i)
    rigid += m.frequencies_Hz[i] <= kRigidFrequencyFraction * f_max;
  return stability_from_eigenvalues(m.damped_eigenvalues, rigid);
}

}  // namespace shudder::analysis
