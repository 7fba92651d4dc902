#include "components/multirate_clutch.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

namespace shudder::components {

namespace {
constexpr double kDivergedTemp_C = 1e4;
}  // namespace

// Per clutch: its thermal workspace, the ring heat at the last step's end and the hold's
// temperatures (header).
struct MultirateCoupling::Slot {
  MultirateClutch in;
  const clutch::ThermalModel& th;
  clutch::ThermalWorkspace workspace;
  const dynamics::FrictionContact& c;
  Eigen::VectorXd heat_before, heat_now, seen_C, seen_end_C, last_C, now_C;
};

MultirateCoupling::MultirateCoupling(dynamics::Simulation& sim, const std::vector<MultirateClutch>& clutches,
                                     double end_s, double slow_step_s, double sample_rate_Hz,
                                     std::vector<double> breaks_s, std::function<void(double t_s)> at_break)
    : sim_(sim),
      end_s_(end_s),
      slow_step_s_(slow_step_s),
      sample_rate_Hz_(sample_rate_Hz),
      t0_s_(sim.time_s()),
      snap_s_(1e-9 * slow_step_s),
      breaks_s_(std::move(breaks_s)),
      at_break_(std::move(at_break)),
      ta_s_(sim.time_s()),
      sa_(sim.sample()) {
  if (std::isfinite(end_s) && sample_rate_Hz > 0) {
    n_samples_ = static_cast<long>(std::floor(end_s * sample_rate_Hz + 1e-9));
    for (long k = 1; k <= n_samples_; ++k) sample_times_.push_back(static_cast<double>(k) / sample_rate_Hz);
  } else if (sample_rate_Hz > 0) {
    n_samples_ = std::numeric_limits<long>::max();  // no end: no samples, but slow steps snap onto their times
  }
  slots_.reserve(clutches.size());
  for (const auto& in : clutches) {
    const auto& th = in.clutch->thermal();
    const int nr = th.radial_cells();
    Slot s{in,
           th,
           clutch::ThermalWorkspace(th),
           sim.network().contacts()[static_cast<std::size_t>(in.contact)],
           Eigen::VectorXd(nr),
           Eigen::VectorXd(nr),
           in.context->held().ring_temp_C,
           in.context->held().ring_temp_C,
           th.interface_temps_C(*in.state),
           Eigen::VectorXd(nr)};
    for (int i = 0; i < nr; ++i) s.heat_before[i] = sim.channel_heat_J(in.contact, i);
    slots_.push_back(std::move(s));
  }
}

MultirateCoupling::~MultirateCoupling() = default;

// Step k ends at t0 + k·step (a product, not a running sum), moved onto a sample time or the
// duration when round-off is all that separates them (header).
double MultirateCoupling::step_end(long k) const {
  double tb = std::min(t0_s_ + static_cast<double>(k) * slow_step_s_, end_s_);
  if (end_s_ - tb < snap_s_) return end_s_;
  const double nearest = std::round(tb * sample_rate_Hz_);
  if (n_samples_ > 0 && nearest >= 1 && nearest <= static_cast<double>(n_samples_) &&
      std::abs(nearest / sample_rate_Hz_ - tb) < snap_s_)
    tb = nearest / sample_rate_Hz_;
  return tb;
}

void MultirateCoupling::advance_to(double t_s, const std::function<void(const dynamics::Sample&)>& on_sample,
                                   const std::function<void(const SlowStep&)>& after_step) {
  const double target = std::min(t_s, end_s_);
  while (sim_.time_s() < target - 1e-12) {
    const double tb = step_end(k_);
    // This call ends the slow step when it reaches its end (to the steps' round-off).
    const bool completes = target >= tb - snap_s_;
    const double until = completes ? tb : target;
    bool break_at_end = false;
    // A break within round-off of where the simulation stands was taken there already.
    for (auto br = std::upper_bound(breaks_s_.begin(), breaks_s_.end(), sim_.time_s() + snap_s_);
         br != breaks_s_.end() && *br <= until + snap_s_; ++br) {
      if (*br >= tb - snap_s_) {
        break_at_end = completes;
        break;
      }
      sim_.advance(*br, sample_times_, on_sample);
      if (at_break_) at_break_(*br);
      sim_.restart();
    }
    sim_.advance(until, sample_times_, on_sample);
    if (!completes) return;
    const auto sb = sim_.sample();
    finish_slow_step(ta_s_, tb, sb);
    if (break_at_end && at_break_) at_break_(tb);
    after_step(SlowStep{ta_s_, tb, sa_, sb});
    sim_.restart();
    ++k_;
    ta_s_ = sim_.time_s();
    sa_ = sim_.sample();
  }
}

void MultirateCoupling::add_breaks(const std::vector<double>& later_s) {
  breaks_s_.erase(breaks_s_.begin(), std::lower_bound(breaks_s_.begin(), breaks_s_.end(), sim_.time_s() - snap_s_));
  breaks_s_.insert(breaks_s_.end(), later_s.begin(), later_s.end());
}

void MultirateCoupling::finish_slow_step(double ta, double tb, const dynamics::Sample& sb) {
  const double dt = tb - ta;
  const double next_dt = step_end(k_ + 1) - tb;
  for (auto& s : slots_) {
    const int nr = s.th.radial_cells();
    auto& ts = *s.in.state;
    for (int i = 0; i < nr; ++i) s.heat_now[i] = sim_.channel_heat_J(s.in.contact, i);
    const auto twist = [&](const dynamics::Sample& smp) {
      const auto angle = [&](int node) { return node == dynamics::kGround ? 0.0 : smp.theta_rad[node]; };
      return angle(s.c.a) - angle(s.c.b);
    };
    const double mean_slip = (twist(sb) - twist(sa_)) / dt;
    if (s.in.data_range)  // the inputs the friction was evaluated at over this step (mid-step temperatures)
      s.in.data_range->add(dt, mean_slip, s.th.ring_radius_m(), 0.5 * (s.seen_C + s.seen_end_C),
                           s.in.clamp_force_N ? 0.5 * (s.in.clamp_force_N(sa_) + s.in.clamp_force_N(sb))
                                              : s.in.context->held().normal_force_N(0.5 * (ta + tb)));
    s.th.step(ts, s.workspace, dt, (s.heat_now - s.heat_before) / dt, mean_slip);
    ts.time_s = tb;
    s.heat_before = s.heat_now;
    s.now_C = s.th.interface_temps_C(ts);
    // A thermal state far outside any physical range is a numerical failure, as a non-finite
    // mechanical state is (dynamics/simulation.cpp). Without this check the hold would feed
    // friction at such temperatures to the integrator, which then creeps on with ever smaller
    // steps instead of failing (seen: a diagnosis candidate with a 1 J/K rig part behind a
    // 1000 W/K conductance diverges to 1e94 °C within 0.5 s). 1e4 °C: far above any disc or oil.
    if (!s.now_C.allFinite() || s.now_C.cwiseAbs().maxCoeff() > kDivergedTemp_C)
      throw std::runtime_error(
          "thermal step diverged at t = " + std::to_string(tb) + " s: interface temperature " +
          (s.now_C.allFinite() ? std::to_string(s.now_C.cwiseAbs().maxCoeff()) + " degC" : std::string("not finite")));
    if (next_dt > 0) {
      s.seen_C = s.seen_end_C;
      s.seen_end_C = s.now_C + (s.now_C - s.last_C) * (next_dt / dt);
      s.in.context->set_ring_temperature_ramp(s.seen_C, s.seen_end_C, tb, tb + next_dt);
    }
    s.last_C = s.now_C;
  }
}

void run_multirate(dynamics::Simulation& sim, const std::vector<MultirateClutch>& clutches, double duration_s,
                   double slow_step_s, double sample_rate_Hz,
                   const std::function<void(const dynamics::Sample&)>& on_sample,
                   const std::function<void(const SlowStep&)>& after_step, const std::vector<double>& breaks_s,
                   const std::function<void(double t_s)>& at_break) {
  MultirateCoupling coupling(sim, clutches, duration_s, slow_step_s, sample_rate_Hz, breaks_s, at_break);
  coupling.advance_to(duration_s, on_sample, after_step);
}

}  // namespace shudder::components
