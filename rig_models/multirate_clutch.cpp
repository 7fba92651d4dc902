#include "rig_models/multirate_clutch.hpp"

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

namespace shudder::rig_models {

namespace {
constexpr double kDivergedTemp_C = 1e4;
}  // namespace

void run_multirate(dynamics::Simulation& sim, ClutchContext& context, const clutch::WetClutch& clutch,
                   clutch::ThermalState& ts, int contact, double duration_s, double slow_step_s,
                   double sample_rate_Hz, const std::function<void(const dynamics::Sample&)>& on_sample,
                   const std::function<void(const SlowStep&)>& after_step,
                   clutch::FrictionDataRange* data_range) {
  std::vector<double> sample_times;
  const long n_samples = static_cast<long>(std::floor(duration_s * sample_rate_Hz + 1e-9));
  for (long k = 1; k <= n_samples; ++k) sample_times.push_back(static_cast<double>(k) / sample_rate_Hz);

  const auto& th = clutch.thermal();
  clutch::ThermalWorkspace workspace(th);
  const auto& c = sim.network().contacts()[static_cast<std::size_t>(contact)];
  const int nr = th.radial_cells();
  Eigen::VectorXd heat_before(nr), heat_now(nr);
  for (int i = 0; i < nr; ++i) heat_before[i] = sim.channel_heat_J(contact, i);
  // Step k ends at t0 + k·step (a product, not a running sum), moved onto a sample time or the
  // duration when round-off is all that separates them (header).
  const double t0 = sim.time_s();
  const double snap_s = 1e-9 * slow_step_s;
  const auto step_end = [&](long k) {
    double tb = std::min(t0 + static_cast<double>(k) * slow_step_s, duration_s);
    if (duration_s - tb < snap_s) return duration_s;
    const double nearest = std::round(tb * sample_rate_Hz);
    if (nearest >= 1 && nearest <= static_cast<double>(n_samples) &&
        std::abs(nearest / sample_rate_Hz - tb) < snap_s)
      tb = nearest / sample_rate_Hz;
    return tb;
  };
  // The first-order hold (header): the friction's temperatures over the coming step go from
  // where they ended (`seen_C`) to the extrapolation of the last two thermal updates.
  Eigen::VectorXd seen_C = context.held().ring_temp_C, seen_end_C = seen_C;
  Eigen::VectorXd last_C = th.interface_temps_C(ts), now_C(nr);
  for (long k = 1; sim.time_s() < duration_s - 1e-12; ++k) {
    const double ta = sim.time_s();
    const double tb = step_end(k);
    const auto sa = sim.sample();
    sim.advance(tb, sample_times, on_sample);
    const auto sb = sim.sample();
    const double dt = tb - ta;
    for (int i = 0; i < nr; ++i) heat_now[i] = sim.channel_heat_J(contact, i);
    const auto twist = [&](const dynamics::Sample& s) {
      const auto angle = [&](int node) { return node == dynamics::kGround ? 0.0 : s.theta_rad[node]; };
      return angle(c.a) - angle(c.b);
    };
    const double mean_slip = (twist(sb) - twist(sa)) / dt;
    if (data_range)  // the inputs the friction was evaluated at over this step (mid-step temperatures)
      data_range->add(dt, mean_slip, th.ring_radius_m(), 0.5 * (seen_C + seen_end_C),
                      context.held().normal_force_N(0.5 * (ta + tb)));
    th.step(ts, workspace, dt, (heat_now - heat_before) / dt, mean_slip);
    ts.time_s = tb;
    heat_before = heat_now;
    now_C = th.interface_temps_C(ts);
    // A thermal state far outside any physical range is a numerical failure, as a non-finite
    // mechanical state is (dynamics/simulation.cpp). Without this check the hold would feed
    // friction at such temperatures to the integrator, which then creeps on with ever smaller
    // steps instead of failing (seen: a diagnosis candidate with a 1 J/K rig part behind a
    // 1000 W/K conductance diverges to 1e94 °C within 0.5 s). 1e4 °C: far above any disc or oil.
    if (!now_C.allFinite() || now_C.cwiseAbs().maxCoeff() > kDivergedTemp_C)
      throw std::runtime_error("thermal step diverged at t = " + std::to_string(tb) + " s: interface temperature " +
                               (now_C.allFinite() ? std::to_string(now_C.cwiseAbs().maxCoeff()) + " degC"
                                                  : std::string("not finite")));
    const double next_dt = step_end(k + 1) - tb;
    if (next_dt > 0) {
      seen_C = seen_end_C;
      seen_end_C = now_C + (now_C - last_C) * (next_dt / dt);
      context.set_ring_temperature_ramp(seen_C, seen_end_C, tb, tb + next_dt);
    }
    last_C = now_C;
    after_step(SlowStep{ta, tb, sa, sb});
    sim.restart();
  }
}

}  // namespace shudder::rig_models
