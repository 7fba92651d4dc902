#include "components/network_stepper.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>

namespace shudder::components {

namespace {

// Every signal's jumps over (0, until_s), for the stepper's restarts.
std::vector<double> input_breaks(const NetworkSpec& spec, double until_s) {
  std::vector<double> t;
  const auto add = [&](const Signal& s) {
    const auto k = s.knots(0.0, until_s);
    t.insert(t.end(), k.begin(), k.end());
  };
  for (const auto& c : spec.clutches) {
    if (c.law != ClutchSpec::Law::kHaldex) {
      add(c.force_signal);
      continue;
    }
    add(c.haldex.pedal);
    if (c.haldex.valve_opening) add(*c.haldex.valve_opening);
    if (c.haldex.valve_pressure_bar) add(*c.haldex.valve_pressure_bar);
  }
  for (const auto& s : spec.torque_sources) add(s.torque_Nm);
  for (const auto& s : spec.speed_sources) add(s.speed_rpm);
  for (const auto& m : spec.motors) add(m.speed_rpm);
  for (const auto& e : spec.engines) add(e.throttle);
  return t;
}

}  // namespace

NetworkStepper::NetworkStepper(const NetworkSpec& spec, double end_s) : built_(build_network(spec)) {
  const auto& cfg = spec.settings;
  if (!(cfg.duration_s > 0) || !(cfg.thermal_step_s > 0) || !(cfg.sample_rate_Hz > 0))
    throw std::invalid_argument("duration, thermal step and sample rate must be > 0");

  wet_index_.assign(built_->clutches.size(), -1);
  for (std::size_t c = 0; c < built_->clutches.size(); ++c)
    if (built_->clutches[c].wet) {
      wet_index_[c] = static_cast<int>(thermal_.size());
      thermal_.push_back(built_->clutches[c].wet->initial_state());
    }

  // Each Haldex coupling's control unit, its first command set before the simulation reads the
  // valve's start opening from it.
  for (std::size_t c = 0; c < built_->clutches.size(); ++c)
    if (built_->clutches[c].haldex) {
      try {
        units_.emplace_back(built_->clutches[c]);
      } catch (const std::invalid_argument& e) {
        throw NetworkError(built_->clutches[c].name(), e.what());
      }
      unit_wet_.push_back(static_cast<std::size_t>(wet_index_[c]));
      units_.back().start(built_->initial_speed_rad_s, thermal_[unit_wet_.back()]);
    }

  sim_ = std::make_unique<dynamics::Simulation>(built_->network, cfg.integrator);
  sim_->initialize(0.0, built_->initial_angle_rad, built_->initial_speed_rad_s, built_->initial_motor_integral);

  // Each wet clutch's tally of its friction law used outside its data (clutch/friction_data_range.hpp).
  ranges_.reserve(thermal_.size());
  for (const auto& bc : built_->clutches)
    if (bc.wet) ranges_.emplace_back(*bc.wet->fluid().friction);
  std::vector<components::MultirateClutch> wet;
  for (std::size_t c = 0; c < built_->clutches.size(); ++c) {
    const BuiltClutch& bc = built_->clutches[c];
    if (!bc.wet) continue;
    const auto w = static_cast<std::size_t>(wet_index_[c]);
    wet.push_back({bc.context.get(), bc.wet.get(), &thermal_[w], bc.contact, &ranges_[w]});
    if (bc.haldex) wet.back().clamp_force_N = [&bc](const dynamics::Sample& s) { return bc.normal_force_N(s); };
  }
  // Restarts: the inputs' jumps and the control units' instants.
  const double until_s = std::isfinite(end_s) ? end_s : cfg.duration_s;
  std::vector<double> breaks = input_breaks(spec, until_s);
  for (const auto& u : units_) {
    const auto t = u.instants(0.0, until_s);
    breaks.insert(breaks.end(), t.begin(), t.end());
  }
  instants_until_s_ = std::isfinite(end_s) || units_.empty() ? INFINITY : until_s;
  instants_chunk_s_ = cfg.duration_s;
  std::sort(breaks.begin(), breaks.end());
  breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
  // Without a wet clutch the network is integrated in one stretch between the breaks.
  const double slow_step = wet.empty() ? (std::isfinite(end_s) ? end_s : cfg.duration_s) : cfg.thermal_step_s;
  coupling_ = std::make_unique<components::MultirateCoupling>(
      *sim_, wet, end_s, slow_step, cfg.sample_rate_Hz, std::move(breaks),
      units_.empty() ? std::function<void(double)>() : [this](double t) {
        const dynamics::Sample s = sim_->sample();
        for (auto& u : units_) u.at(t, s);
      });
}

NetworkStepper::~NetworkStepper() = default;

void NetworkStepper::advance_to(double t_s, const std::function<void(const dynamics::Sample&)>& on_sample,
                                const std::function<void(const components::SlowStep&)>& after_step) {
  // Without an end (an FMU) the control units' instants past those known so far.
  while (t_s >= instants_until_s_ - 1e-6) {
    const double from = instants_until_s_, until = std::max(t_s, from) + instants_chunk_s_;
    std::vector<double> more;
    for (const auto& u : units_) {
      const auto t = u.instants(from, until);
      more.insert(more.end(), t.begin(), t.end());
    }
    std::sort(more.begin(), more.end());
    more.erase(std::unique(more.begin(), more.end()), more.end());
    coupling_->add_breaks(more);
    instants_until_s_ = until;
  }
  coupling_->advance_to(t_s, on_sample, [&](const components::SlowStep& step) {
    for (std::size_t u = 0; u < units_.size(); ++u) units_[u].update_oil(thermal_[unit_wet_[u]]);
    if (after_step) after_step(step);
  });
}

}  // namespace shudder::components
