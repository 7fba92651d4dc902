#include "studies/clutch_prediction.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>

#include "dynamics/linearisation.hpp"

namespace shudder::studies {

studies::Prediction predict_clutch(components::BuiltNetwork& built, std::size_t clutch,
                                   const studies::OperatingWindow& w, const std::vector<dynamics::Sample>& snapshots) {
  using studies::Prediction;
  if (!(w.normal_force_N > 0)) return Prediction::none("the clutch is not loaded over the judged window");
  const auto& net = built.network;
  const std::size_t contacts = net.contacts().size();
  dynamics::LinearOperatingPoint op;
  int count = 0;
  std::vector<int> stuck_count(contacts, 0);
  for (const auto& s : snapshots) {
    if (s.t_s < w.from_s || s.t_s > w.to_s) continue;
    if (count == 0) {
      op.omega_rad_s = s.omega_rad_s;
      op.element_states = s.element_states;
      op.contact_states = s.contact_states;
    } else {
      op.omega_rad_s += s.omega_rad_s;
      op.element_states += s.element_states;
      op.contact_states += s.contact_states;
    }
    for (std::size_t c = 0; c < contacts; ++c) stuck_count[c] += s.modes[c] == dynamics::ContactMode::kStuck;
    ++count;
  }
  if (count == 0) return Prediction::none("no state of the run was kept inside the judged window");
  op.omega_rad_s /= count;
  op.element_states /= count;
  op.contact_states /= count;
  // The linearisation takes the states of the elements that are not periodic forcings (a firing
  // pulsation has no linear part about the mean motion).
  {
    std::vector<double> kept;
    Eigen::Index at = 0;
    for (const auto& e : net.force_elements()) {
      const int m = e.law->states();
      if (!e.law->is_periodic_forcing())
        for (int i = 0; i < m; ++i) kept.push_back(op.element_states[at + i]);
      at += m;
    }
    op.element_states = Eigen::Map<const Eigen::VectorXd>(kept.data(), static_cast<Eigen::Index>(kept.size()));
  }
  op.t_s = 0.5 * (w.from_s + w.to_s);
  op.stuck.resize(contacts);
  for (std::size_t c = 0; c < contacts; ++c) op.stuck[c] = 2 * stuck_count[c] > count;
  const components::BuiltClutch& bc = built.clutches[clutch];
  op.stuck[static_cast<std::size_t>(bc.contact)] = false;
  if (bc.wet) {
    if (!std::isfinite(w.interface_temp_C)) return Prediction::none("the interface temperature is not recorded");
    bc.context->set_ring_temperatures(Eigen::VectorXd::Constant(bc.wet->thermal().radial_cells(), w.interface_temp_C));
  }
  std::vector<dynamics::LinearMode> modes;
  try {
    modes = dynamics::linear_modes(dynamics::linearise_network(net, op), false);
  } catch (const std::invalid_argument& e) {
    return Prediction::none(e.what());
  }
  Prediction p;
  p.made = true;
  p.method =
      "network linearised about the judged window's mean motion (this clutch slipping at its mean slip, the other "
      "contacts as they mostly were; friction slopes as dampers" +
      std::string(bc.wet ? ", every ring at the window's mean interface temperature)" : ")");
  p.margin_per_s = -std::numeric_limits<double>::infinity();
  // A rigid-body motion (a car rolling) is a double zero eigenvalue, which the eigensolver returns
  // as a pair with a round-off imaginary part: below 1e-6 of the largest |λ| it is no oscillation.
  double largest = 0;
  for (const auto& m : modes) largest = std::max(largest, std::abs(m.eigenvalue));
  for (const auto& m : modes) {
    p.margin_per_s = std::max(p.margin_per_s, m.eigenvalue.real());
    if (std::abs(m.eigenvalue) <= 1e-6 * largest) continue;
    if (m.eigenvalue.imag() > 0 && !(m.eigenvalue.real() <= p.oscillatory_margin_per_s)) {
      p.oscillatory_margin_per_s = m.eigenvalue.real();
      p.frequency_Hz = m.frequency_Hz;
    }
  }
  if (modes.empty()) p.margin_per_s = Prediction::kNaN;
  return p;
}

}  // namespace shudder::studies
